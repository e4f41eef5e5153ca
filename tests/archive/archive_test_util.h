/* Helpers shared by the archive tests: scratch directories, archiving a
 * face list after building and validating it, and comparing face lists bit
 * for bit. */
#ifndef MESHTOPO_TEST_ARCHIVE_UTIL_H
#define MESHTOPO_TEST_ARCHIVE_UTIL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/archive.h"

/* A fresh directory under $TMPDIR (or /tmp), path written into buf. */
bool at_tmpdir(char *buf, size_t size);

/* Removes a scratch directory and the files in it (one level). */
void at_rmdir(const char *dir);

/* Builds list (checking the build and mt_mesh_validate), archives it as
 * mesh_id / version with the given utime, source and hash. Returns the
 * write's status; *out_mesh (may be NULL) keeps the built mesh. */
mt_status at_archive_list(mt_archive *archive, const char *mesh_id, uint32_t version,
                          const mt_face_list *list, uint64_t hash, mt_mesh **out_mesh);

/* Whether two face lists are identical: counts, sizes, indices, and
 * positions bit for bit (both NULL counts as equal). */
bool at_face_lists_equal(const mt_face_list *a, const mt_face_list *b);

/* A stand-in content hash for the tests (FNV-1a over the arrays), with the
 * signature mt_archive_verify_file takes. */
mt_status at_hash(void *ctx, const mt_face_list *faces, uint64_t *out_hash, mt_diag *diag);

/* Reads every .off and .off.gz mesh of the corpus and calls fn(name, list,
 * ctx) for each (the list is freed after the call). A file that does not
 * read is a test failure. Returns how many meshes were visited. */
int at_for_each_corpus_mesh(void (*fn)(const char *name, const mt_face_list *list, void *ctx),
                            void *ctx);

/* Writes `size` bytes to path; false on failure. */
bool at_write_bytes(const char *path, const void *data, size_t size);

/* Copies a file; false on failure. */
bool at_copy_file(const char *from, const char *to, long truncate_to);

/* Whether two files hold the same bytes (false when either cannot be read). */
bool at_same_bytes(const char *a, const char *b);

/* Damage done to an archive file with the HDF5 C API (false on failure):
 * one uint32 or int32 entry of a 1-D dataset overwritten, an integer
 * attribute of object `obj` replaced (stored as int64 or uint64), a link
 * (dataset, group) or an attribute deleted. */
bool at_poke_u32(const char *path, const char *dataset, uint64_t index, uint32_t value);
bool at_set_attr_i64(const char *path, const char *obj, const char *name, int64_t value);
bool at_set_attr_u64(const char *path, const char *obj, const char *name, uint64_t value);
bool at_delete(const char *path, const char *link);
bool at_delete_attr(const char *path, const char *obj, const char *name);

/* Reads one uint32 entry of a 1-D dataset (0 on failure). */
uint32_t at_peek_u32(const char *path, const char *dataset, uint64_t index);

#endif
