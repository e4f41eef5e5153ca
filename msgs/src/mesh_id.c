/* The mesh-id rule (meshtopo/protocol.h), the one copy every side calls: a
 * mesh id is a name a robot chose, sent over the network; it must never read
 * as a path nor carry control bytes into logs. */
#include <string.h>

#include "meshtopo/msgs.h"
#include "meshtopo/protocol.h"

/* Names the offending byte of a refused id in diag (already set). */
static mt_status refused_at(mt_diag *diag, uint64_t at)
{
    if (diag) diag->byte_offset = at;
    return MT_ERR_INVALID_ARG;
}

mt_status mt_msgs_mesh_id_check(const char *id, mt_diag *diag)
{
    if (!id) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "mesh id is missing (NULL)");
    size_t len = strnlen(id, MESHTOPO_MESH_T_MESH_ID_MAX + 1);
    if (len == 0) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "mesh id is empty");
    if (len > MESHTOPO_MESH_T_MESH_ID_MAX)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG,
                           "mesh id is %zu bytes long; the limit is %d bytes", strlen(id),
                           MESHTOPO_MESH_T_MESH_ID_MAX);
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)id[i];
        if (c < 0x20 || c > 0x7e) {
            mt_diag_set(diag, MT_ERR_INVALID_ARG,
                        "mesh id byte %zu is 0x%02x: only printable ASCII (0x20 to 0x7e) is "
                        "allowed",
                        i, c);
            return refused_at(diag, i);
        }
        if (c == '/' || (c == '.' && id[i + 1] == '.')) {
            mt_diag_set(diag, MT_ERR_INVALID_ARG,
                        "mesh id contains %s at byte %zu: ids must not look like paths",
                        c == '/' ? "'/'" : "\"..\"", i);
            return refused_at(diag, i);
        }
    }
    if (diag) mt_diag_clear(diag);
    return MT_OK;
}
