/* The one table between status_code_t values (msgs/status_code_t.lcm), their
 * names and mt_status, both ways (meshtopo/protocol.h): a reply's code read
 * as a library status, and a library status sent as a code. */
#include "meshtopo/msgs.h"
#include "meshtopo/protocol.h"

/* Which way a row maps. */
enum {
    TO_STATUS = 1,   /* the code reads as this status */
    FROM_STATUS = 2, /* this status is sent as the code */
    BOTH = TO_STATUS | FROM_STATUS,
};

typedef struct code_entry {
    int32_t code;
    const char *name;
    mt_status status;
    int ways;
} code_entry;

/* A status no FROM_STATUS row names has no code of its own: what it means
 * depends on what failed (a build's failure, a query's bug), so the caller
 * says (mt_msgs_code_of_status's `otherwise`). */
static const code_entry codes[] = {
    {MESHTOPO_STATUS_CODE_T_OK, "OK", MT_OK, BOTH},
    {MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "BAD_REQUEST", MT_ERR_INVALID_ARG, BOTH},
    {MESHTOPO_STATUS_CODE_T_UNDECODABLE, "UNDECODABLE", MT_ERR_PARSE, TO_STATUS},
    {MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH, "UNKNOWN_MESH", MT_ERR_NOT_FOUND, TO_STATUS},
    {MESHTOPO_STATUS_CODE_T_UNKNOWN_KIND, "UNKNOWN_KIND", MT_ERR_UNSUPPORTED, TO_STATUS},
    {MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE, "OUT_OF_RANGE", MT_ERR_OUT_OF_RANGE, TO_STATUS},
    {MESHTOPO_STATUS_CODE_T_NOT_FOUND, "NOT_FOUND", MT_ERR_NOT_FOUND, TO_STATUS},
    {MESHTOPO_STATUS_CODE_T_TOO_LARGE, "TOO_LARGE", MT_ERR_TOO_LARGE, BOTH},
    {MESHTOPO_STATUS_CODE_T_BUILD_FAILED, "BUILD_FAILED", MT_ERR_CORRUPT, TO_STATUS},
    {MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED, "DEFECT_REFUSED", MT_ERR_DEFECT, TO_STATUS},
    {MESHTOPO_STATUS_CODE_T_BUSY, "BUSY", MT_ERR_IO, TO_STATUS},
    {MESHTOPO_STATUS_CODE_T_INTERNAL, "INTERNAL", MT_ERR_IO, TO_STATUS},
    {MESHTOPO_STATUS_CODE_T_INTERNAL, "INTERNAL", MT_ERR_NOMEM, FROM_STATUS},
    {MESHTOPO_STATUS_CODE_T_NO_GEOMETRY, "NO_GEOMETRY", MT_ERR_NO_GEOMETRY, BOTH},
    {MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED, "ARCHIVE_FAILED", MT_ERR_IO, TO_STATUS},
};

static const code_entry *find(int32_t code)
{
    for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++)
        if (codes[i].code == code && (codes[i].ways & TO_STATUS)) return &codes[i];
    return NULL;
}

int32_t mt_msgs_code_of_status(mt_status status, int32_t otherwise)
{
    for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++)
        if (codes[i].status == status && (codes[i].ways & FROM_STATUS)) return codes[i].code;
    return otherwise;
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
