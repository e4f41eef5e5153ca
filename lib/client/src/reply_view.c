/* Reading a reply_t (meshtopo/client_reply.h): one check of the two-level
 * CSR, then accessors that index it. Below the rest of the client: it calls
 * nothing of it. */
#include <math.h>

#include "meshtopo/client_reply.h"

/* offsets[0 .. count) starts at 0, never decreases and ends at `end`. */
static mt_status check_offsets(const char *name, const int32_t *offsets, int32_t count,
                               int32_t expected_count, int32_t end, const char *end_name,
                               mt_diag *diag)
{
    if (count != expected_count)
        return mt_diag_set(diag, MT_ERR_CORRUPT, "reply_t.%s has %d entries, expected %d", name,
                           (int)count, (int)expected_count);
    if (offsets[0] != 0)
        return mt_diag_set(diag, MT_ERR_CORRUPT, "reply_t.%s[0] = %d, expected 0", name,
                           (int)offsets[0]);
    for (int32_t i = 1; i < count; i++)
        if (offsets[i] < offsets[i - 1])
            return mt_diag_set(diag, MT_ERR_CORRUPT, "reply_t.%s[%d] = %d is below %s[%d] = %d",
                               name, (int)i, (int)offsets[i], name, (int)i - 1,
                               (int)offsets[i - 1]);
    if (offsets[count - 1] != end)
        return mt_diag_set(diag, MT_ERR_CORRUPT, "reply_t.%s[%d] = %d, expected %s = %d", name,
                           (int)count - 1, (int)offsets[count - 1], end_name, (int)end);
    return MT_OK;
}

mt_status mt_client_reply_check(const meshtopo_reply_t *r, mt_diag *diag)
{
    if (diag) mt_diag_clear(diag);
    /* Counts are never negative in a decoded message (mt_msgs_decode). */
    if (r->num_items == 0 && r->num_groups == 0 && r->num_item_offsets == 0 &&
        r->num_value_offsets == 0 && r->num_values == 0 && r->num_values2 == 0)
        return MT_OK;
    mt_status s = check_offsets("item_offsets", r->item_offsets, r->num_item_offsets,
                                r->num_items + 1, r->num_groups, "num_groups", diag);
    if (s == MT_OK)
        s = check_offsets("value_offsets", r->value_offsets, r->num_value_offsets,
                          r->num_groups + 1, r->num_values, "num_values", diag);
    if (s == MT_OK)
        s = check_offsets("value2_offsets", r->value2_offsets, r->num_value_offsets,
                          r->num_groups + 1, r->num_values2, "num_values2", diag);
    return s;
}

size_t mt_client_reply_num_items(const meshtopo_reply_t *r)
{
    return (size_t)r->num_items;
}

mt_client_item mt_client_reply_item(const meshtopo_reply_t *r, size_t item)
{
    mt_client_item it = {
        .status = r->item_status[item],
        .first_group = (size_t)r->item_offsets[item],
        .num_groups = (size_t)(r->item_offsets[item + 1] - r->item_offsets[item]),
    };
    return it;
}

mt_client_group mt_client_reply_group(const meshtopo_reply_t *r, size_t group)
{
    const int32_t v = r->value_offsets[group], w = r->value2_offsets[group];
    mt_client_group g = {
        .boundary = r->group_boundary[group] != 0,
        /* No arithmetic on NULL: empty arrays decode as NULL. */
        .values = r->values ? r->values + v : r->values,
        .num_values = (size_t)(r->value_offsets[group + 1] - v),
        .values2 = r->values2 ? r->values2 + w : r->values2,
        .num_values2 = (size_t)(r->value2_offsets[group + 1] - w),
    };
    return g;
}

mt_client_group mt_client_item_group(const meshtopo_reply_t *r, const mt_client_item *item,
                                     size_t k)
{
    return mt_client_reply_group(r, item->first_group + k);
}

double mt_client_reply_real(const meshtopo_reply_t *r, size_t item)
{
    return item < (size_t)r->num_reals ? r->reals[item] : NAN;
}
