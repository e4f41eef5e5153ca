/* What every file-reader fuzz target checks: any input gives MT_OK with a
 * consistent face list, or an error with a message and a zeroed list; never
 * a crash, a leak or a read out of bounds. And the ways of reading the same
 * bytes agree: read whole, on three threads, through a window of a few
 * bytes (so the window moves on at every possible place), on three threads
 * through windows of a few hundred bytes (each next one read ahead while
 * they parse), and wrapped as gzip (stored deflate blocks, so the streamed
 * inflation runs too) must give the same result,
 * bar the documented differences of streamed gzip data (io.h): damage in
 * the gzip data, and the size checks of a header, may be found after
 * another error the whole read did not reach (the read fails either way). */
#ifndef MESHTOPO_FUZZ_READER_H
#define MESHTOPO_FUZZ_READER_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/io.h"

/* Checks one read's outcome; returns its status. */
static inline mt_status mt_fuzz_read(const uint8_t *data, size_t size, mt_format format,
                                     const char *name, const mt_read_options *options,
                                     mt_face_list *list, mt_diag *diag)
{
    mt_status status = mt_read_memory_with(data, size, format, name, options, list, diag);
    if (status == MT_OK) {
        if (mt_face_list_check(list, NULL) != MT_OK) __builtin_trap();
        if (list->num_verts && !list->positions) __builtin_trap();
    } else {
        if (list->num_verts || list->num_faces || list->num_indices || list->positions ||
            list->face_sizes || list->face_indices || diag->message[0] == '\0' ||
            memchr(diag->message, '\0', sizeof diag->message) == NULL)
            __builtin_trap();
    }
    return status;
}

static inline int mt_fuzz_same_list(const mt_face_list *a, const mt_face_list *b)
{
    return a->num_verts == b->num_verts && a->num_faces == b->num_faces &&
           a->num_indices == b->num_indices &&
           memcmp(a->positions, b->positions, 3 * sizeof(double) * a->num_verts) == 0 &&
           memcmp(a->face_sizes, b->face_sizes, sizeof(uint32_t) * a->num_faces) == 0 &&
           memcmp(a->face_indices, b->face_indices, sizeof(uint32_t) * a->num_indices) == 0;
}

/* A message the streamed gzip read may give in another order (see above). */
static inline int mt_fuzz_order_may_differ(const char *message)
{
    return strstr(message, "gzip data") || strstr(message, "gzip stream") ||
           strstr(message, "bytes follow") || strstr(message, "bytes of data but only") ||
           strstr(message, "larger than the rest of the file") ||
           strstr(message, "runs past the end of the data");
}

/* Reads data again with `options` and checks the outcome against the
 * whole read's; `gzip`: data is gzip (given or wrapped). */
static inline void mt_fuzz_compare(const uint8_t *data, size_t size, mt_format format,
                                   const char *name, const mt_read_options *options, int gzip,
                                   mt_status want, const mt_face_list *want_list,
                                   const mt_diag *want_diag)
{
    mt_face_list list;
    mt_diag diag;
    mt_status status = mt_fuzz_read(data, size, format, name, options, &list, &diag);
    if (gzip && want == MT_ERR_PARSE && mt_fuzz_order_may_differ(want_diag->message)) {
        if (status == MT_OK) __builtin_trap(); /* another error, found first */
    } else if (status != want) {
        __builtin_trap();
    } else if (status == MT_OK) {
        if (!mt_fuzz_same_list(&list, want_list)) __builtin_trap();
    } else if (strcmp(diag.message, want_diag->message) != 0 || diag.line != want_diag->line ||
               diag.byte_offset != want_diag->byte_offset) {
        __builtin_trap();
    }
    mt_face_list_free(&list);
}

static inline uint32_t mt_fuzz_crc32(const uint8_t *p, size_t n)
{
    uint32_t crc = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int k = 0; k < 8; k++) crc = crc & 1 ? (crc >> 1) ^ 0xedb88320u : crc >> 1;
    }
    return ~crc;
}

/* The gzip form of data with stored deflate blocks (malloc'd), or NULL. */
static inline uint8_t *mt_fuzz_gzip(const uint8_t *data, size_t size, size_t *out_size)
{
    uint8_t *out = malloc(size + 18 + 5 * (size / 65535 + 1));
    if (!out) return NULL;
    static const uint8_t header[10] = {0x1f, 0x8b, 8, 0, 0, 0, 0, 0, 0, 0xff};
    memcpy(out, header, sizeof header);
    size_t o = sizeof header, i = 0;
    do {
        size_t len = size - i < 65535 ? size - i : 65535;
        out[o++] = i + len == size;
        out[o++] = (uint8_t)len;
        out[o++] = (uint8_t)(len >> 8);
        out[o++] = (uint8_t)~len;
        out[o++] = (uint8_t)(~len >> 8);
        if (len) memcpy(out + o, data + i, len);
        o += len;
        i += len;
    } while (i < size);
    uint32_t crc = mt_fuzz_crc32(data, size);
    for (int k = 0; k < 4; k++) out[o + (size_t)k] = (uint8_t)(crc >> (8 * k));
    for (int k = 0; k < 4; k++) out[o + 4 + (size_t)k] = (uint8_t)((uint32_t)size >> (8 * k));
    *out_size = o + 8;
    return out;
}

static inline int mt_fuzz_reader(const uint8_t *data, size_t size, mt_format format,
                                 const char *name)
{
    mt_face_list list;
    mt_diag diag;
    mt_status status = mt_fuzz_read(data, size, format, name, NULL, &list, &diag);
    mt_read_options options;
    memset(&options, 0, sizeof options);
    options.threads = 3; /* text runs in three parts (tiny ones in the fuzz build) */
    mt_fuzz_compare(data, size, format, name, &options, 0, status, &list, &diag);
    options.threads = 0;
    options.window_bytes = 1 + size % 13;
    int is_gzip = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
    mt_fuzz_compare(data, size, format, name, &options, is_gzip, status, &list, &diag);
    /* windows that hold several parts: each next one is read ahead */
    options.threads = 3;
    options.window_bytes = 160 + size % 97;
    mt_fuzz_compare(data, size, format, name, &options, is_gzip, status, &list, &diag);
    options.threads = 0;
    if (!is_gzip) {
        size_t gz_size;
        uint8_t *gz = mt_fuzz_gzip(data, size, &gz_size);
        if (gz) {
            options.window_bytes = 1 + size % 5;
            mt_fuzz_compare(gz, gz_size, format, name, &options, 1, status, &list, &diag);
            free(gz);
        }
    }
    mt_face_list_free(&list);
    return 0;
}

#endif
