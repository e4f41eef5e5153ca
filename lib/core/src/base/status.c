/* Status texts, diagnostics and the defect table's names, all generated from
 * the X-macro tables in status.h and report.h. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "base/base.h"
#include "meshtopo/report.h"
#include "meshtopo/status.h"

const char *mt_strerror(mt_status status)
{
    switch (status) {
#define MT__STATUS_TEXT(name, text) \
    case name:                      \
        return text;
        MT_STATUS_TABLE(MT__STATUS_TEXT)
#undef MT__STATUS_TEXT
        default:
            return "unknown status";
    }
}

void mt_diag_clear(mt_diag *diag)
{
    if (!diag) return;
    memset(diag, 0, sizeof *diag);
    diag->byte_offset = UINT64_MAX;
    diag->element = MT_NONE;
}

mt_status mt_diag_set(mt_diag *diag, mt_status status, const char *fmt, ...)
{
    if (!diag) return status;
    mt_diag_clear(diag);
    diag->status = status;
    va_list args;
    va_start(args, fmt);
    vsnprintf(diag->message, sizeof diag->message, fmt, args);
    va_end(args);
    return status;
}

mt_status mt__fail(mt_diag *diag, mt_status status, uint32_t element, const char *fmt, ...)
{
    if (!diag) return status;
    diag->status = status;
    diag->element = element;
    va_list args;
    va_start(args, fmt);
    vsnprintf(diag->message, sizeof diag->message, fmt, args);
    va_end(args);
    return status;
}

const char *mt_defect_key(mt_defect_kind kind)
{
    switch (kind) {
#define MT__DEFECT_KEY(name, key, text) \
    case name:                          \
        return key;
        MT_DEFECT_TABLE(MT__DEFECT_KEY)
#undef MT__DEFECT_KEY
        default:
            return "unknown_defect";
    }
}

const char *mt_defect_description(mt_defect_kind kind)
{
    switch (kind) {
#define MT__DEFECT_TEXT(name, key, text) \
    case name:                           \
        return text;
        MT_DEFECT_TABLE(MT__DEFECT_TEXT)
#undef MT__DEFECT_TEXT
        default:
            return "unknown defect";
    }
}
