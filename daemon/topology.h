/* meshtopod's topology reports: a built mesh's mt_report copied field by
 * field into a meshtopo_topology_t (msgs/topology_t.lcm). Pure functions,
 * any thread. */
#ifndef MESHTOPOD_TOPOLOGY_H
#define MESHTOPOD_TOPOLOGY_H

#include <stddef.h>
#include <stdint.h>

#include "mesh_store.h"
#include "meshtopo/msgs.h"

/* Entries listed per array in a topology_t published with a build; the
 * REPORT and DEFECTS queries give the complete lists. */
#define MTD_TOPOLOGY_LIST_MAX 65536u

/* Fills out (zeroed first) from a built mesh's report; at most list_max
 * entries per list (SIZE_MAX for all). Returns 0, or -1 when out of memory
 * (out then owns nothing). Free with mtd_topology_free. */
int mtd_topology_fill(const mt_mesh *mesh, const mtd_mesh_info *info, int64_t build_duration_us,
                      size_t list_max, meshtopo_topology_t *out);

/* Frees what mtd_topology_fill allocated. NULL-safe. */
void mtd_topology_free(meshtopo_topology_t *topology);

#endif
