/* Writing entry point: the format comes from the argument or the path's
 * suffix, ".gz" compresses, the list is checked before any file is created,
 * and the writers run under the C locale so that their numbers (io_number.c)
 * always read back bit for bit. */
#include <stdbool.h>

#include "io_internal.h"

mt_status mt_write_file(const char *path, mt_format format, const mt_face_list *list, mt_diag *diag)
{
    return mt_write_file_with(path, format, list, NULL, diag);
}

mt_status mt_write_file_with(const char *path, mt_format format, const mt_face_list *list,
                             const mt_write_options *options, mt_diag *diag)
{
    static const mt_write_options defaults;
    if (!options) options = &defaults;
    mt_diag_clear(diag);
    mt__io_src none = {.name = path ? path : "<null>"};
    if (!path || !*path || !list)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "NULL or empty path, or NULL face list");
    if ((unsigned)format > (unsigned)MT_FORMAT_STL_BINARY)
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
                           "cannot tell the format from the name (use .off, .obj, .ply or "
                           ".stl, optionally with .gz)");
    bool colors = options->vertex_colors || options->face_colors;
    if (colors && format != MT_FORMAT_PLY_ASCII && format != MT_FORMAT_PLY_BINARY_LE &&
        format != MT_FORMAT_PLY_BINARY_BE)
        return mt__io_fail(diag, MT_ERR_UNSUPPORTED, &none, MT__POS_NONE, 0, MT_NONE,
                           "colours are written to PLY files only");
    if (format == MT_FORMAT_OBJ) {
        status = mt__obj_check_writable(list, path, diag);
        if (status != MT_OK) return status;
    }
    if (format == MT_FORMAT_STL_ASCII || format == MT_FORMAT_STL_BINARY) {
        status = mt__stl_check_writable(list, format, path, diag);
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
        case MT_FORMAT_STL_ASCII:
        case MT_FORMAT_STL_BINARY:
            status = mt__write_stl(sink, list, format, diag);
            break;
        default:
            status = mt__write_ply(sink, list, format, options, diag);
            break;
    }
    mt__c_locale_leave(&locale);
    if (status != MT_OK) {
        mt__sink_abort(sink);
        return status;
    }
    return mt__sink_close(sink, diag);
}
