/* Edge and duplicate-face counts of an operation. The touched edges are the
 * sides of the valid faces going and coming, the touched cycles their
 * vertex cycles. Their counts before the change are read by walking the
 * face list of each edge's smaller vertex (and of each cycle's smallest)
 * once (map_link.c drives the walk); after = before + the change. Each
 * edge then moves between the count classes of DEFINITIONS.md. */
#include <assert.h>
#include <string.h>

#include "map/map_internal.h"

static uint64_t edge_key(uint32_t a, uint32_t b)
{
    return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
}

/* ---- vertex cycles: start at the smallest vertex, go towards the smaller
 * of its two neighbours, so both directions of a cycle read the same. ---- */

typedef struct cycle {
    const uint32_t *c;
    uint32_t n, hash;
} cycle;

static void cycle_start(const uint32_t *c, uint32_t n, uint32_t *out_start, uint32_t *out_step)
{
    uint32_t m = 0;
    for (uint32_t i = 1; i < n; i++)
        if (c[i] < c[m]) m = i;
    *out_start = m;
    *out_step = c[(m + 1) % n] < c[(m + n - 1) % n] ? 1 : n - 1;
}

static uint32_t cycle_hash(const uint32_t *c, uint32_t n)
{
    uint32_t at, step;
    cycle_start(c, n, &at, &step);
    uint64_t h = n;
    for (uint32_t i = 0; i < n; i++, at = (at + step) % n) h = mt__mix64(h ^ c[at]);
    return (uint32_t)h;
}

static bool cycle_equal(const cycle *a, const cycle *b)
{
    if (a->n != b->n || a->hash != b->hash) return false;
    uint32_t ia, sa, ib, sb;
    cycle_start(a->c, a->n, &ia, &sa);
    cycle_start(b->c, b->n, &ib, &sb);
    for (uint32_t i = 0; i < a->n; i++, ia = (ia + sa) % a->n, ib = (ib + sb) % b->n)
        if (a->c[ia] != b->c[ib]) return false;
    return true;
}

static uint32_t tc_hash_fn(const void *plan, uint32_t k)
{
    return ((const mt__map_plan *)plan)->tc_hash[k];
}

static bool tc_eq_fn(const void *plan, uint32_t k, const void *key)
{
    const mt__map_plan *p = plan;
    cycle a = {p->tc_corners[k], p->tc_size[k], p->tc_hash[k]};
    return cycle_equal(&a, key);
}

/* Counts one valid face (corners c[0..n)) of a version into the touched
 * edges and cycles with sign. */
static void add_face(mt__map_plan *p, const uint32_t *c, uint32_t n, int32_t sign)
{
    for (uint32_t j = 0; j < n; j++) {
        const uint32_t a = c[j], b = c[j + 1 < n ? j + 1 : 0];
        bool added;
        const uint32_t k = mt__keymap_put(&p->te, edge_key(a, b), &added);
        if (added) p->te_dfwd[k] = p->te_dbwd[k] = 0, p->te_fwd[k] = p->te_bwd[k] = 0;
        if (a < b)
            p->te_dfwd[k] += sign;
        else
            p->te_dbwd[k] += sign;
    }
    cycle probe = {c, n, cycle_hash(c, n)};
    uint32_t k = mt__table_find(&p->tc, probe.hash, tc_eq_fn, p, &probe);
    if (k == MT_NONE) {
        k = p->num_tc++;
        p->tc_corners[k] = c;
        p->tc_size[k] = n;
        p->tc_hash[k] = probe.hash;
        p->tc_delta[k] = 0;
        p->tc_old[k] = 0;
        mt__table_insert(&p->tc, probe.hash, k);
    }
    p->tc_delta[k] += sign;
}

mt_status mt__plan_edges(mt__map_plan *p)
{
    const mt_map *map = p->map;
    const mt__map_block *old = p->old, *b = p->block;
    const uint32_t sides = (old ? old->num_indices : 0) + (b ? b->num_indices : 0);
    const uint32_t faces = (old ? old->valid_faces : 0) + (b ? b->valid_faces : 0);
    const size_t ns = sides ? sides : 1, nf = faces ? faces : 1;
    if (mt__keymap_init(&p->te, sides) != MT_OK) return MT_ERR_NOMEM;
    p->te_dfwd = mt__malloc(ns * sizeof(int32_t));
    p->te_dbwd = mt__malloc(ns * sizeof(int32_t));
    p->te_fwd = mt__malloc(ns * sizeof(uint32_t));
    p->te_bwd = mt__malloc(ns * sizeof(uint32_t));
    p->tc_corners = mt__malloc(nf * sizeof(const uint32_t *));
    p->tc_size = mt__malloc(nf * sizeof(uint32_t));
    p->tc_hash = mt__malloc(nf * sizeof(uint32_t));
    p->tc_delta = mt__malloc(nf * sizeof(int32_t));
    p->tc_old = mt__malloc(nf * sizeof(uint32_t));
    if (!p->te_dfwd || !p->te_dbwd || !p->te_fwd || !p->te_bwd || !p->tc_corners || !p->tc_size ||
        !p->tc_hash || !p->tc_delta || !p->tc_old)
        return MT_ERR_NOMEM;
    if (mt__table_reserve(&p->tc, faces, tc_hash_fn, p) != MT_OK) return MT_ERR_NOMEM;
    if (old) {
        for (uint32_t i = 0; i < old->num_faces; i++) {
            if (!(map->face_local[old->face_ids[i]] & MT__MAP_VALID)) continue;
            add_face(p, old->corners + mt__blk_begin(old, i), mt__blk_size(old, i), -1);
        }
    }
    if (b) {
        for (uint32_t i = 0; i < b->num_faces; i++)
            if (p->b_valid[i]) add_face(p, b->corners + mt__blk_begin(b, i), mt__blk_size(b, i), 1);
    }
    return MT_OK;
}

void mt__plan_edges_walk_face(mt__map_plan *p, uint32_t a, const uint32_t *c, uint32_t n,
                              uint32_t at)
{
    const uint32_t next = c[at + 1 < n ? at + 1 : 0], prev = c[at ? at - 1 : n - 1];
    if (a < next) {
        const uint32_t k = mt__keymap_get(&p->te, (uint64_t)a << 32 | next);
        if (k != MT_NONE) p->te_fwd[k]++;
    }
    if (a < prev) {
        const uint32_t k = mt__keymap_get(&p->te, (uint64_t)a << 32 | prev);
        if (k != MT_NONE) p->te_bwd[k]++;
    }
    if (p->num_tc == 0) return;
    for (uint32_t i = 0; i < n; i++)
        if (c[i] < a) return;
    cycle probe = {c, n, cycle_hash(c, n)};
    const uint32_t k = mt__table_find(&p->tc, probe.hash, tc_eq_fn, p, &probe);
    if (k != MT_NONE) p->tc_old[k]++;
}

/* Adds (sign +1) or takes away (-1) what one edge with fwd and bwd uses
 * contributes to the counts. */
static mt_status edge_counts(mt__map_plan *p, int64_t fwd, int64_t bwd, int64_t sign)
{
    const int64_t use = fwd + bwd;
    if (use == 0) return MT_OK;
    int64_t *n = p->change.n;
    n[MT__T_EDGES] += sign;
    n[MT__T_BOUNDARY] += sign * (use == 1);
    n[MT__T_NM_EDGES] += sign * (use > 2);
    n[MT__T_INCONSISTENT] += sign * (use == 2 && (fwd == 2 || bwd == 2));
    n[MT__T_DUP_DIRECTED] += sign * (fwd >= 2 || bwd >= 2);
    return mt__hist_note(&p->use_changes, p->use_small, (uint32_t)use, sign);
}

mt_status mt__plan_edges_finish(mt__map_plan *p)
{
    for (uint32_t k = 0; k < p->te.count; k++) {
        const int64_t f0 = p->te_fwd[k], b0 = p->te_bwd[k];
        const int64_t f1 = f0 + p->te_dfwd[k], b1 = b0 + p->te_dbwd[k];
        assert(f1 >= 0 && b1 >= 0);
        if (f0 == f1 && b0 == b1) continue;
        if (edge_counts(p, f0, b0, -1) != MT_OK || edge_counts(p, f1, b1, 1) != MT_OK)
            return MT_ERR_NOMEM;
    }
    for (uint32_t k = 0; k < p->num_tc; k++) {
        const int64_t before = p->tc_old[k], after = before + p->tc_delta[k];
        assert(after >= 0);
        p->change.n[MT__T_CLASSES] += (after > 0) - (before > 0);
    }
    return MT_OK;
}
