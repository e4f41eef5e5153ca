/* meshtopo::msgs protocol rules that are code, not fields: the mesh-id rule,
 * the owner of a mesh id in a cluster, and the one table between
 * status_code_t values, mt_status and names. The
 * daemon, the client and the tools call these; the numeric limits are
 * const members of the .lcm types (MESHTOPO_MESH_T_MESH_ID_MAX, ...). Pure
 * functions, any thread. */
#ifndef MESHTOPO_PROTOCOL_H
#define MESHTOPO_PROTOCOL_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/msgs.h" /* the limits: MESHTOPO_MESH_T_MESH_ID_MAX, ... */
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Checks a mesh id: not NULL, not empty, at most MESHTOPO_MESH_T_MESH_ID_MAX
 * (255) bytes, printable ASCII only (0x20 to 0x7e), no '/' and no "..".
 * Mesh ids come from the network and end up in archive names and logs, so a
 * bad one is refused rather than repaired. Returns MT_OK or
 * MT_ERR_INVALID_ARG with diag (NULL-safe) naming the rule broken and
 * diag->byte_offset the offending byte (UINT64_MAX for the NULL, empty and
 * length rules). The rule itself is meshtopo::ident's mt_mesh_id_check
 * (meshtopo/mesh_ident.h), which the archive calls too. */
mt_status mt_msgs_mesh_id_check(const char *id, mt_diag *diag);

/* Which member of a cluster (meshtopod --cluster) owns a mesh id:
 * rendezvous (highest-random-weight) hashing over the members' seeds, each
 * member's seed being mt_msgs_cluster_seed of its heartbeat's instance
 * (status_t.instance). Returns the index in seeds[0 .. num_members - 1] (0
 * when num_members is 0). Every member computes the same, and so can a
 * client or a tool that reads the heartbeats. */
uint64_t mt_msgs_cluster_seed(const char *instance);
size_t mt_msgs_cluster_owner(const uint64_t *seeds, size_t num_members, const char *mesh_id);

/* The mt_status a status_code_t value stands for (MT_ERR_IO for a code this
 * table does not know: a newer daemon's). */
mt_status mt_msgs_status_of_code(int32_t code);

/* The status_code_t value that sends a library status: MT_OK is OK,
 * MT_ERR_INVALID_ARG BAD_REQUEST, MT_ERR_TOO_LARGE TOO_LARGE,
 * MT_ERR_NO_GEOMETRY NO_GEOMETRY, MT_ERR_NOMEM INTERNAL; any other status
 * gives `otherwise`, the code of the failure the caller met (BUILD_FAILED
 * for a build, INTERNAL for a query the daemon had checked). The same table
 * as mt_msgs_status_of_code, read the other way. */
int32_t mt_msgs_code_of_status(mt_status status, int32_t otherwise);

/* The name of a status_code_t value ("OK", "BAD_REQUEST", ...), or
 * "UNKNOWN_CODE". */
const char *mt_msgs_code_name(int32_t code);

#ifdef __cplusplus
}
#endif

#endif
