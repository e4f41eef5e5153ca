/* meshtopod's kept content buffer: the buffer of the last finished chunked
 * submission (a mesh's content, reassembled), kept for the next transfer it
 * fits, because mapping and zeroing fresh pages for every mesh costs more
 * than the network does. At most one buffer is kept. Its own mutex: the LCM
 * thread takes buffers (transfer.c), build workers give them back (submit.c). */
#ifndef MESHTOPOD_CONTENT_POOL_H
#define MESHTOPOD_CONTENT_POOL_H

#include <stddef.h>

#include "meshtopo/status.h"

typedef struct mtd_content_pool mtd_content_pool;

/* MT_OK or MT_ERR_NOMEM. */
mt_status mtd_content_pool_create(mtd_content_pool **out_pool);

/* Frees the kept buffer and the pool. NULL-safe. */
void mtd_content_pool_destroy(mtd_content_pool *pool);

/* A buffer of at least `size` bytes: the kept one when it is large enough,
 * else a new mapping whose pages cost memory only once written (NULL when
 * out of address space). *out_capacity gets its size. */
void *mtd_content_take(mtd_content_pool *pool, size_t size, size_t *out_capacity);

/* Gives back a buffer of `capacity` bytes: it is kept for the next take (the
 * one kept before is freed). NULL-safe. */
void mtd_content_release(mtd_content_pool *pool, void *content, size_t capacity);

/* Unmaps a buffer from mtd_content_take without keeping it: what an
 * abandoned transfer held goes back to the system. NULL-safe. */
void mtd_content_discard(void *content, size_t capacity);

/* The kept buffer (NULL when none) and its capacity, for tests and stats. */
const void *mtd_content_pool_kept(mtd_content_pool *pool, size_t *out_capacity);

#endif
