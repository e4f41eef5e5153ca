/* Format names and the format a path's suffix names (.off, .obj, .ply,
 * .stl, each optionally followed by .gz; letters in any case). */
#include <stddef.h>

#include "io_internal.h"

const char *mt_format_name(mt_format format)
{
    switch (format) {
        case MT_FORMAT_AUTO:
            return "auto";
        case MT_FORMAT_OFF:
            return "off";
        case MT_FORMAT_OBJ:
            return "obj";
        case MT_FORMAT_PLY_ASCII:
            return "ply-ascii";
        case MT_FORMAT_PLY_BINARY_LE:
            return "ply-le";
        case MT_FORMAT_PLY_BINARY_BE:
            return "ply-be";
        case MT_FORMAT_STL_ASCII:
            return "stl-ascii";
        case MT_FORMAT_STL_BINARY:
            return "stl-binary";
    }
    return "unknown";
}

/* 1 when s (length n) ends with the lower-case suffix. */
static int ends_with(const char *s, size_t n, const char *suffix, size_t m)
{
    if (n < m) return 0;
    for (size_t i = 0; i < m; i++) {
        char c = s[n - m + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != suffix[i]) return 0;
    }
    return 1;
}

mt_format mt_format_from_path(const char *path)
{
    if (!path) return MT_FORMAT_AUTO;
    size_t n = strlen(path);
    if (ends_with(path, n, ".gz", 3)) n -= 3;
    if (ends_with(path, n, ".off", 4)) return MT_FORMAT_OFF;
    if (ends_with(path, n, ".obj", 4)) return MT_FORMAT_OBJ;
    if (ends_with(path, n, ".ply", 4)) return MT_FORMAT_PLY_BINARY_LE;
    if (ends_with(path, n, ".stl", 4)) return MT_FORMAT_STL_BINARY;
    return MT_FORMAT_AUTO;
}

int mt__path_is_gzip(const char *path)
{
    return path && ends_with(path, strlen(path), ".gz", 3);
}
