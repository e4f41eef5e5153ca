/* gzip input (RFC 1952) inflated with zlib a piece at a time, as the
 * window of the input moves on (io_source.c): every member of a
 * multi-member file, then only zero bytes (padding) to the end. Nothing is
 * inflated ahead of what the parser asks for, so a small file that
 * inflates to gigabytes costs time, never memory. Errors name the offset in
 * the compressed bytes. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <zlib.h>

#include "io_internal.h"

struct mt__inflater {
    z_stream zs;
    int member_end; /* a member ended: what follows is not looked at yet */
};

mt__inflater *mt__inflater_new(void)
{
    mt__inflater *z = calloc(1, sizeof *z);
    if (!z) return NULL;
    if (inflateInit2(&z->zs, 16 + MAX_WBITS) != Z_OK) {
        free(z);
        return NULL;
    }
    return z;
}

mt__inflater *mt__inflater_dup(const mt__inflater *z)
{
    mt__inflater *copy = calloc(1, sizeof *copy);
    if (!copy) return NULL;
    if (inflateCopy(&copy->zs, (z_streamp)&z->zs) != Z_OK) {
        free(copy);
        return NULL;
    }
    copy->member_end = z->member_end;
    return copy;
}

void mt__inflater_free(mt__inflater *z)
{
    if (!z) return;
    inflateEnd(&z->zs);
    free(z);
}

static int all_zero(const unsigned char *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (p[i]) return 0;
    return 1;
}

static mt_status read_error(const mt__io_src *src, int err, mt_diag *diag)
{
    char text[256];
    if (strerror_r(err, text, sizeof text) != 0) snprintf(text, sizeof text, "error %d", err);
    return mt__io_fail(diag, MT_ERR_IO, src, MT__POS_NONE, 0, MT_NONE, "cannot read: %s", text);
}

/* After a member: another member starts (1), or only zero bytes follow to
 * the end (0, *done set), or something else does (-1, diag filled). */
static int after_member(mt__inflater *z, mt__io_raw *raw, const mt__io_src *src, int *done,
                        mt_status *status, mt_diag *diag)
{
    while (raw->end - raw->p < 2 && mt__raw_more(raw)) continue;
    size_t left = (size_t)(raw->end - raw->p);
    if (mt__is_gzip(raw->p, left)) {
        if (inflateReset(&z->zs) != Z_OK) {
            *status = mt__io_fail_nomem(diag, src);
            return -1;
        }
        z->member_end = 0;
        return 1;
    }
    uint64_t at = raw->offset;
    for (;;) {
        if (!all_zero(raw->p, left)) {
            *status = mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE, at, MT_NONE,
                                  "unexpected data after the end of the gzip stream");
            return -1;
        }
        raw->p += left;
        raw->offset += left;
        if (!mt__raw_more(raw)) break;
        left = (size_t)(raw->end - raw->p);
    }
    if (raw->err) {
        *status = read_error(src, raw->err, diag);
        return -1;
    }
    *done = 1;
    return 0;
}

size_t mt__inflate(mt__inflater *z, mt__io_raw *raw, unsigned char *out, size_t room,
                   const mt__io_src *src, int *done, mt_status *status, mt_diag *diag)
{
    size_t made = 0;
    while (made < room) {
        if (z->member_end) {
            if (after_member(z, raw, src, done, status, diag) <= 0) break;
            continue;
        }
        if (raw->p == raw->end && !mt__raw_more(raw) && raw->err) {
            *status = read_error(src, raw->err, diag);
            break;
        }
        size_t avail = (size_t)(raw->end - raw->p);
        uInt in = avail < UINT_MAX ? (uInt)avail : UINT_MAX;
        size_t want = room - made;
        z->zs.next_in = (Bytef *)raw->p;
        z->zs.avail_in = in;
        z->zs.next_out = out + made;
        z->zs.avail_out = want < UINT_MAX ? (uInt)want : UINT_MAX;
        int ret = inflate(&z->zs, Z_NO_FLUSH);
        size_t used = in - z->zs.avail_in;
        raw->p += used;
        raw->offset += used;
        made = (size_t)(z->zs.next_out - out);
        if (ret == Z_STREAM_END) {
            z->member_end = 1;
            continue;
        }
        if (ret == Z_MEM_ERROR) {
            *status = mt__io_fail_nomem(diag, src);
            break;
        }
        if (ret != Z_OK && ret != Z_BUF_ERROR) {
            *status =
                mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE, raw->offset, MT_NONE,
                            "corrupt gzip data (%s)", z->zs.msg ? z->zs.msg : "inflate failed");
            break;
        }
        if (z->zs.avail_in == 0 && raw->p == raw->end && raw->at_end && z->zs.avail_out > 0) {
            *status = mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE, raw->offset, MT_NONE,
                                  "gzip data ends before the end of its stream (truncated file)");
            break;
        }
    }
    return made;
}
