/* Reading entry points: the whole file is read (or inflated, for gzip
 * recognised by its magic bytes) into memory, its format told from the
 * content or the name, and handed to one parser under the C locale. On any
 * failure *out is zeroed and everything allocated is released. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io_internal.h"

static int looks_like_ply(const mt__io_src *src)
{
    return src->size >= 4 && memcmp(src->data, "ply", 3) == 0 &&
           (src->data[3] == '\n' || src->data[3] == '\r');
}

static mt_status read_decoded(const mt__io_src *src, mt_format format, mt_face_list *out,
                              mt_diag *diag)
{
    if (format == MT_FORMAT_AUTO) {
        mt_format by_name = mt_format_from_path(src->name);
        if (mt__looks_like_off(src))
            format = MT_FORMAT_OFF;
        else if (looks_like_ply(src))
            format = MT_FORMAT_PLY_ASCII; /* the header tells the encoding */
        else if (by_name != MT_FORMAT_AUTO)
            format = by_name;
        else if (mt__looks_like_obj(src))
            format = MT_FORMAT_OBJ;
        else
            return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, 0, MT_NONE,
                               "cannot tell the format: no OFF or PLY header, no OBJ "
                               "keyword, no known file suffix");
    }
    mt__locale_state locale;
    mt__c_locale_enter(&locale);
    mt_status status;
    switch (format) {
        case MT_FORMAT_OFF:
            status = mt__read_off(src, out, diag);
            break;
        case MT_FORMAT_OBJ:
            status = mt__read_obj(src, out, diag);
            break;
        default: /* any PLY format: the header names the encoding */
            status = mt__read_ply(src, out, diag);
            break;
    }
    mt__c_locale_leave(&locale);
    if (status != MT_OK) memset(out, 0, sizeof *out);
    return status;
}

/* Checks the arguments shared by both readers. */
static mt_status check_args(mt_format format, mt_face_list *out, const char *name, mt_diag *diag)
{
    mt_diag_clear(diag);
    mt__io_src none = {name ? name : "<memory>", NULL, 0};
    if (!out)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "NULL output face list");
    memset(out, 0, sizeof *out);
    if ((unsigned)format > (unsigned)MT_FORMAT_PLY_BINARY_BE)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "unknown format %d", (int)format);
    return MT_OK;
}

/* Inflates src when it is gzip and parses it. *owned, when not NULL, is a
 * buffer holding src's bytes that may be freed as soon as it is inflated. */
static mt_status read_any(mt__io_src *src, unsigned char **owned, mt_format format,
                          mt_face_list *out, mt_diag *diag)
{
    if (!mt__is_gzip(src->data, src->size)) return read_decoded(src, format, out, diag);
    unsigned char *inflated;
    size_t inflated_size;
    mt_status status = mt__inflate(src, &inflated, &inflated_size, diag);
    if (owned) {
        free(*owned);
        *owned = NULL;
    }
    if (status != MT_OK) return status;
    mt__io_src plain = {src->name, inflated, inflated_size};
    status = read_decoded(&plain, format, out, diag);
    free(inflated);
    return status;
}

mt_status mt_read_memory(const void *data, size_t size, mt_format format, const char *name,
                         mt_face_list *out, mt_diag *diag)
{
    mt_status status = check_args(format, out, name, diag);
    if (status != MT_OK) return status;
    mt__io_src src = {name ? name : "<memory>", data, size};
    if (!data && size)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &src, MT__POS_NONE, 0, MT_NONE,
                           "NULL data of %zu bytes", size);
    if (!data) src.data = (const unsigned char *)"";
    return read_any(&src, NULL, format, out, diag);
}

static mt_status io_error(mt_diag *diag, const char *path, const char *what, int err)
{
    char text[256];
    if (strerror_r(err, text, sizeof text) != 0) snprintf(text, sizeof text, "error %d", err);
    mt__io_src src = {path, NULL, 0};
    return mt__io_fail(diag, MT_ERR_IO, &src, MT__POS_NONE, 0, MT_NONE, "%s: %s", what, text);
}

/* Reads all of fd into a new buffer. Returns 0 or an errno value. */
static int read_all(int fd, unsigned char **out, size_t *out_size)
{
    struct stat st;
    if (fstat(fd, &st) != 0) return errno;
    if (S_ISDIR(st.st_mode)) return EISDIR;
    size_t cap = 65536;
    if (S_ISREG(st.st_mode) && st.st_size > 0) {
        if ((uint64_t)st.st_size >= (uint64_t)SIZE_MAX) return EFBIG;
        cap = (size_t)st.st_size + 1; /* +1: end of file is seen without growing */
    }
    unsigned char *buf = malloc(cap);
    if (!buf) return ENOMEM;
    size_t len = 0;
    for (;;) {
        if (len == cap) {
            if (cap > SIZE_MAX / 2) {
                free(buf);
                return EFBIG;
            }
            unsigned char *p = realloc(buf, cap * 2);
            if (!p) {
                free(buf);
                return ENOMEM;
            }
            buf = p;
            cap *= 2;
        }
        size_t want = cap - len < (1u << 30) ? cap - len : (1u << 30);
        ssize_t got = read(fd, buf + len, want);
        if (got < 0) {
            if (errno == EINTR) continue;
            int err = errno;
            free(buf);
            return err;
        }
        if (got == 0) break;
        len += (size_t)got;
    }
    *out = buf;
    *out_size = len;
    return 0;
}

mt_status mt_read_file(const char *path, mt_format format, mt_face_list *out, mt_diag *diag)
{
    mt_status status = check_args(format, out, path, diag);
    if (status != MT_OK) return status;
    if (!path) {
        mt__io_src none = {"<null>", NULL, 0};
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE, "NULL path");
    }
    int fd;
    do fd = open(path, O_RDONLY | O_CLOEXEC);
    while (fd < 0 && errno == EINTR);
    if (fd < 0) return io_error(diag, path, "cannot open", errno);
    unsigned char *buf = NULL;
    size_t size = 0;
    int err = read_all(fd, &buf, &size);
    close(fd);
    if (err) return io_error(diag, path, "cannot read", err);
    mt__io_src src = {path, buf, size};
    status = read_any(&src, &buf, format, out, diag);
    free(buf);
    return status;
}
