/* meshtopod's log: one line per event on stderr, in the form
 *   2026-11-22T06:40:01.123Z meshtopod[4242] info submit mesh_id=room version=3
 * (UTC time, program and pid, level, event name, then key=value details),
 * so that journald, grep and scripts read it alike. Each line is written
 * with a single write(2), so lines from several threads never interleave. */
#ifndef MESHTOPOD_LOG_H
#define MESHTOPOD_LOG_H

#include "meshtopo/status.h"

typedef enum mtd_log_level {
    MTD_LOG_ERROR = 0,
    MTD_LOG_WARN = 1,
    MTD_LOG_INFO = 2,
    MTD_LOG_DEBUG = 3,
} mtd_log_level;

/* Parses "error", "warn", "info" or "debug". MT_ERR_INVALID_ARG otherwise. */
mt_status mtd_log_level_parse(const char *text, mtd_log_level *out_level);

/* Name of a level, as printed in each line. */
const char *mtd_log_level_name(mtd_log_level level);

/* Events above this level are dropped (default MTD_LOG_INFO). Thread safe. */
void mtd_log_set_level(mtd_log_level level);

/* Sends the lines to fd instead of stderr (tests); -1 restores stderr. */
void mtd_log_set_fd(int fd);

/* Logs one event: `event` is a short word (start, submit, query, error, ...),
 * the format gives the key=value details. Newlines in the details are
 * replaced by spaces, and a line longer than 4 KiB is cut and ends in "...",
 * so one event is always one line. */
void mtd_log(mtd_log_level level, const char *event, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
