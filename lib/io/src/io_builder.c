/* The face list a reader fills: three arrays that grow geometrically (so n
 * appends cost O(log n) reallocations, never one allocation per element)
 * and are trimmed and handed over as an mt_face_list at the end, or that
 * get their room at once when a header's counts fit the input. A reader
 * may have the growth past MT__IO_BLIND_BYTES confirmed first (confirm). */
#include <stdlib.h>

#include "io_internal.h"

/* The capacity that holds at least n elements: doubling from cap (at
 * least 1024), or exactly n when the doubling would overflow. 0 when n
 * elements of `elem` bytes cannot be addressed. */
static size_t grown(size_t cap, size_t n, size_t elem)
{
    size_t max = SIZE_MAX / elem;
    if (n > max) return 0;
    size_t want = cap < 1024 ? 1024 : cap;
    while (want < n) want = want > max / 2 ? max : want * 2;
    return want;
}

/* Before the arrays grow to `bytes` in all: asks confirm once when that
 * passes MT__IO_BLIND_BYTES. Returns 0 when it refused. */
static int may_grow(mt__builder *b, uint64_t bytes)
{
    if (b->refused != MT_OK) return 0;
    if (!b->confirm || b->confirmed || bytes <= MT__IO_BLIND_BYTES) return 1;
    b->confirmed = 1;
    b->refused = b->confirm(b->confirm_ctx, &b->refusal);
    return b->refused == MT_OK;
}

/* Bytes of the arrays with these capacities. */
static uint64_t bytes_of(size_t verts, size_t faces, size_t indices)
{
    return 3 * sizeof(double) * (uint64_t)verts + sizeof(uint32_t) * ((uint64_t)faces + indices);
}

/* Grows *data (elem bytes each, capacity *cap) to `want` elements, or to
 * exactly n when that much memory is not there. */
static int grow(void **data, size_t *cap, size_t want, size_t n, size_t elem)
{
    void *p = realloc(*data, want * elem);
    if (!p) {
        /* the doubling may be too greedy for the memory left: try exactly n */
        if (want == n) return 0;
        p = realloc(*data, n * elem);
        if (!p) return 0;
        want = n;
    }
    *data = p;
    *cap = want;
    return 1;
}

int mt__builder_reserve_verts(mt__builder *b, size_t n)
{
    if (n <= b->cap_verts) return 1;
    size_t want = n > SIZE_MAX / 3 ? 0 : grown(b->cap_verts, n, 3 * sizeof(double));
    if (!want || !may_grow(b, bytes_of(want, b->cap_faces, b->cap_indices))) return 0;
    void *data = b->positions;
    if (!grow(&data, &b->cap_verts, want, n, 3 * sizeof(double))) return 0;
    b->positions = data;
    return 1;
}

int mt__builder_reserve_faces(mt__builder *b, size_t n)
{
    if (n <= b->cap_faces) return 1;
    size_t want = grown(b->cap_faces, n, sizeof(uint32_t));
    if (!want || !may_grow(b, bytes_of(b->cap_verts, want, b->cap_indices))) return 0;
    void *data = b->sizes;
    if (!grow(&data, &b->cap_faces, want, n, sizeof(uint32_t))) return 0;
    b->sizes = data;
    return 1;
}

int mt__builder_reserve_indices(mt__builder *b, size_t n)
{
    if (n <= b->cap_indices) return 1;
    size_t want = grown(b->cap_indices, n, sizeof(uint32_t));
    if (!want || !may_grow(b, bytes_of(b->cap_verts, b->cap_faces, want))) return 0;
    void *data = b->indices;
    if (!grow(&data, &b->cap_indices, want, n, sizeof(uint32_t))) return 0;
    b->indices = data;
    return 1;
}

void mt__builder_reserve_declared(mt__builder *b, uint64_t verts, uint64_t faces, uint64_t indices)
{
    if (verts > SIZE_MAX || faces > SIZE_MAX || indices > SIZE_MAX) return;
    if (mt__builder_reserve_verts(b, (size_t)verts) && mt__builder_reserve_faces(b, (size_t)faces))
        mt__builder_reserve_indices(b, (size_t)indices);
}

mt_status mt__builder_fail(const mt__builder *b, const mt__io_src *src, mt_diag *diag)
{
    if (b->refused == MT_OK) return mt__io_fail_nomem(diag, src);
    if (diag) *diag = b->refusal;
    return b->refused;
}

/* Shrinks an array to exactly n elements (at least one, so that pointers
 * are never NULL); keeps the larger block when realloc refuses. */
static void *trim(void *data, size_t n, size_t elem)
{
    void *p = realloc(data, (n ? n : 1) * elem);
    return p ? p : data;
}

mt_status mt__builder_finish(mt__builder *b, mt_face_list *out, const mt__io_src *src,
                             mt_diag *diag)
{
    memset(out, 0, sizeof *out);
    if (b->num_verts > MT__IO_MAX_VERTS)
        return mt__io_fail(diag, MT_ERR_TOO_LARGE, src, MT__POS_NONE, 0, MT_NONE,
                           "%zu vertices: more than meshtopo's limit of %u", b->num_verts,
                           MT__IO_MAX_VERTS);
    if (b->num_faces > UINT32_MAX)
        return mt__io_fail(diag, MT_ERR_TOO_LARGE, src, MT__POS_NONE, 0, MT_NONE,
                           "%zu faces: more than meshtopo's limit of %u", b->num_faces, UINT32_MAX);
    /* Make sure every array exists (a list of 0 faces still gets pointers). */
    if ((!b->positions && !mt__builder_reserve_verts(b, 1)) ||
        (!b->sizes && !mt__builder_reserve_faces(b, 1)) ||
        (!b->indices && !mt__builder_reserve_indices(b, 1)))
        return mt__io_fail_nomem(diag, src);
    out->num_verts = (uint32_t)b->num_verts;
    out->num_faces = (uint32_t)b->num_faces;
    out->num_indices = b->num_indices;
    out->positions = trim(b->positions, 3 * b->num_verts, sizeof(double));
    out->face_sizes = trim(b->sizes, b->num_faces, sizeof(uint32_t));
    out->face_indices = trim(b->indices, b->num_indices, sizeof(uint32_t));
    memset(b, 0, sizeof *b);
    return MT_OK;
}

void mt__builder_free(mt__builder *b)
{
    free(b->positions);
    free(b->sizes);
    free(b->indices);
    memset(b, 0, sizeof *b);
}

mt_status mt__builder_read(mt__io_src *src, mt__builder_reader read, mt_face_list *out,
                           mt_diag *diag)
{
    mt__builder b;
    memset(&b, 0, sizeof b);
    mt_status status = read(src, &b, diag);
    /* A reader's confirm context lives in its frame, gone by now. */
    b.confirm = NULL;
    b.confirm_ctx = NULL;
    if (status == MT_OK) status = mt__builder_finish(&b, out, src, diag);
    mt__builder_free(&b);
    return status;
}
