/* meshtopod's error record: how many errors it has met and the text and time
 * of the last one, for the heartbeat (status_t.errors, last_error). The one
 * place where errors are noted; its own mutex, any thread. */
#ifndef MESHTOPOD_ERROR_LOG_H
#define MESHTOPOD_ERROR_LOG_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

/* Longest error text kept or sent in a reply, with its NUL (longer ones are
 * cut). */
#define MTD_ERROR_MAX 512

typedef struct mtd_error_log mtd_error_log;

/* MT_OK or MT_ERR_NOMEM. */
mt_status mtd_error_log_create(mtd_error_log **out_log);

/* NULL-safe. */
void mtd_error_log_destroy(mtd_error_log *log);

/* Counts one error and keeps its text (NULL reads as "") as the last one. */
void mtd_error_log_note(mtd_error_log *log, const char *text);
/* mtd_error_log_note of "WHAT: MESSAGE" (each cut to fit). */
void mtd_error_log_note_event(mtd_error_log *log, const char *what, const char *message);

/* What the heartbeat reports. */
typedef struct mtd_error_summary {
    int64_t count;
    int64_t last_utime; /* 0 before the first error */
    char last[MTD_ERROR_MAX];
} mtd_error_summary;

void mtd_error_log_get(mtd_error_log *log, mtd_error_summary *out_summary);

#endif
