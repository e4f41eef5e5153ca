/* Checks of large answers against the core library, shared by
 * test_meshtopod_parts (memq://) and meshtopod_parts_client (netns): a
 * VERTEX_RING or BOUNDARY_LOOPS reply_t checked with mt_client_reply_check,
 * then compared through the reply accessors, item by item and value by value,
 * with mt_vert_ring / mt_boundary_loops on the same mesh built in-process.
 * Also the grid with holes both use. */
#ifndef MESHTOPO_TEST_PARTS_EXPECT_H
#define MESHTOPO_TEST_PARTS_EXPECT_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/client_reply.h"
#include "meshtopo/core.h"

/* 0 when r (status OK, offsets as mt_client_reply_check wants them; r may
 * come straight from a decoder) holds exactly the one-rings of ids[0..n) of
 * mesh; otherwise -1 with the first difference in why. */
int mt_test_check_rings(const mt_mesh *mesh, const uint32_t *ids, size_t n,
                        const meshtopo_reply_t *r, char *why, size_t why_size);

/* 0 when r holds exactly mesh's boundary loops, in mt_boundary_loops' order. */
int mt_test_check_loops(const mt_mesh *mesh, const meshtopo_reply_t *r, char *why, size_t why_size);

/* A grid of nx * ny quads as triangles (mt_gen_grid) with the two triangles
 * of every `every`-th cell in both directions (from cell (every/2,
 * every/2)) removed: one more boundary loop of 4 vertices per hole. */
mt_status mt_test_grid_with_holes(uint32_t nx, uint32_t ny, uint32_t every, mt_face_list *out);

#endif
