/* The mesh-id rule (meshtopo/mesh_ident.h), the one copy every side calls
 * (msgs' mt_msgs_mesh_id_check is this rule): a mesh id is a name a robot
 * chose, sent over the network; it must never read as a path nor carry
 * control bytes into logs. */
#include <string.h>

#include "meshtopo/mesh_ident.h"

/* Names the offending byte of a refused id in diag (already set). */
static mt_status refused_at(mt_diag *diag, uint64_t at)
{
    if (diag) diag->byte_offset = at;
    return MT_ERR_INVALID_ARG;
}

mt_status mt_mesh_id_check(const char *id, mt_diag *diag)
{
    if (!id) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "mesh id is missing (NULL)");
    size_t len = strnlen(id, MT_MESH_ID_MAX + 1);
    if (len == 0) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "mesh id is empty");
    if (len > MT_MESH_ID_MAX)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG,
                           "mesh id is %zu bytes long; the limit is %d bytes", strlen(id),
                           MT_MESH_ID_MAX);
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
    mt_diag_clear(diag);
    return MT_OK;
}
