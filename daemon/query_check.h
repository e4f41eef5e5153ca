/* meshtopod's checks of a query_t against the query-kind table
 * (meshtopo/query_kinds.h): the kind, the shape of its ids, the version,
 * then the ids against the mesh's counts. A query failing one is answered
 * with its status and no items. Pure functions, any thread. */
#ifndef MESHTOPOD_QUERY_CHECK_H
#define MESHTOPOD_QUERY_CHECK_H

#include "answer.h"
#include "meshtopo/query_kinds.h"

/* Checks the kind and the shape of the ids (not their range) and the
 * version; returns the kind's row, or NULL with a failed (UNKNOWN_KIND,
 * BAD_REQUEST). */
const mt_msgs_query_kind *mtd_query_check(mtd_answer *a, const meshtopo_query_t *q);

/* Checks the ids of a query of kind k against the mesh's counts
 * (OUT_OF_RANGE). */
void mtd_query_check_ids(mtd_answer *a, const mt_msgs_query_kind *k, const meshtopo_query_t *q,
                         const mt_mesh *mesh);

#endif
