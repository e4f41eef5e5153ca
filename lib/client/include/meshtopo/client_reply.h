/* meshtopo::client: reading a reply_t without touching its offset arrays.
 * A reply holds every item of a batch as two-level CSR (items -> groups ->
 * values, values2; msgs/reply_t.lcm has the table of what each query kind
 * puts where). The client checks those arrays once, before it hands a reply
 * out (mt_client_query, mt_client_list, the asynchronous callback): a reply
 * whose offsets do not describe its arrays fails the call with
 * MT_ERR_CORRUPT. The accessors below then index a handed-out reply without
 * further checks. Pure functions, any thread. */
#ifndef MESHTOPO_CLIENT_REPLY_H
#define MESHTOPO_CLIENT_REPLY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/msgs.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One item of a batch: the answer for one id (or id pair, loop, kind). */
typedef struct mt_client_item {
    int32_t status;     /* status_code_t: OK, or NOT_FOUND (then no groups) */
    size_t first_group; /* its groups are first_group .. first_group + num_groups - 1 */
    size_t num_groups;
} mt_client_item;

/* One group of an item: a fan of a one-ring, a side of a face, a loop, ... */
typedef struct mt_client_group {
    bool boundary; /* an open fan, or a side with no face across */
    const int32_t *values;
    size_t num_values;
    const int32_t *values2;
    size_t num_values2;
} mt_client_group;

/* Checks that reply's offsets describe its arrays: item_offsets has
 * num_items + 1 entries, value_offsets and value2_offsets num_groups + 1,
 * each starting at 0, never decreasing and ending at num_groups, num_values
 * and num_values2 (a reply with no items and no groups may carry no offsets
 * at all). MT_OK, or MT_ERR_CORRUPT with diag (NULL-safe) naming the array
 * and the entry. The client runs this on every reply it hands out. */
mt_status mt_client_reply_check(const meshtopo_reply_t *reply, mt_diag *diag);

/* Items in the reply. */
size_t mt_client_reply_num_items(const meshtopo_reply_t *reply);

/* Item `item` (< mt_client_reply_num_items) of a checked reply. */
mt_client_item mt_client_reply_item(const meshtopo_reply_t *reply, size_t item);

/* Group `group` (< reply->num_groups) of a checked reply. */
mt_client_group mt_client_reply_group(const meshtopo_reply_t *reply, size_t group);

/* The k-th group (k < item.num_groups) of an item of a checked reply. */
mt_client_group mt_client_item_group(const meshtopo_reply_t *reply, const mt_client_item *item,
                                     size_t k);

/* The real value of item `item` for the kinds that give one per item
 * (DIHEDRAL_ANGLES, ANGLE_DEFICITS; CONVEXITY's volume is item 0), or NaN
 * when the reply has none for it. */
double mt_client_reply_real(const meshtopo_reply_t *reply, size_t item);

#ifdef __cplusplus
}
#endif

#endif
