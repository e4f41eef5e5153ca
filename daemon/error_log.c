/* meshtopod's error record (error_log.h): a count and the last error's text
 * and time under one mutex. Any thread. */
#include "error_log.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#include "clock.h"

struct mtd_error_log {
    pthread_mutex_t lock;
    mtd_error_summary summary;
};

mt_status mtd_error_log_create(mtd_error_log **out_log)
{
    *out_log = calloc(1, sizeof **out_log);
    if (!*out_log) return MT_ERR_NOMEM;
    pthread_mutex_init(&(*out_log)->lock, NULL);
    return MT_OK;
}

void mtd_error_log_destroy(mtd_error_log *log)
{
    if (!log) return;
    pthread_mutex_destroy(&log->lock);
    free(log);
}

void mtd_error_log_note(mtd_error_log *log, const char *text)
{
    int64_t now = mtd_now_utime();
    pthread_mutex_lock(&log->lock);
    log->summary.count++;
    snprintf(log->summary.last, sizeof log->summary.last, "%s", text ? text : "");
    log->summary.last_utime = now;
    pthread_mutex_unlock(&log->lock);
}

void mtd_error_log_note_event(mtd_error_log *log, const char *what, const char *message)
{
    char text[MTD_ERROR_MAX];
    snprintf(text, sizeof text, "%.40s: %.400s", what, message);
    mtd_error_log_note(log, text);
}

void mtd_error_log_get(mtd_error_log *log, mtd_error_summary *out_summary)
{
    pthread_mutex_lock(&log->lock);
    *out_summary = log->summary;
    pthread_mutex_unlock(&log->lock);
}
