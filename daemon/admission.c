/* meshtopod's admission by cost (admission.h): the estimate, the limits and
 * the reservations of admitted builds, with a count per sender. Senders are
 * few at a time (a build queue's worth at most), so they sit in a short
 * list. */
#include "admission.h"

#include <inttypes.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/msgs.h"

/* Below this a mesh's claim is never compared with what it carries: the
 * arrays of a few hundred elements cost more than their bytes on the wire,
 * and a megabyte per message is no lever. */
#define CLAIM_FLOOR_BYTES (1u << 20)

/* An archive file's fixed part (HDF5 superblock, groups, attributes). */
#define ARCHIVE_FILE_BYTES (64u << 10)

typedef struct sender_count {
    struct sender_count *next;
    uint32_t builds;
    char name[]; /* the reply channel */
} sender_count;

struct mtd_admission {
    mtd_admission_limits limits;
    pthread_mutex_t lock;
    uint64_t memory, archive; /* reserved */
    sender_count *senders;
};

mtd_cost mtd_cost_estimate(uint32_t num_verts, bool has_positions, uint32_t num_faces,
                           uint64_t num_indices)
{
    uint64_t v = num_verts, f = num_faces, i = num_indices;
    uint64_t positions = has_positions ? 24 * v : 0;
    mtd_cost cost;
    /* The core's arrays: per vertex a half-edge and a component, per face a
     * half-edge, per corner a half-edge (12 bytes) with room for the copies
     * and bundles of non-manifold spots. */
    cost.memory = 8 * v + positions + 4 * f + 18 * i;
    /* mesh_t's content: four counts, the positions, face sizes and indices. */
    cost.carried = 16 + positions + 4 * f + 4 * i;
    /* The file keeps the face list as sent and the half-edge arrays. */
    cost.archive = ARCHIVE_FILE_BYTES + cost.carried + cost.memory;
    return cost;
}

mt_status mtd_admission_create(const mtd_admission_limits *limits, mtd_admission **out)
{
    *out = calloc(1, sizeof **out);
    if (!*out) return MT_ERR_NOMEM;
    (*out)->limits = *limits;
    pthread_mutex_init(&(*out)->lock, NULL);
    return MT_OK;
}

void mtd_admission_destroy(mtd_admission *a)
{
    if (!a) return;
    while (a->senders) {
        sender_count *s = a->senders;
        a->senders = s->next;
        free(s);
    }
    pthread_mutex_destroy(&a->lock);
    free(a);
}

static sender_count **find_sender(mtd_admission *a, const char *name)
{
    sender_count **link = &a->senders;
    while (*link && strcmp((*link)->name, name) != 0) link = &(*link)->next;
    return link;
}

/* TOO_LARGE: the submission alone is over a limit, whatever else is held. */
static int32_t check_alone(const mtd_admission_limits *l, const mtd_cost *c, char *error,
                           size_t size)
{
    if (l->max_claim_ratio && c->memory > CLAIM_FLOOR_BYTES &&
        c->memory / l->max_claim_ratio > c->carried) {
        snprintf(error, size,
                 "the mesh claims %" PRIu64 " bytes of memory for the %" PRIu64
                 " bytes it carries, more than %" PRIu32
                 " times as much (--max-claim-ratio): vertices that no face uses and no "
                 "position describes?",
                 c->memory, c->carried, l->max_claim_ratio);
        return MESHTOPO_STATUS_CODE_T_TOO_LARGE;
    }
    if (l->max_store_bytes && c->memory > l->max_store_bytes) {
        snprintf(error, size,
                 "the mesh needs about %" PRIu64 " bytes of memory, more than the store's %" PRIu64
                 " (--max-store-bytes)",
                 c->memory, l->max_store_bytes);
        return MESHTOPO_STATUS_CODE_T_TOO_LARGE;
    }
    if (l->max_archive_bytes && c->archive > l->max_archive_bytes) {
        snprintf(error, size,
                 "the mesh needs about %" PRIu64 " archive bytes, more than the archive's %" PRIu64
                 " (--max-archive-bytes)",
                 c->archive, l->max_archive_bytes);
        return MESHTOPO_STATUS_CODE_T_TOO_LARGE;
    }
    return MESHTOPO_STATUS_CODE_T_OK;
}

int32_t mtd_admission_take(mtd_admission *a, const char *sender, const mtd_cost *cost,
                           uint64_t held_memory, uint64_t held_archive, char *error,
                           size_t error_size)
{
    const mtd_admission_limits *l = &a->limits;
    int32_t status = check_alone(l, cost, error, error_size);
    if (status != MESHTOPO_STATUS_CODE_T_OK) return status;
    pthread_mutex_lock(&a->lock);
    sender_count **link = find_sender(a, sender);
    uint64_t memory = held_memory + a->memory, archive = held_archive + a->archive;
    if (l->max_store_bytes && memory + cost->memory > l->max_store_bytes) {
        snprintf(error, error_size,
                 "the store holds %" PRIu64 " of its %" PRIu64
                 " bytes (--max-store-bytes, builds under way included) and the mesh needs "
                 "about %" PRIu64 ": retry later",
                 memory, l->max_store_bytes, cost->memory);
        status = MESHTOPO_STATUS_CODE_T_BUSY;
    } else if (l->max_archive_bytes && archive + cost->archive > l->max_archive_bytes) {
        snprintf(error, error_size,
                 "the archive holds %" PRIu64 " of its %" PRIu64
                 " bytes (--max-archive-bytes, writes under way included) and the mesh needs "
                 "about %" PRIu64,
                 archive, l->max_archive_bytes, cost->archive);
        status = MESHTOPO_STATUS_CODE_T_BUSY;
    } else if (l->builds_per_sender && *link && (*link)->builds >= l->builds_per_sender) {
        snprintf(error, error_size,
                 "reply channel '%s' has %" PRIu32
                 " builds waiting or running, its share of the build queue: retry later",
                 sender, (*link)->builds);
        status = MESHTOPO_STATUS_CODE_T_BUSY;
    } else {
        if (!*link) {
            size_t n = strlen(sender);
            *link = calloc(1, sizeof **link + n + 1);
            if (*link) memcpy((*link)->name, sender, n + 1);
        }
        if (*link) {
            (*link)->builds++;
            a->memory += cost->memory;
            a->archive += cost->archive;
        } else {
            snprintf(error, error_size, "out of memory admitting the mesh");
            status = MESHTOPO_STATUS_CODE_T_INTERNAL;
        }
    }
    pthread_mutex_unlock(&a->lock);
    return status;
}

void mtd_admission_give_back(mtd_admission *a, const char *sender, const mtd_cost *cost)
{
    pthread_mutex_lock(&a->lock);
    sender_count **link = find_sender(a, sender);
    if (*link) {
        a->memory -= cost->memory < a->memory ? cost->memory : a->memory;
        a->archive -= cost->archive < a->archive ? cost->archive : a->archive;
        if (--(*link)->builds == 0) {
            sender_count *s = *link;
            *link = s->next;
            free(s);
        }
    }
    pthread_mutex_unlock(&a->lock);
}

void mtd_admission_reserved(mtd_admission *a, uint64_t *out_memory, uint64_t *out_archive)
{
    pthread_mutex_lock(&a->lock);
    *out_memory = a->memory;
    *out_archive = a->archive;
    pthread_mutex_unlock(&a->lock);
}
