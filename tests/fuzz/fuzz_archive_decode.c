/* libFuzzer target for the archive's decoders (meshtopo/archive.h):
 * mt_archive_decode_faces turns the face list datasets read from a file
 * into a face list, mt_archive_check_vtk checks the VTKHDF datasets against
 * it. The input bytes become arrays of any lengths and values, each in a
 * buffer of exactly its length, so a read past a given length is caught.
 * HDF5's own file parser is not fuzzed here: it is HDF5's code, and the
 * reader hands these functions only buffers sized from checked dataspaces.
 *
 * Input layout (missing bytes read as 0):
 *   byte 0    flags: bit 0 positions given, bit 1 num_verts from 4 raw bytes
 *             (any int32), bit 2 positions rows off by one, bit 3 corrupt the
 *             VTKHDF arrays with the bytes left over
 *   byte 1    V = byte % 40 (or 4 raw bytes with bit 1: negative, below 2^16, or
 *             mapped above the 2^31 - 1 limit)
 *   byte      F = byte % 40, then F face sizes as signed bytes (negative ones too)
 *   byte      I = byte % 200 indices, then I signed index bytes
 *   the rest  corruptions of the VTKHDF arrays: (array, position, value) triples
 * A successful decode must give a face list whose build validates and
 * whose exact VTKHDF arrays check; a corrupted one must be refused unless
 * the corruption changed nothing. Any disagreement calls abort(). */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/archive.h"
#include "meshtopo/validate.h"

typedef struct reader {
    const uint8_t *data;
    size_t size, pos;
} reader;

static uint8_t next(reader *r)
{
    return r->pos < r->size ? r->data[r->pos++] : 0;
}

static void *alloc(size_t n)
{
    return malloc(n ? n : 1);
}

/* The exact VTKHDF arrays of a face list and its build, each malloc'ed to
 * its length. */
static void make_vtk(const mt_face_list *list, const mt_mesh *mesh, mt_archive_vtk_arrays *v,
                     uint8_t *kept)
{
    mt_mesh_view view;
    mt_mesh_get_view(mesh, &view);
    uint64_t cells = 0, ids = 0;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        kept[f] = view.face_he[f] != MT_NONE;
        if (kept[f]) {
            cells++;
            ids += list->face_sizes[f];
        }
    }
    double *points = alloc(3 * (size_t)list->num_verts * sizeof(double));
    int64_t *conn = alloc((size_t)ids * sizeof(int64_t));
    int64_t *offs = alloc((size_t)(cells + 1) * sizeof(int64_t));
    uint8_t *types = alloc((size_t)cells);
    int64_t *face_ids = alloc((size_t)cells * sizeof(int64_t));
    for (size_t i = 0; i < 3 * (size_t)list->num_verts; i++)
        points[i] = list->positions ? list->positions[i] : 0.0;
    uint64_t c = 0, pos = 0, start = 0;
    offs[0] = 0;
    for (uint32_t f = 0; f < list->num_faces; start += list->face_sizes[f], f++) {
        if (!kept[f]) continue;
        uint32_t n = list->face_sizes[f];
        for (uint32_t k = 0; k < n; k++) conn[pos + k] = list->face_indices[start + k];
        pos += n;
        types[c] = n == 3 ? 5 : n == 4 ? 9 : 7;
        face_ids[c] = f;
        offs[++c] = (int64_t)pos;
    }
    *v = (mt_archive_vtk_arrays){list->num_verts,
                                 (int64_t)cells,
                                 (int64_t)ids,
                                 points,
                                 list->num_verts,
                                 conn,
                                 ids,
                                 offs,
                                 cells + 1,
                                 types,
                                 cells,
                                 face_ids,
                                 cells};
}

static void free_vtk(mt_archive_vtk_arrays *v)
{
    free((void *)v->points);
    free((void *)v->connectivity);
    free((void *)v->offsets);
    free((void *)v->types);
    free((void *)v->face_ids);
}

/* Changes one value or length of the arrays; returns whether it changed
 * anything the check compares. Lengths only shrink (the buffers stay valid). */
static bool corrupt(mt_archive_vtk_arrays *v, uint8_t which, uint8_t where, uint8_t value)
{
    int64_t delta = (int8_t)value == 0 ? 1 : (int8_t)value;
    switch (which % 9) {
        case 0:
            v->number_of_points += delta;
            return true;
        case 1:
            v->number_of_cells += delta;
            return true;
        case 2:
            v->number_of_connectivity_ids += delta;
            return true;
        case 3:
            if (v->num_connectivity == 0) return false;
            ((int64_t *)v->connectivity)[where % v->num_connectivity] += delta;
            return true;
        case 4:
            if (v->num_offsets == 0) return false;
            ((int64_t *)v->offsets)[where % v->num_offsets] += delta;
            return true;
        case 5:
            if (v->num_types == 0) return false;
            ((uint8_t *)v->types)[where % v->num_types] ^= (uint8_t)(value | 1);
            return true;
        case 6:
            if (v->num_face_ids == 0) return false;
            ((int64_t *)v->face_ids)[where % v->num_face_ids] += delta;
            return true;
        case 7:
            if (v->num_offsets == 0) return false;
            v->num_offsets--;
            return true;
        default:
            if (v->num_connectivity == 0) return false;
            v->num_connectivity--;
            return true;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    reader r = {data, size, 0};
    uint8_t flags = next(&r);
    mt_archive_face_arrays a;
    memset(&a, 0, sizeof a);
    if (flags & 2) {
        uint32_t raw = 0;
        for (int k = 0; k < 4; k++) raw = raw << 8 | next(&r);
        /* Negative counts and counts past the limit; large valid ones would
         * only measure the allocator. */
        int32_t v = (int32_t)raw;
        a.num_verts = v < 0 || v < 0x10000 ? v : 0x7fffffffll + 1 + (v & 0xff);
    } else {
        a.num_verts = next(&r) % 40;
    }
    uint64_t nf = next(&r) % 40;
    int32_t *counts = alloc(nf * sizeof(int32_t));
    for (uint64_t i = 0; i < nf; i++) counts[i] = (int8_t)next(&r);
    uint64_t ni = next(&r) % 200;
    int32_t *indices = alloc(ni * sizeof(int32_t));
    for (uint64_t i = 0; i < ni; i++) indices[i] = (int8_t)next(&r);
    uint64_t rows = 0;
    if ((flags & 1) && a.num_verts >= 0 && a.num_verts < 40)
        rows = (uint64_t)a.num_verts + ((flags & 4) ? 1 : 0);
    double *positions = alloc(rows * 3 * sizeof(double));
    for (uint64_t i = 0; i < rows * 3; i++) positions[i] = (double)(int8_t)next(&r) / 4.0;
    a.positions = rows ? positions : NULL;
    a.positions_rows = rows;
    a.counts = counts;
    a.num_counts = nf;
    a.indices = indices;
    a.num_indices = ni;

    mt_face_list list;
    mt_diag diag;
    mt_status st = mt_archive_decode_faces(&a, "fuzz", &list, &diag);
    if (st == MT_OK) {
        if (list.num_faces != nf || list.num_indices != ni ||
            list.num_verts != (uint32_t)a.num_verts || mt_face_list_check(&list, NULL) != MT_OK)
            abort();
        mt_mesh *mesh = NULL;
        if (mt_mesh_build(&list, NULL, &mesh, &diag) != MT_OK) abort();
        if (mt_mesh_validate(mesh, &diag) != MT_OK) abort();
        uint8_t *kept = alloc(list.num_faces);
        mt_archive_vtk_arrays v;
        make_vtk(&list, mesh, &v, kept);
        if (mt_archive_check_vtk(&v, &list, kept, "fuzz", &diag) != MT_OK) abort();
        if (flags & 8) {
            bool changed = false;
            while (r.pos < r.size) {
                uint8_t which = next(&r), where = next(&r), value = next(&r);
                changed |= corrupt(&v, which, where, value);
            }
            if (mt_archive_check_vtk(&v, &list, kept, "fuzz", &diag) == MT_OK && changed) {
                /* Possible only when corruptions cancelled out; recheck from scratch. */
                mt_archive_vtk_arrays fresh;
                make_vtk(&list, mesh, &fresh, kept);
                bool same = fresh.number_of_points == v.number_of_points &&
                            fresh.number_of_cells == v.number_of_cells &&
                            fresh.number_of_connectivity_ids == v.number_of_connectivity_ids &&
                            fresh.num_offsets == v.num_offsets &&
                            fresh.num_connectivity == v.num_connectivity &&
                            memcmp(fresh.connectivity, v.connectivity,
                                   (size_t)v.num_connectivity * sizeof(int64_t)) == 0 &&
                            memcmp(fresh.offsets, v.offsets,
                                   (size_t)v.num_offsets * sizeof(int64_t)) == 0 &&
                            memcmp(fresh.types, v.types, (size_t)v.num_types) == 0 &&
                            memcmp(fresh.face_ids, v.face_ids,
                                   (size_t)v.num_face_ids * sizeof(int64_t)) == 0;
                free_vtk(&fresh);
                if (!same) abort();
            }
        }
        free_vtk(&v);
        free(kept);
        mt_mesh_destroy(mesh);
        mt_face_list_free(&list);
    } else if (st != MT_ERR_PARSE && st != MT_ERR_TOO_LARGE) {
        abort();
    }
    free(counts);
    free(indices);
    free(positions);
    return 0;
}
