/* A block's face records in the map: corners as welded map vertex ids,
 * out-of-range entries encoded as MT_NONE - r (r-th distinct bad value of
 * the face), and the record classified exactly as build_faces.c does after
 * welding: degenerate (fewer than 3 entries or a value repeated), out of
 * range, or valid. Only a vertex's first corner in a face joins its face
 * list. Also the face-level count changes of an operation. */
#include <stdlib.h>
#include <string.h>

#include "map/map_internal.h"

typedef struct keyed_pos {
    uint64_t key;
    uint32_t pos;
} keyed_pos;

static int compare_keyed(const void *pa, const void *pb)
{
    const keyed_pos *a = pa, *b = pb;
    if (a->key != b->key) return (a->key > b->key) - (a->key < b->key);
    return (a->pos > b->pos) - (a->pos < b->pos);
}

/* The welded value of a block index: its map vertex, or the index tagged
 * as out of range. */
static uint64_t welded_key(const mt__map_block *b, uint32_t x)
{
    return x < b->num_verts ? b->vert_map[x] : (1ull << 32 | x);
}

/* first[j] = the first position holding the same welded value as j. */
static mt_status first_occurrences(const mt__map_block *b, const uint32_t *x, uint32_t n,
                                   uint32_t *first, mt__vec *sorted)
{
    if (n <= 8) {
        for (uint32_t j = 0; j < n; j++) {
            const uint64_t k = welded_key(b, x[j]);
            uint32_t i = 0;
            while (i < j && welded_key(b, x[i]) != k) i++;
            first[j] = i;
        }
        return MT_OK;
    }
    sorted->len = 0;
    for (uint32_t j = 0; j < n; j++) {
        keyed_pos kp = {welded_key(b, x[j]), j};
        if (mt__vec_push(sorted, &kp) != MT_OK) return MT_ERR_NOMEM;
    }
    keyed_pos *s = sorted->data;
    qsort(s, n, sizeof *s, compare_keyed);
    for (uint32_t i = 0; i < n; i++)
        first[s[i].pos] = (i > 0 && s[i - 1].key == s[i].key) ? first[s[i - 1].pos] : s[i].pos;
    return MT_OK;
}

/* Fills the corners of face i (entries x[0..n) at corner c0); returns
 * whether the face is valid. */
static void encode_face(mt__map_block *b, const uint32_t *x, uint32_t n, uint32_t c0,
                        const uint32_t *first, uint32_t *rank, bool *out_valid)
{
    uint32_t distinct = 0, oor = 0, r = 0;
    for (uint32_t j = 0; j < n; j++) {
        const bool own = first[j] == j;
        distinct += own;
        if (x[j] < b->num_verts) {
            b->corners[c0 + j] = b->vert_map[x[j]];
            b->corner_next[c0 + j] = own ? 0 : MT__MAP_UNLINKED;
        } else {
            oor++;
            if (own) rank[j] = r++;
            b->corners[c0 + j] = MT_NONE - rank[first[j]];
            b->corner_next[c0 + j] = MT__MAP_UNLINKED;
        }
    }
    const bool degenerate = n < 3 || distinct < n;
    b->degenerate_faces += degenerate;
    b->oor_indices += oor;
    b->oor_faces += oor > 0;
    *out_valid = !degenerate && oor == 0;
    b->valid_faces += *out_valid;
}

static mt_status push_size(mt__map_plan *p, uint32_t size, int64_t change)
{
    return mt__hist_note(&p->size_changes, p->size_small, size, change);
}

/* The new block's faces. */
static mt_status encode_block(mt__map_plan *p)
{
    mt__map_block *b = p->block;
    const mt_face_list *in = p->input;
    mt__vec scratch = {NULL, 0, 0, sizeof(uint32_t)}, sorted = {NULL, 0, 0, sizeof(keyed_pos)};
    mt_status s = MT_OK;
    uint32_t offset = 0;
    p->b_valid = mt__malloc(b->num_faces ? b->num_faces : 1);
    if (!p->b_valid) return MT_ERR_NOMEM;
    for (uint32_t i = 0; i < b->num_faces && s == MT_OK; i++) {
        const uint32_t n = in->face_sizes[i];
        if (b->face_first) b->face_first[i] = offset;
        uint32_t small[16], *first = small;
        if (n > 8) {
            scratch.len = 0;
            const uint32_t zero = 0;
            for (uint32_t j = 0; j < 2 * n && s == MT_OK; j++) s = mt__vec_push(&scratch, &zero);
            if (s != MT_OK) break;
            first = scratch.data;
        }
        uint32_t *rank = first + n;
        s = first_occurrences(b, in->face_indices + offset, n, first, &sorted);
        if (s != MT_OK) break;
        bool valid;
        encode_face(b, in->face_indices + offset, n, offset, first, rank, &valid);
        p->b_valid[i] = valid;
        b->face_ids[i] = p->map->face_end + i;
        s = push_size(p, n, 1);
        offset += n;
    }
    if (b->face_first) b->face_first[b->num_faces] = offset;
    mt__vec_free(&scratch);
    mt__vec_free(&sorted);
    return s;
}

/* CSR of the new block's faces at each touched vertex (linked corners). */
static mt_status faces_by_vertex(mt__map_plan *p)
{
    const mt__map_block *b = p->block;
    const uint32_t nt = p->num_tv;
    p->tv_bfirst = mt__calloc((size_t)nt + 1, sizeof(uint32_t));
    p->tv_bface = mt__malloc((size_t)(b->num_indices ? b->num_indices : 1) * sizeof(uint32_t));
    if (!p->tv_bfirst || !p->tv_bface) return MT_ERR_NOMEM;
    for (uint32_t c = 0; c < b->num_indices; c++)
        if (b->corner_next[c] != MT__MAP_UNLINKED)
            p->tv_bfirst[mt__keymap_get(&p->tv, b->corners[c]) + 1]++;
    for (uint32_t t = 0; t < nt; t++) p->tv_bfirst[t + 1] += p->tv_bfirst[t];
    for (uint32_t i = 0; i < b->num_faces; i++) {
        const uint32_t c0 = mt__blk_begin(b, i), n = mt__blk_size(b, i);
        for (uint32_t c = c0; c < c0 + n; c++) {
            if (b->corner_next[c] == MT__MAP_UNLINKED) continue;
            const uint32_t t = mt__keymap_get(&p->tv, b->corners[c]);
            /* tv_bfirst[t] is moved forward while filling, then restored. */
            p->tv_bface[p->tv_bfirst[t]++] = i;
        }
    }
    for (uint32_t t = nt; t > 0; t--) p->tv_bfirst[t] = p->tv_bfirst[t - 1];
    p->tv_bfirst[0] = 0;
    return MT_OK;
}

static void add_block_tally(mt__tally *t, const mt__map_block *b, int64_t sign)
{
    t->n[MT__T_FACES] += sign * b->num_faces;
    t->n[MT__T_FACES_VALID] += sign * b->valid_faces;
    t->n[MT__T_HALF_EDGES] += sign * (int64_t)b->num_indices;
    t->n[MT__T_DEGENERATE] += sign * b->degenerate_faces;
    t->n[MT__T_OOR_INDICES] += sign * (int64_t)b->oor_indices;
    t->n[MT__T_OOR_FACES] += sign * b->oor_faces;
}

mt_status mt__plan_faces(mt__map_plan *p)
{
    const mt__map_block *old = p->old;
    if (old) {
        for (uint32_t i = 0; i < old->num_faces; i++)
            if (push_size(p, mt__blk_size(old, i), -1) != MT_OK) return MT_ERR_NOMEM;
        add_block_tally(&p->change, old, -1);
    }
    if (!p->block) return MT_OK;
    if ((uint64_t)p->map->face_end + p->block->num_faces > MT_MAP_MAX_FACE_ID)
        return mt__fail(p->diag, MT_ERR_TOO_LARGE, MT_NONE,
                        MT__KEY_FMT ": the map has used all %u face ids; compact it",
                        MT__KEY_ARGS(p->key), MT_MAP_MAX_FACE_ID);
    mt_status s = encode_block(p);
    if (s == MT_OK) s = faces_by_vertex(p);
    if (s != MT_OK) return s;
    add_block_tally(&p->change, p->block, 1);
    return MT_OK;
}
