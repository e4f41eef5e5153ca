/* meshtopod's kept content buffer (content_pool.h): one buffer and its size
 * under a mutex. Any thread. */
#include "content_pool.h"

#include <pthread.h>
#include <stdlib.h>

struct mtd_content_pool {
    pthread_mutex_t lock;
    void *kept;
    size_t capacity;
};

mt_status mtd_content_pool_create(mtd_content_pool **out_pool)
{
    *out_pool = calloc(1, sizeof **out_pool);
    if (!*out_pool) return MT_ERR_NOMEM;
    pthread_mutex_init(&(*out_pool)->lock, NULL);
    return MT_OK;
}

void mtd_content_pool_destroy(mtd_content_pool *pool)
{
    if (!pool) return;
    free(pool->kept);
    pthread_mutex_destroy(&pool->lock);
    free(pool);
}

void *mtd_content_take(mtd_content_pool *pool, size_t size, size_t *out_capacity)
{
    void *content = NULL;
    pthread_mutex_lock(&pool->lock);
    if (pool->kept && pool->capacity >= size) {
        content = pool->kept;
        *out_capacity = pool->capacity;
        pool->kept = NULL;
        pool->capacity = 0;
    }
    pthread_mutex_unlock(&pool->lock);
    if (!content) {
        content = malloc(size);
        *out_capacity = size;
    }
    return content;
}

void mtd_content_release(mtd_content_pool *pool, void *content, size_t capacity)
{
    if (!content) return;
    pthread_mutex_lock(&pool->lock);
    void *older = pool->kept;
    pool->kept = content;
    pool->capacity = capacity;
    pthread_mutex_unlock(&pool->lock);
    free(older);
}

const void *mtd_content_pool_kept(mtd_content_pool *pool, size_t *out_capacity)
{
    pthread_mutex_lock(&pool->lock);
    const void *kept = pool->kept;
    if (out_capacity) *out_capacity = pool->capacity;
    pthread_mutex_unlock(&pool->lock);
    return kept;
}
