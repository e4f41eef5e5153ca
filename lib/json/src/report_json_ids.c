/* Id lists for meshtopo::json's writers: a JSON array of ids, and the
 * sorted sets without repeats that the corpus answers list
 * (report_json_internal.h). */
#include <stdlib.h>

#include "report_json_internal.h"

void mt__json_write_ids(mt_json *j, const uint32_t *ids, size_t count)
{
    mt_json_array_begin(j);
    for (size_t i = 0; i < count; i++) mt_json_uint(j, ids[i]);
    mt_json_array_end(j);
}

static int compare_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

size_t mt__json_sort_unique(uint32_t *ids, size_t count)
{
    if (count == 0) return 0;
    qsort(ids, count, sizeof *ids, compare_u32);
    size_t out = 1;
    for (size_t i = 1; i < count; i++)
        if (ids[i] != ids[out - 1]) ids[out++] = ids[i];
    return out;
}
