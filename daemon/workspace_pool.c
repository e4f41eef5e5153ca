/* meshtopod's kept build workspace (workspace_pool.h): one workspace under a
 * mutex, taken and given back around each build, and the target of meshes
 * the store drops; prepared at start by a build of a grid when asked
 * (--prepare-faces). Any thread. */
#include "workspace_pool.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#include "meshtopo/generate.h"

struct mtd_workspace_pool {
    pthread_mutex_t lock;
    mt_build_workspace *kept;
};

mt_status mtd_workspace_pool_create(mtd_workspace_pool **out_pool)
{
    *out_pool = calloc(1, sizeof **out_pool);
    if (!*out_pool) return MT_ERR_NOMEM;
    pthread_mutex_init(&(*out_pool)->lock, NULL);
    return MT_OK;
}

void mtd_workspace_pool_destroy(mtd_workspace_pool *pool)
{
    if (!pool) return;
    mt_build_workspace_destroy(pool->kept);
    pthread_mutex_destroy(&pool->lock);
    free(pool);
}

mt_build_workspace *mtd_workspace_take(mtd_workspace_pool *pool)
{
    pthread_mutex_lock(&pool->lock);
    mt_build_workspace *w = pool->kept;
    pool->kept = NULL;
    pthread_mutex_unlock(&pool->lock);
    return w ? w : mt_build_workspace_create();
}

void mtd_workspace_release(mtd_workspace_pool *pool, mt_build_workspace *workspace)
{
    if (!workspace) return;
    pthread_mutex_lock(&pool->lock);
    mt_build_workspace *other = pool->kept;
    if (other && mt_build_workspace_bytes(other) > mt_build_workspace_bytes(workspace)) {
        mt_build_workspace *swap = workspace;
        workspace = other;
        other = swap;
    }
    pool->kept = workspace;
    pthread_mutex_unlock(&pool->lock);
    mt_build_workspace_destroy(other);
}

void mtd_workspace_recycle_mesh(void *pool_ctx, mt_mesh *mesh)
{
    mtd_workspace_pool *pool = pool_ctx;
    pthread_mutex_lock(&pool->lock);
    if (pool->kept) {
        mt_build_workspace_recycle(pool->kept, mesh);
        mesh = NULL;
    }
    pthread_mutex_unlock(&pool->lock);
    mt_mesh_destroy(mesh);
}

const mt_build_workspace *mtd_workspace_pool_kept(mtd_workspace_pool *pool)
{
    pthread_mutex_lock(&pool->lock);
    const mt_build_workspace *kept = pool->kept;
    pthread_mutex_unlock(&pool->lock);
    return kept;
}

mt_status mtd_workspace_pool_prepare(mtd_workspace_pool *pool, uint32_t faces, mt_diag *out_diag)
{
    mt_diag local;
    mt_diag *diag = out_diag ? out_diag : &local;
    mt_diag_clear(diag);
    if (faces == 0) return MT_OK;
    /* side x side cells of two triangles: at least `faces` triangles */
    uint32_t side = 1;
    while (2 * (uint64_t)side * side < faces) side++;
    mt_face_list grid;
    mt_status s = mt_gen_grid(side, side, true, &grid);
    if (s != MT_OK) {
        snprintf(diag->message, sizeof diag->message,
                 "cannot generate a grid of %u triangles to prepare the build memory: %s", faces,
                 mt_strerror(s));
        diag->status = s;
        return s;
    }
    /* as the build workers build: one thread each */
    mt_build_options options = {.threads = 1, .workspace = mtd_workspace_take(pool)};
    mt_mesh *mesh = NULL;
    s = mt_mesh_build(&grid, &options, &mesh, diag);
    mt_face_list_free(&grid);
    if (s == MT_OK) mt_build_workspace_recycle(options.workspace, mesh);
    mtd_workspace_release(pool, options.workspace);
    return s;
}

size_t mtd_workspace_pool_bytes(mtd_workspace_pool *pool)
{
    pthread_mutex_lock(&pool->lock);
    size_t bytes = pool->kept ? mt_build_workspace_bytes(pool->kept) : 0;
    pthread_mutex_unlock(&pool->lock);
    return bytes;
}
