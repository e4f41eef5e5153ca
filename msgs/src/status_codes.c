/* The one table between status_code_t values (msgs/status_code_t.lcm), the
 * mt_status each stands for and its name (meshtopo/protocol.h). */
#include "meshtopo/msgs.h"
#include "meshtopo/protocol.h"

typedef struct code_entry {
    int32_t code;
    const char *name;
    mt_status status;
} code_entry;

static const code_entry codes[] = {
    {MESHTOPO_STATUS_CODE_T_OK, "OK", MT_OK},
    {MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "BAD_REQUEST", MT_ERR_INVALID_ARG},
    {MESHTOPO_STATUS_CODE_T_UNDECODABLE, "UNDECODABLE", MT_ERR_PARSE},
    {MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH, "UNKNOWN_MESH", MT_ERR_NOT_FOUND},
    {MESHTOPO_STATUS_CODE_T_UNKNOWN_KIND, "UNKNOWN_KIND", MT_ERR_UNSUPPORTED},
    {MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE, "OUT_OF_RANGE", MT_ERR_OUT_OF_RANGE},
    {MESHTOPO_STATUS_CODE_T_NOT_FOUND, "NOT_FOUND", MT_ERR_NOT_FOUND},
    {MESHTOPO_STATUS_CODE_T_TOO_LARGE, "TOO_LARGE", MT_ERR_TOO_LARGE},
    {MESHTOPO_STATUS_CODE_T_BUILD_FAILED, "BUILD_FAILED", MT_ERR_CORRUPT},
    {MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED, "DEFECT_REFUSED", MT_ERR_DEFECT},
    {MESHTOPO_STATUS_CODE_T_BUSY, "BUSY", MT_ERR_IO},
    {MESHTOPO_STATUS_CODE_T_INTERNAL, "INTERNAL", MT_ERR_IO},
    {MESHTOPO_STATUS_CODE_T_NO_GEOMETRY, "NO_GEOMETRY", MT_ERR_NO_GEOMETRY},
    {MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED, "ARCHIVE_FAILED", MT_ERR_IO},
};

static const code_entry *find(int32_t code)
{
    for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++)
        if (codes[i].code == code) return &codes[i];
    return NULL;
}

mt_status mt_msgs_status_of_code(int32_t code)
{
    const code_entry *e = find(code);
    return e ? e->status : MT_ERR_IO;
}

const char *mt_msgs_code_name(int32_t code)
{
    const code_entry *e = find(code);
    return e ? e->name : "UNKNOWN_CODE";
}
