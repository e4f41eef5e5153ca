/* meshtopo::msgs protocol rules that are code, not fields: the mesh-id rule
 * and the one table between status_code_t values, mt_status and names. The
 * daemon, the client and the archive call these; the numeric limits are
 * const members of the .lcm types (MESHTOPO_MESH_T_MESH_ID_MAX, ...). Pure
 * functions, any thread. */
#ifndef MESHTOPO_PROTOCOL_H
#define MESHTOPO_PROTOCOL_H

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
 * length rules). */
mt_status mt_msgs_mesh_id_check(const char *id, mt_diag *diag);

/* The mt_status a status_code_t value stands for (MT_ERR_IO for a code this
 * table does not know: a newer daemon's). */
mt_status mt_msgs_status_of_code(int32_t code);

/* The name of a status_code_t value ("OK", "BAD_REQUEST", ...), or
 * "UNKNOWN_CODE". */
const char *mt_msgs_code_name(int32_t code);

#ifdef __cplusplus
}
#endif

#endif
