/* The bare HDF5 side of `meshtopo-bench archive`: the datasets an archive
 * file holds (VTKHDF cells, face list, half-edge arrays), written with
 * nothing but H5Fcreate/H5Dcreate/H5Dwrite in the same layout and filters
 * as mt_archive_write_with, and the ones a reload needs read back with
 * H5Dread. Attributes and the small report datasets are left out: they are
 * a few kilobytes. */
#include <fcntl.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "bench_archive.h"
#include "meshtopo/mesh_parts.h"

#define MAX_DATASETS 24
#define CHUNK_BYTES (1u << 20) /* as the archive's deflated layout */

typedef struct bare_dataset {
    const char *path;
    hid_t ftype, mtype;
    int rank;
    hsize_t dims[2];
    const void *data;
    bool reload; /* read by a reload */
} bare_dataset;

struct mt__bare_set {
    bare_dataset ds[MAX_DATASETS];
    int count;
    int64_t counts[3];
    double *points;
    int64_t *connectivity, *offsets, *face_ids;
    uint8_t *types;
};

static void add(mt__bare_set *s, const char *path, hid_t ftype, hid_t mtype, int rank, hsize_t rows,
                hsize_t cols, const void *data, bool reload)
{
    bare_dataset *d = &s->ds[s->count++];
    d->path = path;
    d->ftype = ftype;
    d->mtype = mtype;
    d->rank = rank;
    d->dims[0] = rows;
    d->dims[1] = cols;
    d->data = data;
    d->reload = reload;
}

void mt__bare_set_free(mt__bare_set *s)
{
    if (!s) return;
    free(s->points);
    free(s->connectivity);
    free(s->offsets);
    free(s->face_ids);
    free(s->types);
    free(s);
}

mt__bare_set *mt__bare_set_make(const mt_face_list *list, const mt_mesh *mesh)
{
    mt__bare_set *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    mt_mesh_parts p;
    mt_mesh_get_parts(mesh, &p);
    uint64_t cells = 0, ids = 0;
    for (uint32_t f = 0; f < list->num_faces; f++)
        if (p.face_he[f] != MT_NONE) {
            cells++;
            ids += list->face_sizes[f];
        }
    s->points = calloc(3 * (size_t)list->num_verts + 1, sizeof(double));
    s->connectivity = malloc((size_t)(ids + 1) * sizeof(int64_t));
    s->offsets = malloc((size_t)(cells + 1) * sizeof(int64_t));
    s->face_ids = malloc((size_t)(cells + 1) * sizeof(int64_t));
    s->types = malloc((size_t)cells + 1);
    if (!s->points || !s->connectivity || !s->offsets || !s->face_ids || !s->types) {
        mt__bare_set_free(s);
        return NULL;
    }
    if (list->positions)
        memcpy(s->points, list->positions, 3 * (size_t)list->num_verts * sizeof(double));
    uint64_t cell = 0, pos = 0, start = 0;
    s->offsets[0] = 0;
    for (uint32_t f = 0; f < list->num_faces; start += list->face_sizes[f], f++) {
        if (p.face_he[f] == MT_NONE) continue;
        uint32_t n = list->face_sizes[f];
        for (uint32_t k = 0; k < n; k++) s->connectivity[pos + k] = list->face_indices[start + k];
        pos += n;
        s->types[cell] = n == 3 ? 5 : n == 4 ? 9 : 7;
        s->face_ids[cell] = f;
        s->offsets[++cell] = (int64_t)pos;
    }
    s->counts[0] = list->num_verts;
    s->counts[1] = (int64_t)cells;
    s->counts[2] = (int64_t)ids;
    add(s, "/VTKHDF/NumberOfPoints", H5T_STD_I64LE, H5T_NATIVE_INT64, 1, 1, 0, &s->counts[0], 0);
    add(s, "/VTKHDF/NumberOfCells", H5T_STD_I64LE, H5T_NATIVE_INT64, 1, 1, 0, &s->counts[1], 0);
    add(s, "/VTKHDF/NumberOfConnectivityIds", H5T_STD_I64LE, H5T_NATIVE_INT64, 1, 1, 0,
        &s->counts[2], 0);
    add(s, "/VTKHDF/Points", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, list->num_verts, 3, s->points,
        true);
    add(s, "/VTKHDF/Connectivity", H5T_STD_I64LE, H5T_NATIVE_INT64, 1, ids, 0, s->connectivity, 0);
    add(s, "/VTKHDF/Offsets", H5T_STD_I64LE, H5T_NATIVE_INT64, 1, cells + 1, 0, s->offsets, 0);
    add(s, "/VTKHDF/Types", H5T_STD_U8LE, H5T_NATIVE_UINT8, 1, cells, 0, s->types, 0);
    add(s, "/VTKHDF/CellData/original_face_id", H5T_STD_I64LE, H5T_NATIVE_INT64, 1, cells, 0,
        s->face_ids, 0);
    add(s, "/meshtopo/face_vertex_counts", H5T_STD_I32LE, H5T_NATIVE_INT32, 1, list->num_faces, 0,
        list->face_sizes, 0);
    add(s, "/meshtopo/face_vertex_indices", H5T_STD_I32LE, H5T_NATIVE_INT32, 1, list->num_indices,
        0, list->face_indices, 0);
    const hid_t u = H5T_STD_U32LE, m = H5T_NATIVE_UINT32;
    const uint32_t nhe = p.num_half_edges, nvi = p.num_verts_internal;
    add(s, "/meshtopo/halfedge/head", u, m, 1, nhe, 0, p.he_head, true);
    add(s, "/meshtopo/halfedge/next", u, m, 1, nhe, 0, p.he_next, true);
    add(s, "/meshtopo/halfedge/face", u, m, 1, nhe, 0, p.he_face, true);
    add(s, "/meshtopo/halfedge/face_halfedge", u, m, 1, p.num_faces, 0, p.face_he, true);
    add(s, "/meshtopo/halfedge/vertex_halfedge", u, m, 1, nvi, 0, p.vert_he, true);
    add(s, "/meshtopo/halfedge/copy_original", u, m, 1, p.num_copies, 0, p.copy_original, true);
    add(s, "/meshtopo/halfedge/copies_sorted", u, m, 1, p.num_copies, 0, p.copies_sorted, true);
    add(s, "/meshtopo/halfedge/bundle_offsets", u, m, 1, p.num_bundles ? p.num_bundles + 1 : 0, 0,
        p.bundle_offsets, true);
    add(s, "/meshtopo/halfedge/bundle_edges", u, m, 1, p.num_bundled, 0, p.bundle_edges, true);
    add(s, "/meshtopo/halfedge/bundled_sorted", u, m, 1, p.num_bundled, 0, p.bundled_sorted, true);
    add(s, "/meshtopo/halfedge/bundled_bundle", u, m, 1, p.num_bundled, 0, p.bundled_bundle, true);
    add(s, "/meshtopo/halfedge/vertex_component", u, m, 1, p.vert_component ? nvi : 0, 0,
        p.vert_component, true);
    return s;
}

static uint64_t dataset_bytes(const bare_dataset *d)
{
    uint64_t n = d->dims[0] * (d->rank == 2 ? d->dims[1] : 1);
    return n * H5Tget_size(d->ftype);
}

uint64_t mt__bare_set_write_bytes(const mt__bare_set *s)
{
    uint64_t total = 0;
    for (int i = 0; i < s->count; i++) total += dataset_bytes(&s->ds[i]);
    return total;
}

uint64_t mt__bare_set_reload_bytes(const mt__bare_set *s)
{
    uint64_t total = 0;
    for (int i = 0; i < s->count; i++)
        if (s->ds[i].reload) total += dataset_bytes(&s->ds[i]);
    return total;
}

/* Blosc's parameters as the archive sets them (archive_h5.c): level 5,
 * bit shuffle, LZ4. */
static const unsigned blosc_lz4_params[7] = {0, 0, 0, 0, 5, 2, 1};

/* The archive's rule: contiguous under 4 KiB or uncompressed, else 1 MiB
 * chunks with shuffle + deflate level 1 or with Blosc LZ4. */
static hid_t make_dcpl(const bare_dataset *d, mt_archive_compression compression)
{
    const bool deflate = compression == MT_ARCHIVE_COMPRESSION_DEFLATE;
    const bool lz4 = compression == MT_ARCHIVE_COMPRESSION_LZ4;
    if ((!deflate && !lz4) || dataset_bytes(d) < 4096) return H5P_DEFAULT;
    hsize_t row_bytes = H5Tget_size(d->ftype) * (d->rank == 2 ? d->dims[1] : 1);
    hsize_t chunk[2] = {CHUNK_BYTES / row_bytes, d->rank == 2 ? d->dims[1] : 1};
    if (chunk[0] < 1) chunk[0] = 1;
    if (chunk[0] > d->dims[0]) chunk[0] = d->dims[0];
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, d->rank, chunk);
    if (lz4) {
        H5Pset_filter(dcpl, 32001, H5Z_FLAG_OPTIONAL, 7, blosc_lz4_params);
    } else {
        H5Pset_shuffle(dcpl);
        H5Pset_deflate(dcpl, 1);
    }
    return dcpl;
}

bool mt__bare_write(const mt__bare_set *s, const char *path, mt_archive_compression compression,
                    double *out_write_ms, double *out_fsync_ms, char *err, size_t err_size)
{
    double t0 = mt__bench_now_ms();
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
    hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    H5Pclose(fapl);
    if (file < 0) {
        snprintf(err, err_size, "%s: H5Fcreate failed", path);
        return false;
    }
    bool ok = true;
    static const char *const groups[] = {"/VTKHDF",   "/VTKHDF/CellData",   "/VTKHDF/PointData",
                                         "/meshtopo", "/meshtopo/halfedge", "/meshtopo/report"};
    for (size_t i = 0; ok && i < sizeof groups / sizeof groups[0]; i++) {
        hid_t g = H5Gcreate2(file, groups[i], H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        ok = g >= 0;
        if (g >= 0) H5Gclose(g);
    }
    for (int i = 0; ok && i < s->count; i++) {
        const bare_dataset *d = &s->ds[i];
        hid_t dcpl = make_dcpl(d, compression);
        hid_t space = H5Screate_simple(d->rank, d->dims, NULL);
        hid_t dset = H5Dcreate2(file, d->path, d->ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
        ok = dset >= 0 && (dataset_bytes(d) == 0 ||
                           H5Dwrite(dset, d->mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, d->data) >= 0);
        if (!ok) snprintf(err, err_size, "%s: writing %s failed", path, d->path);
        if (dset >= 0) H5Dclose(dset);
        H5Sclose(space);
        if (dcpl != H5P_DEFAULT) H5Pclose(dcpl);
    }
    if (ok && H5Lcreate_hard(file, "/VTKHDF/Points", file, "/meshtopo/positions", H5P_DEFAULT,
                             H5P_DEFAULT) < 0) {
        snprintf(err, err_size, "%s: linking /meshtopo/positions failed", path);
        ok = false;
    }
    if (ok && H5Fflush(file, H5F_SCOPE_GLOBAL) < 0) ok = false;
    if (H5Fclose(file) < 0) ok = false;
    double t1 = mt__bench_now_ms();
    int fd = ok ? open(path, O_RDONLY) : -1;
    if (ok && (fd < 0 || fsync(fd) != 0)) {
        snprintf(err, err_size, "%s: fsync failed", path);
        ok = false;
    }
    if (fd >= 0) close(fd);
    *out_write_ms = t1 - t0;
    *out_fsync_ms = mt__bench_now_ms() - t1;
    return ok;
}

bool mt__bare_read(const mt__bare_set *s, const char *path, double *out_ms, char *err,
                   size_t err_size)
{
    void *buffers[MAX_DATASETS] = {0};
    double t0 = mt__bench_now_ms();
    hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    bool ok = file >= 0;
    if (!ok) snprintf(err, err_size, "%s: H5Fopen failed", path);
    for (int i = 0; ok && i < s->count; i++) {
        const bare_dataset *d = &s->ds[i];
        if (!d->reload) continue;
        const char *name = strcmp(d->path, "/VTKHDF/Points") == 0 ? "/meshtopo/positions" : d->path;
        uint64_t bytes = dataset_bytes(d);
        buffers[i] = malloc(bytes ? bytes : 1);
        hid_t dset = H5Dopen2(file, name, H5P_DEFAULT);
        ok =
            buffers[i] && dset >= 0 &&
            (bytes == 0 || H5Dread(dset, d->mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffers[i]) >= 0);
        if (!ok) snprintf(err, err_size, "%s: reading %s failed", path, name);
        if (dset >= 0) H5Dclose(dset);
    }
    if (file >= 0) H5Fclose(file);
    *out_ms = mt__bench_now_ms() - t0;
    for (int i = 0; ok && i < s->count; i++)
        if (buffers[i] && dataset_bytes(&s->ds[i]) &&
            memcmp(buffers[i], s->ds[i].data, dataset_bytes(&s->ds[i])) != 0) {
            snprintf(err, err_size, "%s: %s read back differs", path, s->ds[i].path);
            ok = false;
        }
    for (int i = 0; i < s->count; i++) free(buffers[i]);
    return ok;
}
