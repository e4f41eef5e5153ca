/* gzip input (RFC 1952) inflated with zlib into one buffer: every member of
 * a multi-member file, trailing zero padding allowed. The output grows
 * geometrically from a size hint that is only trusted when plausible, and
 * is refused above 16 GiB or when it would not fit in memory, so a small
 * gzip bomb cannot make us allocate more than it really inflates to. */
#include <limits.h>
#include <stdlib.h>
#include <zlib.h>

#include "io_internal.h"

/* Largest inflated size accepted. */
#define MT__INFLATE_LIMIT ((uint64_t)16 << 30)

static size_t inflate_limit(void)
{
    return MT__INFLATE_LIMIT < (uint64_t)SIZE_MAX ? (size_t)MT__INFLATE_LIMIT : SIZE_MAX - 1;
}

/* Initial capacity: the size in the last member's trailer (ISIZE, the size
 * modulo 2^32) when deflate could produce it from this input (ratio at most
 * about 1032:1), else a few times the input. */
static size_t initial_capacity(const unsigned char *data, size_t size, size_t limit)
{
    uint64_t ratio_cap = (uint64_t)size * 1040u + 4096u;
    uint64_t guess = (uint64_t)size * 4u + 4096u;
    if (size >= 18) {
        const unsigned char *t = data + size - 4;
        uint64_t isize =
            (uint64_t)t[0] | (uint64_t)t[1] << 8 | (uint64_t)t[2] << 16 | (uint64_t)t[3] << 24;
        if (isize + 1 <= ratio_cap) guess = isize + 1;
    }
    if (guess > limit) guess = limit;
    return (size_t)guess;
}

static int all_zero(const unsigned char *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (p[i]) return 0;
    return 1;
}

mt_status mt__inflate(const mt__io_src *src, unsigned char **out, size_t *out_size, mt_diag *diag)
{
    *out = NULL;
    *out_size = 0;
    const unsigned char *data = src->data;
    size_t size = src->size;
    size_t limit = inflate_limit();
    size_t cap = initial_capacity(data, size, limit);
    unsigned char *buf = malloc(cap);
    if (!buf) return mt__io_fail_nomem(diag, src);

    z_stream zs;
    memset(&zs, 0, sizeof zs);
    if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) {
        free(buf);
        return mt__io_fail_nomem(diag, src);
    }
    size_t fed = 0; /* input bytes handed to zlib so far */
    size_t len = 0; /* output bytes produced so far */
    mt_status status = MT_OK;
    for (;;) {
        if (zs.avail_in == 0 && fed < size) {
            size_t chunk = size - fed < UINT_MAX ? size - fed : UINT_MAX;
            zs.next_in = (unsigned char *)(data + fed);
            zs.avail_in = (uInt)chunk;
            fed += chunk;
        }
        if (len == cap) {
            if (cap >= limit) {
                status = mt__io_fail(diag, MT_ERR_TOO_LARGE, src, MT__POS_NONE, 0, MT_NONE,
                                     "gzip data inflates to more than %zu bytes", limit);
                break;
            }
            size_t grown = cap > limit / 2 ? limit : cap * 2;
            unsigned char *p = realloc(buf, grown);
            if (!p) {
                status = mt__io_fail(diag, MT_ERR_NOMEM, src, MT__POS_NONE, 0, MT_NONE,
                                     "out of memory inflating gzip data (%zu bytes so far)", len);
                break;
            }
            buf = p;
            cap = grown;
        }
        size_t room = cap - len < UINT_MAX ? cap - len : UINT_MAX;
        zs.next_out = buf + len;
        zs.avail_out = (uInt)room;
        int ret = inflate(&zs, Z_NO_FLUSH);
        len = (size_t)(zs.next_out - buf);
        size_t consumed = (size_t)(zs.next_in - data);
        if (ret == Z_STREAM_END) {
            if (consumed < size && mt__is_gzip(data + consumed, size - consumed)) {
                if (inflateReset(&zs) != Z_OK) {
                    status = mt__io_fail_nomem(diag, src);
                    break;
                }
                continue;
            }
            if (consumed < size && !all_zero(data + consumed, size - consumed))
                status = mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE, consumed, MT_NONE,
                                     "unexpected data after the end of the gzip stream");
            break;
        }
        if (ret == Z_MEM_ERROR) {
            status = mt__io_fail_nomem(diag, src);
            break;
        }
        if (ret != Z_OK && ret != Z_BUF_ERROR) {
            status = mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE, consumed, MT_NONE,
                                 "corrupt gzip data (%s)", zs.msg ? zs.msg : "inflate failed");
            break;
        }
        if (zs.avail_in == 0 && fed == size && zs.avail_out > 0) {
            status = mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE, size, MT_NONE,
                                 "gzip data ends before the end of its stream (truncated file)");
            break;
        }
    }
    inflateEnd(&zs);
    if (status != MT_OK) {
        free(buf);
        return status;
    }
    *out = buf;
    *out_size = len;
    return MT_OK;
}
