/* meshtopod's fair share of query work (fair_share.h). Charges sit in
 * one-second buckets, the current and the previous one; the sliding window
 * counts the previous bucket in proportion to how much of it is still
 * inside. Senders are few at a time and kept in an array, pruned when their
 * charge has left the window; past MAX_SENDERS new senders go uncounted
 * (a node inventing reply channels gets many shares anyway). */
#include "fair_share.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/msgs.h"

#define WINDOW_US 1000000
#define MAX_SENDERS 1024

typedef struct sender_charge {
    char name[MESHTOPO_MESH_T_REPLY_CHANNEL_MAX + 1];
    int64_t previous_us, current_us; /* charged in the previous and current buckets */
} sender_charge;

struct mtd_fair_share {
    sender_charge *senders;
    size_t count;
    int64_t bucket_start_us; /* of the current bucket */
};

mt_status mtd_fair_share_create(mtd_fair_share **out_share)
{
    *out_share = calloc(1, sizeof **out_share);
    if (!*out_share) return MT_ERR_NOMEM;
    (*out_share)->senders = calloc(MAX_SENDERS, sizeof *(*out_share)->senders);
    if (!(*out_share)->senders) {
        free(*out_share);
        *out_share = NULL;
        return MT_ERR_NOMEM;
    }
    return MT_OK;
}

void mtd_fair_share_destroy(mtd_fair_share *share)
{
    if (!share) return;
    free(share->senders);
    free(share);
}

/* Moves the buckets on to now and drops senders with nothing left. */
static void advance(mtd_fair_share *s, int64_t now_us)
{
    if (now_us - s->bucket_start_us < WINDOW_US) return;
    bool skipped = now_us - s->bucket_start_us >= 2 * WINDOW_US; /* a whole idle bucket */
    s->bucket_start_us = now_us - (now_us - s->bucket_start_us) % WINDOW_US;
    size_t kept = 0;
    for (size_t i = 0; i < s->count; i++) {
        sender_charge *c = &s->senders[i];
        c->previous_us = skipped ? 0 : c->current_us;
        c->current_us = 0;
        if (c->previous_us > 0) s->senders[kept++] = *c;
    }
    s->count = kept;
}

/* A sender's charge within the sliding window. */
static int64_t charge_of(const mtd_fair_share *s, const sender_charge *c, int64_t now_us)
{
    int64_t into = now_us - s->bucket_start_us;
    return c->current_us + c->previous_us * (WINDOW_US - into) / WINDOW_US;
}

static sender_charge *find(mtd_fair_share *s, const char *sender)
{
    for (size_t i = 0; i < s->count; i++)
        if (strcmp(s->senders[i].name, sender) == 0) return &s->senders[i];
    return NULL;
}

bool mtd_fair_share_allowed(mtd_fair_share *s, const char *sender, int64_t now_us, char *why,
                            size_t why_size)
{
    advance(s, now_us);
    sender_charge *mine = find(s, sender);
    if (!mine) return true;
    int64_t total = 0, own = charge_of(s, mine, now_us);
    size_t active = 0;
    for (size_t i = 0; i < s->count; i++) {
        int64_t c = charge_of(s, &s->senders[i], now_us);
        total += c;
        if (c > 0) active++;
    }
    if (active < 2 || total < WINDOW_US / 2) return true;
    int64_t share = WINDOW_US / (int64_t)active;
    if (own <= share) return true;
    snprintf(why, why_size,
             "reply channel '%s' used %" PRId64
             " ms of the last second's query time, over its "
             "share of %" PRId64 " ms among %zu senders: retry later",
             sender, own / 1000, share / 1000, active);
    return false;
}

void mtd_fair_share_charge(mtd_fair_share *s, const char *sender, int64_t now_us, int64_t cost_us)
{
    if (cost_us <= 0) return;
    advance(s, now_us);
    sender_charge *c = find(s, sender);
    if (!c) {
        if (s->count == MAX_SENDERS) return;
        c = &s->senders[s->count++];
        memset(c, 0, sizeof *c);
        snprintf(c->name, sizeof c->name, "%s", sender);
    }
    c->current_us += cost_us;
}
