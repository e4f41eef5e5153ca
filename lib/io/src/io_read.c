/* Reading entry points: a plain buffer is parsed where it is; a file, and
 * gzip data (recognised by its magic bytes), are parsed through a window
 * that moves on as the parser advances (io_source.c). The format is told
 * from the content or the name and the input handed to one parser under
 * the C locale. On any failure *out is zeroed and everything allocated is
 * released; a failure of the input itself (unreadable, corrupt gzip, over
 * the input limit) is reported rather than what the parser made of the
 * input cut short. */
#include <assert.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io_internal.h"

/* The content tells the format within this many bytes or not at all. */
#define DETECT_BYTES ((size_t)64 << 10)

/* Tells the format from the start of the input (widening the window, from
 * the input's start, while the content cannot tell yet and the window
 * holds less than DETECT_BYTES), else from the name. STL comes after the
 * OFF and PLY headers (so that their binary data never needs a window
 * that shows 256 bytes), a binary STL file by its length first: its
 * 80-byte header may start with "solid". */
static mt_status detect_format(mt__io_src *src, mt_format *format, mt_diag *diag)
{
    mt_format by_name = mt_format_from_path(src->name);
    int by_name_stl = by_name == MT_FORMAT_STL_BINARY;
    int off, ply, obj, stl;
    mt_format stl_format = MT_FORMAT_AUTO;
    for (;;) {
        off = mt__looks_like_off(src);
        ply = off == 1 ? 0 : mt__looks_like_ply(src);
        stl = off == 1 || ply == 1 ? 0 : mt__looks_like_stl(src, by_name_stl, &stl_format);
        obj = off == 1 || ply == 1 || stl == 1 || by_name != MT_FORMAT_AUTO
                  ? 0
                  : mt__looks_like_obj(src);
        if ((off >= 0 && ply >= 0 && obj >= 0 && stl >= 0) || src->size >= DETECT_BYTES) break;
        size_t keep = 0;
        mt__src_more(src, &keep); /* more in view, or the end reached: then all can tell */
    }
    if (off == 1)
        *format = MT_FORMAT_OFF;
    else if (ply == 1)
        *format = MT_FORMAT_PLY_ASCII; /* the header tells the encoding */
    else if (stl == 1)
        *format = stl_format;
    else if (by_name != MT_FORMAT_AUTO)
        *format = by_name;
    else if (obj == 1)
        *format = MT_FORMAT_OBJ;
    else if (mt__looks_like_stl(src, 1, &stl_format) == 1) /* gzip'd binary STL, unnamed */
        *format = stl_format;
    else
        return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, 0, MT_NONE,
                           "cannot tell the format: no OFF, PLY or STL header, no OBJ "
                           "keyword, no known file suffix");
    return MT_OK;
}

/* Parses src (opened) with `format`; src is closed. */
static mt_status read_source(mt__io_src *src, mt_format format, mt_face_list *out, mt_diag *diag)
{
    mt_status status = MT_OK;
    if (format == MT_FORMAT_AUTO) status = detect_format(src, &format, diag);
    if (status == MT_OK) {
        mt__locale_state locale;
        mt__c_locale_enter(&locale);
        switch (format) {
            case MT_FORMAT_OFF:
                status = mt__read_off(src, out, diag);
                break;
            case MT_FORMAT_OBJ:
                status = mt__read_obj(src, out, diag);
                break;
            case MT_FORMAT_STL_ASCII:
                status = mt__read_stl_ascii(src, out, diag);
                break;
            case MT_FORMAT_STL_BINARY:
                status = mt__read_stl_binary(src, out, diag);
                break;
            default: /* any PLY format: the header names the encoding */
                status = mt__read_ply(src, out, diag);
                break;
        }
        mt__c_locale_leave(&locale);
    }
    /* A parse that succeeded has read its input to the end. */
    assert(status != MT_OK || src->eof);
    mt_status input = mt__src_status(src, diag);
    if (input != MT_OK) {
        if (status == MT_OK) mt_face_list_free(out);
        status = input;
    }
    mt__bulk_free(src->bulk);
    src->bulk = NULL;
    mt__src_close(src);
    if (status != MT_OK) memset(out, 0, sizeof *out);
    return status;
}

/* Checks the arguments shared by both readers. */
static mt_status check_args(mt_format format, mt_face_list *out, const char *name, mt_diag *diag)
{
    mt_diag_clear(diag);
    mt__io_src none = {.name = name ? name : "<memory>"};
    if (!out)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "NULL output face list");
    memset(out, 0, sizeof *out);
    if ((unsigned)format > (unsigned)MT_FORMAT_STL_BINARY)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "unknown format %d", (int)format);
    return MT_OK;
}

static uint64_t max_input(const mt_read_options *options)
{
    return options && options->max_input_bytes ? options->max_input_bytes
                                               : MT_READ_DEFAULT_MAX_INPUT_BYTES;
}

mt_status mt_read_memory_with(const void *data, size_t size, mt_format format, const char *name,
                              const mt_read_options *options, mt_face_list *out, mt_diag *diag)
{
    mt_status status = check_args(format, out, name, diag);
    if (status != MT_OK) return status;
    mt__io_src src;
    mt__src_init_buffer(&src, name ? name : "<memory>", data, size);
    if (!data && size)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &src, MT__POS_NONE, 0, MT_NONE,
                           "NULL data of %zu bytes", size);
    int gzip = mt__is_gzip(src.data, size);
    if (!gzip && size > max_input(options))
        return mt__io_fail(diag, MT_ERR_TOO_LARGE, &src, MT__POS_NONE, 0, MT_NONE,
                           "%zu bytes: more than the input limit of %llu bytes", size,
                           (unsigned long long)max_input(options));
    if (gzip || (options && options->window_bytes)) {
        status = mt__src_open(&src, src.name, -1, data, size, size, options, diag);
        if (status != MT_OK) return status;
    }
    src.threads = options ? options->threads : 0;
    return read_source(&src, format, out, diag);
}

mt_status mt_read_memory(const void *data, size_t size, mt_format format, const char *name,
                         mt_face_list *out, mt_diag *diag)
{
    return mt_read_memory_with(data, size, format, name, NULL, out, diag);
}

static mt_status io_error(mt_diag *diag, const char *path, const char *what, int err)
{
    char text[256];
    if (strerror_r(err, text, sizeof text) != 0) snprintf(text, sizeof text, "error %d", err);
    mt__io_src src = {.name = path};
    return mt__io_fail(diag, MT_ERR_IO, &src, MT__POS_NONE, 0, MT_NONE, "%s: %s", what, text);
}

/* Reads the open descriptor fd (named `name` in messages) to its end. */
static mt_status read_fd(int fd, const char *name, mt_format format, const mt_read_options *options,
                         mt_face_list *out, mt_diag *diag)
{
    struct stat st;
    int err = fstat(fd, &st) != 0 ? errno : S_ISDIR(st.st_mode) ? EISDIR : 0;
    if (err) return io_error(diag, name, "cannot read", err);
    /* A regular file's size is its length (used for the size checks) unless
     * it is gzip; mt__src_open tells. */
    uint64_t total = S_ISREG(st.st_mode) ? (uint64_t)st.st_size : MT__UNKNOWN;
    mt__io_src src;
    mt_status status = mt__src_open(&src, name, fd, NULL, 0, total, options, diag);
    src.threads = options ? options->threads : 0;
    if (status == MT_OK) status = read_source(&src, format, out, diag);
    return status;
}

mt_status mt_read_file_with(const char *path, mt_format format, const mt_read_options *options,
                            mt_face_list *out, mt_diag *diag)
{
    mt_status status = check_args(format, out, path, diag);
    if (status != MT_OK) return status;
    if (!path) {
        mt__io_src none = {.name = "<null>"};
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE, "NULL path");
    }
    int fd;
    do fd = open(path, O_RDONLY | O_CLOEXEC);
    while (fd < 0 && errno == EINTR);
    if (fd < 0) return io_error(diag, path, "cannot open", errno);
    status = read_fd(fd, path, format, options, out, diag);
    close(fd);
    return status;
}

mt_status mt_read_fd_with(int fd, const char *name, mt_format format,
                          const mt_read_options *options, mt_face_list *out, mt_diag *diag)
{
    char fallback[32];
    if (!name) {
        snprintf(fallback, sizeof fallback, "fd %d", fd);
        name = fallback;
    }
    mt_status status = check_args(format, out, name, diag);
    if (status != MT_OK) return status;
    if (fd < 0) return io_error(diag, name, "cannot read", EBADF);
    return read_fd(fd, name, format, options, out, diag);
}

mt_status mt_read_file(const char *path, mt_format format, mt_face_list *out, mt_diag *diag)
{
    return mt_read_file_with(path, format, NULL, out, diag);
}
