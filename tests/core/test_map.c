/* Unit tests of the block map (map.h): every error (NULL arguments, weld
 * modes, inconsistent and oversize blocks, unknown blocks, conflicting
 * positions), the welding rules (-0.0, NaN, infinity, per-face vertices),
 * id stability and translation both ways, compaction's maps, clear, bad
 * face records counted as the full build counts them, and fail-after-N
 * allocation runs in which every failing operation must return
 * MT_ERR_NOMEM and leave the map exactly as it was; the comparison with a
 * full build's report (mt_map_compare_report) failing as it should. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "map_split.h"
#include "mesh/mesh_internal.h"
#include "meshtopo/generate.h"
#include "meshtopo/map.h"

static mt_map *new_map(mt_map_weld weld)
{
    mt_map_options opts = {weld, 0.0};
    mt_map *map = NULL;
    CHECK_OK(mt_map_create(&opts, &map, NULL));
    return map;
}

static mt_map_key key3(int x, int y, int z)
{
    mt_map_key k = {x, y, z};
    return k;
}

/* A list over caller arrays (not to be freed). */
static mt_face_list view(uint32_t nv, double *pos, uint32_t nf, uint32_t *sizes, uint64_t ni,
                         uint32_t *idx)
{
    mt_face_list l = {nv, nf, ni, pos, sizes, idx};
    return l;
}

static void check_zero_counts(const mt_map *map)
{
    mt_map_counts c, zero;
    memset(&zero, 0, sizeof zero);
    zero.manifold = zero.consistently_oriented = true; /* as a full build of nothing says */
    mt_map_get_counts(map, &c);
    CHECK(memcmp(&c, &zero, sizeof c) == 0);
}

static void test_map_create_errors(void)
{
    mt_map *map = (mt_map *)&map;
    mt_diag d;
    mt_map_options eps = {MT_MAP_WELD_EPS, 0.0}; /* eps mode needs eps > 0 (test_map_eps.c) */
    CHECK_STATUS(mt_map_create(&eps, &map, &d), MT_ERR_INVALID_ARG);
    CHECK(map == NULL);
    CHECK(strstr(d.message, "MT_MAP_WELD_EPS") != NULL);
    mt_map_options bad = {(mt_map_weld)7, 0.0};
    CHECK_STATUS(mt_map_create(&bad, &map, &d), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_map_create(NULL, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK_OK(mt_map_create(NULL, &map, &d));
    CHECK(map != NULL);
    check_zero_counts(map);
    mt_map_destroy(map);
    mt_map_destroy(NULL);
    /* NULL-safe readers. */
    mt_map_counts c;
    mt_map_get_counts(NULL, &c);
    CHECK_EQ(c.num_faces, 0);
    CHECK(!mt_map_has_block(NULL, key3(0, 0, 0)));
    CHECK(mt_map_vert_position(NULL, 0) == NULL);
    CHECK_EQ(mt_map_memory_bytes(NULL), 0);
    CHECK_STATUS(mt_map_clear(NULL, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_map_compact(NULL, NULL, 0, NULL, 0, &d), MT_ERR_INVALID_ARG);
}

static void test_map_put_errors(void)
{
    mt_map *map = new_map(MT_MAP_WELD_EXACT);
    mt_diag d;
    double pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t sizes[1] = {3}, idx[3] = {0, 1, 2};
    mt_face_list tri = view(3, pos, 1, sizes, 3, idx);
    const mt_map_key k = key3(1, 2, -3);

    CHECK_STATUS(mt_map_put(NULL, k, &tri, NULL, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_map_put(map, k, NULL, NULL, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK(strstr(d.message, "block (1, 2, -3)") != NULL);

    mt_face_list bad = tri;
    bad.num_indices = 4; /* sizes add up to 3 */
    CHECK_STATUS(mt_map_put(map, k, &bad, NULL, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK(strstr(d.message, "block (1, 2, -3)") != NULL);
    bad = tri;
    bad.face_sizes = NULL;
    CHECK_STATUS(mt_map_put(map, k, &bad, NULL, NULL, &d), MT_ERR_INVALID_ARG);
    bad = tri;
    bad.positions = NULL;
    CHECK_STATUS(mt_map_put(map, k, &bad, NULL, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK(strstr(d.message, "positions") != NULL);
    uint32_t ids[3] = {0, 1, 2};
    CHECK_STATUS(mt_map_put(map, k, &tri, ids, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK(strstr(d.message, "vertex ids") != NULL);

    /* Past the limits: refused on the counts alone. */
    bad = tri;
    bad.num_verts = MT_MAP_BLOCK_MAX_VERTS + 1;
    CHECK_STATUS(mt_map_put(map, k, &bad, NULL, NULL, &d), MT_ERR_TOO_LARGE);
    CHECK(strstr(d.message, "block (1, 2, -3)") != NULL);
    CHECK(strstr(d.message, "at most") != NULL);
    bad = tri;
    bad.num_faces = MT_MAP_BLOCK_MAX_FACES + 1;
    CHECK_STATUS(mt_map_put(map, k, &bad, NULL, NULL, &d), MT_ERR_TOO_LARGE);
    bad = tri;
    bad.num_indices = (uint64_t)MT_MAP_BLOCK_MAX_INDICES + 1;
    CHECK_STATUS(mt_map_put(map, k, &bad, NULL, NULL, &d), MT_ERR_TOO_LARGE);
    uint32_t long_sizes[1] = {MT_MAP_BLOCK_MAX_FACE_SIZE + 1};
    uint32_t *long_idx = calloc(MT_MAP_BLOCK_MAX_FACE_SIZE + 1, sizeof *long_idx);
    bad = view(3, pos, 1, long_sizes, MT_MAP_BLOCK_MAX_FACE_SIZE + 1, long_idx);
    CHECK_STATUS(mt_map_put(map, k, &bad, NULL, NULL, &d), MT_ERR_TOO_LARGE);
    CHECK(strstr(d.message, "face 0 has 257 entries") != NULL);
    free(long_idx);
    check_zero_counts(map);
    CHECK(!mt_map_has_block(map, k));

    /* Unknown block. */
    mt_map_delta delta;
    CHECK_STATUS(mt_map_remove(map, k, &delta, &d), MT_ERR_NOT_FOUND);
    CHECK(strstr(d.message, "block (1, 2, -3)") != NULL);
    CHECK_STATUS(mt_map_remove(NULL, k, NULL, &d), MT_ERR_INVALID_ARG);
    uint32_t out;
    CHECK_STATUS(mt_map_block_vert(map, k, 0, &out), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_map_block_face(map, k, 0, &out), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_map_face_origin(map, 0, NULL, NULL), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_map_vert_origin(map, 0, NULL, NULL), MT_ERR_OUT_OF_RANGE);

    /* A good put, then out-of-range locals. */
    CHECK_OK(mt_map_put(map, k, &tri, NULL, &delta, &d));
    CHECK_EQ(d.status, MT_OK);
    CHECK(mt_map_has_block(map, k));
    CHECK_STATUS(mt_map_block_vert(map, k, 3, &out), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_map_block_face(map, k, 1, &out), MT_ERR_OUT_OF_RANGE);
    size_t count = 0;
    CHECK_STATUS(mt_map_face_verts(map, 0, NULL, 0, &count), MT_OK);
    CHECK_EQ(count, 3);
    uint32_t two[2];
    CHECK_STATUS(mt_map_face_verts(map, 0, two, 2, &count), MT_ERR_BUFFER_TOO_SMALL);
    mt_histogram_bin bin;
    CHECK_OK(mt_map_edge_use_histogram(map, NULL, 0, &count));
    CHECK_EQ(count, 1);
    CHECK_OK(mt_map_edge_use_histogram(map, &bin, 1, &count));
    CHECK_EQ(bin.key, 1);
    CHECK_EQ(bin.count, 3);
    mt_map_key keys[1];
    CHECK_OK(mt_map_blocks(map, NULL, 0, &count));
    CHECK_EQ(count, 1);
    CHECK_OK(mt_map_blocks(map, keys, 1, &count));
    CHECK_EQ(keys[0].z, -3);
    mt_face_list list;
    uint32_t few[1];
    CHECK_STATUS(mt_map_face_list(map, &list, few, 1, NULL, 0, &d), MT_ERR_BUFFER_TOO_SMALL);
    uint32_t ends[2];
    CHECK_STATUS(mt_map_compact(map, ends, 1, NULL, 0, &d), MT_ERR_BUFFER_TOO_SMALL);
    mt_map_destroy(map);

    /* None mode needs ids, below the limit, one position per id. */
    map = new_map(MT_MAP_WELD_NONE);
    CHECK_STATUS(mt_map_put(map, k, &tri, NULL, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK(strstr(d.message, "id") != NULL);
    uint32_t huge[3] = {0, MT_MAP_MAX_VERT_ID, 2};
    CHECK_STATUS(mt_map_put(map, k, &tri, huge, NULL, &d), MT_ERR_TOO_LARGE);
    uint32_t same[3] = {4, 4, 5};
    CHECK_STATUS(mt_map_put(map, k, &tri, same, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK(strstr(d.message, "map vertex 4") != NULL);
    check_zero_counts(map);
    mt_map_destroy(map);
}

/* Two triangles in two blocks sharing the seam 1-2 with duplicated seam
 * vertices: one edge of use 2, one map vertex per position. */
static void test_map_weld_rules(void)
{
    mt_map *map = new_map(MT_MAP_WELD_EXACT);
    double a_pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    double b_pos[9] = {1, 0, -0.0, 1, 1, 0, -0.0, 1, 0}; /* -0.0 welds with 0.0 */
    uint32_t sizes[1] = {3}, a_idx[3] = {0, 1, 2}, b_idx[3] = {0, 1, 2};
    mt_face_list a = view(3, a_pos, 1, sizes, 3, a_idx), b = view(3, b_pos, 1, sizes, 3, b_idx);
    mt_map_delta d;
    CHECK_OK(mt_map_put(map, key3(0, 0, 0), &a, NULL, &d, NULL));
    CHECK_EQ(d.op, MT_MAP_OP_PUT_NEW);
    CHECK_EQ(d.num_verts_added, 3);
    CHECK_OK(mt_map_put(map, key3(1, 0, 0), &b, NULL, &d, NULL));
    CHECK_EQ(d.num_verts_added, 1); /* (1, 1, 0) only */
    CHECK_EQ(d.verts_added[0], 3);
    mt_map_counts c;
    mt_map_get_counts(map, &c);
    CHECK_EQ(c.num_verts, 4);
    CHECK_EQ(c.num_edges, 5);
    CHECK_EQ(c.boundary_edges, 4);
    CHECK_EQ(c.euler_characteristic, 1);
    CHECK(c.consistently_oriented);
    CHECK_EQ(map_check_full(map, "two blocks"), 0);
    uint32_t v;
    CHECK_OK(mt_map_block_vert(map, key3(1, 0, 0), 2, &v));
    CHECK_EQ(v, 2);

    /* NaN and infinity never weld: a third block repeating a's corners with
     * a NaN copy of vertex 0 makes a new vertex, and so does infinity. */
    double c_pos[12] = {NAN, 0, 0, 1, 0, 0, 0, 1, 0, INFINITY, 5, 5};
    double d_pos[12] = {NAN, 0, 0, 1, 0, 0, 0, 1, 0, INFINITY, 5, 5};
    uint32_t c_sizes[2] = {3, 3}, c_idx[6] = {0, 1, 2, 3, 1, 2};
    mt_face_list cl = view(4, c_pos, 2, c_sizes, 6, c_idx),
                 dl = view(4, d_pos, 2, c_sizes, 6, c_idx);
    CHECK_OK(mt_map_put(map, key3(2, 0, 0), &cl, NULL, &d, NULL));
    CHECK_EQ(d.num_verts_added, 2);
    CHECK_OK(mt_map_put(map, key3(3, 0, 0), &dl, NULL, &d, NULL));
    CHECK_EQ(d.num_verts_added, 2);
    mt_map_get_counts(map, &c);
    CHECK_EQ(c.num_verts, 8);
    CHECK_EQ(c.nonfinite_vertices, 4);
    CHECK_EQ(map_check_full(map, "NaN blocks"), 0);
    mt_map_destroy(map);

    /* Per-face vertices (voxblox) weld into the grid a full build sees. */
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(6, 5, true, &grid));
    map_block_set soup;
    map_split(&grid, 2.0, true, &soup);
    map = new_map(MT_MAP_WELD_EXACT);
    for (size_t i = 0; i < soup.count; i++)
        CHECK_OK(mt_map_put(map, soup.blocks[i].key, &soup.blocks[i].list, NULL, NULL, NULL));
    mt_map_get_counts(map, &c);
    CHECK_EQ(c.num_verts, grid.num_verts);
    CHECK_EQ(c.num_faces_valid, grid.num_faces);
    CHECK_EQ(c.euler_characteristic, 1);
    CHECK(c.manifold);
    CHECK_EQ(map_check_against_list(map, &grid, "soup vs grid"), 0);
    map_block_set_free(&soup);
    mt_face_list_free(&grid);
    mt_map_destroy(map);
}

/* Bad records are kept and counted as mt_mesh_build counts them. */
static void test_map_bad_faces(void)
{
    mt_map *map = new_map(MT_MAP_WELD_EXACT);
    double pos[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, NAN, 2, 2, 0, 0, 0};
    /* vertex 5 welds with vertex 0: face (0, 1, 5) is degenerate after welding */
    uint32_t sizes[7] = {3, 3, 3, 2, 0, 4, 3};
    uint32_t idx[18] = {0, 1, 2, 1, 3, 2, 0, 9, 9, 1, 2, 0, 1, 77, 78, 0, 1, 5};
    mt_face_list l = view(6, pos, 7, sizes, 18, idx);
    mt_map_delta d;
    CHECK_OK(mt_map_put(map, key3(0, 0, 0), &l, NULL, &d, NULL));
    mt_map_counts c;
    mt_map_get_counts(map, &c);
    CHECK_EQ(c.num_verts, 5);
    CHECK_EQ(c.num_faces, 7);
    CHECK_EQ(c.num_faces_valid, 2);
    CHECK_EQ(c.degenerate_faces, 4);
    CHECK_EQ(c.out_of_range_indices, 4);
    CHECK_EQ(c.faces_with_out_of_range_indices, 2);
    CHECK_EQ(c.nonfinite_vertices, 1);
    CHECK_EQ(c.isolated_vertices, 1);
    CHECK_EQ(c.unreferenced_vertices, 1);
    CHECK_EQ(map_check_full(map, "bad faces"), 0);
    uint32_t corners[4];
    size_t n;
    CHECK_OK(mt_map_face_verts(map, d.faces_added[5], corners, 4, &n));
    CHECK_EQ(n, 4);
    CHECK_EQ(corners[2], MT_NONE);
    /* The map's face list writes 77, 78 as two distinct out-of-range values. */
    mt_face_list out;
    CHECK_OK(mt_map_face_list(map, &out, NULL, 0, NULL, 0, NULL));
    CHECK_EQ(out.face_indices[13], MT_NONE);
    CHECK_EQ(out.face_indices[14], MT_NONE - 1);
    CHECK_EQ(out.face_indices[7], out.face_indices[8]);
    mt_face_list_free(&out);
    /* Removing the block takes everything. */
    CHECK_OK(mt_map_remove(map, key3(0, 0, 0), &d, NULL));
    CHECK_EQ(d.num_verts_removed, 5);
    CHECK_EQ(d.num_faces_removed, 7);
    check_zero_counts(map);
    /* An empty block, and one of two vertices at one position and no face. */
    mt_face_list empty = view(0, NULL, 0, NULL, 0, NULL);
    CHECK_OK(mt_map_put(map, key3(5, 5, 5), &empty, NULL, &d, NULL));
    mt_map_get_counts(map, &c);
    CHECK_EQ(c.num_blocks, 1);
    CHECK_EQ(c.num_verts + c.num_faces, 0);
    double twice[6] = {3, 3, 3, 3, 3, 3};
    mt_face_list lonely = view(2, twice, 0, NULL, 0, NULL);
    CHECK_OK(mt_map_put(map, key3(5, 5, 6), &lonely, NULL, &d, NULL));
    mt_map_get_counts(map, &c);
    CHECK_EQ(c.num_blocks, 2);
    CHECK_EQ(c.num_verts, 1);
    CHECK_EQ(c.isolated_vertices, 1);
    CHECK_EQ(c.unreferenced_vertices, 1);
    CHECK_EQ(c.euler_characteristic, 1);
    CHECK_EQ(map_check_full(map, "empty and lonely blocks"), 0);
    CHECK_OK(mt_map_remove(map, key3(5, 5, 5), &d, NULL));
    CHECK_OK(mt_map_remove(map, key3(5, 5, 6), &d, NULL));
    CHECK_EQ(d.num_verts_removed, 1);
    check_zero_counts(map);
    mt_map_destroy(map);
}

/* A grid in four blocks: ids stay while their elements exist, are not given
 * again before a compaction, translate both ways, and compaction's maps
 * carry them. */
static void test_map_ids(void)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(8, 8, true, &grid));
    map_block_set set;
    map_split(&grid, 4.0, false, &set);
    CHECK_EQ(set.count, 4);
    mt_map *map = new_map(MT_MAP_WELD_EXACT);
    uint32_t faces[4][64], verts[4][64];
    for (size_t b = 0; b < 4; b++) {
        mt_map_delta d;
        CHECK_OK(mt_map_put(map, set.blocks[b].key, &set.blocks[b].list, NULL, &d, NULL));
        CHECK_EQ(d.num_faces_added, 32);
        for (uint32_t f = 0; f < 32; f++) faces[b][f] = d.faces_added[f];
        for (uint32_t u = 0; u < set.blocks[b].list.num_verts; u++)
            CHECK_OK(mt_map_block_vert(map, set.blocks[b].key, u, &verts[b][u]));
    }
    CHECK_EQ(map_check_against_list(map, &grid, "four blocks"), 0);
    /* The centre vertex (4, 4) is in all four blocks; remove its origin's
     * block and it keeps its id with another origin. */
    const double centre[3] = {4, 4, 0};
    uint32_t vc = MT_NONE;
    for (uint32_t u = 0; u < set.blocks[0].list.num_verts; u++)
        if (memcmp(&set.blocks[0].list.positions[3 * u], centre, sizeof centre) == 0)
            vc = verts[0][u];
    CHECK(vc != MT_NONE);
    mt_map_key origin;
    uint32_t local;
    CHECK_OK(mt_map_vert_origin(map, vc, &origin, &local));
    size_t ob = 0;
    while (ob < 4 && memcmp(&set.blocks[ob].key, &origin, sizeof origin) != 0) ob++;
    CHECK(ob < 4);
    mt_map_delta d;
    CHECK_OK(mt_map_remove(map, origin, &d, NULL));
    CHECK_EQ(d.num_faces_removed, 32);
    mt_map_key now;
    CHECK_OK(mt_map_vert_origin(map, vc, &now, &local));
    CHECK(memcmp(&now, &origin, sizeof now) != 0);
    uint32_t back;
    CHECK_OK(mt_map_block_vert(map, now, local, &back));
    CHECK_EQ(back, vc);
    CHECK(mt_map_vert_position(map, vc) != NULL);
    for (uint32_t f = 0; f < 32; f++)
        CHECK_STATUS(mt_map_face_origin(map, faces[ob][f], NULL, NULL), MT_ERR_NOT_FOUND);
    /* The others kept their ids. */
    for (size_t b = 0; b < 4; b++) {
        if (b == ob) continue;
        for (uint32_t f = 0; f < 32; f++) {
            uint32_t id;
            CHECK_OK(mt_map_block_face(map, set.blocks[b].key, f, &id));
            CHECK_EQ(id, faces[b][f]);
        }
    }
    /* Put back: new ids, none reused before compaction. */
    uint32_t vend, fend;
    mt_map_id_ends(map, &vend, &fend);
    CHECK_EQ(fend, 128);
    CHECK_OK(mt_map_put(map, set.blocks[ob].key, &set.blocks[ob].list, NULL, &d, NULL));
    CHECK_EQ(d.faces_added[0], 128);
    CHECK_EQ(map_check_against_list(map, &grid, "put back"), 0);
    /* Replace with the same content: vertices keep their ids, faces are new. */
    CHECK_OK(mt_map_put(map, set.blocks[ob].key, &set.blocks[ob].list, NULL, &d, NULL));
    CHECK_EQ(d.op, MT_MAP_OP_REPLACE);
    CHECK_EQ(d.num_verts_added, 0);
    CHECK_EQ(d.num_verts_removed, 0);
    CHECK_EQ(d.faces_removed[0], 128);
    CHECK_EQ(d.faces_added[0], 160);
    CHECK_EQ(d.before.num_edges, d.after.num_edges);
    /* Compaction: dense ids, maps old -> new. */
    mt_map_id_ends(map, &vend, &fend);
    CHECK_EQ(fend, 192);
    uint32_t vmap[256], fmap[256];
    CHECK_OK(mt_map_compact(map, vmap, 256, fmap, 256, NULL));
    for (uint32_t f = 0; f < 128; f++) CHECK_EQ(fmap[f] == MT_NONE, f / 32 == ob);
    for (uint32_t f = 128; f < 160; f++) CHECK_EQ(fmap[f], MT_NONE);
    for (uint32_t f = 160; f < 192; f++) CHECK_EQ(fmap[f], 96 + f - 160);
    mt_map_id_ends(map, &vend, &fend);
    CHECK_EQ(fend, 128);
    CHECK_EQ(vend, grid.num_verts);
    for (size_t b = 0; b < 4; b++) {
        if (b == ob) continue;
        for (uint32_t f = 0; f < 32; f++) {
            uint32_t id;
            mt_map_key k;
            CHECK_OK(mt_map_block_face(map, set.blocks[b].key, f, &id));
            CHECK_EQ(id, fmap[faces[b][f]]);
            CHECK_OK(mt_map_face_origin(map, id, &k, &local));
            CHECK_EQ(local, f);
        }
        for (uint32_t u = 0; u < set.blocks[b].list.num_verts; u++) {
            uint32_t id;
            CHECK_OK(mt_map_block_vert(map, set.blocks[b].key, u, &id));
            CHECK_EQ(id, vmap[verts[b][u]]);
        }
    }
    CHECK_EQ(map_check_full(map, "compacted"), 0);
    /* New ids continue densely after a compaction. */
    CHECK_OK(mt_map_remove(map, set.blocks[ob].key, NULL, NULL));
    CHECK_OK(mt_map_put(map, set.blocks[ob].key, &set.blocks[ob].list, NULL, &d, NULL));
    CHECK_EQ(d.faces_added[0], 128);
    /* Clear: empty, ids from 0 again. */
    CHECK_OK(mt_map_clear(map, &d, NULL));
    CHECK(d.all_removed);
    CHECK_EQ(d.before.num_faces, 128);
    check_zero_counts(map);
    mt_map_id_ends(map, &vend, &fend);
    CHECK_EQ(vend + fend, 0);
    CHECK_OK(mt_map_put(map, set.blocks[0].key, &set.blocks[0].list, NULL, &d, NULL));
    CHECK_EQ(d.faces_added[0], 0);
    CHECK_EQ(map_check_full(map, "after clear"), 0);
    mt_map_destroy(map);
    map_block_set_free(&set);
    mt_face_list_free(&grid);
}

/* None mode: the sender's ids; one position per id; compaction keeps them. */
static void test_map_none_mode(void)
{
    mt_map *map = new_map(MT_MAP_WELD_NONE);
    double a_pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, b_pos[9] = {1, 0, 0, 1, 1, 0, 0, 1, 0};
    uint32_t sizes[1] = {3}, idx[3] = {0, 1, 2};
    uint32_t a_ids[3] = {10, 11, 12}, b_ids[3] = {11, 13, 12};
    mt_face_list a = view(3, a_pos, 1, sizes, 3, idx), b = view(3, b_pos, 1, sizes, 3, idx);
    mt_map_delta d;
    mt_diag diag;
    CHECK_OK(mt_map_put(map, key3(0, 0, 0), &a, a_ids, &d, &diag));
    CHECK_EQ(d.num_verts_added, 3);
    CHECK_EQ(d.verts_added[0], 10);
    CHECK_OK(mt_map_put(map, key3(1, 0, 0), &b, b_ids, &d, &diag));
    mt_map_counts c;
    mt_map_get_counts(map, &c);
    CHECK_EQ(c.num_verts, 4);
    CHECK_EQ(c.num_edges, 5);
    CHECK_EQ(map_check_full(map, "none mode"), 0);
    /* Same position as a value: -0.0 is accepted. */
    double b2_pos[9] = {1, -0.0, 0, 1, 1, 0, 0, 1, 0};
    mt_face_list b2 = view(3, b2_pos, 1, sizes, 3, idx);
    CHECK_OK(mt_map_put(map, key3(1, 0, 0), &b2, b_ids, &d, &diag));
    /* Another position for vertex 11, which block (0, 0, 0) holds: refused. */
    double b3_pos[9] = {1, 0.5, 0, 1, 1, 0, 0, 1, 0};
    mt_face_list b3 = view(3, b3_pos, 1, sizes, 3, idx);
    CHECK_STATUS(mt_map_put(map, key3(1, 0, 0), &b3, b_ids, &d, &diag), MT_ERR_INVALID_ARG);
    CHECK(strstr(diag.message, "block (1, 0, 0)") != NULL);
    CHECK(strstr(diag.message, "map vertex 11") != NULL);
    mt_map_counts after;
    mt_map_get_counts(map, &after);
    CHECK(memcmp(&c, &after, sizeof c) == 0);
    /* Vertex 13 is only block (1, 0, 0)'s: a new version may move it. */
    double b4_pos[9] = {1, 0, 0, 7, 7, 7, 0, 1, 0};
    mt_face_list b4 = view(3, b4_pos, 1, sizes, 3, idx);
    CHECK_OK(mt_map_put(map, key3(1, 0, 0), &b4, b_ids, &d, &diag));
    CHECK_EQ(mt_map_vert_position(map, 13)[0], 7.0);
    CHECK_EQ(map_check_full(map, "moved"), 0);
    /* Compaction keeps the sender's vertex ids. */
    uint32_t vmap[14], fmap[8];
    CHECK_OK(mt_map_compact(map, vmap, 14, fmap, 8, NULL));
    CHECK_EQ(vmap[10], 10);
    CHECK_EQ(vmap[13], 13);
    CHECK_EQ(vmap[0], MT_NONE);
    uint32_t v;
    CHECK_OK(mt_map_block_vert(map, key3(1, 0, 0), 1, &v));
    CHECK_EQ(v, 13);
    CHECK_EQ(map_check_full(map, "none compacted"), 0);
    mt_map_destroy(map);
}

/* ---- fail-after-N ----------------------------------------------------------- */

/* Everything observable of a map, to compare before and after a failure. */
typedef struct snapshot {
    mt_map_counts counts;
    uint32_t vend, fend;
    mt_face_list list;
    uint32_t *vids, *fids;
} snapshot;

static void take(const mt_map *map, snapshot *s)
{
    mt_map_get_counts(map, &s->counts);
    mt_map_id_ends(map, &s->vend, &s->fend);
    s->vids = malloc((size_t)(s->counts.num_verts + 1) * sizeof(uint32_t));
    s->fids = malloc((size_t)(s->counts.num_faces + 1) * sizeof(uint32_t));
    CHECK_OK(mt_map_face_list(map, &s->list, s->vids, s->counts.num_verts, s->fids,
                              s->counts.num_faces, NULL));
}

static void drop(snapshot *s)
{
    mt_face_list_free(&s->list);
    free(s->vids);
    free(s->fids);
}

static bool same(const snapshot *a, const snapshot *b)
{
    const mt_face_list *x = &a->list, *y = &b->list;
    return memcmp(&a->counts, &b->counts, sizeof a->counts) == 0 && a->vend == b->vend &&
           a->fend == b->fend && x->num_indices == y->num_indices &&
           memcmp(x->positions, y->positions, (size_t)x->num_verts * 3 * sizeof(double)) == 0 &&
           memcmp(x->face_sizes, y->face_sizes, (size_t)x->num_faces * sizeof(uint32_t)) == 0 &&
           memcmp(x->face_indices, y->face_indices, (size_t)x->num_indices * sizeof(uint32_t)) ==
               0 &&
           memcmp(a->vids, b->vids, (size_t)a->counts.num_verts * sizeof(uint32_t)) == 0 &&
           memcmp(a->fids, b->fids, (size_t)a->counts.num_faces * sizeof(uint32_t)) == 0;
}

typedef enum { OP_PUT, OP_REMOVE, OP_COMPACT } op_kind;

/* Runs one operation with the Nth allocation failing, for N = 0, 1, ...
 * until it succeeds; each failure must leave the map as it was. */
static void fail_until_done(mt_map *map, op_kind kind, mt_map_key key, const mt_face_list *list,
                            int *failures)
{
    snapshot before, after;
    take(map, &before);
    for (long n = 0; n < 10000; n++) {
        mt_diag d;
        mt_map_delta delta;
        mt__test_fail_alloc_after(n);
        mt_status s = kind == OP_PUT      ? mt_map_put(map, key, list, NULL, &delta, &d)
                      : kind == OP_REMOVE ? mt_map_remove(map, key, &delta, &d)
                                          : mt_map_compact(map, NULL, 0, NULL, 0, &d);
        mt__test_fail_alloc_after(-1);
        if (s == MT_OK) break;
        (*failures)++;
        CHECK_EQ(s, MT_ERR_NOMEM);
        CHECK(strstr(d.message, "memory") != NULL);
        if (kind != OP_COMPACT) CHECK(strstr(d.message, "block (") != NULL);
        take(map, &after);
        const bool unchanged = same(&before, &after);
        drop(&after);
        if (!unchanged) {
            mt_test_fail(__FILE__, __LINE__, "op %d failing at allocation %ld changed the map",
                         (int)kind, n);
            break;
        }
    }
    drop(&before);
}

static void test_map_fail_after_n(void)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(10, 10, true, &grid));
    map_block_set set;
    map_split(&grid, 3.0, false, &set);
    mt_map *map = new_map(MT_MAP_WELD_EXACT);
    int failures = 0;
    for (size_t b = 0; b < set.count; b++)
        fail_until_done(map, OP_PUT, set.blocks[b].key, &set.blocks[b].list, &failures);
    CHECK_EQ(map_check_against_list(map, &grid, "fail-after-N puts"), 0);
    /* Replacements with defects (a fin, a NaN, a bad record), removals,
     * compaction. */
    double pos[15] = {1, 1, 0, 2, 1, 0, 1.5, 1.5, 2, NAN, 0, 0, 1, 2, 0};
    uint32_t sizes[4] = {3, 3, 3, 4}, idx[13] = {0, 1, 2, 0, 3, 4, 1, 0, 2, 0, 9, 9, 4};
    mt_face_list odd = {5, 4, 13, pos, sizes, idx};
    fail_until_done(map, OP_PUT, set.blocks[0].key, &odd, &failures);
    fail_until_done(map, OP_PUT, set.blocks[1].key, &set.blocks[0].list, &failures);
    fail_until_done(map, OP_REMOVE, set.blocks[2].key, NULL, &failures);
    fail_until_done(map, OP_COMPACT, set.blocks[0].key, NULL, &failures);
    fail_until_done(map, OP_PUT, set.blocks[2].key, &set.blocks[2].list, &failures);
    printf("%d failing allocations, each leaving the map unchanged\n", failures);
    CHECK(failures > 40);
    CHECK_EQ(map_check_full(map, "after fail-after-N"), 0);
    /* mt_map_face_list fails cleanly too. */
    mt_face_list out;
    mt__test_fail_alloc_after(0);
    CHECK_STATUS(mt_map_face_list(map, &out, NULL, 0, NULL, 0, NULL), MT_ERR_NOMEM);
    mt__test_fail_alloc_after(-1);
    CHECK(out.positions == NULL);
    mt_map_destroy(map);
    /* And creation. */
    mt__test_fail_alloc_after(0);
    CHECK_STATUS(mt_map_create(NULL, &map, NULL), MT_ERR_NOMEM);
    mt__test_fail_alloc_after(-1);
    CHECK(map == NULL);
    map_block_set_free(&set);
    mt_face_list_free(&grid);
}

/* The same in eps mode (test_map_eps.c has the rest): the spatial hash's
 * allocations fail cleanly too. */
static void test_map_eps_fail_after_n(void)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(8, 8, true, &grid));
    map_block_set set;
    map_split(&grid, 3.0, true, &set); /* a vertex per corner: copies weld within the put */
    mt_map_options opts = {MT_MAP_WELD_EPS, 0.25};
    mt_map *map = NULL;
    CHECK_OK(mt_map_create(&opts, &map, NULL));
    int failures = 0;
    for (size_t b = 0; b < set.count; b++)
        fail_until_done(map, OP_PUT, set.blocks[b].key, &set.blocks[b].list, &failures);
    CHECK_EQ(map_check_against_list(map, &grid, "eps fail-after-N puts"), 0);
    fail_until_done(map, OP_PUT, set.blocks[1].key, &set.blocks[0].list, &failures);
    fail_until_done(map, OP_REMOVE, set.blocks[2].key, NULL, &failures);
    fail_until_done(map, OP_COMPACT, set.blocks[0].key, NULL, &failures);
    fail_until_done(map, OP_PUT, set.blocks[2].key, &set.blocks[2].list, &failures);
    CHECK(failures > 20);
    CHECK_EQ(map_check_full(map, "after eps fail-after-N"), 0);
    mt_map_destroy(map);
    map_block_set_free(&set);
    mt_face_list_free(&grid);
}

/* mt_map_compare_report: equal to the report of its own union, and every
 * difference named with both values against another mesh's report or an
 * altered one, the message cut safely when it runs long. */
static void test_map_compare_report(void)
{
    mt_face_list tris, quads;
    CHECK_OK(mt_gen_grid(3, 2, true, &tris));
    CHECK_OK(mt_gen_grid(3, 2, false, &quads));
    mt_map *map = new_map(MT_MAP_WELD_EXACT);
    CHECK_OK(mt_map_put(map, key3(0, 0, 0), &tris, NULL, NULL, NULL));
    mt_build_options opts;
    memset(&opts, 0, sizeof opts);
    mt_mesh *same = NULL, *other = NULL;
    CHECK_OK(mt_mesh_build(&tris, &opts, &same, NULL));
    CHECK_OK(mt_mesh_build(&quads, &opts, &other, NULL));
    if (!same || !other) goto done;
    mt_diag d;
    CHECK_OK(mt_map_compare_report(map, mt_mesh_report(same), &d));
    CHECK_EQ(d.message[0], '\0');

    /* The same vertices as quads: fewer faces and edges, other histograms. */
    CHECK_STATUS(mt_map_compare_report(map, mt_mesh_report(other), &d), MT_ERR_CORRUPT);
    CHECK_EQ(d.status, MT_ERR_CORRUPT);
    CHECK(strstr(d.message, "num_faces map 12, build 6") != NULL);
    CHECK(strstr(d.message, "num_edges map 23, build 17") != NULL);
    CHECK(strstr(d.message, "face_size_histogram map {3:12}, build {4:6}") != NULL);
    CHECK(strstr(d.message, "num_verts") == NULL); /* only what differs */
    CHECK_STATUS(mt_map_compare_report(map, mt_mesh_report(other), NULL), MT_ERR_CORRUPT);

    /* One count and one flag altered: exactly those two, in counts order. */
    mt_report r = *mt_mesh_report(same);
    r.nonmanifold_edges = 1;
    r.manifold = false;
    CHECK_STATUS(mt_map_compare_report(map, &r, &d), MT_ERR_CORRUPT);
    CHECK(strcmp(d.message, "nonmanifold_edges map 0, build 1; manifold map 1, build 0") == 0);

    /* A histogram too long for the message: cut, NUL-terminated, "...". */
    mt_histogram_bin bins[300];
    for (uint32_t i = 0; i < 300; i++) bins[i].key = 3 + i, bins[i].count = 1000000 + i;
    r = *mt_mesh_report(same);
    r.face_size_histogram = bins;
    r.num_face_size_bins = 300;
    CHECK_STATUS(mt_map_compare_report(map, &r, &d), MT_ERR_CORRUPT);
    const size_t len = strlen(d.message);
    CHECK_EQ(len, sizeof d.message - 1);
    CHECK(strncmp(d.message, "face_size_histogram map {3:12}, build {3:1000000 4:", 51) == 0);
    CHECK(len >= 3 && strcmp(d.message + len - 3, "...") == 0);

    CHECK_STATUS(mt_map_compare_report(NULL, &r, &d), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_map_compare_report(map, NULL, &d), MT_ERR_INVALID_ARG);
done:
    mt_mesh_destroy(same);
    mt_mesh_destroy(other);
    mt_map_destroy(map);
    mt_face_list_free(&tris);
    mt_face_list_free(&quads);
}

static const mt_test_case cases[] = {
    {"map_create_errors", test_map_create_errors},
    {"map_put_errors", test_map_put_errors},
    {"map_weld_rules", test_map_weld_rules},
    {"map_bad_faces", test_map_bad_faces},
    {"map_ids", test_map_ids},
    {"map_none_mode", test_map_none_mode},
    {"map_fail_after_n", test_map_fail_after_n},
    {"map_eps_fail_after_n", test_map_eps_fail_after_n},
    {"map_compare_report", test_map_compare_report},
};
const mt_test_table mt_tests_map = {cases, sizeof cases / sizeof cases[0]};
