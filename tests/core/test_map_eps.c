/* Tests of the block map's weld within a tolerance (MT_MAP_WELD_EPS, map.h):
 * the options it refuses; blocks put without removals give exactly
 * mt_face_list_weld(eps) of the blocks end to end in put order (positions,
 * ids and faces, jittered seams, near-eps distances, NaN); and random
 * puts, replacements, removals, clears and compactions keep the counts
 * equal to a full build of mt_map_face_list and the documented guarantees:
 * each block vertex lies within eps of its map vertex, and live finite map
 * vertices are pairwise more than eps apart. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "map_split.h"
#include "meshtopo/generate.h"
#include "meshtopo/io.h"
#include "meshtopo/map.h"

static mt_map *eps_map(double eps)
{
    mt_map_options opts = {MT_MAP_WELD_EPS, eps};
    mt_map *map = NULL;
    CHECK_OK(mt_map_create(&opts, &map, NULL));
    return map;
}

static mt_map_key key3(int x, int y, int z)
{
    mt_map_key k = {x, y, z};
    return k;
}

static uint64_t mix(uint64_t x)
{
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    x ^= x >> 33;
    return x;
}

/* A deterministic value in [-1, 1) from a seed. */
static double unit(uint64_t seed)
{
    return (double)(mix(seed) >> 11) / 4503599627370496.0 - 1.0;
}

/* Moves every vertex of each block by up to `amount` per axis (a sender's
 * noise: seam copies no longer agree bitwise). */
static void jitter(map_block_set *set, double amount, uint64_t seed)
{
    for (size_t b = 0; b < set->count; b++) {
        mt_face_list *l = &set->blocks[b].list;
        for (uint32_t i = 0; i < 3 * l->num_verts; i++)
            l->positions[i] += amount * unit(seed ^ (b << 40) ^ i);
    }
}

/* The blocks end to end (no out-of-range entries here), welded within eps. */
static void concat_welded(const map_block_set *set, double eps, mt_face_list *out)
{
    uint64_t nv = 0, nf = 0, ni = 0;
    for (size_t b = 0; b < set->count; b++) {
        nv += set->blocks[b].list.num_verts;
        nf += set->blocks[b].list.num_faces;
        ni += set->blocks[b].list.num_indices;
    }
    CHECK_OK(mt_face_list_alloc(out, (uint32_t)nv, (uint32_t)nf, ni, NULL));
    uint32_t voff = 0, foff = 0;
    uint64_t at = 0;
    for (size_t b = 0; b < set->count; b++) {
        const mt_face_list *l = &set->blocks[b].list;
        memcpy(&out->positions[3 * (size_t)voff], l->positions,
               (size_t)l->num_verts * 3 * sizeof(double));
        memcpy(&out->face_sizes[foff], l->face_sizes, (size_t)l->num_faces * sizeof(uint32_t));
        for (uint64_t i = 0; i < l->num_indices; i++)
            out->face_indices[at + i] = voff + l->face_indices[i];
        voff += l->num_verts;
        foff += l->num_faces;
        at += l->num_indices;
    }
    CHECK_OK(mt_face_list_weld(out, eps, NULL, NULL, NULL));
}

/* Puts every block in order; the map's union must be the welded concatenation
 * exactly: the same positions (bitwise) in the same order, the same faces. */
static void check_puts_equal_weld(const char *what, map_block_set *set, double eps)
{
    mt_map *map = eps_map(eps);
    for (size_t b = 0; b < set->count; b++)
        CHECK_OK(mt_map_put(map, set->blocks[b].key, &set->blocks[b].list, NULL, NULL, NULL));
    mt_face_list want, got;
    concat_welded(set, eps, &want);
    CHECK_OK(mt_map_face_list(map, &got, NULL, 0, NULL, 0, NULL));
    CHECK_EQ(got.num_verts, want.num_verts);
    CHECK_EQ(got.num_faces, want.num_faces);
    CHECK_EQ(got.num_indices, want.num_indices);
    if (got.num_verts == want.num_verts && got.num_indices == want.num_indices) {
        CHECK(memcmp(got.positions, want.positions, (size_t)got.num_verts * 3 * sizeof(double)) ==
              0);
        CHECK(memcmp(got.face_indices, want.face_indices,
                     (size_t)got.num_indices * sizeof(uint32_t)) == 0);
    }
    if (map_check_full(map, what) != 0) fprintf(stderr, "  (%s)\n", what);
    mt_face_list_free(&want);
    mt_face_list_free(&got);
    mt_map_destroy(map);
}

static void test_map_eps_options(void)
{
    mt_map *map = (mt_map *)&map;
    mt_diag d;
    const double bad[] = {0.0, -1e-3, NAN, INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        mt_map_options opts = {MT_MAP_WELD_EPS, bad[i]};
        CHECK_STATUS(mt_map_create(&opts, &map, &d), MT_ERR_INVALID_ARG);
        CHECK(map == NULL);
        CHECK(strstr(d.message, "eps") != NULL);
    }
    map = eps_map(0.5);
    double pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t sizes[1] = {3}, idx[3] = {0, 1, 2}, ids[3] = {0, 1, 2};
    mt_face_list l = {3, 1, 3, pos, sizes, idx};
    CHECK_STATUS(mt_map_put(map, key3(0, 0, 0), &l, ids, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK_OK(mt_map_put(map, key3(0, 0, 0), &l, NULL, NULL, &d));
    mt_map_destroy(map);
}

/* Two blocks whose seam copies sit at distances around eps; ties go to the
 * lowest map id; NaN and infinity never weld. */
static void test_map_eps_rules(void)
{
    const double eps = 0.25;
    mt_map *map = eps_map(eps);
    double a_pos[9] = {0, 0, 0, 1, 0, 0, 0.5, 0, 0}; /* 0.5 apart: two vertices */
    uint32_t sizes[1] = {3}, idx[3] = {0, 1, 2};
    mt_face_list a = {3, 1, 3, a_pos, sizes, idx};
    mt_map_delta delta;
    CHECK_OK(mt_map_put(map, key3(0, 0, 0), &a, NULL, &delta, NULL));
    CHECK_EQ(delta.num_verts_added, 3);
    /* (0.25, 0, 0) is exactly eps from vertices 0 and 2: the lowest id, 0.
     * (1.25 + 2^-50, 0, 0) is just past eps from vertex 1: a new vertex.
     * (0.6, 0.1, 0) is within eps of vertex 2 only. */
    double b_pos[9] = {0.25, 0, 0, 1.25 + ldexp(1, -50), 0, 0, 0.6, 0.1, 0};
    mt_face_list b = {3, 1, 3, b_pos, sizes, idx};
    CHECK_OK(mt_map_put(map, key3(1, 0, 0), &b, NULL, &delta, NULL));
    CHECK_EQ(delta.num_verts_added, 1);
    uint32_t v;
    CHECK_OK(mt_map_block_vert(map, key3(1, 0, 0), 0, &v));
    CHECK_EQ(v, 0);
    CHECK_OK(mt_map_block_vert(map, key3(1, 0, 0), 1, &v));
    CHECK_EQ(v, 3);
    CHECK_OK(mt_map_block_vert(map, key3(1, 0, 0), 2, &v));
    CHECK_EQ(v, 2);
    /* A map vertex keeps the position it was made with. */
    const double *p = mt_map_vert_position(map, 0);
    CHECK(p != NULL && p[0] == 0.0);
    /* Inside one block: the second copy merges into the first. */
    double c_pos[9] = {5, 5, 5, 5.1, 5, 5, 5, 5.2, 5};
    mt_face_list c = {3, 1, 3, c_pos, sizes, idx};
    CHECK_OK(mt_map_put(map, key3(2, 0, 0), &c, NULL, &delta, NULL));
    CHECK_EQ(delta.num_verts_added, 1);
    /* NaN and infinity never weld. */
    double n_pos[9] = {NAN, 0, 0, NAN, 0, 0, INFINITY, 0, 0};
    mt_face_list n = {3, 1, 3, n_pos, sizes, idx};
    CHECK_OK(mt_map_put(map, key3(3, 0, 0), &n, NULL, &delta, NULL));
    CHECK_EQ(delta.num_verts_added, 3);
    CHECK_EQ(map_check_full(map, "eps rules"), 0);
    /* After block 0 goes, vertices 0 and 2 live on (block 1 holds them) at
     * their first positions; a new copy near vertex 1's old place finds
     * vertex 3's position too far and makes a vertex of its own. */
    CHECK_OK(mt_map_remove(map, key3(0, 0, 0), &delta, NULL));
    CHECK_EQ(delta.num_verts_removed, 1); /* vertex 1 */
    double e_pos[9] = {1.0, 0, 0, 0.1, 0, 0, 0.6, 0.2, 0};
    mt_face_list e = {3, 1, 3, e_pos, sizes, idx};
    CHECK_OK(mt_map_put(map, key3(0, 0, 0), &e, NULL, &delta, NULL));
    CHECK_EQ(delta.num_verts_added, 1);
    CHECK_OK(mt_map_block_vert(map, key3(0, 0, 0), 1, &v));
    CHECK_EQ(v, 0);
    CHECK_OK(mt_map_block_vert(map, key3(0, 0, 0), 2, &v));
    CHECK_EQ(v, 2);
    CHECK_EQ(map_check_full(map, "eps rules after a removal"), 0);
    mt_map_destroy(map);
}

/* Without removals the map is mt_face_list_weld(eps) of the blocks in put
 * order, bit for bit: seams jittered well inside eps, and jitter that makes
 * copies straddle eps and weld into neighbours (order decides there). */
static void test_map_eps_equals_weld(void)
{
    mt_face_list grid, torus;
    CHECK_OK(mt_gen_grid(16, 12, true, &grid));
    CHECK_OK(mt_gen_torus(20, 10, &torus));
    const struct {
        const char *what;
        const mt_face_list *mesh;
        double size, eps, noise;
        bool soup;
    } cases[] = {
        {"grid, seams jittered inside eps", &grid, 4.0, 1e-3, 2.5e-4, false},
        {"grid soup, jittered inside eps", &grid, 3.0, 1e-3, 2.5e-4, true},
        {"grid, copies straddle eps", &grid, 4.0, 0.6, 0.2, false},
        {"grid soup, copies straddle eps", &grid, 2.0, 0.5, 0.2, true},
        {"torus, jittered", &torus, 0.5, 0.02, 0.006, false},
        {"torus soup, coarse eps", &torus, 0.5, 0.3, 0.05, true},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        map_block_set set;
        map_split(cases[i].mesh, cases[i].size, cases[i].soup, &set);
        jitter(&set, cases[i].noise, 0x1234 + i);
        check_puts_equal_weld(cases[i].what, &set, cases[i].eps);
        map_block_set_free(&set);
    }
    mt_face_list_free(&grid);
    mt_face_list_free(&torus);
}

/* The guarantees after any sequence: every finite block vertex within eps of
 * its map vertex, live finite map vertices pairwise more than eps apart. */
static int check_guarantees(const mt_map *map, const map_block_set *set, const bool *in, double eps,
                            const char *what)
{
    int bad = 0;
    for (size_t b = 0; b < set->count && !bad; b++) {
        if (!in[b]) continue;
        const mt_face_list *l = &set->blocks[b].list;
        for (uint32_t u = 0; u < l->num_verts && !bad; u++) {
            const double *x = &l->positions[3 * (size_t)u];
            if (!(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]))) continue;
            uint32_t v = MT_NONE;
            CHECK_OK(mt_map_block_vert(map, set->blocks[b].key, u, &v));
            const double *p = mt_map_vert_position(map, v);
            const double d = p ? sqrt((x[0] - p[0]) * (x[0] - p[0]) +
                                      (x[1] - p[1]) * (x[1] - p[1]) + (x[2] - p[2]) * (x[2] - p[2]))
                               : INFINITY;
            if (d > eps * (1 + 1e-12)) {
                mt_test_fail(__FILE__, __LINE__, "%s: block vertex %u is %g from map vertex %u",
                             what, u, d, v);
                bad++;
            }
        }
    }
    uint32_t vend = 0, fend = 0;
    mt_map_id_ends(map, &vend, &fend);
    for (uint32_t a = 0; a < vend && !bad; a++) {
        const double *p = mt_map_vert_position(map, a);
        if (!p || !(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]))) continue;
        for (uint32_t c = a + 1; c < vend && !bad; c++) {
            const double *q = mt_map_vert_position(map, c);
            if (!q || !(isfinite(q[0]) && isfinite(q[1]) && isfinite(q[2]))) continue;
            const double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                  (p[2] - q[2]) * (p[2] - q[2]));
            if (d <= eps * (1 - 1e-12)) {
                mt_test_fail(__FILE__, __LINE__, "%s: live vertices %u and %u are %g apart", what,
                             a, c, d);
                bad++;
            }
        }
    }
    return bad;
}

/* Random puts (fresh jitter each time: a replacement moves the seam),
 * removals, clears and compactions, with seams duplicated per block and
 * with a vertex per face corner (copies inside a block weld too). */
static void run_random(bool soup, uint64_t rng)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(12, 10, true, &grid));
    const double eps = 0.3;
    map_block_set base, cur;
    map_split(&grid, 3.0, soup, &base);
    map_split(&grid, 3.0, soup, &cur);
    bool *in = calloc(base.count, sizeof *in);
    CHECK(in != NULL);
    mt_map *map = eps_map(eps);
    char what[96];
    for (int op = 0; op < 400 && mt_test_failures() == 0; op++) {
        rng = mix(rng + 0x632be59bd9b4e019ull);
        const size_t b = (size_t)(rng % base.count);
        const unsigned kind = (unsigned)((rng >> 20) % 16);
        snprintf(what, sizeof what, "eps random%s op %d (kind %u, block %zu)", soup ? " soup" : "",
                 op, kind, b);
        if (kind < 10) {
            /* A new version: the base block moved by fresh noise up to 0.2. */
            mt_face_list *l = &cur.blocks[b].list;
            const mt_face_list *o = &base.blocks[b].list;
            for (uint32_t i = 0; i < 3 * l->num_verts; i++)
                l->positions[i] = o->positions[i] + 0.2 * unit(rng ^ ((uint64_t)i << 32));
            CHECK_OK(mt_map_put(map, cur.blocks[b].key, l, NULL, NULL, NULL));
            in[b] = true;
        } else if (kind < 14) {
            CHECK_STATUS(mt_map_remove(map, cur.blocks[b].key, NULL, NULL),
                         in[b] ? MT_OK : MT_ERR_NOT_FOUND);
            in[b] = false;
        } else if (kind == 14) {
            CHECK_OK(mt_map_compact(map, NULL, 0, NULL, 0, NULL));
        } else if ((rng >> 40) % 4 == 0) {
            CHECK_OK(mt_map_clear(map, NULL, NULL));
            memset(in, 0, base.count * sizeof *in);
        }
        CHECK_EQ(map_check_full(map, what), 0);
        CHECK_EQ(check_guarantees(map, &cur, in, eps, what), 0);
    }
    mt_map_destroy(map);
    free(in);
    map_block_set_free(&base);
    map_block_set_free(&cur);
    mt_face_list_free(&grid);
}

static void test_map_eps_random(void)
{
    run_random(false, 0x9e3779b97f4a7c15ull);
    run_random(true, 0xda942042e4dd58b5ull);
}

static const mt_test_case cases[] = {
    {"map_eps_options", test_map_eps_options},
    {"map_eps_rules", test_map_eps_rules},
    {"map_eps_equals_weld", test_map_eps_equals_weld},
    {"map_eps_random", test_map_eps_random},
};
const mt_test_table mt_tests_map_eps = {cases, sizeof cases / sizeof cases[0]};
