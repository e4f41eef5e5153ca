/* The replay plan of `meshtopo replay`: parses --since/--until times
 * (microseconds since the epoch or ISO 8601 UTC, converted with the proleptic
 * Gregorian calendar, no time zone database involved), selects archived
 * versions by id and time and orders them by utime with their scaled offsets. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cmd_replay.h"

/* Reads exactly `n` decimal digits at *p, advancing it. */
static bool digits_read(const char **p, int n, int *out)
{
    int v = 0;
    for (int i = 0; i < n; i++) {
        char c = (*p)[i];
        if (c < '0' || c > '9') return false;
        v = v * 10 + (c - '0');
    }
    *p += n;
    *out = v;
    return true;
}

static bool is_leap(int y)
{
    return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

/* Days from 1970-01-01 to y-m-d (Howard Hinnant's days_from_civil). */
static int64_t days_from_civil(int64_t y, int m, int d)
{
    y -= m <= 2;
    int64_t era = (y >= 0 ? y : y - 399) / 400;
    int64_t yoe = y - era * 400;
    int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

static bool iso_parse(const char *text, int64_t *out)
{
    static const int month_days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const char *p = text;
    int y, mo, d, h, mi, s;
    if (!digits_read(&p, 4, &y) || *p++ != '-' || !digits_read(&p, 2, &mo) || *p++ != '-' ||
        !digits_read(&p, 2, &d) || *p++ != 'T' || !digits_read(&p, 2, &h) || *p++ != ':' ||
        !digits_read(&p, 2, &mi) || *p++ != ':' || !digits_read(&p, 2, &s))
        return false;
    if (mo < 1 || mo > 12 || d < 1 || h > 23 || mi > 59 || s > 59) return false;
    if (d > month_days[mo - 1] + (mo == 2 && is_leap(y))) return false;
    int64_t micros = 0;
    if (*p == '.') {
        p++;
        int n = 0;
        while (*p >= '0' && *p <= '9') {
            if (++n > 6) return false;
            micros = micros * 10 + (*p++ - '0');
        }
        if (n == 0) return false;
        for (; n < 6; n++) micros *= 10;
    }
    if (strcmp(p, "Z") != 0 && strcmp(p, "+00:00") != 0) return false;
    int64_t seconds = days_from_civil(y, mo, d) * 86400 + (int64_t)h * 3600 + mi * 60 + s;
    *out = seconds * 1000000 + micros;
    return true;
}

bool cli_replay_parse_time(const char *text, int64_t *out_utime)
{
    if (!text[0]) return false;
    if (strspn(text, "0123456789") == strlen(text)) {
        if (strlen(text) > 18) return false; /* keeps the value far below INT64_MAX */
        *out_utime = (int64_t)strtoll(text, NULL, 10);
        return true;
    }
    return iso_parse(text, out_utime);
}

static int item_compare(const void *a, const void *b)
{
    const mt_archive_entry *x = ((const cli_replay_item *)a)->entry;
    const mt_archive_entry *y = ((const cli_replay_item *)b)->entry;
    if (x->utime != y->utime) return x->utime < y->utime ? -1 : 1;
    int c = strcmp(x->mesh_id, y->mesh_id);
    if (c != 0) return c;
    return x->version < y->version ? -1 : x->version > y->version;
}

/* Whether `id` is one of the comma-separated ids of `list`. */
static bool id_listed(const char *list, const char *id)
{
    size_t len = strlen(id);
    for (const char *p = list;;) {
        size_t n = strcspn(p, ",");
        if (n == len && memcmp(p, id, len) == 0) return true;
        if (!p[n]) return false;
        p += n + 1;
    }
}

/* Reports every id of the list no readable entry has; true when all exist. */
static bool ids_check(const mt_archive_listing *listing, const char *list)
{
    bool ok = true;
    for (const char *p = list;;) {
        size_t n = strcspn(p, ",");
        bool found = false;
        for (size_t i = 0; i < listing->count && !found; i++) {
            const mt_archive_entry *e = &listing->entries[i];
            found = e->status == MT_OK && strlen(e->mesh_id) == n && memcmp(e->mesh_id, p, n) == 0;
        }
        if (!found) {
            cli_error("replay", "--ids: no archived version of mesh '%.*s'", (int)n, p);
            ok = false;
        }
        if (!p[n]) return ok;
        p += n + 1;
    }
}

int cli_replay_plan_make(const mt_archive_listing *listing, const cli_replay_filter *filter,
                         double rate, cli_replay_plan *out)
{
    memset(out, 0, sizeof *out);
    if (filter->ids && !ids_check(listing, filter->ids)) return CLI_EXIT_USAGE;
    if (listing->count == 0) return CLI_EXIT_OK;
    out->items = calloc(listing->count, sizeof *out->items);
    if (!out->items) {
        cli_error("replay", "out of memory for %zu archive entries", listing->count);
        return CLI_EXIT_READ;
    }
    for (size_t i = 0; i < listing->count; i++) {
        const mt_archive_entry *e = &listing->entries[i];
        if (e->status != MT_OK) continue;
        if (filter->ids && !id_listed(filter->ids, e->mesh_id)) continue;
        if (filter->has_since && e->utime < filter->since) continue;
        if (filter->has_until && e->utime >= filter->until) continue;
        out->items[out->count++].entry = e;
    }
    qsort(out->items, out->count, sizeof *out->items, item_compare);
    for (size_t i = 0; i < out->count; i++) {
        double gap_s = (double)(out->items[i].entry->utime - out->items[0].entry->utime) / 1e6;
        out->items[i].offset_s = rate > 0 ? gap_s / rate : 0.0;
    }
    return CLI_EXIT_OK;
}

void cli_replay_plan_free(cli_replay_plan *plan)
{
    if (!plan) return;
    free(plan->items);
    memset(plan, 0, sizeof *plan);
}
