/* The block map's randomised equivalence test (map.h): long deterministic
 * sequences of puts, replacements with changed blocks (holes, fins that
 * make seams non-manifold, flipped and duplicated faces, bowties,
 * degenerate and out-of-range records, NaN and -0.0 coordinates, isolated
 * vertices), removals, clears and compactions, over generated surfaces and
 * corpus meshes split into blocks with duplicated seams (nvblox) or
 * per-face vertices (voxblox). After every operation the map's counts and
 * histograms must equal those of mt_mesh_build of mt_map_face_list (also
 * validated) and of the union of the blocks welded by mt_face_list_weld,
 * and a sample of rings, face neighbours and edge faces the build's;
 * deltas, id stability and translation are checked along the way. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "map_mutate.h"
#include "map_split.h"
#include "meshtopo/generate.h"
#include "meshtopo/io.h"
#include "meshtopo/map.h"

/* Vertices and faces whose queries are compared after each operation. */
#define QUERY_SAMPLES 12

/* ---- the model: what the map must hold ---------------------------------- */

/* What the runs must have met (counted after each operation). */
enum { SEEN_COUNT = 13 };
static const char *const seen_names[SEEN_COUNT] = {"nonmanifold_edges",
                                                   "bowtie_vertices",
                                                   "nonmanifold_vertices",
                                                   "inconsistent_orientation_edges",
                                                   "duplicate_directed_edges",
                                                   "duplicate_faces",
                                                   "degenerate_faces",
                                                   "faces_with_out_of_range_indices",
                                                   "nonfinite_vertices",
                                                   "isolated_vertices",
                                                   "unreferenced_vertices",
                                                   "boundary_edges",
                                                   "closed"};

typedef struct entry {
    mt_map_key key;
    mt_face_list list;  /* the block as put */
    uint32_t *ids;      /* none mode: its vertex ids */
    uint32_t *face_ids; /* map ids given at the put (renumbered by compactions) */
    uint32_t *vert_ids;
    bool changed; /* a changed version of the mapper's block */
} entry;

typedef struct run {
    const char *name;
    mt_map *map;
    mt_map_weld weld;
    const map_block_set *set;
    entry *e;
    size_t n, cap;
    uint64_t rng;
    uint32_t op;
    uint32_t next_id; /* none mode: ids for vertices a change adds */
    mt_map_counts counts;
    uint32_t seen[SEEN_COUNT]; /* operations after which each kind of defect was there */
    uint32_t max_faces;
    uint32_t clean_states; /* faces, all manifold, oriented, no bad record, nothing isolated */
} run;

static bool same_key(mt_map_key a, mt_map_key b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

static entry *model_find(run *r, mt_map_key key)
{
    for (size_t i = 0; i < r->n; i++)
        if (same_key(r->e[i].key, key)) return &r->e[i];
    return NULL;
}

static void entry_free(entry *e)
{
    mt_face_list_free(&e->list);
    free(e->ids);
    free(e->face_ids);
    free(e->vert_ids);
}

static void model_remove(run *r, entry *e)
{
    entry_free(e);
    *e = r->e[--r->n];
}

static void model_clear(run *r)
{
    for (size_t i = 0; i < r->n; i++) entry_free(&r->e[i]);
    r->n = 0;
}

static entry *model_slot(run *r, mt_map_key key)
{
    entry *e = model_find(r, key);
    if (e) {
        entry_free(e);
    } else {
        if (r->n == r->cap) {
            r->cap = r->cap * 2 + 16;
            r->e = realloc(r->e, r->cap * sizeof *r->e);
            if (!r->e) abort();
        }
        e = &r->e[r->n++];
    }
    memset(e, 0, sizeof *e);
    e->key = key;
    return e;
}

/* ---- checks ---------------------------------------------------------------- */

/* Records a failure naming the run and the operation. */
static void failf(const run *r, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static void failf(const run *r, int line, const char *fmt, ...)
{
    char text[400];
    va_list args;
    va_start(args, fmt);
    vsnprintf(text, sizeof text, fmt, args);
    va_end(args);
    mt_test_fail(__FILE__, line, "%s op %u: %s", r->name, r->op, text);
}

#define FAIL(r, ...) failf((r), __LINE__, __VA_ARGS__)

static bool counts_equal(const mt_map_counts *a, const mt_map_counts *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

/* The union of the model's blocks: welded (exact) or by the sender's ids
 * (none), the reference the map must equal. */
static void reference_list(run *r, mt_face_list *out)
{
    const mt_face_list **lists = malloc((r->n ? r->n : 1) * sizeof *lists);
    if (!lists) abort();
    for (size_t i = 0; i < r->n; i++) lists[i] = &r->e[i].list;
    if (r->weld == MT_MAP_WELD_EXACT) {
        map_union_welded(lists, r->n, out);
        free(lists);
        return;
    }
    /* None mode: the ids in use, densely in id order. */
    uint32_t max = 0;
    for (size_t i = 0; i < r->n; i++)
        for (uint32_t u = 0; u < r->e[i].list.num_verts; u++)
            if (r->e[i].ids[u] + 1 > max) max = r->e[i].ids[u] + 1;
    uint32_t *dense = malloc((size_t)(max ? max : 1) * sizeof *dense);
    uint64_t nf = 0, ni = 0;
    for (uint32_t v = 0; v < max; v++) dense[v] = MT_NONE;
    for (size_t i = 0; i < r->n; i++) {
        for (uint32_t u = 0; u < r->e[i].list.num_verts; u++) dense[r->e[i].ids[u]] = 0;
        nf += r->e[i].list.num_faces;
        ni += r->e[i].list.num_indices;
    }
    uint32_t nv = 0;
    for (uint32_t v = 0; v < max; v++)
        if (dense[v] != MT_NONE) dense[v] = nv++;
    mt_diag d;
    if (mt_face_list_alloc(out, nv, (uint32_t)nf, ni, &d) != MT_OK) abort();
    uint32_t f_out = 0;
    uint64_t at = 0;
    for (size_t i = 0; i < r->n; i++) {
        const mt_face_list *l = &r->e[i].list;
        for (uint32_t u = 0; u < l->num_verts; u++)
            memcpy(&out->positions[3 * (size_t)dense[r->e[i].ids[u]]], &l->positions[3 * (size_t)u],
                   3 * sizeof(double));
        uint64_t in = 0;
        for (uint32_t f = 0; f < l->num_faces; f++) {
            const uint32_t n = l->face_sizes[f];
            uint32_t rank = 0;
            out->face_sizes[f_out++] = n;
            for (uint32_t j = 0; j < n; j++) {
                const uint32_t x = l->face_indices[in + j];
                if (x < l->num_verts) {
                    out->face_indices[at + j] = dense[r->e[i].ids[x]];
                    continue;
                }
                uint32_t k = 0;
                while (k < j && l->face_indices[in + k] != x) k++;
                out->face_indices[at + j] = k < j ? out->face_indices[at + k] : MT_NONE - rank++;
            }
            in += n;
            at += n;
        }
    }
    free(dense);
    free(lists);
}

static void check_equivalence(run *r)
{
    char what[160];
    snprintf(what, sizeof what, "%s op %u (map face list)", r->name, r->op);
    map_check_full(r->map, what);
    snprintf(what, sizeof what, "%s op %u (queries)", r->name, r->op);
    map_check_queries(r->map, what, r->rng + r->op, QUERY_SAMPLES);
    mt_face_list ref;
    reference_list(r, &ref);
    snprintf(what, sizeof what, "%s op %u (welded union)", r->name, r->op);
    map_check_against_list(r->map, &ref, what);
    mt_face_list_free(&ref);
}

/* Ids recorded at each put still translate both ways. */
static void check_ids(run *r)
{
    for (size_t i = 0; i < r->n; i++) {
        const entry *e = &r->e[i];
        for (uint32_t f = 0; f < e->list.num_faces; f++) {
            uint32_t id = MT_NONE, local = MT_NONE;
            mt_map_key key = {0, 0, 0};
            if (mt_map_block_face(r->map, e->key, f, &id) != MT_OK || id != e->face_ids[f] ||
                mt_map_face_origin(r->map, id, &key, &local) != MT_OK || !same_key(key, e->key) ||
                local != f) {
                FAIL(r, "block (%d,%d,%d) face %u: map id %u, recorded %u, origin %u", e->key.x,
                     e->key.y, e->key.z, f, id, e->face_ids[f], local);
                return;
            }
        }
        for (uint32_t u = 0; u < e->list.num_verts; u++) {
            uint32_t v = MT_NONE, local = MT_NONE, back = MT_NONE;
            mt_map_key key = {0, 0, 0};
            if (mt_map_block_vert(r->map, e->key, u, &v) != MT_OK || v != e->vert_ids[u] ||
                mt_map_vert_origin(r->map, v, &key, &local) != MT_OK ||
                mt_map_block_vert(r->map, key, local, &back) != MT_OK || back != v) {
                FAIL(r, "block (%d,%d,%d) vertex %u: map id %u, recorded %u, back %u", e->key.x,
                     e->key.y, e->key.z, u, v, e->vert_ids[u], back);
                return;
            }
            const double *p = mt_map_vert_position(r->map, v), *q = &e->list.positions[3 * u];
            bool same = p != NULL;
            for (int k = 0; k < 3 && same; k++) same = p[k] == q[k] || (isnan(p[k]) && isnan(q[k]));
            if (!same) {
                FAIL(r, "block (%d,%d,%d) vertex %u: map vertex %u elsewhere", e->key.x, e->key.y,
                     e->key.z, u, v);
                return;
            }
        }
    }
}

/* ---- operations ------------------------------------------------------------ */

static void record(run *r, entry *e, const mt_map_delta *d)
{
    const uint32_t nf = e->list.num_faces, nv = e->list.num_verts;
    e->face_ids = malloc((size_t)(nf ? nf : 1) * sizeof(uint32_t));
    e->vert_ids = malloc((size_t)(nv ? nv : 1) * sizeof(uint32_t));
    if (!e->face_ids || !e->vert_ids) abort();
    if (d->num_faces_added != nf)
        FAIL(r, "delta adds %zu faces, block has %u", d->num_faces_added, nf);
    for (uint32_t f = 0; f < nf && f < d->num_faces_added; f++) e->face_ids[f] = d->faces_added[f];
    for (uint32_t u = 0; u < nv; u++) {
        e->vert_ids[u] = MT_NONE;
        CHECK_OK(mt_map_block_vert(r->map, e->key, u, &e->vert_ids[u]));
    }
}

/* The delta's removed faces are the old version's, its vertex lists name
 * vertices that died or were born. */
static void check_delta(run *r, const mt_map_delta *d, const uint32_t *old_faces, size_t n_old)
{
    if (!counts_equal(&d->before, &r->counts)) FAIL(r, "delta.before is not the counts before");
    mt_map_counts now;
    mt_map_get_counts(r->map, &now);
    if (!counts_equal(&d->after, &now)) FAIL(r, "delta.after is not the counts after");
    if (d->num_faces_removed != n_old ||
        (n_old && memcmp(d->faces_removed, old_faces, n_old * sizeof *old_faces) != 0))
        FAIL(r, "delta removes %zu faces, expected %zu", d->num_faces_removed, n_old);
    for (size_t i = 0; i < d->num_verts_removed; i++)
        if (mt_map_vert_position(r->map, d->verts_removed[i]))
            FAIL(r, "removed vertex %u is alive", d->verts_removed[i]);
    for (size_t i = 0; i < d->num_verts_added; i++)
        if (!mt_map_vert_position(r->map, d->verts_added[i]))
            FAIL(r, "added vertex %u is not alive", d->verts_added[i]);
    if ((int64_t)d->after.num_verts - d->before.num_verts !=
        (int64_t)d->num_verts_added - (int64_t)d->num_verts_removed)
        FAIL(r, "vertex count moved by %lld, delta lists %zu added %zu removed",
             (long long)d->after.num_verts - d->before.num_verts, d->num_verts_added,
             d->num_verts_removed);
    r->counts = now;
}

/* None mode: the block's vertex ids, source ids for the source's
 * vertices and new ones for what a change added. */
static uint32_t *ids_for(run *r, const map_block_src *src, const mt_face_list *list)
{
    uint32_t *ids = malloc((size_t)(list->num_verts ? list->num_verts : 1) * sizeof *ids);
    if (!ids) abort();
    for (uint32_t u = 0; u < list->num_verts; u++)
        ids[u] = u < src->list.num_verts ? src->ids[u] : r->next_id++;
    return ids;
}

static void op_put(run *r, const map_block_src *src, bool change)
{
    mt_face_list list;
    map_list_copy(&src->list, &list);
    if (change) map_mutate(&list, r->set, &r->rng);
    uint32_t *ids = r->weld == MT_MAP_WELD_NONE ? ids_for(r, src, &list) : NULL;
    entry *old = model_find(r, src->key);
    size_t n_old = old ? old->list.num_faces : 0;
    uint32_t *old_faces = malloc((n_old ? n_old : 1) * sizeof *old_faces);
    if (n_old) memcpy(old_faces, old->face_ids, n_old * sizeof *old_faces);
    mt_map_delta d;
    mt_diag diag;
    mt_status s = mt_map_put(r->map, src->key, &list, ids, &d, &diag);
    if (s == MT_ERR_INVALID_ARG && r->weld == MT_MAP_WELD_NONE &&
        strstr(diag.message, "position")) {
        /* A change moved a vertex other blocks hold: refused, nothing changed. */
        mt_map_counts now;
        mt_map_get_counts(r->map, &now);
        if (!counts_equal(&now, &r->counts)) FAIL(r, "a refused put changed the counts");
        mt_face_list_free(&list);
        free(ids);
        free(old_faces);
        return;
    }
    if (s != MT_OK) {
        FAIL(r, "put (%d,%d,%d): %s", src->key.x, src->key.y, src->key.z, diag.message);
        mt_face_list_free(&list);
        free(ids);
        free(old_faces);
        return;
    }
    if (d.op != (old ? MT_MAP_OP_REPLACE : MT_MAP_OP_PUT_NEW)) FAIL(r, "delta op %d", (int)d.op);
    check_delta(r, &d, old_faces, n_old);
    entry *e = model_slot(r, src->key);
    e->changed = change;
    e->list = list;
    e->ids = ids;
    record(r, e, &d);
    free(old_faces);
}

static void op_remove(run *r)
{
    mt_map_delta d;
    mt_diag diag;
    if (r->n == 0 || map_rng_below(&r->rng, 10) == 0) {
        const mt_map_key nowhere = {12345, -6789, 1};
        CHECK_STATUS(mt_map_remove(r->map, nowhere, &d, &diag), MT_ERR_NOT_FOUND);
        mt_map_counts now;
        mt_map_get_counts(r->map, &now);
        if (!counts_equal(&now, &r->counts)) FAIL(r, "a failed remove changed the counts");
        return;
    }
    entry *e = &r->e[map_rng_below(&r->rng, (uint32_t)r->n)];
    mt_status s = mt_map_remove(r->map, e->key, &d, &diag);
    if (s != MT_OK) {
        FAIL(r, "remove: %s", diag.message);
        return;
    }
    if (d.op != MT_MAP_OP_REMOVE || d.num_faces_added != 0) FAIL(r, "remove delta");
    check_delta(r, &d, e->face_ids, e->list.num_faces);
    model_remove(r, e);
}

static void op_clear(run *r)
{
    mt_map_delta d;
    CHECK_OK(mt_map_clear(r->map, &d, NULL));
    if (!d.all_removed || d.op != MT_MAP_OP_CLEAR || d.after.num_faces || d.after.num_verts)
        FAIL(r, "clear delta");
    model_clear(r);
    mt_map_get_counts(r->map, &r->counts);
    uint32_t ve, fe;
    mt_map_id_ends(r->map, &ve, &fe);
    if (ve || fe) FAIL(r, "clear left id ends %u %u", ve, fe);
}

static void op_compact(run *r)
{
    uint32_t ve, fe;
    mt_map_id_ends(r->map, &ve, &fe);
    uint32_t *vmap = malloc((size_t)(ve ? ve : 1) * sizeof *vmap);
    uint32_t *fmap = malloc((size_t)(fe ? fe : 1) * sizeof *fmap);
    if (!vmap || !fmap) abort();
    if (ve)
        CHECK_STATUS(mt_map_compact(r->map, vmap, ve - 1, fmap, fe, NULL), MT_ERR_BUFFER_TOO_SMALL);
    CHECK_OK(mt_map_compact(r->map, vmap, ve, fmap, fe, NULL));
    uint32_t ve2, fe2;
    mt_map_id_ends(r->map, &ve2, &fe2);
    mt_map_counts now;
    mt_map_get_counts(r->map, &now);
    if (!counts_equal(&now, &r->counts)) FAIL(r, "compact changed the counts");
    if (fe2 != now.num_faces || (r->weld == MT_MAP_WELD_EXACT && ve2 != now.num_verts))
        FAIL(r, "compact left ends %u %u for %u vertices %u faces", ve2, fe2, now.num_verts,
             now.num_faces);
    for (size_t i = 0; i < r->n; i++) {
        entry *e = &r->e[i];
        for (uint32_t f = 0; f < e->list.num_faces; f++) {
            const uint32_t g = fmap[e->face_ids[f]];
            if (g == MT_NONE || g >= fe2) FAIL(r, "compact lost face %u", e->face_ids[f]);
            e->face_ids[f] = g;
        }
        for (uint32_t u = 0; u < e->list.num_verts; u++) {
            const uint32_t w = vmap[e->vert_ids[u]];
            if (w == MT_NONE || w >= ve2) FAIL(r, "compact lost vertex %u", e->vert_ids[u]);
            e->vert_ids[u] = w;
        }
    }
    free(vmap);
    free(fmap);
}

/* One random operation. Runs alternate between messy phases (changed
 * blocks half the time, removals) and clean ones (blocks mostly as the
 * mapper made them, few removals), so the map also gets back to clean,
 * closed states: holes close, non-manifold seams heal. */
static void step(run *r)
{
    const bool clean = (r->op / 250) % 2 == 1;
    const uint32_t roll = map_rng_below(&r->rng, 1000);
    const uint32_t change_one_in = clean ? 40 : 2;
    const map_block_src *src = &r->set->blocks[map_rng_below(&r->rng, (uint32_t)r->set->count)];
    if (clean && map_rng_below(&r->rng, 2) == 0) {
        /* Fill the map: the first block it lacks, from a random start. */
        const size_t start = map_rng_below(&r->rng, (uint32_t)r->set->count);
        for (size_t i = 0; i < r->set->count; i++) {
            const map_block_src *b = &r->set->blocks[(start + i) % r->set->count];
            if (!model_find(r, b->key)) {
                src = b;
                break;
            }
        }
    }
    if (roll < 3) {
        op_clear(r);
    } else if (roll < 10) {
        op_compact(r);
    } else if (roll < (clean ? 700u : 550u)) {
        op_put(r, src, map_rng_below(&r->rng, change_one_in) == 0);
    } else if (roll < (clean ? 970u : 850u) && r->n > 0) {
        /* Replace a block the map holds with a version of it (in a clean
         * phase, a changed one first). */
        const entry *e = &r->e[map_rng_below(&r->rng, (uint32_t)r->n)];
        for (size_t i = 0; clean && !e->changed && i < r->n; i++)
            if (r->e[i].changed) e = &r->e[i];
        for (size_t b = 0; b < r->set->count; b++)
            if (same_key(r->set->blocks[b].key, e->key)) src = &r->set->blocks[b];
        op_put(r, src,
               clean ? map_rng_below(&r->rng, change_one_in) == 0 : map_rng_below(&r->rng, 4) != 0);
    } else {
        op_remove(r);
    }
    check_equivalence(r);
    if (r->op % 16 == 0) check_ids(r);
    const mt_map_counts *c = &r->counts;
    const uint64_t seen[SEEN_COUNT] = {c->nonmanifold_edges,
                                       c->bowtie_vertices,
                                       c->nonmanifold_vertices,
                                       c->inconsistent_orientation_edges,
                                       c->duplicate_directed_edges,
                                       c->duplicate_faces,
                                       c->degenerate_faces,
                                       c->faces_with_out_of_range_indices,
                                       c->nonfinite_vertices,
                                       c->isolated_vertices,
                                       c->unreferenced_vertices,
                                       c->boundary_edges,
                                       c->closed};
    for (int k = 0; k < SEEN_COUNT; k++) r->seen[k] += seen[k] > 0;
    r->clean_states += c->num_faces > 0 && c->manifold && c->consistently_oriented &&
                       c->degenerate_faces == 0 && c->isolated_vertices == 0;
    if (c->num_faces > r->max_faces) r->max_faces = c->num_faces;
}

/* Operations per run: `base`, scaled by MESHTOPO_MAP_OPS_PERCENT. */
static uint32_t op_count(uint32_t base)
{
    const char *env = getenv("MESHTOPO_MAP_OPS_PERCENT");
    if (env && *env) return (uint32_t)((uint64_t)base * strtoul(env, NULL, 10) / 100);
    return base;
}

/* Runs `ops` random operations over the blocks of `set`; must_see: fail
 * unless every kind of defect was met, and a state without them (and for a
 * closed surface, the closed state). */
static void run_ops(const char *name, const map_block_set *set, mt_map_weld weld, uint32_t ops,
                    uint64_t seed, bool must_see)
{
    run r;
    memset(&r, 0, sizeof r);
    r.name = name;
    r.set = set;
    r.weld = weld;
    r.rng = seed;
    for (size_t b = 0; b < set->count; b++)
        for (uint32_t u = 0; u < set->blocks[b].list.num_verts; u++)
            if (set->blocks[b].ids[u] >= r.next_id) r.next_id = set->blocks[b].ids[u] + 1;
    mt_map_options opts = {weld, 0.0};
    CHECK_OK(mt_map_create(&opts, &r.map, NULL));
    if (!r.map || set->count == 0) return;
    mt_map_get_counts(r.map, &r.counts);
    ops = op_count(ops);
    for (r.op = 1; r.op <= ops && mt_test_failures() == 0; r.op++) step(&r);
    check_ids(&r);
    printf("%s: %u operations, %zu blocks at the end, %u faces, %u at most\n  with", name, r.op - 1,
           r.n, r.counts.num_faces, r.max_faces);
    for (int k = 0; k < SEEN_COUNT; k++) printf(" %s %u,", seen_names[k], r.seen[k]);
    printf(" clean %u\n", r.clean_states);
    if (must_see) {
        for (int k = 0; k < SEEN_COUNT - 1; k++)
            if (r.seen[k] == 0)
                mt_test_fail(__FILE__, __LINE__, "%s: never met %s", name, seen_names[k]);
        if (r.clean_states == 0) mt_test_fail(__FILE__, __LINE__, "%s: never clean", name);
        if (strstr(name, "torus") && r.seen[SEEN_COUNT - 1] == 0)
            mt_test_fail(__FILE__, __LINE__, "%s: never closed", name);
    }
    model_clear(&r);
    free(r.e);
    mt_map_destroy(r.map);
}

static void run_list(const char *name, const mt_face_list *list, double size, bool soup,
                     mt_map_weld weld, uint32_t ops, uint64_t seed, bool must_see)
{
    map_block_set set;
    map_split(list, size, soup, &set);
    run_ops(name, &set, weld, ops, seed, must_see);
    map_block_set_free(&set);
}

static void test_map_random_grid(void)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(20, 20, true, &grid));
    run_list("grid 20x20, blocks of 4, seams duplicated", &grid, 4.0, false, MT_MAP_WELD_EXACT,
             3000, 0x9e3779b97f4a7c15ull, true);
    mt_face_list_free(&grid);
}

static void test_map_random_soup(void)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(12, 12, true, &grid));
    run_list("grid 12x12, blocks of 3, a vertex per corner", &grid, 3.0, true, MT_MAP_WELD_EXACT,
             1500, 0x2545f4914f6cdd1dull, true);
    mt_face_list_free(&grid);
}

static void test_map_random_torus(void)
{
    mt_face_list torus;
    CHECK_OK(mt_gen_torus(24, 12, &torus));
    run_list("torus 24x12, blocks of 0.4", &torus, 0.4, false, MT_MAP_WELD_EXACT, 1500,
             0xda942042e4dd58b5ull, true);
    mt_face_list_free(&torus);
}

static void test_map_random_quads(void)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(16, 16, false, &grid));
    run_list("quad grid 16x16, blocks of 4", &grid, 4.0, false, MT_MAP_WELD_EXACT, 1000,
             0x853c49e6748fea9bull, true);
    mt_face_list_free(&grid);
}

static void test_map_random_none(void)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(16, 16, true, &grid));
    run_list("grid 16x16, sender's ids (weld none)", &grid, 4.0, false, MT_MAP_WELD_NONE, 1000,
             0x5851f42d4c957f2dull, false);
    mt_face_list_free(&grid);
}

/* Corpus meshes (defects of every kind), blocks a third of their extent,
 * seams duplicated or every face with its own vertices. */
static void test_map_random_corpus_meshes(void)
{
    static const char *const names[] = {"assimp_malformed",
                                        "cgal_eight",
                                        "cgal_many_umbrellas",
                                        "cgal_elephant_with_holes",
                                        "openmesh_cube_minimal_quads",
                                        "trimesh_joined_tetrahedra",
                                        "trimesh_multibody_stl_soup",
                                        "trimesh_notenoughindices",
                                        "vcg_moebius",
                                        "vcg_nonmanifold",
                                        "cgal_prim"};
    uint64_t seed = 0x1234567887654321ull;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s.off", mt_test_corpus_dir(), names[i]);
        mt_face_list list;
        mt_diag d;
        if (mt_read_file(path, MT_FORMAT_AUTO, &list, &d) != MT_OK) {
            mt_test_fail(__FILE__, __LINE__, "%s: %s", path, d.message);
            continue;
        }
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (uint32_t v = 0; v < list.num_verts; v++)
            for (int k = 0; k < 3; k++) {
                const double x = list.positions[3 * (size_t)v + k];
                if (x < lo[k]) lo[k] = x;
                if (x > hi[k]) hi[k] = x;
            }
        double extent = 0;
        for (int k = 0; k < 3; k++)
            if (hi[k] - lo[k] > extent) extent = hi[k] - lo[k];
        /* Every other mesh as voxblox sends it: each face its own vertices. */
        run_list(names[i], &list, extent > 0 ? extent / 3 : 1.0, i % 2 == 1, MT_MAP_WELD_EXACT, 500,
                 seed += 0x9e3779b97f4a7c15ull, false);
        mt_face_list_free(&list);
    }
}

static const mt_test_case cases[] = {
    {"map_random_grid", test_map_random_grid},
    {"map_random_soup", test_map_random_soup},
    {"map_random_torus", test_map_random_torus},
    {"map_random_quads", test_map_random_quads},
    {"map_random_none", test_map_random_none},
    {"map_random_corpus", test_map_random_corpus_meshes},
};
const mt_test_table mt_tests_map_random = {cases, sizeof cases / sizeof cases[0]};
