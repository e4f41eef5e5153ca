/* Test helpers for the block map (map.h): a mesh split into blocks the way
 * mappers send them (by face centroid on a grid, seam vertices duplicated
 * per block, or every face with its own vertices as voxblox does), the
 * reference union of blocks welded with mt_face_list_weld, and the check
 * that a map's counts equal a full build's report. */
#ifndef MESHTOPO_TEST_MAP_SPLIT_H
#define MESHTOPO_TEST_MAP_SPLIT_H

#include <stdbool.h>
#include <stddef.h>

#include "meshtopo/face_list.h"
#include "meshtopo/map.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"

typedef struct map_block_src {
    mt_map_key key;
    mt_face_list list; /* owned (malloc'd arrays) */
    uint32_t *ids;     /* [list.num_verts] source vertex ids (the none mode's map ids) */
} map_block_src;

typedef struct map_block_set {
    map_block_src *blocks;
    size_t count;
} map_block_set;

/* Splits `list` into blocks of side `size` by face centroid (over its
 * in-range corners; faces without a finite one go to block (-999, 0, 0)).
 * Each block lists the vertices its faces use, in first-use order (soup:
 * every face gets new vertices of its own). An out-of-range index stays out
 * of range: it becomes block vertex count + 7 + its rank among the face's
 * distinct bad values. Aborts the test on allocation failure. */
void map_split(const mt_face_list *list, double size, bool soup, map_block_set *out);
void map_block_set_free(map_block_set *set);

/* Deep copy of a face list (malloc'd; free with mt_face_list_free). */
void map_list_copy(const mt_face_list *src, mt_face_list *dst);

/* The union of the lists as map.h defines it (out-of-range entries as
 * MT_NONE - r), welded with mt_face_list_weld(eps 0). */
void map_union_welded(const mt_face_list *const *lists, size_t n, mt_face_list *out);

/* Builds `list`, validates the mesh and checks the map's counts and
 * histograms against its report (mt_map_compare_report); `what` names the
 * situation in the failures recorded. Returns the number of failures. */
int map_check_against_list(const mt_map *map, const mt_face_list *list, const char *what);

/* mt_map_face_list of the map, built and compared (plus id arrays checked
 * against the map's translation functions). Returns the differences. */
int map_check_full(const mt_map *map, const char *what);

/* map_queries.c: `samples` vertices (rings, the faces of each edge at them
 * and of one other pair) and `samples` faces (neighbours), every one when
 * there are fewer, picked from `seed`, asked of the map and of a full build
 * of its union; every answer must be the build's in map ids. Returns the
 * number of failures (also recorded with mt_test_fail). */
int map_check_queries(const mt_map *map, const char *what, uint64_t seed, uint32_t samples);

#endif
