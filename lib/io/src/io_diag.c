/* Error reports of meshtopo::io: every parse error names the file and the
 * line (text) or byte offset (binary) it was found at, so messages read
 * "mesh.off:17: face 3: expected 4 vertex indices, found 2". Line numbers
 * are counted only when an error is reported, never while parsing. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "io_internal.h"

static uint64_t line_of(const mt__io_src *src, size_t offset)
{
    uint64_t line = 1;
    if (offset > src->size) offset = src->size;
    const unsigned char *p = src->data, *end = src->data + offset;
    while (p < end) {
        const unsigned char *nl = memchr(p, '\n', (size_t)(end - p));
        if (!nl) break;
        line++;
        p = nl + 1;
    }
    return line;
}

mt_status mt__io_fail(mt_diag *diag, mt_status status, const mt__io_src *src, mt__io_pos pos,
                      size_t offset, uint32_t element, const char *fmt, ...)
{
    if (!diag) return status;
    diag->status = status;
    diag->element = element;
    diag->line = 0;
    diag->byte_offset = UINT64_MAX;
    const char *name = src && src->name ? src->name : "<memory>";
    int n;
    if (pos == MT__POS_LINE && src) {
        diag->line = line_of(src, offset);
        diag->byte_offset = offset;
        n = snprintf(diag->message, sizeof diag->message, "%s:%llu: ", name,
                     (unsigned long long)diag->line);
    } else if (pos == MT__POS_BYTE) {
        diag->byte_offset = offset;
        n = snprintf(diag->message, sizeof diag->message, "%s: byte offset %llu: ", name,
                     (unsigned long long)offset);
    } else {
        n = snprintf(diag->message, sizeof diag->message, "%s: ", name);
    }
    if (n < 0) n = 0;
    if ((size_t)n < sizeof diag->message) {
        va_list args;
        va_start(args, fmt);
        vsnprintf(diag->message + n, sizeof diag->message - (size_t)n, fmt, args);
        va_end(args);
    }
    return status;
}

mt_status mt__io_fail_nomem(mt_diag *diag, const mt__io_src *src)
{
    return mt__io_fail(diag, MT_ERR_NOMEM, src, MT__POS_NONE, 0, MT_NONE,
                       "out of memory while reading the mesh");
}

void mt__io_excerpt(char *buf, size_t bufsize, const unsigned char *s, size_t len)
{
    static const char hex[] = "0123456789abcdef";
    size_t o = 0;
    if (bufsize == 0) return;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = s[i];
        size_t need = (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'') ? 1 : 4;
        if (o + need + 4 > bufsize || i >= 40) {
            if (o + 4 <= bufsize) {
                memcpy(buf + o, "...", 3);
                o += 3;
            }
            break;
        }
        if (need == 1) {
            buf[o++] = (char)c;
        } else {
            buf[o++] = '\\';
            buf[o++] = 'x';
            buf[o++] = hex[c >> 4];
            buf[o++] = hex[c & 15];
        }
    }
    buf[o] = '\0';
}
