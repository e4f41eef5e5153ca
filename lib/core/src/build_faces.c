/* Build phase "faces": one pass over the face records. Classifies each record
 * (valid, out-of-range index, fewer than 3 distinct vertices), records the
 * defects, the size histogram and the corners leaving each vertex (the counts
 * of the counting sort in build_edges.c), and copies the positions while
 * checking they are finite. Rejected records get face_he = MT_NONE. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "build_internal.h"

mt_status mt__add_defect(mt__build *b, mt_defect_kind kind, uint32_t x, uint32_t y, uint32_t z)
{
    mt_defect d = {(uint32_t)kind, x, y, z};
    return mt__vec_push(&b->defects, &d);
}

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

/* Distinct values among n indices (n small: pairwise; large: sorted copy). */
static mt_status count_distinct(mt__build *b, const uint32_t *idx, uint32_t n, uint32_t *out)
{
    if (n <= 8) {
        uint32_t distinct = 0;
        for (uint32_t i = 0; i < n; i++) {
            uint32_t j = 0;
            while (j < i && idx[j] != idx[i]) j++;
            distinct += (j == i);
        }
        *out = distinct;
        return MT_OK;
    }
    b->scratch.len = 0;
    for (uint32_t i = 0; i < n; i++)
        if (mt__vec_push(&b->scratch, &idx[i]) != MT_OK) return MT_ERR_NOMEM;
    uint32_t *s = b->scratch.data;
    qsort(s, n, sizeof *s, compare_u32);
    uint32_t distinct = 1;
    for (uint32_t i = 1; i < n; i++) distinct += (s[i] != s[i - 1]);
    *out = distinct;
    return MT_OK;
}

static mt_status reject_face(mt__build *b, uint32_t f, const uint32_t *idx, uint32_t n)
{
    const uint32_t nv = b->m->num_verts;
    uint32_t bad_pos = MT_NONE, bad_count = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (idx[i] >= nv) {
            if (bad_pos == MT_NONE) bad_pos = i;
            bad_count++;
        } else if (mt__vec_push(&b->invalid_refs, &idx[i]) != MT_OK) {
            return MT_ERR_NOMEM;
        }
    }
    if (bad_count) {
        b->out_of_range_entries += bad_count;
        b->out_of_range_faces++;
        if (mt__add_defect(b, MT_DEFECT_OUT_OF_RANGE_INDEX, f, idx[bad_pos], bad_pos) != MT_OK)
            return MT_ERR_NOMEM;
    }
    uint32_t distinct = n;
    if (n >= 3 && count_distinct(b, idx, n, &distinct) != MT_OK) return MT_ERR_NOMEM;
    if (n < 3 || distinct < n) {
        b->degenerate_faces++;
        if (mt__add_defect(b, MT_DEFECT_DEGENERATE_FACE, f, distinct, n) != MT_OK)
            return MT_ERR_NOMEM;
    }
    b->m->face_he[f] = MT_NONE;
    return MT_OK;
}

/* 1 when the face's indices are all in range and distinct. */
static int face_is_valid(const uint32_t *idx, uint32_t n, uint32_t nv, mt__build *b)
{
    if (n < 3) return 0;
    for (uint32_t i = 0; i < n; i++)
        if (idx[i] >= nv) return 0;
    if (n == 3) return idx[0] != idx[1] && idx[1] != idx[2] && idx[0] != idx[2];
    uint32_t distinct = 0;
    if (count_distinct(b, idx, n, &distinct) != MT_OK) return -1;
    return distinct == n;
}

static mt_status copy_positions(mt__build *b)
{
    const mt_face_list *in = b->in;
    mt_mesh *m = b->m;
    if (!in->positions) return MT_OK;
    memcpy(m->positions, in->positions, (size_t)in->num_verts * 3 * sizeof(double));
    for (uint32_t v = 0; v < in->num_verts; v++) {
        const double *p = &in->positions[3 * (size_t)v];
        for (uint32_t axis = 0; axis < 3; axis++) {
            if (isfinite(p[axis])) continue;
            b->nonfinite_vertices++;
            if (mt__add_defect(b, MT_DEFECT_NONFINITE_COORD, v, axis, 0) != MT_OK)
                return MT_ERR_NOMEM;
            break;
        }
    }
    return MT_OK;
}

mt_status mt__build_faces(mt__build *b)
{
    const mt_face_list *in = b->in;
    mt_mesh *m = b->m;
    const uint32_t nv = in->num_verts;
    uint32_t *degree = b->bucket_start; /* counts now, starts after the prefix sum */
    uint64_t offset = 0;
    for (uint32_t f = 0; f < in->num_faces; f++) {
        const uint32_t n = in->face_sizes[f];
        const uint32_t *idx = in->face_indices + offset;
        offset += n;
        if (n < MT__SMALL_SIZES)
            b->size_hist[n]++;
        else if (mt__vec_push(&b->large_sizes, &n) != MT_OK)
            return MT_ERR_NOMEM;
        int valid = face_is_valid(idx, n, nv, b);
        if (valid < 0) return MT_ERR_NOMEM;
        if (!valid) {
            if (reject_face(b, f, idx, n) != MT_OK) return MT_ERR_NOMEM;
            continue;
        }
        if (b->num_corners + n > MT__MAX_CORNERS)
            return mt__fail(b->diag, MT_ERR_TOO_LARGE, f,
                            "face %u: more than %u face sides in total", f, MT__MAX_CORNERS);
        b->num_corners += n;
        m->face_he[f] = 0;
        for (uint32_t i = 0; i < n; i++) degree[idx[i]]++;
    }
    return copy_positions(b);
}
