/* Build phase "faces": one pass over the face records, split by face range
 * across the parts. Classifies each record (valid, out-of-range index,
 * degenerate: fewer than 3 entries or a vertex repeated anywhere in it, as
 * tests/corpus/DEFINITIONS.md counts them), records the defects and the
 * size histogram, and counts per part the corners leaving each vertex (for
 * the fans) and the sides filed in each block (for the matching in
 * build_edges.c). Positions are copied and checked to be finite, split by
 * vertex range. Rejected records get face_he = MT_NONE. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "build/build_phases.h"

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

/* Distinct values among n indices (n small: pairwise; large: sorted copy). */
static mt_status count_distinct(mt__part *p, const uint32_t *idx, uint32_t n, uint32_t *out)
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
    p->scratch.len = 0;
    for (uint32_t i = 0; i < n; i++)
        if (mt__vec_push(&p->scratch, &idx[i]) != MT_OK) return MT_ERR_NOMEM;
    uint32_t *s = p->scratch.data;
    qsort(s, n, sizeof *s, compare_u32);
    uint32_t distinct = 1;
    for (uint32_t i = 1; i < n; i++) distinct += (s[i] != s[i - 1]);
    *out = distinct;
    return MT_OK;
}

static mt_status reject_face(mt__part *p, uint32_t nv, uint32_t f, const uint32_t *idx, uint32_t n)
{
    uint32_t bad_pos = MT_NONE, bad_count = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (idx[i] >= nv) {
            if (bad_pos == MT_NONE) bad_pos = i;
            bad_count++;
        } else if (mt__vec_push(&p->invalid_refs, &idx[i]) != MT_OK) {
            return MT_ERR_NOMEM;
        }
    }
    if (bad_count) {
        p->out_of_range_entries += bad_count;
        p->out_of_range_faces++;
        if (mt__push_defect(&p->defects, MT_DEFECT_OUT_OF_RANGE_INDEX, f, idx[bad_pos], bad_pos) !=
            MT_OK)
            return MT_ERR_NOMEM;
    }
    uint32_t distinct = 0;
    if (count_distinct(p, idx, n, &distinct) != MT_OK) return MT_ERR_NOMEM;
    if (n < 3 || distinct < n) {
        p->degenerate_faces++;
        if (mt__push_defect(&p->defects, MT_DEFECT_DEGENERATE_FACE, f, distinct, n) != MT_OK)
            return MT_ERR_NOMEM;
    }
    return MT_OK;
}

/* 1 when the face's indices are all in range and distinct, -1 on no memory. */
static int face_is_valid(mt__part *p, const uint32_t *idx, uint32_t n, uint32_t nv)
{
    if (n < 3) return 0;
    for (uint32_t i = 0; i < n; i++)
        if (idx[i] >= nv) return 0;
    if (n == 3) return idx[0] != idx[1] && idx[1] != idx[2] && idx[0] != idx[2];
    uint32_t distinct = 0;
    if (count_distinct(p, idx, n, &distinct) != MT_OK) return -1;
    return distinct == n;
}

/* 1 when a double is NaN or infinite: all exponent bits set. */
static inline uint64_t nonfinite_bits(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return (bits >> 52 & 0x7ff) == 0x7ff;
}

static mt_status copy_positions(mt__build *b, mt__part *p)
{
    const mt_face_list *in = b->in;
    if (!in->positions) return MT_OK;
    const size_t first = 3 * (size_t)p->vert_begin, end = 3 * (size_t)p->vert_end;
    const double *src = in->positions;
    double *dst = b->m->positions;
    /* Copy (unless the mesh took the caller's array) and test in one pass;
     * name the bad vertices only if there are any. */
    uint64_t any_bad = 0;
    if (b->positions_taken) {
        for (size_t i = first; i < end; i++) any_bad |= nonfinite_bits(src[i]);
    } else {
        for (size_t i = first; i < end; i++) {
            dst[i] = src[i];
            any_bad |= nonfinite_bits(src[i]);
        }
    }
    if (!any_bad) return MT_OK;
    for (uint32_t v = p->vert_begin; v < p->vert_end; v++) {
        const double *pos = &src[3 * (size_t)v];
        for (uint32_t axis = 0; axis < 3; axis++) {
            if (isfinite(pos[axis])) continue;
            p->nonfinite_vertices++;
            if (mt__push_defect(&p->defects, MT_DEFECT_NONFINITE_COORD, v, axis, 0) != MT_OK)
                return MT_ERR_NOMEM;
            break;
        }
    }
    return MT_OK;
}

static mt_status classify_faces(mt__build *b, mt__part *p)
{
    const mt_face_list *in = b->in;
    const uint32_t nv = in->num_verts;
    uint32_t *face_he = b->m->face_he, *degree = p->degree, *block_sides = p->block_sides;
    uint32_t offset = p->index_begin;
    for (uint32_t f = p->face_begin; f < p->face_end; f++) {
        const uint32_t n = in->face_sizes[f];
        const uint32_t *idx = n ? in->face_indices + offset : NULL; /* NULL when no indices */
        offset += n;
        if (n < MT__SMALL_SIZES)
            p->size_hist[n]++;
        else if (mt__vec_push(&p->large_sizes, &n) != MT_OK)
            return MT_ERR_NOMEM;
        int valid = face_is_valid(p, idx, n, nv);
        if (valid < 0) return MT_ERR_NOMEM;
        if (!valid) {
            face_he[f] = MT_NONE;
            if (reject_face(p, nv, f, idx, n) != MT_OK) return MT_ERR_NOMEM;
            continue;
        }
        p->num_corners += n;
        face_he[f] = 0;
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t tail = idx[i], head = idx[i + 1 < n ? i + 1 : 0];
            if (offset - n + i + MT__PREFETCH_DISTANCE < in->num_indices) {
                const uint32_t ahead = in->face_indices[offset - n + i + MT__PREFETCH_DISTANCE];
                __builtin_prefetch(&degree[ahead < nv ? ahead : 0], 1);
            }
            degree[tail]++;
            block_sides[mt__block_of(b, tail < head ? tail : head)]++;
        }
    }
    return MT_OK;
}

static void faces_part(mt__build *b, uint32_t t)
{
    mt__part *p = &b->part[t];
    p->status = classify_faces(b, p);
    if (p->status == MT_OK) p->status = copy_positions(b, p);
}

/* Folds the parts' counts and lists into the build. */
static mt_status merge_parts(mt__build *b)
{
    for (uint32_t t = 0; t < b->parts; t++) {
        mt__part *p = &b->part[t];
        if (p->status != MT_OK) return p->status;
        b->num_corners += p->num_corners;
        for (uint32_t k = 0; k < MT__SMALL_SIZES; k++) b->size_hist[k] += p->size_hist[k];
        b->out_of_range_entries += p->out_of_range_entries;
        b->out_of_range_faces += p->out_of_range_faces;
        b->degenerate_faces += p->degenerate_faces;
        b->nonfinite_vertices += p->nonfinite_vertices;
        if (mt__vec_append(&b->large_sizes, &p->large_sizes) != MT_OK ||
            mt__vec_append(&b->invalid_refs, &p->invalid_refs) != MT_OK ||
            mt__vec_append(&b->defects, &p->defects) != MT_OK)
            return MT_ERR_NOMEM;
        mt__vec_free(&p->scratch);
    }
    if (b->num_corners > MT__MAX_CORNERS)
        return mt__fail(b->diag, MT_ERR_TOO_LARGE, MT_NONE,
                        "build: %llu sides of valid faces; at most %u are supported",
                        (unsigned long long)b->num_corners, MT__MAX_CORNERS);
    return MT_OK;
}

mt_status mt__build_faces(mt__build *b)
{
    mt__parallel_run(b, faces_part);
    return merge_parts(b);
}
