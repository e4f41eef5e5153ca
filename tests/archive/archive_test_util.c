/* Helpers shared by the archive tests (see archive_test_util.h). */
#include "archive_test_util.h"

#include <dirent.h>
#include <hdf5.h>
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

bool at_same_bytes(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    bool same = fa && fb;
    while (same) {
        int ca = fgetc(fa), cb = fgetc(fb);
        if (ca != cb) same = false;
        if (ca == EOF || cb == EOF) break;
    }
    if (fa) fclose(fa);
    if (fb) fclose(fb);
    return same;
}

/* Selects entry `index` of a 1-D dataset for a one-element read or write. */
static bool select_one(hid_t d, uint64_t index, hid_t *out_space, hid_t *out_mem)
{
    hsize_t at = index, one = 1;
    *out_space = H5Dget_space(d);
    *out_mem = H5Screate_simple(1, &one, NULL);
    return *out_space >= 0 && *out_mem >= 0 &&
           H5Sselect_hyperslab(*out_space, H5S_SELECT_SET, &at, NULL, &one, NULL) >= 0;
}

bool at_poke_u32(const char *path, const char *dataset, uint64_t index, uint32_t value)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t d = f < 0 ? -1 : H5Dopen2(f, dataset, H5P_DEFAULT);
    hid_t space = -1, mem = -1;
    bool ok = d >= 0 && select_one(d, index, &space, &mem) &&
              H5Dwrite(d, H5T_NATIVE_UINT32, mem, space, H5P_DEFAULT, &value) >= 0;
    if (mem >= 0) H5Sclose(mem);
    if (space >= 0) H5Sclose(space);
    if (d >= 0) H5Dclose(d);
    return f >= 0 && H5Fclose(f) >= 0 && ok;
}

uint32_t at_peek_u32(const char *path, const char *dataset, uint64_t index)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    uint32_t value = 0;
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f < 0 ? -1 : H5Dopen2(f, dataset, H5P_DEFAULT);
    hid_t space = -1, mem = -1;
    if (d >= 0 && select_one(d, index, &space, &mem))
        H5Dread(d, H5T_NATIVE_UINT32, mem, space, H5P_DEFAULT, &value);
    if (mem >= 0) H5Sclose(mem);
    if (space >= 0) H5Sclose(space);
    if (d >= 0) H5Dclose(d);
    if (f >= 0) H5Fclose(f);
    return value;
}

static bool set_attr(const char *path, const char *obj, const char *name, hid_t ftype, hid_t mtype,
                     const void *value)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t o = f < 0 ? -1 : H5Oopen(f, obj, H5P_DEFAULT);
    if (o >= 0) H5Adelete(o, name);
    hid_t s = H5Screate(H5S_SCALAR);
    hid_t a = o < 0 ? -1 : H5Acreate2(o, name, ftype, s, H5P_DEFAULT, H5P_DEFAULT);
    bool ok = a >= 0 && H5Awrite(a, mtype, value) >= 0;
    if (a >= 0) H5Aclose(a);
    H5Sclose(s);
    if (o >= 0) H5Oclose(o);
    return f >= 0 && H5Fclose(f) >= 0 && ok;
}

bool at_set_attr_i64(const char *path, const char *obj, const char *name, int64_t value)
{
    return set_attr(path, obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

bool at_set_attr_u64(const char *path, const char *obj, const char *name, uint64_t value)
{
    return set_attr(path, obj, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value);
}

bool at_delete(const char *path, const char *link)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    bool ok = f >= 0 && H5Ldelete(f, link, H5P_DEFAULT) >= 0;
    return f >= 0 && H5Fclose(f) >= 0 && ok;
}

bool at_delete_attr(const char *path, const char *obj, const char *name)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t o = f < 0 ? -1 : H5Oopen(f, obj, H5P_DEFAULT);
    bool ok = o >= 0 && H5Adelete(o, name) >= 0;
    if (o >= 0) H5Oclose(o);
    return f >= 0 && H5Fclose(f) >= 0 && ok;
}
