/* meshtopo::io: what each format reads, case by case: OFF variants
 * (COFF/NOFF, comments, faces over several lines, colours), OBJ index forms
 * (negative, v/vt/vn, 0, bare f, continuation), PLY ascii and binary little
 * and big endian built byte by byte, and multi-member gzip. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "io_test_util.h"
#include "meshtopo/io.h"

/* CHECKs the face sizes and flat indices of list. */
static void check_faces(const mt_face_list *list, const uint32_t *sizes, uint32_t num_faces,
                        const uint32_t *indices, uint64_t num_indices)
{
    CHECK_EQ(list->num_faces, num_faces);
    CHECK_EQ(list->num_indices, num_indices);
    if (list->num_faces != num_faces || list->num_indices != num_indices) return;
    for (uint32_t f = 0; f < num_faces; f++) CHECK_EQ(list->face_sizes[f], sizes[f]);
    for (uint64_t k = 0; k < num_indices; k++) CHECK_EQ(list->face_indices[k], indices[k]);
    CHECK_OK(mt_face_list_check(list, NULL));
}

/* ---- OFF --------------------------------------------------------------- */

static void test_off_variants(void)
{
    mt_face_list list;
    mt_diag diag;
    /* Comments everywhere, counts on the header line, a face over three
     * lines, faces of 0, 1 and 2 vertices, colour values after indices. */
    const char *text =
        "OFF 4 6 0 # counts on the header line\n"
        "# a comment line\n"
        "0 0 0\n"
        "1 0 0 # trailing comment\n"
        "\n"
        "0 1 0\n"
        "  0.5 0.5 1e0\n"
        "3 0 1 2 255 0 0\n"
        "4 0\n"
        "   1 # still face 1\n"
        "2 3\n"
        "0\n"
        "1 3\n"
        "2 2 3 0.1 0.2 0.3 1.0\n"
        "3 -1 3 4\n";
    CHECK_OK(io_test_read_text(text, MT_FORMAT_OFF, "v.off", &list, &diag));
    static const uint32_t sizes[] = {3, 4, 0, 1, 2, 3};
    static const uint32_t idx[] = {0, 1, 2, 0, 1, 2, 3, 3, 2, 3, UINT32_MAX, 3, 4};
    check_faces(&list, sizes, 6, idx, 13);
    CHECK_EQ(list.num_verts, 4);
    if (list.num_verts == 4) CHECK(list.positions[9] == 0.5 && list.positions[11] == 1.0);
    mt_face_list_free(&list);

    /* COFF / NOFF / CNOFF: per-vertex extras skipped to the end of the line;
     * \r\n line ends. */
    static const char *const headers[] = {"COFF", "NOFF", "CNOFF", "STOFF"};
    for (int h = 0; h < 4; h++) {
        char buf[512];
        snprintf(buf, sizeof buf,
                 "%s\r\n3 1 3\r\n0 0 0 1 0 0 1\r\n1 0 0 0 1 0 1 9 9\r\n0 1 0 0 0 1\r\n"
                 "3 0 1 2\r\n",
                 headers[h]);
        CHECK_OK(io_test_read_text(buf, MT_FORMAT_AUTO, NULL, &list, &diag));
        static const uint32_t one[] = {3};
        static const uint32_t tri[] = {0, 1, 2};
        check_faces(&list, one, 1, tri, 3);
        CHECK_EQ(list.num_verts, 3);
        if (list.num_verts == 3) CHECK(list.positions[3] == 1.0 && list.positions[7] == 1.0);
        mt_face_list_free(&list);
    }
    /* Old Mac line ends ('\r' only) with colours to skip. */
    CHECK_OK(io_test_read_text("COFF\r3 1 0\r0 0 0 9\r1 0 0 9\r0 1 0 9\r3 0 1 2 7 7 7\r",
                               MT_FORMAT_OFF, NULL, &list, &diag));
    CHECK_EQ(list.num_faces, 1);
    CHECK_EQ(list.num_indices, 3);
    mt_face_list_free(&list);
    /* Counts without the edge count, no final newline. */
    CHECK_OK(io_test_read_text("OFF\n1 1\n1 2 3\n1 0", MT_FORMAT_OFF, NULL, &list, &diag));
    CHECK_EQ(list.num_faces, 1);
    CHECK_EQ(list.num_indices, 1);
    mt_face_list_free(&list);
    /* Binary OFF and 4D OFF are refused as unsupported. */
    CHECK_STATUS(io_test_read_text("OFF BINARY\n", MT_FORMAT_OFF, NULL, &list, &diag),
                 MT_ERR_UNSUPPORTED);
    CHECK_STATUS(io_test_read_text("4OFF\n1 0 0\n1 2 3 4\n", MT_FORMAT_OFF, NULL, &list, &diag),
                 MT_ERR_UNSUPPORTED);
}

/* Coordinates in every notation read to the correctly rounded double. */
static void test_off_number_forms(void)
{
    static const struct {
        const char *text;
        double value;
    } cases[] = {
        {"1", 1.0},
        {"-0", -0.0},
        {"+2.5", 2.5},
        {".5", 0.5},
        {"5.", 5.0},
        {"1e3", 1000.0},
        {"1E-3", 0.001},
        {"0.1", 0.1},
        {"0.30000000000000004", 0.30000000000000004},
        {"123456789012345678901234567890", 1.2345678901234568e29},
        {"2.2250738585072014e-308", 2.2250738585072014e-308},
        {"4.9406564584124654e-324", 4.9406564584124654e-324},
        {"1.7976931348623157e308", 1.7976931348623157e308},
        {"9007199254740993", 9007199254740992.0},
        {"0x1p-2", 0.25},
        {"0.000000000000000000000000000001", 1e-30},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char buf[256];
        snprintf(buf, sizeof buf, "OFF\n1 0 0\n%s 0 0\n", cases[i].text);
        mt_face_list list;
        mt_diag diag;
        CHECK_OK(io_test_read_text(buf, MT_FORMAT_OFF, NULL, &list, &diag));
        if (list.num_verts != 1) continue;
        if (memcmp(&list.positions[0], &cases[i].value, sizeof(double)) != 0)
            mt_test_fail(__FILE__, __LINE__, "'%s' read as %.17g, expected %.17g", cases[i].text,
                         list.positions[0], cases[i].value);
        mt_face_list_free(&list);
    }
}

/* Random decimals of every length and exponent read exactly as strtod reads
 * them (the exact fast path and the strtod fallback must agree), in OFF,
 * OBJ and ASCII PLY. */
static void test_number_parsing_matches_strtod(void)
{
    enum { N = 20000 };
    size_t cap = (size_t)N * 3 * 40 + 256;
    char *off = malloc(cap), *obj = malloc(cap), *ply = malloc(cap);
    double *expected = malloc(sizeof(double) * 3 * N);
    if (!off || !obj || !ply || !expected) {
        mt_test_fail(__FILE__, __LINE__, "out of memory");
        free(off), free(obj), free(ply), free(expected);
        return;
    }
    size_t o = (size_t)snprintf(off, cap, "OFF\n%d 0 0\n", N);
    size_t b = 0;
    size_t p = (size_t)snprintf(ply, cap,
                                "ply\nformat ascii 1.0\nelement vertex %d\nproperty double x\n"
                                "property double y\nproperty double z\nend_header\n",
                                N);
    uint64_t state = 12345;
    for (int k = 0; k < 3 * N; k++) {
        char num[64];
        size_t n = 0;
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        uint64_t r = state >> 11;
        if (r & 1) num[n++] = '-';
        int digits = 1 + (int)((r >> 1) % 22);
        int point = (int)((r >> 6) % (unsigned)(digits + 2)) - 1; /* -1: none */
        for (int i = 0; i < digits; i++) {
            if (i == point) num[n++] = '.';
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            num[n++] = (char)('0' + (state >> 33) % 10);
        }
        if ((r >> 12) & 1)
            n += (size_t)snprintf(num + n, sizeof num - n, "e%d", (int)((r >> 13) % 90) - 45);
        num[n] = '\0';
        expected[k] = strtod(num, NULL);
        const char *sep = k % 3 == 2 ? "\n" : " ";
        if (k % 3 == 0) b += (size_t)snprintf(obj + b, cap - b, "v ");
        o += (size_t)snprintf(off + o, cap - o, "%s%s", num, sep);
        b += (size_t)snprintf(obj + b, cap - b, "%s%s", num, sep);
        p += (size_t)snprintf(ply + p, cap - p, "%s%s", num, sep);
    }
    const char *texts[3] = {off, obj, ply};
    const mt_format formats[3] = {MT_FORMAT_OFF, MT_FORMAT_OBJ, MT_FORMAT_PLY_ASCII};
    for (int t = 0; t < 3; t++) {
        mt_face_list list;
        mt_diag diag;
        mt_status status = io_test_read_text(texts[t], formats[t], "numbers", &list, &diag);
        CHECK_OK(status);
        if (status != MT_OK) continue;
        CHECK_EQ(list.num_verts, N);
        int bad = 0;
        for (int k = 0; k < 3 * N && list.num_verts == N; k++) {
            if (memcmp(&list.positions[k], &expected[k], sizeof(double)) != 0 && bad++ < 5)
                mt_test_fail(__FILE__, __LINE__,
                             "format %d: coordinate %d is %.17g, strtod "
                             "gives %.17g",
                             t, k, list.positions[k], expected[k]);
        }
        mt_face_list_free(&list);
    }
    free(off), free(obj), free(ply), free(expected);
}

/* Tokens at the edges of the fast paths: glued comments, '+' signs, leading
 * zeros, numbers the fast path hands to strtod. */
static void test_off_token_edges(void)
{
    mt_face_list list;
    mt_diag diag;
    const char *text =
        "OFF\n3 2 0\n"
        "0 0 0#glued comment\n"
        "1.0e 0 0\n"
        "+1 1e+0 00000000000000000000000000001\n"
        "3 +0 00000000001 2#c\n"
        "3 2 1 -0\n";
    CHECK_STATUS(io_test_read_text(text, MT_FORMAT_OFF, "e.off", &list, &diag), MT_ERR_PARSE);
    CHECK(strstr(diag.message, "e.off:4: vertex 1: coordinate 0 is not a number, found '1.0e'"));
    char fixed[256];
    snprintf(fixed, sizeof fixed, "%s", text);
    char *e = strstr(fixed, "1.0e ");
    e[3] = ' '; /* "1.0  0 0" */
    CHECK_OK(io_test_read_text(fixed, MT_FORMAT_OFF, "e.off", &list, &diag));
    static const uint32_t sizes[] = {3, 3};
    static const uint32_t idx[] = {0, 1, 2, 2, 1, 0};
    check_faces(&list, sizes, 2, idx, 6);
    if (list.num_verts == 3) {
        CHECK(list.positions[3] == 1.0 && list.positions[6] == 1.0);
        CHECK(list.positions[7] == 1.0 && list.positions[8] == 1.0);
    }
    mt_face_list_free(&list);
}

/* ---- OBJ --------------------------------------------------------------- */

static void test_obj_index_forms(void)
{
    mt_face_list list;
    mt_diag diag;
    const char *text =
        "# cube fragment\r\n"
        "mtllib x.mtl\n"
        "o first\n"
        "v 0 0 0\n"
        "v 1 0 0 1.0\n"         /* w */
        "v 1 1 0 0.5 0.5 0.5\n" /* colour */
        "vt 0 0\nvn 0 0 1\n"
        "v 0 1 0 # comment\n"
        "g group\nusemtl m\ns 1\n"
        "f 1 2 3\n"             /* plain */
        "f 1/1 2/2 3/3 4/4\n"   /* v/vt */
        "f 1/1/1 2/2/1 3/3/1\n" /* v/vt/vn */
        "f 4//1 3//1 1//1\n"    /* v//vn */
        "f -4 -3 -2 -1\n"       /* relative */
        "o second\n"
        "v 2 2 2\n"
        "f -1 -2 -5\n" /* relative to 5 vertices */
        "f 0 1 2\n"    /* 0 is -1 */
        "f\n"          /* empty face */
        "f 5\n"
        "f 1 \\\n 2 \\\r\n 3\n" /* continuation lines */
        "l 1 2\np 3\n"
        "f 4294967295 -2147483648\n"; /* extremes that fit */
    CHECK_OK(io_test_read_text(text, MT_FORMAT_AUTO, "forms.obj", &list, &diag));
    static const uint32_t sizes[] = {3, 4, 3, 3, 4, 3, 3, 0, 1, 3, 2};
    static const uint32_t idx[] = {0,
                                   1,
                                   2,
                                   0,
                                   1,
                                   2,
                                   3,
                                   0,
                                   1,
                                   2,
                                   3,
                                   2,
                                   0,
                                   0,
                                   1,
                                   2,
                                   3,
                                   4,
                                   3,
                                   0,
                                   UINT32_MAX,
                                   0,
                                   1,
                                   4,
                                   0,
                                   1,
                                   2,
                                   4294967294u,
                                   (uint32_t)(5 - 2147483648ll)};
    check_faces(&list, sizes, 11, idx, sizeof idx / sizeof idx[0]);
    CHECK_EQ(list.num_verts, 5);
    if (list.num_verts == 5) {
        CHECK(list.positions[3] == 1.0 && list.positions[7] == 1.0 && list.positions[8] == 0.0);
        CHECK(list.positions[12] == 2.0 && list.positions[14] == 2.0);
    }
    mt_face_list_free(&list);

    /* A relative index before any vertex: negative, stored as two's complement. */
    CHECK_OK(io_test_read_text("f -1 -2\nv 0 0 0\nf -3\n", MT_FORMAT_OBJ, NULL, &list, &diag));
    static const uint32_t s2[] = {2, 1};
    static const uint32_t i2[] = {UINT32_MAX, UINT32_MAX - 1, UINT32_MAX - 1};
    check_faces(&list, s2, 2, i2, 3);
    if (list.num_indices == 3) CHECK_EQ(mt_index_as_signed(list.face_indices[2]), -2);
    mt_face_list_free(&list);
}

/* The corpus's assimp_malformed mesh comes from this OBJ: the readers agree. */
static void test_obj_matches_off(void)
{
    const char *obj =
        "v -0.5 -0.5 0.5\nv -0.5 -0.5 -0.5\nv -0.5 0.5 -0.5\nv -0.5 0.5 0.5\n"
        "v 0.5 -0.5 0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv 0.5 0.5 0.5\n"
        "f 4 12 2 1\nf 2 6 5 1\nf 8 7 6 2\nf 8 7 3 4\nf 5 8 8 1\nf 0 7 8 5\n";
    char path[1024];
    snprintf(path, sizeof path, "%s/assimp_malformed.off", mt_test_corpus_dir());
    mt_face_list from_obj, from_off;
    mt_diag diag;
    CHECK_OK(io_test_read_text(obj, MT_FORMAT_OBJ, "m.obj", &from_obj, &diag));
    CHECK_OK(mt_read_file(path, MT_FORMAT_AUTO, &from_off, &diag));
    io_test_check_same(&from_obj, &from_off, "obj vs off");
    mt_face_list_free(&from_obj);
    mt_face_list_free(&from_off);
}

/* ---- PLY --------------------------------------------------------------- */

typedef struct bytes {
    unsigned char data[4096];
    size_t len;
    int be;
} bytes;

static void put(bytes *b, const void *p, size_t n)
{
    if (b->len + n > sizeof b->data) {
        mt_test_fail(__FILE__, __LINE__, "test buffer overflow");
        return;
    }
    memcpy(b->data + b->len, p, n);
    b->len += n;
}

static void put_text(bytes *b, const char *s)
{
    put(b, s, strlen(s));
}

static void put_uint(bytes *b, uint64_t v, int size)
{
    unsigned char tmp[8];
    for (int k = 0; k < size; k++) tmp[b->be ? size - 1 - k : k] = (unsigned char)(v >> (8 * k));
    put(b, tmp, (size_t)size);
}

static void put_f32(bytes *b, float v)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    put_uint(b, u, 4);
}

static void put_f64(bytes *b, double v)
{
    uint64_t u;
    memcpy(&u, &v, 8);
    put_uint(b, u, 8);
}

/* A binary PLY with properties in unusual order and types, an element to
 * skip between vertex and face, and face properties around the list:
 *   vertex: uchar red, float z, double x, short y(int16), list uchar float uv
 *   edge:   int a, list ushort int path   (skipped)
 *   face:   uchar flags, list ushort short vertex_index, float quality
 * Returns the offset where the face data starts. */
static size_t build_binary_ply(bytes *b, int be)
{
    memset(b, 0, sizeof *b);
    b->be = be;
    put_text(b, "ply\r\n");
    put_text(b, be ? "format binary_big_endian 1.0\n" : "format binary_little_endian 1.0\n");
    put_text(b,
             "comment built byte by byte\n"
             "obj_info test\n"
             "element vertex 3\n"
             "property uchar red\n"
             "property float z\n"
             "property double x\n"
             "property int16 y\n"
             "property list uchar float uv\n"
             "element edge 2\n"
             "property int a\n"
             "property list ushort int path\n"
             "element face 3\n"
             "property uchar flags\n"
             "property list ushort short vertex_index\n"
             "property float quality\n"
             "end_header\n");
    /* vertices: (x, y, z) = (0.1, 7, 2.5), (-3, -1, 0.25), (1e300, 0, -0) */
    put_uint(b, 200, 1), put_f32(b, 2.5f), put_f64(b, 0.1), put_uint(b, 7, 2);
    put_uint(b, 2, 1), put_f32(b, 0.5f), put_f32(b, 0.75f);
    put_uint(b, 1, 1), put_f32(b, 0.25f), put_f64(b, -3.0), put_uint(b, (uint16_t)-1, 2);
    put_uint(b, 0, 1);
    put_uint(b, 0, 1), put_f32(b, -0.0f), put_f64(b, 1e300), put_uint(b, 0, 2);
    put_uint(b, 1, 1), put_f32(b, 1.0f);
    /* edges */
    put_uint(b, 5, 4), put_uint(b, 3, 2), put_uint(b, 0, 4), put_uint(b, 1, 4), put_uint(b, 2, 4);
    put_uint(b, 6, 4), put_uint(b, 0, 2);
    size_t faces = b->len;
    /* faces: (0 1 2), (2 -1 1 0), () */
    put_uint(b, 9, 1), put_uint(b, 3, 2), put_uint(b, 0, 2), put_uint(b, 1, 2), put_uint(b, 2, 2);
    put_f32(b, 1.0f);
    put_uint(b, 9, 1), put_uint(b, 4, 2), put_uint(b, 2, 2), put_uint(b, (uint16_t)-1, 2);
    put_uint(b, 1, 2), put_uint(b, 0, 2), put_f32(b, 0.5f);
    put_uint(b, 0, 1), put_uint(b, 0, 2), put_f32(b, 0.0f);
    return faces;
}

static void check_binary_ply(const mt_face_list *list)
{
    static const uint32_t sizes[] = {3, 4, 0};
    static const uint32_t idx[] = {0, 1, 2, 2, UINT32_MAX, 1, 0};
    check_faces(list, sizes, 3, idx, 7);
    CHECK_EQ(list->num_verts, 3);
    if (list->num_verts != 3) return;
    static const double expected[9] = {0.1, 7, 2.5, -3, -1, 0.25, 1e300, 0, -0.0};
    CHECK(memcmp(list->positions, expected, sizeof expected) == 0);
}

static void test_ply_binary_le(void)
{
    bytes b;
    build_binary_ply(&b, 0);
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(mt_read_memory(b.data, b.len, MT_FORMAT_AUTO, "le.ply", &list, &diag));
    check_binary_ply(&list);
    mt_face_list_free(&list);
    /* Any PLY format reads any encoding: the header decides. */
    CHECK_OK(mt_read_memory(b.data, b.len, MT_FORMAT_PLY_BINARY_BE, "le.ply", &list, &diag));
    check_binary_ply(&list);
    mt_face_list_free(&list);
}

static void test_ply_binary_be(void)
{
    bytes b;
    build_binary_ply(&b, 1);
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(mt_read_memory(b.data, b.len, MT_FORMAT_PLY_BINARY_BE, "be.ply", &list, &diag));
    check_binary_ply(&list);
    mt_face_list_free(&list);
    /* The same bytes in a file, read back through mt_read_file. */
    const char *path = io_test_path("be.ply");
    CHECK(io_test_spill(path, b.data, b.len));
    CHECK_OK(mt_read_file(path, MT_FORMAT_AUTO, &list, &diag));
    check_binary_ply(&list);
    mt_face_list_free(&list);
}

/* Every integer index type, signed and unsigned, as list index and count. */
static void test_ply_binary_index_types(void)
{
    static const char *const types[] = {"char", "uchar", "short", "ushort",
                                        "int",  "uint",  "int8",  "uint32"};
    static const int sizes[] = {1, 1, 2, 2, 4, 4, 1, 4};
    for (int t = 0; t < 8; t++) {
        for (int be = 0; be < 2; be++) {
            bytes b;
            memset(&b, 0, sizeof b);
            b.be = be;
            char header[512];
            snprintf(header, sizeof header,
                     "ply\nformat %s 1.0\nelement vertex 1\nproperty uchar x\n"
                     "property char y\nproperty ushort z\nelement face 1\n"
                     "property list %s %s vertex_indices\nend_header\n",
                     be ? "binary_big_endian" : "binary_little_endian", types[t], types[t]);
            put_text(&b, header);
            put_uint(&b, 255, 1), put_uint(&b, 0xfe, 1), put_uint(&b, 513, 2);
            put_uint(&b, 3, sizes[t]);
            put_uint(&b, 0, sizes[t]), put_uint(&b, 100, sizes[t]);
            put_uint(&b, sizes[t] == 4 ? 0xffffffffull : sizes[t] == 2 ? 0xffff : 0xff, sizes[t]);
            mt_face_list list;
            mt_diag diag;
            CHECK_OK(mt_read_memory(b.data, b.len, MT_FORMAT_AUTO, "t.ply", &list, &diag));
            int is_signed = types[t][0] != 'u';
            uint32_t last = is_signed || sizes[t] == 4 ? UINT32_MAX : sizes[t] == 2 ? 0xffff : 0xff;
            uint32_t idx[3] = {0, 100, last};
            uint32_t three = 3;
            check_faces(&list, &three, 1, idx, 3);
            if (list.num_verts == 1)
                CHECK(list.positions[0] == 255 && list.positions[1] == -2 &&
                      list.positions[2] == 513);
            mt_face_list_free(&list);
        }
    }
}

static void test_ply_ascii(void)
{
    const char *text =
        "ply\n"
        "format ascii 1.0\n"
        "comment z first, extra properties\n"
        "element vertex 4\n"
        "property float z\n"
        "property list uchar int junk\n"
        "property float y\n"
        "property float x\n"
        "property uchar alpha\n"
        "element face 3\n"
        "property list uchar int vertex_indices\n"
        "property int tag\n"
        "element material 1\n"
        "property float shine\n"
        "end_header\n"
        "3 2 7 8 2 1 255\n"
        "0 0 0 0 0\n"
        "-1e2 1 9 0.5 0 7\n"
        "1.5 0 0 -0.25 0\n"
        "3 0 1 2 0\n"
        "4 3 2 -7 0 12\n"
        "0 5\n"
        "0.5\n";
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(io_test_read_text(text, MT_FORMAT_PLY_ASCII, "a.ply", &list, &diag));
    static const uint32_t sizes[] = {3, 4, 0};
    static const uint32_t idx[] = {0, 1, 2, 3, 2, (uint32_t)-7, 0};
    check_faces(&list, sizes, 3, idx, 7);
    CHECK_EQ(list.num_verts, 4);
    if (list.num_verts == 4) {
        static const double expected[12] = {1, 2, 3, 0, 0, 0, 0, 0.5, -100, -0.25, 0, 1.5};
        CHECK(memcmp(list.positions, expected, sizeof expected) == 0);
    }
    mt_face_list_free(&list);
}

/* A point cloud (no face element) and a mesh with no vertex element. */
static void test_ply_missing_elements(void)
{
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(
        io_test_read_text("ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\n"
                          "property double y\nproperty double z\nend_header\n1 2 3\n4 5 6\n",
                          MT_FORMAT_AUTO, NULL, &list, &diag));
    CHECK_EQ(list.num_verts, 2);
    CHECK_EQ(list.num_faces, 0);
    CHECK_OK(mt_face_list_check(&list, NULL));
    mt_face_list_free(&list);
    CHECK_OK(
        io_test_read_text("ply\nformat ascii 1.0\nelement face 1\n"
                          "property list uchar uint vertex_indices\nend_header\n2 5 6\n",
                          MT_FORMAT_AUTO, NULL, &list, &diag));
    static const uint32_t two = 2, idx[] = {5, 6};
    check_faces(&list, &two, 1, idx, 2);
    CHECK_EQ(list.num_verts, 0);
    mt_face_list_free(&list);
}

/* ---- gzip -------------------------------------------------------------- */

/* gzip("OFF\n3 1 0\n0 0 0\n1 0 0\n") and gzip("0 1 0\n3 0 1 2\n"), as
 * made by Python's gzip module (mtime 0): two members of one OFF file. */
static const unsigned char gz_part1[37] = {
    0x1f, 0x8b, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0xff, 0xf3, 0x77, 0x73,
    0xe3, 0x32, 0x56, 0x30, 0x54, 0x30, 0xe0, 0x32, 0x50, 0x00, 0x42, 0x2e, 0x43,
    0x30, 0x09, 0x00, 0xf2, 0x08, 0x0b, 0x21, 0x16, 0x00, 0x00, 0x00};
static const unsigned char gz_part2[32] = {
    0x1f, 0x8b, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0xff, 0x33, 0x50, 0x30, 0x54, 0x30, 0xe0,
    0x32, 0x56, 0x30, 0x00, 0xd2, 0x46, 0x5c, 0x00, 0x7c, 0xaa, 0xe5, 0x41, 0x0e, 0x00, 0x00, 0x00};

static void test_gzip_in_memory(void)
{
    unsigned char buf[128];
    /* Two gzip members one after the other, then zero padding. */
    size_t n1 = sizeof gz_part1, n2 = sizeof gz_part2;
    memcpy(buf, gz_part1, n1);
    memcpy(buf + n1, gz_part2, n2);
    memset(buf + n1 + n2, 0, 16);
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(mt_read_memory(buf, n1 + n2 + 16, MT_FORMAT_AUTO, "two.off.gz", &list, &diag));
    static const uint32_t three = 3, idx[] = {0, 1, 2};
    check_faces(&list, &three, 1, idx, 3);
    CHECK_EQ(list.num_verts, 3);
    mt_face_list_free(&list);
    /* Recognised by its bytes whatever the name. */
    const char *path = io_test_path("plain-name.obj");
    CHECK(io_test_spill(path, buf, n1 + n2));
    CHECK_OK(mt_read_file(path, MT_FORMAT_AUTO, &list, &diag));
    CHECK_EQ(list.num_faces, 1);
    mt_face_list_free(&list);
}

static const mt_test_case cases[] = {
    {"off_variants", test_off_variants},
    {"off_number_forms", test_off_number_forms},
    {"number_parsing_matches_strtod", test_number_parsing_matches_strtod},
    {"off_token_edges", test_off_token_edges},
    {"obj_index_forms", test_obj_index_forms},
    {"obj_matches_off", test_obj_matches_off},
    {"ply_binary_le", test_ply_binary_le},
    {"ply_binary_be", test_ply_binary_be},
    {"ply_binary_index_types", test_ply_binary_index_types},
    {"ply_ascii", test_ply_ascii},
    {"ply_missing_elements", test_ply_missing_elements},
    {"gzip_in_memory", test_gzip_in_memory},
};
const mt_test_table mt_tests_io_formats = {cases, sizeof cases / sizeof cases[0]};
