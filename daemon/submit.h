/* meshtopod's submissions: a decoded mesh_t (whole, or reassembled from
 * chunks by transfer.c) is checked field by field and admitted by its cost
 * (admission.h), built on the worker pool
 * so the LCM thread keeps answering queries, put into the store (which has
 * it archived as its policy says), and only then acknowledged (ack_t with the topology report)
 * and announced on PREFIX+"TOPOLOGY". Handles arrive on the LCM thread;
 * builds, stores and acks run on build workers. */
#ifndef MESHTOPOD_SUBMIT_H
#define MESHTOPOD_SUBMIT_H

#include <lcm/lcm.h>
#include <stddef.h>
#include <stdint.h>

#include "admission.h"
#include "archive_catalog.h"
#include "config.h"
#include "content_pool.h"
#include "meshtopo/msgs.h"
#include "reply.h"
#include "worker_pool.h"
#include "workspace_pool.h"

/* What submissions use; none of it is owned, all must outlive the
 * submitter. */
typedef struct mtd_submit_deps {
    const mtd_config *config; /* the mesh limits */
    lcm_t *lcm;               /* topology broadcasts */
    const char *topology_channel;
    mtd_pool *pool;
    mtd_replies *replies;
    mtd_catalog *catalog;     /* the archive's bytes, for admission; NULL without */
    mtd_store *store;         /* where built meshes go; what it holds, for admission */
    mtd_admission *admission; /* checked before a build is queued */
    mtd_workspace_pool *workspaces;
    mtd_content_pool *contents;
} mtd_submit_deps;

typedef struct mtd_submitter mtd_submitter;

/* MT_OK or MT_ERR_NOMEM. */
mt_status mtd_submitter_create(const mtd_submit_deps *deps, mtd_submitter **out_submitter);

/* NULL-safe. Call once the worker pool has stopped. */
void mtd_submitter_destroy(mtd_submitter *submitter);

/* Handles one decoded mesh_t whose request was new in the request cache
 * (mtd_reply_begin). `encoded` is the received message (for the content
 * hash). Takes ownership of msg (heap-allocated, decoded by mt_msgs_decode). */
void mtd_submit_handle(mtd_submitter *submitter, meshtopo_mesh_t *msg, const void *encoded,
                       size_t encoded_size);

/* A chunked submission, reassembled, whose request was new: msg's strings
 * are heap copies it owns, its arrays point into `content` (a buffer of
 * content_capacity bytes from the content pool), whose hash the decoder
 * computed. Takes msg and content (given back to the content pool). */
void mtd_submit_content(mtd_submitter *submitter, meshtopo_mesh_t *msg, void *content,
                        size_t content_capacity, uint64_t content_hash);

/* Builds finished, failed ones included. */
int64_t mtd_submitter_builds(mtd_submitter *submitter);

#endif
