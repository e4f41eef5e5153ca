/* meshtopod's fair share of query work between senders. Queries run one
 * after another on the LCM thread, so one sender sending large queries
 * without waiting for the answers would make everyone else's wait (and
 * overflow the socket's queue). Each sender (reply channel, the only
 * identity LCM carries) is charged the time its queries took over a sliding
 * window of one second; while the thread is busy (the charges of the window
 * add up to half of it or more) and other senders are active, a sender over
 * its share (the window divided among the active senders) is answered BUSY
 * instead of served, which costs almost nothing, until its charge decays.
 * LCM-free; one owner thread, no lock. */
#ifndef MESHTOPOD_FAIR_SHARE_H
#define MESHTOPOD_FAIR_SHARE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

typedef struct mtd_fair_share mtd_fair_share;

/* MT_OK or MT_ERR_NOMEM. */
mt_status mtd_fair_share_create(mtd_fair_share **out_share);

/* NULL-safe. */
void mtd_fair_share_destroy(mtd_fair_share *share);

/* Whether `sender` may be served at monotonic time now_us; when not, why
 * gets the figures (its charge, its share, the active senders). */
bool mtd_fair_share_allowed(mtd_fair_share *share, const char *sender, int64_t now_us, char *why,
                            size_t why_size);

/* Charges sender `cost_us` of work done at now_us. */
void mtd_fair_share_charge(mtd_fair_share *share, const char *sender, int64_t now_us,
                           int64_t cost_us);

#endif
