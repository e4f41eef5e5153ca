/* libFuzzer target for the block map (meshtopo/map.h): the input bytes drive
 * a sequence of puts, replacements, removals, clears and compactions on a
 * small map, once in each weld mode, exact, none and eps (the same bytes
 * drive the three runs). After every operation the map's counts and
 * histograms must equal the report of mt_mesh_build of mt_map_face_list
 * (validated) and of the union of the blocks the fuzzer holds (welded by
 * mt_face_list_weld for exact; for eps only while nothing was removed or
 * replaced since the last clear, when map.h promises that equality), as
 * tests/core/test_map_random.c checks; in eps mode also map.h's guarantees
 * (block vertices within eps of their map vertex, live vertices more than
 * eps apart), and every vertex's ring, edge faces and every face's
 * neighbours asked of the map must be the build's (map ids). A refused
 * operation must leave the counts unchanged. Any disagreement calls abort()
 * so the fuzzer keeps the input.
 *
 * Input layout (missing bytes read as 0; at most MAX_OPS operations):
 *   per op     op byte % 8: 0-4 put, 5 remove, 6 clear, 7 compact
 *   put        key byte (% NUM_KEYS), V = byte % 9, F = byte % 9,
 *              V position bytes (% 32: 0-15 a point of a shared 4x4 grid, so
 *              blocks share positions; 16-19 the same with -0.0 for 0.0;
 *              20 NaN, 21 another NaN, 22 +Inf, 23 a point off the grid;
 *              24-31 grid points moved by 0.2 or 0.235, within EPS of them
 *              and of each other, so eps welds are chained and tied),
 *              none mode: V id bytes (% 24: the vertex's map id),
 *              F faces: size byte (% 7), then index bytes: 0xFF = UINT32_MAX,
 *              0xF0..0xFE = V + (byte - 0xF0) (out of range), else byte % V
 *   remove     key byte (% NUM_KEYS; a key the map lacks must give NOT_FOUND)
 */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/core.h"
#include "meshtopo/io.h"

#define MAX_OPS 32
#define MAX_BLOCK_VERTS 8
#define MAX_BLOCK_FACES 8
#define MAX_FACE_SIZE 6
#define NUM_KEYS 6
#define EDGE_FACES_MAX 64 /* more than all faces of NUM_KEYS blocks */
#define NUM_IDS 24
#define EPS 0.3

static void require(bool ok, const char *what, int line)
{
    if (ok) return;
    fprintf(stderr, "fuzz_map_ops.c:%d: invariant violated: %s\n", line, what);
    abort();
}

#define REQUIRE(cond) require((cond), #cond, __LINE__)

typedef struct byte_reader {
    const uint8_t *data;
    size_t size, pos;
} byte_reader;

static uint8_t next_byte(byte_reader *r)
{
    return r->pos < r->size ? r->data[r->pos++] : 0;
}

static void *xcalloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    REQUIRE(p != NULL);
    return p;
}

static const mt_map_key keys[NUM_KEYS] = {{0, 0, 0},  {1, 0, 0},  {0, 1, 0},
                                          {-1, 0, 0}, {0, 0, -1}, {INT32_MIN, INT32_MAX, 0}};

static bool same_key(mt_map_key a, mt_map_key b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

/* A block as the fuzzer put it: the model the map must match. */
typedef struct held {
    mt_map_key key;
    mt_face_list list; /* calloc'd arrays */
    uint32_t ids[MAX_BLOCK_VERTS];
} held;

typedef struct model {
    mt_map_weld weld;
    bool none;
    bool in_order; /* eps: no removal or replacement since the last clear */
    held blocks[NUM_KEYS];
    size_t count;
} model;

static void held_free(held *h)
{
    free(h->list.positions);
    free(h->list.face_sizes);
    free(h->list.face_indices);
    memset(&h->list, 0, sizeof h->list);
}

static held *model_find(model *m, mt_map_key key)
{
    for (size_t i = 0; i < m->count; i++)
        if (same_key(m->blocks[i].key, key)) return &m->blocks[i];
    return NULL;
}

static void model_remove(model *m, held *h)
{
    held_free(h);
    *h = m->blocks[--m->count];
}

static void model_clear(model *m)
{
    for (size_t i = 0; i < m->count; i++) held_free(&m->blocks[i]);
    m->count = 0;
}

static void grid_point(uint32_t i, double *p)
{
    p[0] = (double)(i & 3);
    p[1] = (double)((i >> 2) & 3);
    p[2] = 0.0;
}

static void read_position(byte_reader *r, double *p)
{
    const uint32_t b = next_byte(r) % 32;
    if (b >= 28) {
        grid_point(b - 28, p);
        p[0] += 0.15, p[1] += 0.15, p[2] += 0.1;
    } else if (b >= 24) {
        grid_point(b - 24, p);
        p[0] += 0.2;
    } else if (b < 16) {
        grid_point(b, p);
    } else if (b < 20) {
        grid_point((b - 16) * 4, p); /* x = 0 */
        p[0] = -0.0;
        p[2] = -0.0;
    } else if (b == 20) {
        p[0] = p[1] = p[2] = 0.0;
        p[1] = NAN;
    } else if (b == 21) {
        const uint64_t bits = 0x7ff8000000000123ull; /* another NaN payload */
        p[0] = 1.0;
        p[2] = 0.0;
        memcpy(&p[1], &bits, sizeof bits);
    } else if (b == 22) {
        p[0] = INFINITY;
        p[1] = p[2] = 0.0;
    } else {
        p[0] = 0.5;
        p[1] = 0.25;
        p[2] = 1.0;
    }
}

/* Reads a block; the caller frees it with held_free. */
static void read_block(byte_reader *r, bool none, held *out)
{
    memset(out, 0, sizeof *out);
    mt_face_list *l = &out->list;
    l->num_verts = next_byte(r) % (MAX_BLOCK_VERTS + 1);
    l->num_faces = next_byte(r) % (MAX_BLOCK_FACES + 1);
    l->positions = xcalloc((size_t)l->num_verts * 3, sizeof(double));
    for (uint32_t v = 0; v < l->num_verts; v++) read_position(r, &l->positions[3 * (size_t)v]);
    if (none)
        for (uint32_t v = 0; v < l->num_verts; v++) out->ids[v] = next_byte(r) % NUM_IDS;
    l->face_sizes = xcalloc(l->num_faces, sizeof(uint32_t));
    l->face_indices = xcalloc((size_t)l->num_faces * MAX_FACE_SIZE, sizeof(uint32_t));
    uint64_t at = 0;
    for (uint32_t f = 0; f < l->num_faces; f++) {
        const uint32_t n = next_byte(r) % (MAX_FACE_SIZE + 1);
        l->face_sizes[f] = n;
        for (uint32_t i = 0; i < n; i++) {
            const uint8_t b = next_byte(r);
            uint32_t x;
            if (b == 0xFF)
                x = UINT32_MAX;
            else if (b >= 0xF0 || l->num_verts == 0)
                x = l->num_verts + (b >= 0xF0 ? (uint32_t)(b - 0xF0) : 0);
            else
                x = b % l->num_verts;
            l->face_indices[at++] = x;
        }
    }
    l->num_indices = at;
}

/* ---- the union the model holds ------------------------------------------ */

static uint64_t coord_bits(double x)
{
    uint64_t bits;
    if (x == 0.0) x = 0.0;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

static bool pos_equal(const double *a, const double *b)
{
    return coord_bits(a[0]) == coord_bits(b[0]) && coord_bits(a[1]) == coord_bits(b[1]) &&
           coord_bits(a[2]) == coord_bits(b[2]);
}

/* None mode: would putting `h` be refused for two positions under one id
 * (within h, or against a block other than the one under h's key)? */
static bool none_conflict(const model *m, const held *h)
{
    for (uint32_t u = 0; u < h->list.num_verts; u++) {
        const double *p = &h->list.positions[3 * (size_t)u];
        for (uint32_t w = 0; w < u; w++)
            if (h->ids[w] == h->ids[u] && !pos_equal(p, &h->list.positions[3 * (size_t)w]))
                return true;
        for (size_t i = 0; i < m->count; i++) {
            const held *o = &m->blocks[i];
            if (same_key(o->key, h->key)) continue;
            for (uint32_t w = 0; w < o->list.num_verts; w++)
                if (o->ids[w] == h->ids[u] && !pos_equal(p, &o->list.positions[3 * (size_t)w]))
                    return true;
        }
    }
    return false;
}

/* The union of the held blocks as map.h defines it: exact (eps) mode, the
 * lists end to end in the order held (out-of-range entries as MT_NONE - r)
 * welded with eps 0 (EPS); none mode, one vertex per id used, in id order. */
static void model_union(const model *m, mt_face_list *out)
{
    uint32_t nv = 0, nf = 0;
    uint64_t ni = 0;
    for (size_t b = 0; b < m->count; b++)
        nv += m->blocks[b].list.num_verts, nf += m->blocks[b].list.num_faces,
            ni += m->blocks[b].list.num_indices;
    uint32_t rank[NUM_IDS];
    const double *id_pos[NUM_IDS] = {0};
    if (m->none) {
        for (size_t b = 0; b < m->count; b++)
            for (uint32_t v = 0; v < m->blocks[b].list.num_verts; v++)
                if (!id_pos[m->blocks[b].ids[v]])
                    id_pos[m->blocks[b].ids[v]] = &m->blocks[b].list.positions[3 * (size_t)v];
        nv = 0;
        for (uint32_t id = 0; id < NUM_IDS; id++) rank[id] = id_pos[id] ? nv++ : MT_NONE;
    }
    mt_diag d;
    REQUIRE(mt_face_list_alloc(out, nv, nf, ni, &d) == MT_OK);
    if (m->none)
        for (uint32_t id = 0; id < NUM_IDS; id++)
            if (id_pos[id]) memcpy(&out->positions[3 * (size_t)rank[id]], id_pos[id], 24);
    uint32_t voff = 0, foff = 0;
    uint64_t at = 0;
    for (size_t b = 0; b < m->count; b++) {
        const held *h = &m->blocks[b];
        const mt_face_list *l = &h->list;
        if (!m->none && l->num_verts)
            memcpy(&out->positions[3 * (size_t)voff], l->positions,
                   (size_t)l->num_verts * 3 * sizeof(double));
        uint64_t in_at = 0;
        for (uint32_t f = 0; f < l->num_faces; f++) {
            const uint32_t size = l->face_sizes[f];
            const uint32_t *in = l->face_indices + in_at;
            out->face_sizes[foff + f] = size;
            uint32_t r = 0;
            for (uint32_t i = 0; i < size; i++) {
                if (in[i] < l->num_verts) {
                    out->face_indices[at + i] = m->none ? rank[h->ids[in[i]]] : voff + in[i];
                    continue;
                }
                uint32_t j = 0;
                while (j < i && in[j] != in[i]) j++;
                out->face_indices[at + i] = j < i ? out->face_indices[at + j] : MT_NONE - r++;
            }
            at += size;
            in_at += size;
        }
        voff += l->num_verts;
        foff += l->num_faces;
    }
    if (!m->none)
        REQUIRE(mt_face_list_weld(out, m->weld == MT_MAP_WELD_EPS ? EPS : 0, NULL, NULL, &d) ==
                MT_OK);
}

/* ---- the comparison -------------------------------------------------------- */

/* The map's counts and histograms against the report of a build of list. */
static void check_against(const mt_map *map, const mt_face_list *list)
{
    mt_build_options opts = {0};
    opts.threads = 1;
    mt_mesh *mesh = NULL;
    mt_diag d;
    REQUIRE(mt_mesh_build(list, &opts, &mesh, &d) == MT_OK);
    REQUIRE(mt_mesh_validate(mesh, &d) == MT_OK);
    if (mt_map_compare_report(map, mt_mesh_report(mesh), &d) != MT_OK) {
        fprintf(stderr, "fuzz_map_ops.c:%d: map differs from the full build: %s\n", __LINE__,
                d.message);
        abort();
    }
    mt_mesh_destroy(mesh);
}

static bool finite3(const double *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static double dist(const double *p, const double *q)
{
    return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                (p[2] - q[2]) * (p[2] - q[2]));
}

/* map.h's eps guarantees: each finite block vertex lies within EPS of its
 * map vertex, and live finite map vertices are more than EPS apart. */
static void check_eps(const mt_map *map, const model *m)
{
    for (size_t i = 0; i < m->count; i++) {
        const held *h = &m->blocks[i];
        for (uint32_t u = 0; u < h->list.num_verts; u++) {
            const double *x = &h->list.positions[3 * (size_t)u];
            if (!finite3(x)) continue;
            uint32_t v = MT_NONE;
            REQUIRE(mt_map_block_vert(map, h->key, u, &v) == MT_OK);
            const double *p = mt_map_vert_position(map, v);
            REQUIRE(p != NULL && dist(x, p) <= EPS * (1 + 1e-12));
        }
    }
    uint32_t vend = 0, fend = 0;
    mt_map_id_ends(map, &vend, &fend);
    for (uint32_t a = 0; a < vend; a++) {
        const double *p = mt_map_vert_position(map, a);
        if (!p || !finite3(p)) continue;
        for (uint32_t b = a + 1; b < vend; b++) {
            const double *q = mt_map_vert_position(map, b);
            if (q && finite3(q)) REQUIRE(dist(p, q) > EPS * (1 - 1e-12));
        }
    }
}

/* Every vertex's ring, the faces of every edge at it and every face's
 * neighbours, asked of the map and of a build of list (the map's union,
 * vids and fids its map ids): the map's answers are the build's. */
static void check_queries(const mt_map *map, const mt_face_list *list, const uint32_t *vids,
                          const uint32_t *fids)
{
    mt_build_options opts = {0};
    opts.threads = 1;
    mt_mesh *mesh = NULL;
    mt_diag d;
    REQUIRE(mt_mesh_build(list, &opts, &mesh, &d) == MT_OK);
    mt_ring full, mine;
    memset(&full, 0, sizeof full);
    for (uint32_t k = 0; k < list->num_verts; k++) {
        REQUIRE(mt_vert_ring_growing(mesh, k, &full) == MT_OK);
        mine = full;
        mine.neighbors = xcalloc(full.num_neighbors + 1, sizeof(uint32_t));
        mine.faces = xcalloc(full.num_faces + 1, sizeof(uint32_t));
        mine.fans = xcalloc(full.num_fans + 1, sizeof(mt_fan));
        mine.neighbors_capacity = full.num_neighbors + 1;
        mine.faces_capacity = full.num_faces + 1;
        mine.fans_capacity = full.num_fans + 1;
        REQUIRE(mt_map_vert_ring(map, vids[k], &mine, &d) == MT_OK);
        REQUIRE(mine.num_fans == full.num_fans && mine.num_faces == full.num_faces &&
                mine.num_neighbors == full.num_neighbors);
        for (size_t i = 0; i < full.num_fans; i++)
            REQUIRE(mine.fans[i].neighbor_begin == full.fans[i].neighbor_begin &&
                    mine.fans[i].neighbor_count == full.fans[i].neighbor_count &&
                    mine.fans[i].face_begin == full.fans[i].face_begin &&
                    mine.fans[i].face_count == full.fans[i].face_count &&
                    mine.fans[i].boundary == full.fans[i].boundary);
        for (size_t i = 0; i < full.num_faces; i++) REQUIRE(mine.faces[i] == fids[full.faces[i]]);
        for (size_t i = 0; i < full.num_neighbors; i++) {
            REQUIRE(mine.neighbors[i] == vids[full.neighbors[i]]);
            uint32_t a[EDGE_FACES_MAX], b[EDGE_FACES_MAX];
            size_t na = 0, nb = 0;
            const mt_status want =
                mt_edge_faces(mesh, k, full.neighbors[i], a, EDGE_FACES_MAX, &na);
            REQUIRE(mt_map_edge_faces(map, vids[k], mine.neighbors[i], b, EDGE_FACES_MAX, &nb,
                                      &d) == want);
            REQUIRE(want != MT_OK || na == nb);
            for (size_t j = 0; want == MT_OK && j < na; j++) REQUIRE(b[j] == fids[a[j]]);
        }
        free(mine.neighbors);
        free(mine.faces);
        free(mine.fans);
    }
    mt_ring_free(&full);
    mt_face_adjacency adj;
    memset(&adj, 0, sizeof adj);
    for (uint32_t f = 0; f < list->num_faces; f++) {
        const mt_status want = mt_face_neighbors_growing(mesh, f, &adj);
        uint32_t *faces = xcalloc(adj.num_faces + 1, sizeof(uint32_t));
        uint32_t offsets[MAX_FACE_SIZE + 1];
        size_t nf = 0, ne = 0;
        REQUIRE(mt_map_face_neighbors(map, fids[f], faces, adj.num_faces + 1, offsets,
                                      MAX_FACE_SIZE + 1, &nf, &ne, &d) == want);
        REQUIRE(want != MT_OK || (nf == adj.num_faces && ne == adj.num_edges));
        for (size_t i = 0; want == MT_OK && i <= ne; i++) REQUIRE(offsets[i] == adj.offsets[i]);
        for (size_t i = 0; want == MT_OK && i < nf; i++) REQUIRE(faces[i] == fids[adj.faces[i]]);
        free(faces);
    }
    mt_face_adjacency_free(&adj);
    mt_mesh_destroy(mesh);
}

static void check_map(const mt_map *map, const model *m)
{
    mt_map_counts c;
    mt_map_get_counts(map, &c);
    REQUIRE(c.num_blocks == m->count);
    for (size_t i = 0; i < NUM_KEYS; i++)
        REQUIRE(mt_map_has_block(map, keys[i]) == (model_find((model *)m, keys[i]) != NULL));
    uint32_t *vids = xcalloc(c.num_verts, sizeof *vids);
    uint32_t *fids = xcalloc(c.num_faces, sizeof *fids);
    mt_face_list list;
    mt_diag d;
    REQUIRE(mt_map_face_list(map, &list, vids, c.num_verts, fids, c.num_faces, &d) == MT_OK);
    check_against(map, &list);
    check_queries(map, &list, vids, fids);
    /* Each list face is the map face its id names, corner by corner. */
    uint64_t at = 0;
    for (uint32_t f = 0; f < list.num_faces; f++) {
        uint32_t corners[MAX_FACE_SIZE];
        size_t n = 0;
        REQUIRE(mt_map_face_verts(map, fids[f], corners, MAX_FACE_SIZE, &n) == MT_OK);
        REQUIRE(n == list.face_sizes[f]);
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t x = list.face_indices[at + i];
            REQUIRE(corners[i] == (x < list.num_verts ? vids[x] : MT_NONE));
        }
        at += n;
    }
    mt_face_list_free(&list);
    free(vids);
    free(fids);
    if (m->weld != MT_MAP_WELD_EPS || m->in_order) {
        mt_face_list u;
        model_union(m, &u);
        check_against(map, &u);
        mt_face_list_free(&u);
    }
    if (m->weld == MT_MAP_WELD_EPS) check_eps(map, m);
}

static void check_delta(const mt_map_delta *delta, const mt_map_counts *before, const mt_map *map)
{
    mt_map_counts after;
    mt_map_get_counts(map, &after);
    REQUIRE(memcmp(&delta->before, before, sizeof *before) == 0);
    REQUIRE(memcmp(&delta->after, &after, sizeof after) == 0);
}

static void check_unchanged(const mt_map *map, const mt_map_counts *before)
{
    mt_map_counts now;
    mt_map_get_counts(map, &now);
    REQUIRE(memcmp(&now, before, sizeof now) == 0);
}

/* ---- the run ---------------------------------------------------------------- */

static void run(byte_reader *r, mt_map_weld weld)
{
    mt_map_options opts = {0};
    opts.weld = weld;
    opts.eps = weld == MT_MAP_WELD_EPS ? EPS : 0;
    const bool none = weld == MT_MAP_WELD_NONE;
    mt_map *map = NULL;
    mt_diag d;
    REQUIRE(mt_map_create(&opts, &map, &d) == MT_OK);
    model m;
    memset(&m, 0, sizeof m);
    m.weld = weld;
    m.none = none;
    m.in_order = true;
    for (int op = 0; op < MAX_OPS && r->pos < r->size; op++) {
        mt_map_counts before;
        mt_map_get_counts(map, &before);
        mt_map_delta delta;
        const uint8_t kind = next_byte(r) % 8;
        if (kind <= 4) {
            held h;
            const mt_map_key key = keys[next_byte(r) % NUM_KEYS];
            read_block(r, none, &h);
            h.key = key;
            const bool refuse = none && none_conflict(&m, &h);
            const bool replace = model_find(&m, key) != NULL;
            const mt_status s = mt_map_put(map, key, &h.list, none ? h.ids : NULL, &delta, &d);
            if (refuse) {
                REQUIRE(s == MT_ERR_INVALID_ARG);
                check_unchanged(map, &before);
                held_free(&h);
            } else {
                if (s != MT_OK) fprintf(stderr, "put: %s: %s\n", mt_strerror(s), d.message);
                REQUIRE(s == MT_OK);
                REQUIRE(delta.op == (replace ? MT_MAP_OP_REPLACE : MT_MAP_OP_PUT_NEW));
                REQUIRE(delta.num_faces_added == h.list.num_faces);
                check_delta(&delta, &before, map);
                held *slot = model_find(&m, key);
                if (slot) {
                    held_free(slot);
                    m.in_order = false;
                } else {
                    slot = &m.blocks[m.count++];
                }
                *slot = h;
            }
        } else if (kind == 5) {
            const mt_map_key key = keys[next_byte(r) % NUM_KEYS];
            held *h = model_find(&m, key);
            const mt_status s = mt_map_remove(map, key, &delta, &d);
            if (!h) {
                REQUIRE(s == MT_ERR_NOT_FOUND);
                check_unchanged(map, &before);
            } else {
                REQUIRE(s == MT_OK);
                REQUIRE(delta.op == MT_MAP_OP_REMOVE);
                REQUIRE(delta.num_faces_removed == h->list.num_faces);
                check_delta(&delta, &before, map);
                model_remove(&m, h);
                m.in_order = false;
            }
        } else if (kind == 6) {
            REQUIRE(mt_map_clear(map, &delta, &d) == MT_OK);
            REQUIRE(delta.all_removed);
            check_delta(&delta, &before, map);
            model_clear(&m);
            m.in_order = true;
        } else {
            uint32_t vend = 0, fend = 0;
            mt_map_id_ends(map, &vend, &fend);
            uint32_t *vmap = xcalloc(vend, sizeof *vmap);
            uint32_t *fmap = xcalloc(fend, sizeof *fmap);
            if (fend > 0)
                REQUIRE(mt_map_compact(map, vmap, vend, fmap, fend - 1, &d) ==
                        MT_ERR_BUFFER_TOO_SMALL);
            REQUIRE(mt_map_compact(map, vmap, vend, fmap, fend, &d) == MT_OK);
            check_unchanged(map, &before);
            /* Live faces (and vertices, but for none mode whose ids are the
             * sender's) are renumbered densely, in id order. */
            uint32_t live = 0;
            for (uint32_t f = 0; f < fend; f++)
                if (fmap[f] != MT_NONE) REQUIRE(fmap[f] == live++);
            REQUIRE(live == before.num_faces);
            live = 0;
            for (uint32_t v = 0; v < vend; v++)
                if (vmap[v] != MT_NONE) REQUIRE(vmap[v] == (none ? v : live)), live++;
            REQUIRE(live == before.num_verts);
            free(vmap);
            free(fmap);
        }
        check_map(map, &m);
    }
    model_clear(&m);
    mt_map_destroy(map);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const mt_map_weld modes[3] = {MT_MAP_WELD_EXACT, MT_MAP_WELD_NONE, MT_MAP_WELD_EPS};
    for (int i = 0; i < 3; i++) {
        byte_reader r = {data, size, 0};
        run(&r, modes[i]);
    }
    return 0;
}
