/* meshtopod's query routing: one query_t answered with one reply_t (every
 * kind of msgs/query_t.lcm, the same answers as the core library), checked
 * (query_check.h) and handed to its kind's answerer (answer.h) by the
 * query-kind table. Runs on the LCM thread against immutable store entries,
 * so a build never holds it up; a query whose version must first be loaded
 * from the store's backing (the archive), or whose kind the table says a
 * worker answers, is handed to a worker. */
#ifndef MESHTOPOD_QUERY_ROUTE_H
#define MESHTOPOD_QUERY_ROUTE_H

#include "answer.h"
#include "cluster.h"
#include "mesh_store.h"
#include "meshtopo/msgs.h"
#include "reply.h"
#include "worker_pool.h"

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

/* The answerer of a query_t kind, NULL for a kind without one (every kind
 * of the table has one; tests check it). */
mtd_answerer *mtd_query_answerer(int32_t kind);

#endif
