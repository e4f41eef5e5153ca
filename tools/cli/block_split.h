/* Splitting a face list into blocks on a regular grid the way TSDF mappers
 * (voxblox, nvblox) publish a map: each face goes to the grid cell of its
 * centroid, and each block carries its own copies of the vertices its faces
 * use, so seam vertices are duplicated per block. Used by `meshtopo inspect
 * --blocks` to feed an mt_map (meshtopo/map.h) from a file. */
#ifndef MESHTOPO_CLI_BLOCK_SPLIT_H
#define MESHTOPO_CLI_BLOCK_SPLIT_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/map.h"
#include "meshtopo/status.h"

/* The key of faces and vertices that have no finite cell: a face without an
 * in-range corner, a centroid with a NaN or infinite coordinate, or one more
 * than 2^30 cells from the origin. Such faces all go to this one block, so
 * a vertex with a NaN or infinite coordinate is never duplicated (the map
 * never welds those, as mt_face_list_weld does not). */
#define CLI_BLOCK_OUTLIER_KEY ((mt_map_key){INT32_MIN, INT32_MIN, INT32_MIN})

typedef struct cli_block {
    mt_map_key key;
    mt_face_list list; /* malloc'd; faces in the file's order */
    uint32_t *source;  /* [list.num_verts] the file vertex each block vertex copies */
} cli_block;

typedef struct cli_block_set {
    cli_block *blocks; /* ascending key (x, then y, then z) */
    size_t count;
} cli_block_set;

/* Splits `list` (positions required when it has vertices) into blocks of
 * side `size` (finite, > 0) by face centroid over the in-range corners.
 * Each block lists the vertices its faces use in first-use order, then the
 * file's unreferenced vertices whose position falls in its cell (so the
 * union of the blocks welded exactly is the file welded exactly). An
 * out-of-range index stays out of range: UINT32_MAX - r, r its rank among
 * the face's distinct out-of-range values, so equal values stay equal.
 * O((F + V) log(F + V)). MT_ERR_INVALID_ARG (no positions, bad size),
 * MT_ERR_NOMEM; *out is then empty. Free with cli_block_set_free. */
mt_status cli_blocks_split(const mt_face_list *list, double size, cli_block_set *out,
                           mt_diag *diag);
void cli_block_set_free(cli_block_set *set);

#endif
