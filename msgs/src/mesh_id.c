/* The mesh-id rule (meshtopo/protocol.h), the one copy every side calls: a
 * mesh id is a name a robot chose, sent over the network; it must never read
 * as a path nor carry control bytes into logs. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "meshtopo/msgs.h"
#include "meshtopo/protocol.h"

static mt_status refuse(mt_diag *diag, uint64_t byte_offset, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static mt_status refuse(mt_diag *diag, uint64_t byte_offset, const char *fmt, ...)
{
    if (!diag) return MT_ERR_INVALID_ARG;
    mt_diag_clear(diag);
    diag->status = MT_ERR_INVALID_ARG;
    diag->byte_offset = byte_offset;
    va_list args;
    va_start(args, fmt);
    vsnprintf(diag->message, sizeof diag->message, fmt, args);
    va_end(args);
    return MT_ERR_INVALID_ARG;
}

mt_status mt_msgs_mesh_id_check(const char *id, mt_diag *diag)
{
    if (!id) return refuse(diag, UINT64_MAX, "mesh id is missing (NULL)");
    size_t len = strnlen(id, MESHTOPO_MESH_T_MESH_ID_MAX + 1);
    if (len == 0) return refuse(diag, UINT64_MAX, "mesh id is empty");
    if (len > MESHTOPO_MESH_T_MESH_ID_MAX)
        return refuse(diag, UINT64_MAX, "mesh id is %zu bytes long; the limit is %d bytes",
                      strlen(id), MESHTOPO_MESH_T_MESH_ID_MAX);
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)id[i];
        if (c < 0x20 || c > 0x7e)
            return refuse(diag, i,
                          "mesh id byte %zu is 0x%02x: only printable ASCII (0x20 to 0x7e) is "
                          "allowed",
                          i, c);
        if (c == '/')
            return refuse(diag, i, "mesh id contains '/' at byte %zu: ids must not look like paths",
                          i);
        if (c == '.' && id[i + 1] == '.')
            return refuse(diag, i,
                          "mesh id contains \"..\" at byte %zu: ids must not look like paths", i);
    }
    if (diag) mt_diag_clear(diag);
    return MT_OK;
}
