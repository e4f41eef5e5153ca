/* PLY writer: ascii, binary_little_endian or binary_big_endian with
 * "property double x/y/z" and "property list C int vertex_indices", C the
 * smallest of uchar, ushort, uint that holds the largest face, and when
 * given "property uchar red/green/blue" after them (per vertex, per face).
 * Indices are written as signed 32-bit values (an out-of-range -1 stays
 * -1). */
#include <stdbool.h>
#include <stdio.h>

#include "io_internal.h"

static void store32(unsigned char *p, uint32_t v, int be)
{
    for (int k = 0; k < 4; k++) p[be ? 3 - k : k] = (unsigned char)(v >> (8 * k));
}

static void store64(unsigned char *p, uint64_t v, int be)
{
    for (int k = 0; k < 8; k++) p[be ? 7 - k : k] = (unsigned char)(v >> (8 * k));
}

static const char color_properties[] =
    "property uchar red\nproperty uchar green\nproperty uchar blue\n";

/* " r g b" of colors[i] (ascii) or its three bytes, when colors is given. */
static void write_color(mt__sink *s, const uint8_t *colors, size_t i, bool ascii)
{
    if (!colors) return;
    const uint8_t *c = colors + 3 * i;
    if (!ascii) {
        mt__sink_write(s, c, 3);
        return;
    }
    char *p = mt__sink_reserve(s, 16);
    mt__sink_commit(s, (size_t)snprintf(p, 16, " %u %u %u", c[0], c[1], c[2]));
}

mt_status mt__write_ply(mt__sink *s, const mt_face_list *list, mt_format format,
                        const mt_write_options *options, mt_diag *diag)
{
    const uint8_t *vertex_colors = options->vertex_colors, *face_colors = options->face_colors;
    const bool ascii = format == MT_FORMAT_PLY_ASCII;
    uint32_t max_size = 0;
    for (uint32_t f = 0; f < list->num_faces; f++)
        if (list->face_sizes[f] > max_size) max_size = list->face_sizes[f];
    const char *count_type = max_size <= 0xff ? "uchar" : max_size <= 0xffff ? "ushort" : "uint";
    unsigned count_bytes = max_size <= 0xff ? 1 : max_size <= 0xffff ? 2 : 4;
    const char *encoding = format == MT_FORMAT_PLY_ASCII       ? "ascii"
                           : format == MT_FORMAT_PLY_BINARY_BE ? "binary_big_endian"
                                                               : "binary_little_endian";
    char *p = mt__sink_reserve(s, 600);
    int k = snprintf(p, 600,
                     "ply\nformat %s 1.0\ncomment written by meshtopo\nelement vertex %u\n"
                     "property double x\nproperty double y\nproperty double z\n%s"
                     "element face %u\nproperty list %s int vertex_indices\n%send_header\n",
                     encoding, list->num_verts, vertex_colors ? color_properties : "",
                     list->num_faces, count_type, face_colors ? color_properties : "");
    mt__sink_commit(s, (size_t)k);
    const uint32_t *idx = list->face_indices;

    if (ascii) {
        for (uint32_t v = 0; v < list->num_verts; v++) {
            p = mt__sink_reserve(s, 100);
            size_t o = 0;
            for (int c = 0; c < 3; c++) {
                double x = list->positions ? list->positions[3 * (size_t)v + (size_t)c] : 0.0;
                o += mt__format_double(x, p + o);
                if (c < 2) p[o++] = ' ';
            }
            mt__sink_commit(s, o);
            write_color(s, vertex_colors, v, true);
            mt__sink_write(s, "\n", 1);
        }
        for (uint32_t f = 0; f < list->num_faces; f++) {
            p = mt__sink_reserve(s, 32);
            mt__sink_commit(s, mt__format_i64(list->face_sizes[f], p));
            for (uint32_t j = 0; j < list->face_sizes[f]; j++) {
                p = mt__sink_reserve(s, 32);
                p[0] = ' ';
                mt__sink_commit(s, 1 + mt__format_i64(mt_index_as_signed(*idx++), p + 1));
            }
            write_color(s, face_colors, f, true);
            mt__sink_write(s, "\n", 1);
        }
        return MT_OK;
    }

    int be = format == MT_FORMAT_PLY_BINARY_BE;
    for (uint32_t v = 0; v < list->num_verts; v++) {
        unsigned char *q = (unsigned char *)mt__sink_reserve(s, 24);
        for (int c = 0; c < 3; c++) {
            double x = list->positions ? list->positions[3 * (size_t)v + (size_t)c] : 0.0;
            uint64_t bits;
            memcpy(&bits, &x, sizeof bits);
            store64(q + 8 * c, bits, be);
        }
        mt__sink_commit(s, 24);
        write_color(s, vertex_colors, v, false);
    }
    for (uint32_t f = 0; f < list->num_faces; f++) {
        uint32_t size = list->face_sizes[f];
        unsigned char *q = (unsigned char *)mt__sink_reserve(s, 4);
        if (count_bytes == 1) q[0] = (unsigned char)size;
        if (count_bytes == 2) {
            q[be ? 1 : 0] = (unsigned char)size;
            q[be ? 0 : 1] = (unsigned char)(size >> 8);
        }
        if (count_bytes == 4) store32(q, size, be);
        mt__sink_commit(s, count_bytes);
        for (uint32_t j = 0; j < size; j++) {
            q = (unsigned char *)mt__sink_reserve(s, 4);
            store32(q, *idx++, be);
            mt__sink_commit(s, 4);
        }
        write_color(s, face_colors, f, false);
    }
    return MT_OK;
}
