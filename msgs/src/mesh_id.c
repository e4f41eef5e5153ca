/* The mesh-id rule as msgs/ gives it to the daemon, the client and the tools
 * (meshtopo/protocol.h): meshtopo::ident's one copy (mt_mesh_id_check),
 * whose limit is mesh_t's MESH_ID_MAX. */
#include "meshtopo/mesh_ident.h"
#include "meshtopo/msgs.h"
#include "meshtopo/protocol.h"

_Static_assert(MESHTOPO_MESH_T_MESH_ID_MAX == MT_MESH_ID_MAX,
               "msgs/mesh_t.lcm's MESH_ID_MAX is the limit of meshtopo/mesh_ident.h");

mt_status mt_msgs_mesh_id_check(const char *id, mt_diag *diag)
{
    return mt_mesh_id_check(id, diag);
}
