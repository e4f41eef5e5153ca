/* Decoding of the arrays read from an archive file, kept apart from the
 * HDF5 calls so a fuzz target can drive it with arbitrary arrays: the face
 * list datasets become a face list only when their sizes agree, and the
 * VTKHDF datasets are checked cell by cell against the face list. Nothing
 * here reads past a length it was given, whatever the values. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"

#define WHAT(w) ((w) ? (w) : "archive")

mt_status mt_archive_decode_faces(const mt_archive_face_arrays *a, const char *what,
                                  mt_face_list *out, mt_diag *diag)
{
    mt_diag_clear(diag);
    memset(out, 0, sizeof *out);
    if (!a) return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "no arrays to decode");
    if (a->num_verts < 0 || a->num_verts > 0x7fffffff)
        return mt__archive_fail(diag, MT_ERR_PARSE,
                                "%s: attribute num_verts is %lld (must be 0 to 2^31-1)", WHAT(what),
                                (long long)a->num_verts);
    if (a->positions_rows != 0 && a->positions_rows != (uint64_t)a->num_verts)
        return mt__archive_fail(
            diag, MT_ERR_PARSE,
            "%s: dataset /meshtopo/positions has %llu rows but num_verts is %lld", WHAT(what),
            (unsigned long long)a->positions_rows, (long long)a->num_verts);
    if ((a->positions_rows > 0 && !a->positions) || (a->num_counts > 0 && !a->counts) ||
        (a->num_indices > 0 && !a->indices))
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "%s: an array is missing", WHAT(what));
    if (a->num_counts > 0x7fffffff || a->num_indices > 0x7fffffff)
        return mt__archive_fail(
            diag, MT_ERR_TOO_LARGE, "%s: %llu faces and %llu indices exceed the limits (2^31-1)",
            WHAT(what), (unsigned long long)a->num_counts, (unsigned long long)a->num_indices);
    uint64_t sum = 0;
    for (uint64_t f = 0; f < a->num_counts; f++) {
        if (a->counts[f] < 0)
            return mt__archive_fail(
                diag, MT_ERR_PARSE,
                "%s: dataset /meshtopo/face_vertex_counts[%llu] is negative (%d)", WHAT(what),
                (unsigned long long)f, a->counts[f]);
        sum += (uint64_t)a->counts[f]; /* at most 2^31 * 2^31: no overflow */
    }
    if (sum != a->num_indices)
        return mt__archive_fail(diag, MT_ERR_PARSE,
                                "%s: /meshtopo/face_vertex_counts add up to %llu but "
                                "face_vertex_indices has %llu entries",
                                WHAT(what), (unsigned long long)sum,
                                (unsigned long long)a->num_indices);
    /* Positions are allocated for the rows present only: a file without
     * geometry may claim any vertex count without making us allocate for it. */
    mt_face_list list;
    mt_status st = mt_face_list_alloc(&list, (uint32_t)a->positions_rows, (uint32_t)a->num_counts,
                                      a->num_indices, diag);
    if (st != MT_OK) return st;
    list.num_verts = (uint32_t)a->num_verts;
    if (a->positions_rows > 0) {
        memcpy(list.positions, a->positions, (size_t)a->positions_rows * 3 * sizeof(double));
    } else {
        free(list.positions);
        list.positions = NULL;
    }
    for (uint64_t f = 0; f < a->num_counts; f++) list.face_sizes[f] = (uint32_t)a->counts[f];
    /* Indices keep their bits: -1 becomes 0xffffffff, out of range as submitted. */
    if (a->num_indices > 0)
        memcpy(list.face_indices, a->indices, (size_t)a->num_indices * sizeof(uint32_t));
    *out = list;
    return MT_OK;
}

/* VTK cell type of a polygon with n corners. */
static uint8_t cell_type(uint64_t n)
{
    return n == 3 ? 5 : n == 4 ? 9 : 7;
}

mt_status mt_archive_check_vtk(const mt_archive_vtk_arrays *v, const mt_face_list *faces,
                               const uint8_t *face_kept, const char *what, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!v || !faces || (faces->num_faces > 0 && !face_kept))
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_check_vtk: NULL argument");
    const char *w = WHAT(what);
    mt_status st = mt_face_list_check(faces, diag);
    if (st != MT_OK) return st;
    uint64_t cells = 0, ids = 0;
    for (uint32_t f = 0; f < faces->num_faces; f++)
        if (face_kept[f]) {
            cells++;
            ids += faces->face_sizes[f];
        }
    if (v->number_of_points != (int64_t)faces->num_verts || v->points_rows != faces->num_verts)
        return mt__archive_fail(diag, MT_ERR_PARSE,
                                "%s: /VTKHDF NumberOfPoints is %lld and Points has %llu rows, "
                                "expected %u (the vertex count)",
                                w, (long long)v->number_of_points,
                                (unsigned long long)v->points_rows, faces->num_verts);
    if (v->number_of_cells != (int64_t)cells || v->num_types != cells || v->num_face_ids != cells ||
        v->num_offsets != cells + 1)
        return mt__archive_fail(diag, MT_ERR_PARSE,
                                "%s: /VTKHDF has NumberOfCells %lld, %llu Types, %llu Offsets, "
                                "%llu original_face_id; expected %llu cells (the kept faces)",
                                w, (long long)v->number_of_cells, (unsigned long long)v->num_types,
                                (unsigned long long)v->num_offsets,
                                (unsigned long long)v->num_face_ids, (unsigned long long)cells);
    if (v->number_of_connectivity_ids != (int64_t)ids || v->num_connectivity != ids)
        return mt__archive_fail(diag, MT_ERR_PARSE,
                                "%s: /VTKHDF NumberOfConnectivityIds is %lld and Connectivity has "
                                "%llu entries, expected %llu",
                                w, (long long)v->number_of_connectivity_ids,
                                (unsigned long long)v->num_connectivity, (unsigned long long)ids);
    if ((v->points_rows > 0 && !v->points) || (ids > 0 && !v->connectivity) || !v->offsets ||
        (cells > 0 && (!v->types || !v->face_ids)))
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "%s: a VTKHDF array is missing", w);
    for (uint64_t i = 0; i < 3ull * faces->num_verts; i++) {
        double expect = faces->positions ? faces->positions[i] : 0.0;
        if (memcmp(&expect, &v->points[i], sizeof expect) != 0 &&
            !(isnan(expect) && isnan(v->points[i])))
            return mt__archive_fail(diag, MT_ERR_PARSE,
                                    "%s: /VTKHDF/Points row %llu differs from the positions", w,
                                    (unsigned long long)(i / 3));
    }
    if (v->offsets[0] != 0)
        return mt__archive_fail(diag, MT_ERR_PARSE, "%s: /VTKHDF/Offsets[0] is %lld, not 0", w,
                                (long long)v->offsets[0]);
    uint64_t cell = 0, pos = 0, start = 0;
    for (uint32_t f = 0; f < faces->num_faces; start += faces->face_sizes[f], f++) {
        if (!face_kept[f]) continue;
        uint32_t n = faces->face_sizes[f];
        if (v->offsets[cell + 1] != (int64_t)(pos + n))
            return mt__archive_fail(diag, MT_ERR_PARSE,
                                    "%s: /VTKHDF/Offsets[%llu] is %lld, expected %llu", w,
                                    (unsigned long long)(cell + 1), (long long)v->offsets[cell + 1],
                                    (unsigned long long)(pos + n));
        if (v->types[cell] != cell_type(n))
            return mt__archive_fail(diag, MT_ERR_PARSE,
                                    "%s: /VTKHDF/Types[%llu] is %u, expected %u for %u corners", w,
                                    (unsigned long long)cell, v->types[cell], cell_type(n), n);
        if (v->face_ids[cell] != (int64_t)f)
            return mt__archive_fail(diag, MT_ERR_PARSE,
                                    "%s: /VTKHDF/CellData/original_face_id[%llu] is %lld, "
                                    "expected %u",
                                    w, (unsigned long long)cell, (long long)v->face_ids[cell], f);
        for (uint32_t k = 0; k < n; k++)
            if (v->connectivity[pos + k] != (int64_t)faces->face_indices[start + k])
                return mt__archive_fail(diag, MT_ERR_PARSE,
                                        "%s: /VTKHDF/Connectivity[%llu] is %lld, expected %u "
                                        "(face %u)",
                                        w, (unsigned long long)(pos + k),
                                        (long long)v->connectivity[pos + k],
                                        faces->face_indices[start + k], f);
        pos += n;
        cell++;
    }
    return MT_OK;
}
