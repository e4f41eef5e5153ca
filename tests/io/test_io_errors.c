/* meshtopo::io: every kind of malformed input gives MT_ERR_PARSE, a zeroed
 * output list and a message naming the file and the line (text) or byte
 * offset (binary) of the problem. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "io_test_util.h"
#include "meshtopo/io.h"

#define TRI "0 0 0\n1 0 0\n0 1 0\n"

static void test_error_truncated_file(void)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/cgal_tetrahedron.off", mt_test_corpus_dir());
    unsigned char *data;
    size_t size;
    CHECK(io_test_slurp(path, &data, &size));
    if (size < 8) return;
    /* "3 1 3 2\n" cut to "3 1 ": the last face (line 10) lacks two indices. */
    EXPECT_PARSE_ERROR(data, size - 4, MT_FORMAT_OFF, "tet.off", 10, UINT64_MAX,
                       "face 3: expected 3 vertex indices, found 1");
    /* Cut after the faces' counts line: the header promises more. */
    EXPECT_PARSE_ERROR(data, 10, MT_FORMAT_OFF, "tet.off", 2, UINT64_MAX,
                       "the header declares 4 vertices and 4 faces but only");
    /* A face record missing entirely. */
    const char *text = "OFF\n3 2 0\n" TRI "3 0 1 2\n";
    EXPECT_TEXT_ERROR(text, MT_FORMAT_OFF, "short.off", 7, "face 1: expected a face record");
    /* A vertex cut short at the end of the file. */
    EXPECT_TEXT_ERROR("OFF\n2 0 0\n0 0 0\n1 2    # comment\n", MT_FORMAT_OFF, "v.off", 4,
                      "vertex 1: expected 3 coordinates, found 2");
    /* OBJ cut in the middle of a v line. */
    EXPECT_TEXT_ERROR("v 0 0 0\nv 1 0", MT_FORMAT_OBJ, "cut.obj", 2,
                      "vertex 1: expected 3 coordinates, found 2");
    /* ASCII PLY cut in the middle of a face. */
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n" TRI "3 0 1",
        MT_FORMAT_PLY_ASCII, "cut.ply", 13, "face 0 of 1");
    free(data);
}

static void test_error_bad_header(void)
{
    EXPECT_TEXT_ERROR("OFX\n3 1 0\n" TRI "3 0 1 2\n", MT_FORMAT_OFF, "bad.off", 1,
                      "expected an OFF header, found 'OFX'");
    EXPECT_TEXT_ERROR("", MT_FORMAT_OFF, "empty.off", 1, "empty file");
    EXPECT_TEXT_ERROR("# nothing\n\n", MT_FORMAT_OFF, "c.off", 3, "empty file");
    EXPECT_TEXT_ERROR("plx\nformat ascii 1.0\nend_header\n", MT_FORMAT_PLY_ASCII, "bad.ply", 1,
                      "expected the 'ply' magic line");
    EXPECT_TEXT_ERROR("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n",
                      MT_FORMAT_PLY_ASCII, "noend.ply", 5, "no 'end_header'");
    EXPECT_TEXT_ERROR("ply\nformat ebcdic 1.0\nend_header\n", MT_FORMAT_PLY_ASCII, "enc.ply", 2,
                      "unknown PLY encoding 'ebcdic'");
    EXPECT_TEXT_ERROR("ply\nelement vertex 0\nend_header\n", MT_FORMAT_PLY_ASCII, "nofmt.ply", 3,
                      "no 'format' line");
    EXPECT_TEXT_ERROR("ply\nformat ascii 1.0\nproperty float x\nend_header\n", MT_FORMAT_PLY_ASCII,
                      "p.ply", 3, "property before any element");
    EXPECT_TEXT_ERROR("ply\nformat ascii 1.0\nelement vertex 1\nproperty float64x x\nend_header\n",
                      MT_FORMAT_PLY_ASCII, "t.ply", 4, "unknown type 'float64x'");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
        "property float y\nend_header\n1 2\n",
        MT_FORMAT_PLY_ASCII, "xyz.ply", 3, "lacks one of the properties x, y, z");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement face 1\nproperty int vertex_indices\n"
        "end_header\n1\n",
        MT_FORMAT_PLY_ASCII, "s.ply", 4, "must be a list");
    EXPECT_TEXT_ERROR("ply\nformat ascii 1.0\nelement face 0\nend_header\n", MT_FORMAT_PLY_ASCII,
                      "nf.ply", 3, "no vertex_indices list");
    EXPECT_TEXT_ERROR("ply\nformat ascii 1.0\nmagic 3\nend_header\n", MT_FORMAT_PLY_ASCII, "kw.ply",
                      3, "unknown PLY header keyword 'magic'");
}

static void test_error_missing_counts(void)
{
    EXPECT_TEXT_ERROR("OFF\n", MT_FORMAT_OFF, "nc.off", 2, "missing the vertex count");
    EXPECT_TEXT_ERROR("OFF\n# comment only\n3", MT_FORMAT_OFF, "nc.off", 3,
                      "missing the face count");
    EXPECT_TEXT_ERROR("OFF\n0.5 0 0\n", MT_FORMAT_OFF, "fc.off", 2,
                      "expected the vertex count, found '0.5'");
    EXPECT_TEXT_ERROR("OFF\n3 -1 0\n", MT_FORMAT_OFF, "fc.off", 2,
                      "expected the face count, found '-1'");
    EXPECT_TEXT_ERROR("ply\nformat ascii 1.0\nelement vertex\nend_header\n", MT_FORMAT_PLY_ASCII,
                      "ec.ply", 3, "expected 'element NAME COUNT'");
    EXPECT_TEXT_ERROR("ply\nformat ascii 1.0\nelement vertex many\nend_header\n",
                      MT_FORMAT_PLY_ASCII, "ec.ply", 3, "bad element count 'many'");
}

static void test_error_non_numeric_token(void)
{
    EXPECT_TEXT_ERROR("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", MT_FORMAT_OFF, "nn.off", 4,
                      "vertex 1: coordinate 1 is not a number, found 'x'");
    EXPECT_TEXT_ERROR("OFF\n3 1 0\n" TRI "3 0 1.0 2\n", MT_FORMAT_OFF, "nn.off", 6,
                      "face 0: vertex index 1 is not an integer, found '1.0'");
    EXPECT_TEXT_ERROR("OFF\n3 1 0\n" TRI "three 0 1 2\n", MT_FORMAT_OFF, "nn.off", 6,
                      "face 0: expected the number of vertex indices, found 'three'");
    EXPECT_TEXT_ERROR("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\xff\n3 0 1 2\n", MT_FORMAT_OFF, "b.off", 5,
                      "found '0\\xff'");
    EXPECT_TEXT_ERROR("v 0 0 0\nv 1 0 0\n\nv 1 1 zero\n", MT_FORMAT_OBJ, "nn.obj", 4,
                      "vertex 2: coordinate 2 is not a number: 'zero'");
    EXPECT_TEXT_ERROR("v 0 0 0\nf 1 a 1\n", MT_FORMAT_OBJ, "nn.obj", 2, "face 0: bad face entry");
    EXPECT_TEXT_ERROR("v 0 0 0\nf 1/x/1 1 1\n", MT_FORMAT_OBJ, "nn.obj", 2, "'1/x/1'");
    EXPECT_TEXT_ERROR("v 0 0 0\nf 1/1/1/1 1 1\n", MT_FORMAT_OBJ, "nn.obj", 2, "bad face entry");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n1 nan? 3\n",
        MT_FORMAT_PLY_ASCII, "nn.ply", 8, "vertex 0 of 1: property 'y': not a number");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int "
        "vertex_indices\nend_header\nx 1 2\n",
        MT_FORMAT_PLY_ASCII, "nn.ply", 6, "bad list count: 'x'");
}

static void test_error_too_few_indices(void)
{
    /* Face 1 (line 7) says 4 but only 2 follow before the end of the file. */
    EXPECT_TEXT_ERROR("OFF\n3 2 0\n" TRI "3 0 1 2\n4 0 1\n", MT_FORMAT_OFF, "mesh.off", 7,
                      "face 1: expected 4 vertex indices, found 2");
    /* Spread over lines with comments, the message names the face's line. */
    EXPECT_TEXT_ERROR("OFF\n3 1 0\n" TRI "5 0\n# c\n1\n\n2\n", MT_FORMAT_OFF, "mesh.off", 6,
                      "face 0: expected 5 vertex indices, found 3");
}

static void test_error_counts_larger_than_file(void)
{
    EXPECT_TEXT_ERROR("OFF\n2147483648 1 0\n0 0 0\n", MT_FORMAT_OFF, "big.off", 2,
                      "vertex count too large");
    EXPECT_TEXT_ERROR("OFF\n1000000 1 0\n0 0 0\n", MT_FORMAT_OFF, "big.off", 2,
                      "the header declares 1000000 vertices and 1 faces but only 6 bytes follow");
    EXPECT_TEXT_ERROR("OFF\n3 4294967295 0\n" TRI, MT_FORMAT_OFF, "big.off", 2, "but only");
    EXPECT_TEXT_ERROR("OFF\n3 4294967296 0\n" TRI, MT_FORMAT_OFF, "big.off", 2,
                      "face count too large");
    EXPECT_TEXT_ERROR("OFF\n3 99999999999999999999999 0\n" TRI, MT_FORMAT_OFF, "big.off", 2,
                      "face count too large");
    EXPECT_TEXT_ERROR("OFF\n3 1 0\n" TRI "99999999999 0 1 2\n", MT_FORMAT_OFF, "big.off", 6,
                      "face 0: vertex count too large");
    /* PLY: element counts against the bytes after end_header. */
    EXPECT_TEXT_ERROR(
        "ply\nformat binary_little_endian 1.0\nelement vertex 2147483647\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n"
        "0123456789ab",
        MT_FORMAT_PLY_BINARY_LE, "big.ply", 7,
        "need at least 25769803764 bytes of data but only 12 follow");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement vertex 2147483648\nproperty float x\n"
        "end_header\n",
        MT_FORMAT_PLY_ASCII, "big.ply", 3, "vertex count 2147483648 too large");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement junk 18446744073709551615\n"
        "property double a\nproperty double b\nend_header\n1 2\n",
        MT_FORMAT_PLY_ASCII, "big.ply", 6, "need at least");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement face 1\nproperty list uint int "
        "vertex_indices\nend_header\n4000000000 1 2\n",
        MT_FORMAT_PLY_ASCII, "big.ply", 6, "list count larger than the rest of the file");
}

static void test_error_index_too_large(void)
{
    EXPECT_TEXT_ERROR("OFF\n3 1 0\n" TRI "3 0 1 4294967296\n", MT_FORMAT_OFF, "idx.off", 6,
                      "face 0: vertex index 2 does not fit in a 32-bit integer, found "
                      "'4294967296'");
    EXPECT_TEXT_ERROR("OFF\n3 1 0\n" TRI "3 0 -2147483649 1\n", MT_FORMAT_OFF, "idx.off", 6,
                      "does not fit in a 32-bit integer");
    EXPECT_TEXT_ERROR("v 0 0 0\nf 1 2 4294967296\n", MT_FORMAT_OBJ, "idx.obj", 2,
                      "vertex index does not fit in a 32-bit integer");
    EXPECT_TEXT_ERROR("v 0 0 0\nf 1 2 -2147483649/1\n", MT_FORMAT_OBJ, "idx.obj", 2,
                      "does not fit in a 32-bit integer");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int "
        "vertex_indices\nend_header\n3 1 2 123456789012\n",
        MT_FORMAT_PLY_ASCII, "idx.ply", 6, "does not fit in a 32-bit integer");
    /* The largest values that fit are kept. */
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(io_test_read_text("OFF\n0 1 0\n2 4294967295 -2147483648\n", MT_FORMAT_OFF, NULL, &list,
                               &diag));
    CHECK_EQ(list.num_indices, 2);
    if (list.num_indices == 2) {
        CHECK_EQ(list.face_indices[0], UINT32_MAX);
        CHECK_EQ(list.face_indices[1], 0x80000000u);
    }
    mt_face_list_free(&list);
}

/* A binary PLY header for 2 float vertices and faces with `count_type`. */
static size_t binary_header(char *buf, size_t size, const char *count_type, int faces)
{
    return (size_t)snprintf(buf, size,
                            "ply\nformat binary_little_endian 1.0\nelement vertex 2\n"
                            "property float x\nproperty float y\nproperty float z\n"
                            "element face %d\nproperty list %s int vertex_indices\nend_header\n",
                            faces, count_type);
}

static void test_error_binary_ply_cut_mid_element(void)
{
    unsigned char buf[512];
    size_t h = binary_header((char *)buf, sizeof buf, "uchar", 1);
    memset(buf + h, 0, 24); /* two vertices of 3 floats */
    size_t face = h + 24;
    buf[face] = 3; /* then indices 0 1 2 as int32 */
    memset(buf + face + 1, 0, 12);
    buf[face + 5] = 1;
    buf[face + 9] = 2;
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(mt_read_memory(buf, face + 13, MT_FORMAT_AUTO, "cut.ply", &list, &diag));
    CHECK_EQ(list.num_indices, 3);
    mt_face_list_free(&list);
    /* Cut inside the index list: the list runs past the end. */
    EXPECT_PARSE_ERROR(buf, face + 11, MT_FORMAT_AUTO, "cut.ply", 0, face + 1,
                       "face 0 of 1: property 'vertex_indices': the list runs past the end");
    /* Cut inside the second vertex: the size check of the header sees it. */
    h = binary_header((char *)buf, sizeof buf, "uchar", 0);
    memset(buf + h, 0, 24);
    EXPECT_PARSE_ERROR(buf, h + 18, MT_FORMAT_AUTO, "cut.ply", 9, UINT64_MAX,
                       "need at least 24 bytes of data but only 18 follow");
    /* A vertex element with a list: the size check cannot see the cut, the
     * parser finds it in vertex 1's y. */
    h = (size_t)snprintf((char *)buf, sizeof buf,
                         "ply\nformat binary_little_endian 1.0\nelement vertex 2\n"
                         "property list uchar float uv\nproperty float x\nproperty float y\n"
                         "property float z\nend_header\n");
    memset(buf + h, 0, 40);
    buf[h] = 2; /* vertex 0: uv of 2 floats, x y z: 21 bytes; vertex 1: no uv, x */
    EXPECT_PARSE_ERROR(buf, h + 28, MT_FORMAT_AUTO, "uv.ply", 0, h + 26,
                       "vertex 1 of 2: property 'y': unexpected end of data");
    /* Data after the last element. */
    h = binary_header((char *)buf, sizeof buf, "uchar", 0);
    memset(buf + h, 0, 24);
    memcpy(buf + h + 24, "junk", 4);
    EXPECT_PARSE_ERROR(buf, h + 28, MT_FORMAT_AUTO, "junk.ply", 0, h + 24,
                       "unexpected data after the last element");
}

/* Data cut inside a binary element that the size check cannot see: lists. */
static void test_error_binary_ply_cut_in_list(void)
{
    unsigned char buf[512];
    size_t h = binary_header((char *)buf, sizeof buf, "uchar", 3);
    memset(buf + h, 0, 24);
    size_t f = h + 24;
    /* face 0: 1 index; face 1: 200 indices (only 1 present); face 2 count */
    buf[f] = 1, memset(buf + f + 1, 0, 4);
    buf[f + 5] = 200, memset(buf + f + 6, 0, 4);
    buf[f + 10] = 0;
    EXPECT_PARSE_ERROR(buf, f + 11, MT_FORMAT_AUTO, "l.ply", 0, f + 6,
                       "face 1 of 3: property 'vertex_indices': the list runs past the end");
    /* A signed count type with a negative count. */
    h = binary_header((char *)buf, sizeof buf, "char", 1);
    memset(buf + h, 0, 24);
    buf[h + 24] = 0xff;
    EXPECT_PARSE_ERROR(buf, h + 25, MT_FORMAT_AUTO, "n.ply", 0, h + 24, "negative list count");
}

static void test_error_wrong_list_count_type(void)
{
    char buf[512];
    binary_header(buf, sizeof buf, "float", 1);
    EXPECT_TEXT_ERROR(buf, MT_FORMAT_PLY_BINARY_LE, "lc.ply", 8,
                      "list count type must be an integer type, not 'float'");
    binary_header(buf, sizeof buf, "double", 1);
    EXPECT_TEXT_ERROR(buf, MT_FORMAT_PLY_BINARY_LE, "lc.ply", 8, "not 'double'");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar float "
        "vertex_indices\nend_header\n3 0 1 2\n",
        MT_FORMAT_PLY_ASCII, "it.ply", 4,
        "face vertex indices must have an integer type, not 'float'");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar "
        "vertex_indices\nend_header\n3 0 1 2\n",
        MT_FORMAT_PLY_ASCII, "it.ply", 4, "expected 'property list COUNT_TYPE");
}

static void test_error_garbage_gzip(void)
{
    /* The gzip magic followed by nonsense. */
    static const unsigned char garbage[] = {0x1f, 0x8b, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00,
                                            0x02, 0xff, 0xff, 0xff, 0xff, 0xff, 0x12, 0x34};
    EXPECT_PARSE_ERROR(garbage, sizeof garbage, MT_FORMAT_AUTO, "g.off.gz", 0, UINT64_MAX,
                       "corrupt gzip data");
    /* Only the magic. */
    EXPECT_PARSE_ERROR(garbage, 2, MT_FORMAT_OFF, "g.off.gz", 0, 2, "truncated");
    /* A real stream cut short: a gzip file written by meshtopo, halved. */
    mt_face_list list;
    CHECK_OK(mt_face_list_alloc(&list, 100, 0, 0, NULL));
    for (int k = 0; k < 300; k++) list.positions[k] = k * 0.123;
    const char *path = io_test_path("cut.off.gz");
    mt_diag diag;
    CHECK_OK(mt_write_file(path, MT_FORMAT_AUTO, &list, &diag));
    mt_face_list_free(&list);
    unsigned char *data;
    size_t size;
    CHECK(io_test_slurp(path, &data, &size));
    if (size > 40) {
        EXPECT_PARSE_ERROR(data, size / 2, MT_FORMAT_AUTO, "cut.off.gz", 0, size / 2,
                           "gzip data ends before the end of its stream");
        /* A damaged trailer (CRC) is caught too. */
        data[size - 6] ^= 0x55;
        EXPECT_PARSE_ERROR(data, size, MT_FORMAT_AUTO, "crc.off.gz", 0, UINT64_MAX,
                           "corrupt gzip data");
        data[size - 6] ^= 0x55;
        /* Garbage after the stream. */
        unsigned char *more = malloc(size + 3);
        if (more) {
            memcpy(more, data, size);
            memcpy(more + size, "xyz", 3);
            EXPECT_PARSE_ERROR(more, size + 3, MT_FORMAT_AUTO, "tail.off.gz", 0, size,
                               "unexpected data after the end of the gzip stream");
            free(more);
        }
    }
    free(data);
    /* Through mt_read_file as well. */
    const char *gpath = io_test_path("garbage.off.gz");
    CHECK(io_test_spill(gpath, garbage, sizeof garbage));
    CHECK_STATUS(mt_read_file(gpath, MT_FORMAT_AUTO, &list, &diag), MT_ERR_PARSE);
    CHECK(strstr(diag.message, gpath) != NULL);
    CHECK(strstr(diag.message, "byte offset") != NULL);
}

static void test_error_trailing_data(void)
{
    EXPECT_TEXT_ERROR("OFF\n3 1 0\n" TRI "3 0 1 2\n3 0 1 2\n", MT_FORMAT_OFF, "t.off", 7,
                      "unexpected data after the last face (the header declares 1)");
    EXPECT_TEXT_ERROR(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n1 2 3\n4\n",
        MT_FORMAT_PLY_ASCII, "t.ply", 9, "unexpected data after the last element");
}

/* Reads data; any result but MT_OK or MT_ERR_PARSE (with a zeroed list and
 * a message naming the file) is a failure. Returns the status. */
static mt_status read_any_outcome(const unsigned char *data, size_t size, mt_format format,
                                  const char *name, const char *what, size_t at)
{
    mt_face_list list;
    memset(&list, 0xab, sizeof list);
    mt_diag diag;
    mt_status status =
        io_test_read_variants_at(__FILE__, __LINE__, data, size, format, name, &list, &diag);
    if (status == MT_OK) {
        CHECK_OK(mt_face_list_check(&list, NULL));
        mt_face_list_free(&list);
    } else if (status != MT_ERR_PARSE || list.positions || list.face_sizes || list.face_indices ||
               list.num_faces || strncmp(diag.message, name, strlen(name)) != 0) {
        mt_test_fail(__FILE__, __LINE__, "%s %s at %zu: status %d, message '%s'", name, what, at,
                     (int)status, diag.message);
    }
    return status;
}

/* Every prefix and every single-byte change of small files in each format
 * (gzip too) reads cleanly or fails with MT_ERR_PARSE: a deterministic
 * sweep next to the fuzzers, run under the sanitizers with the tests. */
static void test_error_every_truncation_and_byte(void)
{
    mt_face_list list;
    CHECK_OK(mt_face_list_alloc(&list, 5, 4, 11, NULL));
    static const uint32_t sizes[] = {3, 4, 0, 4};
    static const uint32_t idx[] = {0, 1, 2, 1, 2, 3, 4, UINT32_MAX, 4, 0, 300};
    memcpy(list.face_sizes, sizes, sizeof sizes);
    memcpy(list.face_indices, idx, sizeof idx);
    for (int k = 0; k < 15; k++) list.positions[k] = k * 0.25 - 1;
    static const char *const names[] = {"s.off",    "s.obj",    "s.ply",   "s.ascii.ply",
                                        "s.be.ply", "s.off.gz", "s.ply.gz"};
    static const mt_format formats[] = {
        MT_FORMAT_OFF,           MT_FORMAT_OBJ, MT_FORMAT_PLY_BINARY_LE, MT_FORMAT_PLY_ASCII,
        MT_FORMAT_PLY_BINARY_BE, MT_FORMAT_OFF, MT_FORMAT_PLY_BINARY_LE};
    for (size_t f = 0; f < sizeof names / sizeof names[0]; f++) {
        const char *path = io_test_path(names[f]);
        mt_diag diag;
        CHECK_OK(mt_write_file(path, formats[f], &list, &diag));
        unsigned char *data;
        size_t size;
        if (!io_test_slurp(path, &data, &size)) continue;
        CHECK_OK(read_any_outcome(data, size, formats[f], names[f], "whole", size));
        int failures = 0;
        for (size_t cut = 0; cut < size; cut++) {
            /* in a buffer of exactly that size, so ASan sees any overrun */
            unsigned char *prefix = malloc(cut ? cut : 1);
            if (!prefix) continue;
            memcpy(prefix, data, cut);
            failures += read_any_outcome(prefix, cut, formats[f], names[f], "cut", cut) != MT_OK;
            free(prefix);
        }
        /* Binary files cut anywhere must fail (every byte is needed). */
        if (formats[f] != MT_FORMAT_OFF && formats[f] != MT_FORMAT_OBJ &&
            formats[f] != MT_FORMAT_PLY_ASCII)
            CHECK_EQ(failures, (long long)size);
        static const unsigned char flips[] = {0x01, 0x80, 0xff};
        for (size_t at = 0; at < size; at++) {
            for (size_t k = 0; k < sizeof flips; k++) {
                data[at] ^= flips[k];
                read_any_outcome(data, size, formats[f], names[f], "flip", at);
                data[at] ^= flips[k];
            }
        }
        free(data);
    }
    mt_face_list_free(&list);
}

static const mt_test_case cases[] = {
    {"error_truncated_file", test_error_truncated_file},
    {"error_bad_header", test_error_bad_header},
    {"error_missing_counts", test_error_missing_counts},
    {"error_non_numeric_token", test_error_non_numeric_token},
    {"error_too_few_indices", test_error_too_few_indices},
    {"error_counts_larger_than_file", test_error_counts_larger_than_file},
    {"error_index_too_large", test_error_index_too_large},
    {"error_binary_ply_cut_mid_element", test_error_binary_ply_cut_mid_element},
    {"error_binary_ply_cut_in_list", test_error_binary_ply_cut_in_list},
    {"error_wrong_list_count_type", test_error_wrong_list_count_type},
    {"error_garbage_gzip", test_error_garbage_gzip},
    {"error_trailing_data", test_error_trailing_data},
    {"error_every_truncation_and_byte", test_error_every_truncation_and_byte},
};
const mt_test_table mt_tests_io_errors = {cases, sizeof cases / sizeof cases[0]};
