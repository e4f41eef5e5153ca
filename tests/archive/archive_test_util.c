/* Helpers shared by the archive tests (see archive_test_util.h). */
#include "archive_test_util.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness.h"
#include "meshtopo/io.h"
#include "meshtopo/validate.h"

bool at_tmpdir(char *buf, size_t size)
{
    const char *base = getenv("TMPDIR");
    if (!base || !base[0]) base = "/tmp";
    snprintf(buf, size, "%s/meshtopo-archive-XXXXXX", base);
    return mkdtemp(buf) != NULL;
}

void at_rmdir(const char *dir)
{
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *ent;
        while ((ent = readdir(d)) != NULL) {
            if (strcmp(ent->d_name, ".") == 0 || strcmp(ent->d_name, "..") == 0) continue;
            unlinkat(dirfd(d), ent->d_name, 0);
        }
        closedir(d);
    }
    rmdir(dir);
}

mt_status at_archive_list(mt_archive *archive, const char *mesh_id, uint32_t version,
                          const mt_face_list *list, uint64_t hash, mt_mesh **out_mesh)
{
    if (out_mesh) *out_mesh = NULL;
    mt_mesh *mesh = NULL;
    mt_diag diag;
    mt_status st = mt_mesh_build(list, NULL, &mesh, &diag);
    CHECK_OK(st);
    if (st != MT_OK) return st;
    CHECK_OK(mt_mesh_validate(mesh, &diag));
    mt_archive_meta meta = {mesh_id, version, 1700000000000000 + version, "test-node", hash};
    mt_archive_write_stats stats;
    st = mt_archive_write(archive, &meta, list, mesh, &stats, &diag);
    if (st != MT_OK) printf("archive write: %s\n", diag.message);
    if (out_mesh)
        *out_mesh = mesh;
    else
        mt_mesh_destroy(mesh);
    return st;
}

bool at_face_lists_equal(const mt_face_list *a, const mt_face_list *b)
{
    if (a->num_verts != b->num_verts || a->num_faces != b->num_faces ||
        a->num_indices != b->num_indices || (!a->positions) != (!b->positions))
        return false;
    if (a->positions &&
        memcmp(a->positions, b->positions, 3 * (size_t)a->num_verts * sizeof(double)) != 0)
        return false;
    if (a->num_faces && memcmp(a->face_sizes, b->face_sizes, a->num_faces * sizeof(uint32_t)))
        return false;
    if (a->num_indices &&
        memcmp(a->face_indices, b->face_indices, (size_t)a->num_indices * sizeof(uint32_t)))
        return false;
    return true;
}

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

mt_status at_hash(void *ctx, const mt_face_list *f, uint64_t *out_hash, mt_diag *diag)
{
    (void)ctx;
    (void)diag;
    uint64_t h = 0xcbf29ce484222325ull;
    h = fnv(h, &f->num_verts, sizeof f->num_verts);
    if (f->positions) h = fnv(h, f->positions, 3 * (size_t)f->num_verts * sizeof(double));
    if (f->num_faces) h = fnv(h, f->face_sizes, f->num_faces * sizeof(uint32_t));
    if (f->num_indices) h = fnv(h, f->face_indices, (size_t)f->num_indices * sizeof(uint32_t));
    *out_hash = h;
    return MT_OK;
}

bool at_write_bytes(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) return false;
    bool ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

bool at_copy_file(const char *from, const char *to, long truncate_to)
{
    FILE *f = fopen(from, "rb");
    if (!f) return false;
    char *buf = malloc(1 << 20);
    size_t n = buf ? fread(buf, 1, 1 << 20, f) : 0;
    fclose(f);
    if (truncate_to >= 0 && (size_t)truncate_to < n) n = (size_t)truncate_to;
    bool ok = buf && at_write_bytes(to, buf, n);
    free(buf);
    return ok;
}

int at_for_each_corpus_mesh(void (*fn)(const char *name, const mt_face_list *list, void *ctx),
                            void *ctx)
{
    const char *corpus = mt_test_corpus_dir();
    DIR *d = opendir(corpus);
    CHECK(d != NULL);
    if (!d) return 0;
    int meshes = 0;
    struct dirent *ent;
    while ((ent = readdir(d)) != NULL) {
        const char *n = ent->d_name;
        size_t len = strlen(n);
        bool off = len > 4 && strcmp(n + len - 4, ".off") == 0;
        bool gz = len > 7 && strcmp(n + len - 7, ".off.gz") == 0;
        if (!off && !gz) continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", corpus, n);
        mt_face_list list;
        mt_status st = mt_read_file(path, MT_FORMAT_AUTO, &list, NULL);
        CHECK_OK(st);
        if (st != MT_OK) continue;
        fn(n, &list, ctx);
        mt_face_list_free(&list);
        meshes++;
    }
    closedir(d);
    return meshes;
}
