/* Element id lists as typed on the command line: "0,78,157", ranges
 * "10-20" (inclusive), or both mixed. Order and repeats are kept, every id
 * is checked against the element count, and the total is bounded so a
 * range cannot exhaust memory. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* Reads an unsigned decimal at *p (no sign, no spaces); false when there is
 * none or it does not fit in 32 bits. */
static bool read_u32(const char **p, uint32_t *out)
{
    const char *s = *p;
    if (*s < '0' || *s > '9') return false;
    uint64_t v = 0;
    while (*s >= '0' && *s <= '9') {
        v = v * 10u + (uint64_t)(*s - '0');
        if (v > UINT32_MAX) return false;
        s++;
    }
    *p = s;
    *out = (uint32_t)v;
    return true;
}

static bool list_push(mt_id_list *list, size_t *cap, uint32_t id)
{
    if (list->count == *cap) {
        size_t new_cap = *cap ? *cap * 2 : 16;
        uint32_t *ids = realloc(list->ids, new_cap * sizeof *ids);
        if (!ids) return false;
        list->ids = ids;
        *cap = new_cap;
    }
    list->ids[list->count++] = id;
    return true;
}

bool mt_id_list_parse(const char *text, uint32_t limit, size_t max_count, mt_id_list *out,
                      char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    size_t cap = 0;
    const char *p = text;
    while (*p) {
        const char *item = p;
        uint32_t first = 0, last = 0;
        if (!read_u32(&p, &first)) {
            snprintf(err, err_size,
                     "expected an id at '%s' (ids are 0, 1, ... separated by commas)", item);
            goto fail;
        }
        last = first;
        if (*p == '-') {
            p++;
            if (!read_u32(&p, &last) || last < first) {
                snprintf(err, err_size, "bad range at '%s' (write FIRST-LAST with FIRST <= LAST)",
                         item);
                goto fail;
            }
        }
        if (*p != ',' && *p != '\0') {
            snprintf(err, err_size, "unexpected '%c' in '%s'", *p, item);
            goto fail;
        }
        if (last >= limit) {
            snprintf(err, err_size, "id %u is out of range (the mesh has %u)",
                     (unsigned)(first >= limit ? first : limit), (unsigned)limit);
            goto fail;
        }
        if ((uint64_t)last - first + 1u > (uint64_t)(max_count - out->count)) {
            snprintf(err, err_size, "too many ids (at most %zu)", max_count);
            goto fail;
        }
        for (uint64_t id = first; id <= last; id++) {
            if (!list_push(out, &cap, (uint32_t)id)) {
                snprintf(err, err_size, "out of memory");
                goto fail;
            }
        }
        if (*p == ',') {
            p++;
            if (*p == '\0') {
                snprintf(err, err_size, "trailing comma");
                goto fail;
            }
        }
    }
    return true;
fail:
    mt_id_list_free(out);
    return false;
}

void mt_id_list_free(mt_id_list *list)
{
    free(list->ids);
    list->ids = NULL;
    list->count = 0;
}
