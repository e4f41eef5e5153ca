/* meshtopod's kept content buffer (content_pool.h): one buffer and its size
 * under a mutex. Buffers are anonymous mappings rather than malloc's: a
 * mapping costs memory only for the pages written (a transfer touches what
 * it was sent, not what it claims), and unmapping returns them to the system
 * at once, where free() may keep them in the heap. Any thread. */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS, MAP_NORESERVE */
#include "content_pool.h"

#include <pthread.h>
#include <stdlib.h>
#include <sys/mman.h>

struct mtd_content_pool {
    pthread_mutex_t lock;
    void *kept;
    size_t capacity;
};

static void unmap(void *content, size_t capacity)
{
    if (content) munmap(content, capacity);
}

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
    unmap(pool->kept, pool->capacity);
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
        size_t capacity = size ? size : 1;
        /* NORESERVE: a claimed size is address space, not a commitment. */
        content = mmap(NULL, capacity, PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
        if (content == MAP_FAILED) return NULL;
        *out_capacity = capacity;
    }
    return content;
}

void mtd_content_release(mtd_content_pool *pool, void *content, size_t capacity)
{
    if (!content) return;
    pthread_mutex_lock(&pool->lock);
    void *older = pool->kept;
    size_t older_capacity = pool->capacity;
    pool->kept = content;
    pool->capacity = capacity;
    pthread_mutex_unlock(&pool->lock);
    unmap(older, older_capacity);
}

void mtd_content_discard(void *content, size_t capacity)
{
    unmap(content, capacity);
}

const void *mtd_content_pool_kept(mtd_content_pool *pool, size_t *out_capacity)
{
    pthread_mutex_lock(&pool->lock);
    const void *kept = pool->kept;
    if (out_capacity) *out_capacity = pool->capacity;
    pthread_mutex_unlock(&pool->lock);
    return kept;
}
