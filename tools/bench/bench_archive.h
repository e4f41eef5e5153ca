/* `meshtopo-bench archive`: archive write and reload of a large grid timed
 * next to bare HDF5 writes and reads of the same datasets (same layout and
 * filters) and next to a reload by rebuild from the face list.
 * bench_archive.c drives and prints; archive_bare.c holds the bare HDF5 side. */
#ifndef MESHTOPO_BENCH_ARCHIVE_H
#define MESHTOPO_BENCH_ARCHIVE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/archive.h"
#include "meshtopo/face_list.h"
#include "meshtopo/mesh.h"

/* Entry point: argv[0] is "archive". Returns the process exit status. */
int mt__bench_archive_command(int argc, char **argv);

/* The datasets of one archive file as plain arrays, ready to write: the
 * VTKHDF cells of a built mesh, its face list and its half-edge arrays. */
typedef struct mt__bare_set mt__bare_set;

/* Prepares the arrays of `list` and its build `mesh` (both must outlive
 * the set). NULL when out of memory. */
mt__bare_set *mt__bare_set_make(const mt_face_list *list, const mt_mesh *mesh);
void mt__bare_set_free(mt__bare_set *set);

/* Bytes of every dataset written, and of those a reload reads (the
 * half-edge arrays and positions). */
uint64_t mt__bare_set_write_bytes(const mt__bare_set *set);
uint64_t mt__bare_set_reload_bytes(const mt__bare_set *set);

/* Writes every dataset to `path` with bare H5Fcreate/H5Dcreate/H5Dwrite
 * (contiguous, or 1 MiB chunks with shuffle + deflate level 1 like
 * mt_archive_write_with), then H5Fflush and H5Fclose. *out_write_ms is the
 * time up to the close, *out_fsync_ms the fsync of the file after it.
 * Returns false (message in err) on failure. */
bool mt__bare_write(const mt__bare_set *set, const char *path, mt_archive_compression compression,
                    double *out_write_ms, double *out_fsync_ms, char *err, size_t err_size);

/* Reads back with H5Dread, into fresh buffers, the datasets a reload reads
 * (the half-edge arrays and positions) and checks them against the set. */
bool mt__bare_read(const mt__bare_set *set, const char *path, double *out_ms, char *err,
                   size_t err_size);

#endif
