/* Error reports of meshtopo::io: every parse error names the file and the
 * line (text) or byte offset (binary) it was found at, so messages read
 * "mesh.off:17: face 3: expected 4 vertex indices, found 2". Line numbers
 * are counted when an error is reported (and, for input read a window at a
 * time, in the bytes the window drops: io_source.c), never per token. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "io_internal.h"

/* 16 bytes a step where the compiler has vector extensions. */
uint64_t mt__count_newlines(const unsigned char *p, size_t n)
{
    uint64_t count = 0;
    size_t i = 0;
#if defined(__GNUC__)
    typedef unsigned char v16 __attribute__((vector_size(16)));
    const v16 newline = {'\n', '\n', '\n', '\n', '\n', '\n', '\n', '\n',
                         '\n', '\n', '\n', '\n', '\n', '\n', '\n', '\n'};
    while (n - i >= 16) {
        v16 acc = {0};
        size_t steps = (n - i) / 16;
        if (steps > 255) steps = 255; /* each lane counts to 255 at most */
        for (size_t k = 0; k < steps; k++, i += 16) {
            v16 v;
            memcpy(&v, p + i, sizeof v);
            acc -= (v16)(v == newline); /* a match is all ones: -1 */
        }
        for (int k = 0; k < 16; k++) count += acc[k];
    }
#endif
    for (; i < n; i++) count += p[i] == '\n';
    return count;
}

uint64_t mt__src_line(const mt__io_src *src, uint64_t offset)
{
    if (offset < src->base) {
        /* Messages point into the window or at the mark (io_internal.h). */
        return offset == src->mark ? src->mark_line : 0;
    }
    uint64_t rel = offset - src->base;
    if (rel > src->size) rel = src->size;
    return 1 + src->lines + mt__count_newlines(src->data, (size_t)rel);
}

/* Fills diag; line 0 with MT__POS_LINE means: compute it from the offset. */
static mt_status vfail(mt_diag *diag, mt_status status, const mt__io_src *src, mt__io_pos pos,
                       uint64_t offset, uint64_t line, uint32_t element, const char *fmt,
                       va_list args)
{
    if (!diag) return status;
    diag->status = status;
    diag->element = element;
    diag->line = 0;
    diag->byte_offset = UINT64_MAX;
    const char *name = src && src->name ? src->name : "<memory>";
    int n;
    if (pos == MT__POS_LINE && src) {
        diag->line = line ? line : mt__src_line(src, offset);
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
    if ((size_t)n < sizeof diag->message)
        vsnprintf(diag->message + n, sizeof diag->message - (size_t)n, fmt, args);
    return status;
}

mt_status mt__io_fail(mt_diag *diag, mt_status status, const mt__io_src *src, mt__io_pos pos,
                      uint64_t offset, uint32_t element, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    status = vfail(diag, status, src, pos, offset, 0, element, fmt, args);
    va_end(args);
    return status;
}

mt_status mt__io_fail_line(mt_diag *diag, mt_status status, const mt__io_src *src, uint64_t offset,
                           uint64_t line, uint32_t element, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    status = vfail(diag, status, src, MT__POS_LINE, offset, line, element, fmt, args);
    va_end(args);
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
