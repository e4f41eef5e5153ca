/* The block map's adjacency queries (map.h: mt_map_vert_ring,
 * mt_map_face_neighbors, mt_map_edge_faces) on hand-made maps: a hub vertex
 * of high valence (the build heap-sorts its sides) with fins on one of its
 * edges in another block, and every refusal.
 * The randomised runs of test_map_random.c compare samples of the same
 * queries after every operation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "map_split.h"
#include "meshtopo/map.h"

#define RIM 40u                /* rim vertices around the hub */
#define TURN 6.283185307179586 /* a full turn, in radians */
#define FINS 5u                /* extra triangles on the edge hub - rim vertex 1 */

static mt_map *exact_map(void)
{
    mt_map_options opts = {MT_MAP_WELD_EXACT, 0.0};
    mt_map *map = NULL;
    CHECK_OK(mt_map_create(&opts, &map, NULL));
    return map;
}

static void put_point(double *pos, uint32_t v, double x, double y, double z)
{
    pos[3 * v] = x;
    pos[3 * v + 1] = y;
    pos[3 * v + 2] = z;
}

/* The hub disk: vertex 0 at the centre, 1..RIM on the rim, RIM triangles
 * (0, i, i+1). */
static mt_face_list hub_block(void)
{
    mt_face_list l;
    CHECK_OK(mt_face_list_alloc(&l, RIM + 1, RIM, 3 * RIM, NULL));
    put_point(l.positions, 0, 0, 0, 0);
    for (uint32_t i = 1; i <= RIM; i++) {
        const double a = TURN * (i - 1) / RIM;
        put_point(l.positions, i, cos(a), sin(a), 0);
    }
    for (uint32_t f = 0; f < RIM; f++) {
        l.face_sizes[f] = 3;
        l.face_indices[3 * f] = 0;
        l.face_indices[3 * f + 1] = 1 + f;
        l.face_indices[3 * f + 2] = 1 + (f + 1) % RIM;
    }
    return l;
}

/* Fins on the hub's edge to rim vertex 1, alternating direction: its own
 * copies of the hub and of vertex 1 (welded by position) and a tip each. */
static mt_face_list fin_block(void)
{
    mt_face_list l;
    CHECK_OK(mt_face_list_alloc(&l, 2 + FINS, FINS, 3 * FINS, NULL));
    put_point(l.positions, 0, 0, 0, 0);
    put_point(l.positions, 1, 1, 0, 0);
    for (uint32_t k = 0; k < FINS; k++) {
        put_point(l.positions, 2 + k, 0.5, 0.1 * k, 1 + k);
        l.face_sizes[k] = 3;
        l.face_indices[3 * k] = k % 2 ? 1 : 0;
        l.face_indices[3 * k + 1] = k % 2 ? 0 : 1;
        l.face_indices[3 * k + 2] = 2 + k;
    }
    return l;
}

static void test_map_query_fins_at_hub(void)
{
    mt_map *map = exact_map();
    mt_face_list hub = hub_block(), fins = fin_block();
    const mt_map_key hub_key = {0, 0, 0}, fin_key = {1, 0, 0};
    /* Fins first: the hub's sides then come from both blocks, in id order. */
    CHECK_OK(mt_map_put(map, fin_key, &fins, NULL, NULL, NULL));
    CHECK_OK(mt_map_put(map, hub_key, &hub, NULL, NULL, NULL));
    CHECK_EQ(map_check_queries(map, "fins, then the hub", 1, 1000), 0);

    /* The edge hub - 1 has the disk's two faces and every fin. */
    uint32_t hub_v = MT_NONE, rim_v = MT_NONE, faces[16];
    size_t n = 0;
    CHECK_OK(mt_map_block_vert(map, hub_key, 0, &hub_v));
    CHECK_OK(mt_map_block_vert(map, hub_key, 1, &rim_v));
    CHECK_OK(mt_map_edge_faces(map, hub_v, rim_v, faces, 16, &n, NULL));
    CHECK_EQ(n, 2 + FINS);

    /* Without the fins, and with them again after the hub. */
    CHECK_OK(mt_map_remove(map, fin_key, NULL, NULL));
    CHECK_EQ(map_check_queries(map, "the hub alone", 2, 1000), 0);
    CHECK_OK(mt_map_edge_faces(map, hub_v, rim_v, faces, 16, &n, NULL));
    CHECK_EQ(n, 2);
    CHECK_OK(mt_map_put(map, fin_key, &fins, NULL, NULL, NULL));
    CHECK_EQ(map_check_queries(map, "the hub, then fins", 3, 1000), 0);

    mt_face_list_free(&hub);
    mt_face_list_free(&fins);
    mt_map_destroy(map);
}

static void test_map_query_refusals(void)
{
    mt_map *map = exact_map();
    mt_face_list hub = hub_block();
    const mt_map_key key = {0, 0, 0};
    CHECK_OK(mt_map_put(map, key, &hub, NULL, NULL, NULL));
    uint32_t hub_v = MT_NONE, rim_v = MT_NONE, face = MT_NONE;
    CHECK_OK(mt_map_block_vert(map, key, 0, &hub_v));
    CHECK_OK(mt_map_block_vert(map, key, 1, &rim_v));
    CHECK_OK(mt_map_block_face(map, key, 0, &face));

    uint32_t nbr[64], fcs[64], offs[8];
    mt_fan fans[4];
    mt_ring ring = {nbr, 64, fcs, 64, fans, 4, 0, 0, 0};
    mt_diag d;
    size_t nf = 0, ne = 0, n = 0;
    CHECK_STATUS(mt_map_vert_ring(NULL, hub_v, &ring, &d), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_map_vert_ring(map, hub_v, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_map_vert_ring(map, RIM + 1, &ring, &d), MT_ERR_OUT_OF_RANGE);
    CHECK(strstr(d.message, "no live vertex 41") != NULL);
    CHECK_STATUS(mt_map_face_neighbors(map, RIM, fcs, 64, offs, 8, &nf, &ne, &d),
                 MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_map_face_neighbors(map, face, fcs, 64, offs, 8, NULL, &ne, &d),
                 MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_map_edge_faces(map, hub_v, RIM + 7, fcs, 64, &n, &d), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_map_edge_faces(map, hub_v, hub_v, fcs, 64, &n, &d), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_map_edge_faces(map, hub_v, rim_v, fcs, 64, NULL, &d), MT_ERR_INVALID_ARG);

    /* The hub's ring: one closed fan of RIM faces; too small a buffer is
     * refused as the mesh query refuses it. */
    CHECK_OK(mt_map_vert_ring(map, hub_v, &ring, &d));
    CHECK_EQ(ring.num_fans, 1);
    CHECK_EQ(ring.num_faces, RIM);
    CHECK(!ring.fans[0].boundary);
    mt_ring small = {nbr, 8, fcs, 8, fans, 4, 0, 0, 0};
    CHECK_STATUS(mt_map_vert_ring(map, hub_v, &small, &d), MT_ERR_BUFFER_TOO_SMALL);
    /* A rim face: a neighbour across two of its sides, none across the rim. */
    CHECK_OK(mt_map_face_neighbors(map, face, fcs, 64, offs, 8, &nf, &ne, &d));
    CHECK_EQ(ne, 3);
    CHECK_EQ(nf, 2);
    CHECK_STATUS(mt_map_face_neighbors(map, face, fcs, 1, offs, 8, &nf, &ne, &d),
                 MT_ERR_BUFFER_TOO_SMALL);

    /* A removed block's vertices and faces are gone. */
    CHECK_OK(mt_map_remove(map, key, NULL, NULL));
    CHECK_STATUS(mt_map_vert_ring(map, hub_v, &ring, &d), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_map_face_neighbors(map, face, fcs, 64, offs, 8, &nf, &ne, &d),
                 MT_ERR_OUT_OF_RANGE);
    mt_face_list_free(&hub);
    mt_map_destroy(map);
}

static const mt_test_case cases[] = {
    {"map_query_fins_at_hub", test_map_query_fins_at_hub},
    {"map_query_refusals", test_map_query_refusals},
};
const mt_test_table mt_tests_map_query = {cases, sizeof cases / sizeof cases[0]};
