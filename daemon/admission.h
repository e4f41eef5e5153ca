/* meshtopod's admission of submissions by cost. Before a mesh is queued for
 * a build, what it will cost is estimated from its counts (memory of the
 * built mesh, archive bytes) and weighed against what it carries (the bytes
 * of its content) and the limits: a mesh that claims more than
 * --max-claim-ratio times what it carries (vertices no face uses and no
 * position describes are the cheap way to claim much), or that alone
 * exceeds --max-store-bytes or --max-archive-bytes, is refused with
 * TOO_LARGE; one that would exceed them together with what is held and
 * being built now, or whose sender already has its share of the build
 * queue, with BUSY. An admitted mesh's cost stays reserved until its build
 * is stored or fails. Any thread: one mutex. */
#ifndef MESHTOPOD_ADMISSION_H
#define MESHTOPOD_ADMISSION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

/* What a submission will cost and what it carries, in bytes. */
typedef struct mtd_cost {
    uint64_t memory;  /* the built mesh's arrays (its report is charged once built) */
    uint64_t archive; /* its archive file */
    uint64_t carried; /* its content as sent (mesh_t's four count fields and arrays) */
} mtd_cost;

/* The estimate for a mesh of these counts (with or without positions). */
mtd_cost mtd_cost_estimate(uint32_t num_verts, bool has_positions, uint32_t num_faces,
                           uint64_t num_indices);

typedef struct mtd_admission_limits {
    uint64_t max_store_bytes;   /* 0 = no limit */
    uint64_t max_archive_bytes; /* 0 = no limit (or no archive) */
    uint32_t max_claim_ratio;   /* 0 = no limit */
    uint32_t builds_per_sender; /* admitted and not yet finished, per sender; 0 = no limit */
} mtd_admission_limits;

typedef struct mtd_admission mtd_admission;

/* MT_OK or MT_ERR_NOMEM. */
mt_status mtd_admission_create(const mtd_admission_limits *limits, mtd_admission **out);

/* NULL-safe. */
void mtd_admission_destroy(mtd_admission *admission);

/* Admits a submission of `cost` from `sender` (its reply channel) when the
 * store holds held_memory bytes and the archive held_archive bytes: returns
 * MESHTOPO_STATUS_CODE_T_OK with the cost reserved, or TOO_LARGE / BUSY with
 * error naming the limit, its flag and the figures. */
int32_t mtd_admission_take(mtd_admission *admission, const char *sender, const mtd_cost *cost,
                           uint64_t held_memory, uint64_t held_archive, char *error,
                           size_t error_size);

/* Gives back what mtd_admission_take reserved for sender's submission. */
void mtd_admission_give_back(mtd_admission *admission, const char *sender, const mtd_cost *cost);

/* Memory and archive bytes reserved now, by admitted builds not yet finished. */
void mtd_admission_reserved(mtd_admission *admission, uint64_t *out_memory, uint64_t *out_archive);

#endif
