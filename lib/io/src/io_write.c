/* Writing entry point and number text: the format comes from the argument
 * or the path's suffix, ".gz" compresses, the list is checked before any
 * file is created, and numbers are written under the C locale so that a
 * double always reads back bit for bit (shortest of %.15g/%.16g/%.17g). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "io_internal.h"

size_t mt__format_i64(int64_t v, char *buf)
{
    char tmp[24];
    size_t n = 0, o = 0;
    uint64_t u = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
    do {
        tmp[n++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (v < 0) buf[o++] = '-';
    while (n) buf[o++] = tmp[--n];
    buf[o] = '\0';
    return o;
}

size_t mt__format_double(double v, char *buf)
{
    if (isnan(v)) {
        memcpy(buf, signbit(v) ? "-nan" : "nan", signbit(v) ? 5 : 4);
        return signbit(v) ? 4 : 3;
    }
    if (isinf(v)) {
        memcpy(buf, v < 0 ? "-inf" : "inf", v < 0 ? 5 : 4);
        return v < 0 ? 4 : 3;
    }
    /* Small integers (the common 0, 1, -2 ...) print exactly as integers. */
    if (fabs(v) < 1e15 && v == (double)(int64_t)v && !(v == 0 && signbit(v)))
        return mt__format_i64((int64_t)v, buf);
    int n = 0;
    for (int precision = 15; precision <= 17; precision++) {
        n = snprintf(buf, 32, "%.*g", precision, v);
        if (precision == 17 || n <= 0) break;
        /* Read it back exactly: the fast exact path, else strtod. */
        double back;
        const unsigned char *text = (const unsigned char *)buf;
        if (mt__scan_decimal(text, text + n, &back) != (size_t)n) back = strtod(buf, NULL);
        if (back == v) break;
    }
    return n > 0 ? (size_t)n : 0;
}

mt_status mt_write_file(const char *path, mt_format format, const mt_face_list *list, mt_diag *diag)
{
    mt_diag_clear(diag);
    mt__io_src none = {path ? path : "<null>", NULL, 0};
    if (!path || !*path || !list)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "NULL or empty path, or NULL face list");
    if ((unsigned)format > (unsigned)MT_FORMAT_PLY_BINARY_BE)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "unknown format %d", (int)format);
    mt_status status = mt_face_list_check(list, diag);
    if (status != MT_OK) return status;
    if (list->num_verts > MT__IO_MAX_VERTS)
        return mt__io_fail(diag, MT_ERR_TOO_LARGE, &none, MT__POS_NONE, 0, MT_NONE,
                           "%u vertices: more than meshtopo's limit of %u", list->num_verts,
                           MT__IO_MAX_VERTS);
    if (format == MT_FORMAT_AUTO) format = mt_format_from_path(path);
    if (format == MT_FORMAT_AUTO)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "cannot tell the format from the name (use .off, .obj or .ply, "
                           "optionally with .gz)");
    if (format == MT_FORMAT_OBJ) {
        status = mt__obj_check_writable(list, path, diag);
        if (status != MT_OK) return status;
    }

    mt__sink *sink;
    status = mt__sink_open(&sink, path, mt__path_is_gzip(path), diag);
    if (status != MT_OK) return status;
    mt__locale_state locale;
    mt__c_locale_enter(&locale);
    switch (format) {
        case MT_FORMAT_OFF:
            status = mt__write_off(sink, list, diag);
            break;
        case MT_FORMAT_OBJ:
            status = mt__write_obj(sink, list, diag);
            break;
        default:
            status = mt__write_ply(sink, list, format, diag);
            break;
    }
    mt__c_locale_leave(&locale);
    if (status != MT_OK) {
        mt__sink_abort(sink);
        return status;
    }
    return mt__sink_close(sink, diag);
}
