/* meshtopod's memory budget (--memory-budget BYTES): which held versions may
 * be dropped from memory because the archive keeps them, when each was last
 * used, and which to drop first (the least recently used). It decides;
 * the store (mesh_store.c) drops and, on the next query, loads again through
 * its backing. Calls nothing of the daemon; thread safe (one mutex). */
#ifndef MESHTOPOD_MEMORY_BUDGET_H
#define MESHTOPOD_MEMORY_BUDGET_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

typedef struct mtd_budget mtd_budget;

/* A budget of `bytes` (0: no budget, nothing is ever picked). MT_OK or
 * MT_ERR_NOMEM (*out_budget NULL). */
mt_status mtd_budget_create(uint64_t bytes, mtd_budget **out_budget);

/* NULL-safe. */
void mtd_budget_destroy(mtd_budget *budget);

/* The budget in bytes (0: none; also for a NULL budget). */
uint64_t mtd_budget_bytes(const mtd_budget *budget);

/* Whether `held` bytes exceed the budget (false without one). */
bool mtd_budget_over(const mtd_budget *budget, size_t held);

/* (id, version) is held and the archive keeps it: it may be dropped. It
 * counts as just used. Silently nothing when out of memory (it then stays
 * in memory). NULL-safe. */
void mtd_budget_track(mtd_budget *budget, const char *id, uint32_t version);

/* (id, version) was just used (a query fetched it); nothing when it is not
 * tracked. NULL-safe. */
void mtd_budget_touch(mtd_budget *budget, const char *id, uint32_t version);

/* (id, version) is no longer held: not a candidate any more. NULL-safe. */
void mtd_budget_forget(mtd_budget *budget, const char *id, uint32_t version);

/* The least recently used tracked version, no longer tracked after this:
 * its id into id[id_size] and its version. false when none is tracked. */
bool mtd_budget_pick(mtd_budget *budget, char *id, size_t id_size, uint32_t *out_version);

/* Counts one version dropped from memory (the heartbeat's archive_evictions). */
void mtd_budget_count_eviction(mtd_budget *budget);

/* Versions dropped from memory since the start (0 for a NULL budget). */
int64_t mtd_budget_evictions(mtd_budget *budget);

/* Versions tracked now (tests). */
size_t mtd_budget_tracked(mtd_budget *budget);

#endif
