/* Helpers shared by the meshtopo::io tests: a private temporary directory
 * removed at exit, whole-file reads, face-list comparison and checks of
 * parse-error messages. */
#ifndef MESHTOPO_IO_TEST_UTIL_H
#define MESHTOPO_IO_TEST_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/io.h"

/* Path of `name` inside this process's temporary directory (created on
 * first use; the files named through here and the directory are removed at
 * exit). The returned string stays valid until exit. */
const char *io_test_path(const char *name);

/* Reads a whole file; returns 0 on failure. *data is malloc'd. */
int io_test_slurp(const char *path, unsigned char **data, size_t *size);

/* Writes bytes to a file; returns 0 on failure. */
int io_test_spill(const char *path, const void *data, size_t size);

/* Reads NUL-terminated text with mt_read_memory. */
mt_status io_test_read_text(const char *text, mt_format format, const char *name, mt_face_list *out,
                            mt_diag *diag);

/* The gzip form of [data, data + size) with stored (uncompressed) deflate
 * blocks: one member, CRC and length as RFC 1952 says. Returns a malloc'd
 * buffer and its size in *out_size, or NULL. */
unsigned char *io_test_gzip_stored(const void *data, size_t size, size_t *out_size);

/* gzip data that inflates to `members` members, each `member_size` bytes
 * of `pattern` (1 to 4 bytes) repeated, made cheaply (fixed-Huffman
 * deflate: 258-byte matches), so gigabytes fit in a few megabytes. Returns
 * a malloc'd buffer and its size in *out_size, or NULL. */
unsigned char *io_test_gzip_repeat(const char *pattern, size_t pattern_len, uint64_t member_size,
                                   size_t members, size_t *out_size);

/* Reads [data, data + size) whole with mt_read_memory into *out / *diag
 * and returns its status, after CHECKing that the other ways of reading the
 * same bytes agree with it: through windows of a few bytes (the input's
 * length known), and as gzip data (its length unknown until its end; unless
 * the data is gzip already). They must give the same status and list, and
 * the same message, line and byte offset, bar the documented differences
 * of streamed gzip data (the read fails, with another message): when the
 * whole read fails a check of counts against the bytes that follow, the
 * gzip read may report an error it met before the end of the data instead;
 * when the whole read fails on damaged gzip data, a smaller window may
 * meet a parse error in what was inflated before the damage. Reports
 * failures at the caller's line. */
mt_status io_test_read_variants_at(const char *file, int line_no, const void *data, size_t size,
                                   mt_format format, const char *name, mt_face_list *out,
                                   mt_diag *diag);
#define IO_TEST_READ_VARIANTS(data, size, format, name, out, diag) \
    io_test_read_variants_at(__FILE__, __LINE__, data, size, format, name, out, diag)

/* CHECKs that a and b hold the same counts, face sizes, indices and
 * (bit for bit) positions; `what` names the comparison in failures. */
void io_test_check_same(const mt_face_list *a, const mt_face_list *b, const char *what);

/* CHECKs that reading data gives MT_ERR_PARSE, a zeroed list, and a
 * message that contains `name`, the position ("name:LINE: " when line > 0,
 * else "name: byte offset OFFSET: ", any offset when OFFSET is UINT64_MAX;
 * diag.line / diag.byte_offset must match) and `fragment`; the other ways of
 * reading the same bytes must agree (io_test_read_variants_at). Reports
 * failures at the caller's line. */
void io_test_expect_parse_error_at(const char *file, int line_no, const void *data, size_t size,
                                   mt_format format, const char *name, uint64_t line,
                                   uint64_t offset, const char *fragment);
#define EXPECT_PARSE_ERROR(data, size, format, name, line, offset, fragment)                  \
    io_test_expect_parse_error_at(__FILE__, __LINE__, data, size, format, name, line, offset, \
                                  fragment)

/* The same for NUL-terminated text (error at a line). */
#define EXPECT_TEXT_ERROR(text, format, name, line, fragment) \
    EXPECT_PARSE_ERROR(text, strlen(text), format, name, line, UINT64_MAX, fragment)

#endif
