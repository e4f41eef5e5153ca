/* Status codes and diagnostics shared by every meshtopo library.
 * One X-macro table generates the enum and mt_strerror(), so a code and its
 * text cannot drift apart. Details (which face, which line) go into mt_diag. */
#ifndef MESHTOPO_STATUS_H
#define MESHTOPO_STATUS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* "No element": the one invalid index sentinel for vertices, faces, edges, half-edges. */
#define MT_NONE UINT32_MAX

#define MT_STATUS_TABLE(X)                                         \
    X(MT_OK, "success")                                            \
    X(MT_ERR_INVALID_ARG, "invalid argument")                      \
    X(MT_ERR_NOMEM, "out of memory")                               \
    X(MT_ERR_TOO_LARGE, "size exceeds meshtopo's limits")          \
    X(MT_ERR_DEFECT, "mesh has a defect (strict mode refuses it)") \
    X(MT_ERR_BUFFER_TOO_SMALL, "output buffer too small")          \
    X(MT_ERR_OUT_OF_RANGE, "element id out of range")              \
    X(MT_ERR_NOT_FOUND, "no such element")                         \
    X(MT_ERR_IO, "input/output error")                             \
    X(MT_ERR_PARSE, "malformed mesh file")                         \
    X(MT_ERR_UNSUPPORTED, "unsupported format or feature")         \
    X(MT_ERR_CORRUPT, "mesh structure is inconsistent")            \
    X(MT_ERR_REFUSED, "edit refused: it would break the mesh")     \
    X(MT_ERR_NO_GEOMETRY, "mesh has no vertex positions")

typedef enum mt_status {
#define MT__STATUS_ENUM(name, text) name,
    MT_STATUS_TABLE(MT__STATUS_ENUM)
#undef MT__STATUS_ENUM
        MT_STATUS_COUNT
} mt_status;

/* Short English text for a status; never NULL (unknown codes give "unknown status"). */
const char *mt_strerror(mt_status status);

/* Where and why a call failed. Every function taking an mt_diag * accepts NULL.
 * On failure the function fills it; on success it leaves status = MT_OK and
 * message empty. */
typedef struct mt_diag {
    mt_status status;
    char message[512];    /* one line: what is wrong and where (file, line, element) */
    uint64_t line;        /* 1-based line of a text file, 0 when not applicable */
    uint64_t byte_offset; /* byte offset in a file or buffer, UINT64_MAX when not applicable */
    uint32_t element;     /* face, vertex or half-edge id involved, MT_NONE when none */
} mt_diag;

/* Resets a diag to "no error". NULL-safe. */
void mt_diag_clear(mt_diag *diag);

/* Resets diag (NULL-safe), sets its status and formats its message (cut to
 * fit). Returns status, so a failing call can end with
 * `return mt_diag_set(diag, MT_ERR_..., "...", ...);`. */
mt_status mt_diag_set(mt_diag *diag, mt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#ifdef __cplusplus
}
#endif

#endif
