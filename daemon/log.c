/* meshtopod's one-line-per-event log on stderr (format in log.h). syslog(3)
 * is not used: under systemd stderr already goes to the journal, and in a
 * terminal or a test it stays readable and capturable. Any thread: the level
 * and fd are set before threads start, each line is one write(2). */
#define _DEFAULT_SOURCE /* gmtime_r */
#include "log.h"

#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define MTD_LOG_LINE_MAX 4096

static _Atomic int log_level = MTD_LOG_INFO;
static _Atomic int log_fd = -1;

static const char *const level_names[] = {"error", "warn", "info", "debug"};

mt_status mtd_log_level_parse(const char *text, mtd_log_level *out_level)
{
    for (int i = MTD_LOG_ERROR; text && i <= MTD_LOG_DEBUG; i++) {
        if (strcmp(text, level_names[i]) == 0) {
            *out_level = (mtd_log_level)i;
            return MT_OK;
        }
    }
    return MT_ERR_INVALID_ARG;
}

const char *mtd_log_level_name(mtd_log_level level)
{
    return level >= MTD_LOG_ERROR && level <= MTD_LOG_DEBUG ? level_names[level] : "?";
}

void mtd_log_set_level(mtd_log_level level)
{
    atomic_store(&log_level, (int)level);
}

void mtd_log_set_fd(int fd)
{
    atomic_store(&log_fd, fd);
}

/* Appends to line at *len, keeping room for "...\n"; returns 0 when cut. */
static int append(char *line, size_t *len, const char *fmt, va_list ap)
{
    const size_t room = MTD_LOG_LINE_MAX - 5 - *len;
    int n = vsnprintf(line + *len, room, fmt, ap);
    if (n < 0) return 1;
    if ((size_t)n >= room) {
        *len += room - 1;
        return 0;
    }
    *len += (size_t)n;
    return 1;
}

static int append_text(char *line, size_t *len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int whole = append(line, len, fmt, ap);
    va_end(ap);
    return whole;
}

void mtd_log(mtd_log_level level, const char *event, const char *fmt, ...)
{
    if ((int)level > atomic_load(&log_level)) return;
    char line[MTD_LOG_LINE_MAX];
    size_t len = 0;
    struct timespec now;
    struct tm utc;
    clock_gettime(CLOCK_REALTIME, &now);
    gmtime_r(&now.tv_sec, &utc);
    len = strftime(line, sizeof line, "%Y-%m-%dT%H:%M:%S", &utc);
    int whole = append_text(line, &len, ".%03ldZ meshtopod[%ld] %s %s", now.tv_nsec / 1000000,
                            (long)getpid(), mtd_log_level_name(level), event ? event : "-");
    const size_t details = len;
    if (whole && fmt && fmt[0]) {
        line[len++] = ' ';
        va_list ap;
        va_start(ap, fmt);
        whole = append(line, &len, fmt, ap);
        va_end(ap);
    }
    for (size_t i = details; i < len; i++)
        if (line[i] == '\n' || line[i] == '\r') line[i] = ' ';
    if (!whole) {
        memcpy(line + len, "...", 3);
        len += 3;
    }
    line[len++] = '\n';
    int fd = atomic_load(&log_fd);
    ssize_t written = write(fd >= 0 ? fd : STDERR_FILENO, line, len);
    (void)written; /* nowhere left to report a failing log */
}
