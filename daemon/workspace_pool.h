/* meshtopod's kept build workspace: the scratch arrays of the last build
 * (mt_build_workspace), kept for the next one because a build's scratch is
 * its largest allocation and fresh pages cost more than the build. Meshes
 * the store drops are recycled into it (mt_build_workspace_recycle), so a
 * mesh id resubmitted frame after frame is built into the arrays of an
 * earlier version. Its own mutex: build workers take and give it back, the
 * store's dispose hook recycles into it on whichever thread drops a mesh. */
#ifndef MESHTOPOD_WORKSPACE_POOL_H
#define MESHTOPOD_WORKSPACE_POOL_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/mesh.h"

typedef struct mtd_workspace_pool mtd_workspace_pool;

/* MT_OK or MT_ERR_NOMEM. */
mt_status mtd_workspace_pool_create(mtd_workspace_pool **out_pool);

/* Destroys the kept workspace and the pool. NULL-safe. */
void mtd_workspace_pool_destroy(mtd_workspace_pool *pool);

/* The kept workspace, or a new one (NULL when out of memory: the build then
 * allocates its own scratch). The caller gives it back with
 * mtd_workspace_release. A build that finds it taken gets a new one. */
mt_build_workspace *mtd_workspace_take(mtd_workspace_pool *pool);

/* Keeps a workspace for the next build; of two, the larger. NULL-safe. */
void mtd_workspace_release(mtd_workspace_pool *pool, mt_build_workspace *workspace);

/* Disposes of a mesh nobody holds any more (the store's dispose_mesh, with
 * the pool as ctx): its arrays go to the kept workspace for the next build,
 * or it is destroyed while a build has the workspace. */
void mtd_workspace_recycle_mesh(void *pool, mt_mesh *mesh);

/* Makes the kept workspace ready for a first mesh of up to about `faces`
 * triangles: builds a grid of at least that many with it (one thread, as
 * the workers build) and recycles the grid's mesh into it, so that the
 * first real build finds both its scratch and its mesh arrays already
 * faulted in. 0 does nothing. Fails (diag filled) only when memory runs
 * out. */
mt_status mtd_workspace_pool_prepare(mtd_workspace_pool *pool, uint32_t faces, mt_diag *diag);

/* The kept workspace (NULL while a build has it), for tests and stats. */
const mt_build_workspace *mtd_workspace_pool_kept(mtd_workspace_pool *pool);

/* mt_build_workspace_bytes of the kept workspace, 0 when none is kept. */
size_t mtd_workspace_pool_bytes(mtd_workspace_pool *pool);

#endif
