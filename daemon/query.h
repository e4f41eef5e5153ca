/* meshtopod's queries: one query_t answered with one reply_t (every kind of
 * msgs/query_t.lcm, the same answers as the core library). Runs on the LCM
 * thread against immutable store entries, so a build never holds it up; a
 * query whose version must first be loaded from the store's backing (the
 * archive) is handed to a worker, which loads it and answers. */
#ifndef MESHTOPOD_QUERY_H
#define MESHTOPOD_QUERY_H

#include "cluster.h"
#include "mesh_store.h"
#include "meshtopo/msgs.h"
#include "reply.h"
#include "worker_pool.h"

/* A reply whose arrays would exceed this many bytes is refused (TOO_LARGE). */
#define MTD_REPLY_MAX_BYTES (64u << 20)

typedef struct mtd_queries mtd_queries;

/* Answers from `store` through `replies`, loading on `pool`'s workers; in a
 * cluster (NULL: none), a listing of every mesh shows the ids this member
 * owns. None of them owned, all must outlive it. MT_OK or MT_ERR_NOMEM. */
mt_status mtd_queries_create(mtd_store *store, mtd_pool *pool, mtd_replies *replies,
                             mtd_cluster *cluster, mtd_queries **out_queries);

/* NULL-safe. Call once the worker pool has stopped. */
void mtd_queries_destroy(mtd_queries *queries);

/* Answers one decoded query_t whose request was new (mtd_reply_begin). */
void mtd_query_handle(mtd_queries *queries, const meshtopo_query_t *msg);

#endif
