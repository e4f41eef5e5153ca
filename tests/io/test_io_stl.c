/* meshtopo::io: STL, ASCII and binary, read and written (round trips,
 * binary files built byte by byte: attribute byte counts, a header starting
 * with "solid", truncation, trailing data; ASCII errors by line), and
 * mt_face_list_weld: exact on an STL soup of the bunny, within a distance,
 * NaN, -0.0, argument errors. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "io_test_util.h"
#include "meshtopo/io.h"

/* A tetrahedron plus a quad (fan-triangulated by the STL writers), with
 * coordinates that float32 cannot hold exactly. */
static void make_mesh(mt_face_list *list)
{
    static const double pos[] = {0.1, 0.2, 0.3, 1.0 / 3, 0, 0, 0, 1e-7, 0, 0,    0,   2.5,
                                 5,   5,   5,   6,       5, 5, 6, 6,    5, -0.0, 6.0, 5};
    static const uint32_t sizes[] = {3, 3, 3, 3, 4};
    static const uint32_t idx[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3, 4, 5, 6, 7};
    CHECK_OK(mt_face_list_alloc(list, 8, 5, 16, NULL));
    memcpy(list->positions, pos, sizeof pos);
    memcpy(list->face_sizes, sizes, sizeof sizes);
    memcpy(list->face_indices, idx, sizeof idx);
}

/* CHECKs that `soup` holds list's faces fan-triangulated, each triangle's
 * corners as 3 new vertices, positions rounded to float32 when `rounded`. */
static void check_soup(const mt_face_list *list, const mt_face_list *soup, int rounded)
{
    uint32_t t = 0;
    const uint32_t *idx = list->face_indices;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        for (uint32_t j = 1; j + 1 < list->face_sizes[f]; j++, t++) {
            if (t >= soup->num_faces) break;
            CHECK_EQ(soup->face_sizes[t], 3);
            uint32_t corner[3] = {idx[0], idx[j], idx[j + 1]};
            for (int c = 0; c < 3; c++) {
                CHECK_EQ(soup->face_indices[3 * t + (uint32_t)c], 3 * t + (uint32_t)c);
                for (int k = 0; k < 3; k++) {
                    double want = list->positions[3 * corner[c] + (uint32_t)k];
                    if (rounded) want = (float)want;
                    CHECK(soup->positions[3 * (3 * t + (uint32_t)c) + (uint32_t)k] == want);
                }
            }
        }
        idx += list->face_sizes[f];
    }
    CHECK_EQ(soup->num_faces, t);
    CHECK_EQ(soup->num_verts, 3 * t);
    CHECK_OK(mt_face_list_check(soup, NULL));
}

/* Writes list as `name`, reads it back (auto-detected, and through every
 * way io_test_read_variants_at reads the bytes) and checks the soup. */
static void round_trip(const mt_face_list *list, const char *name, mt_format format, int rounded)
{
    const char *path = io_test_path(name);
    mt_diag diag;
    CHECK_OK(mt_write_file(path, format, list, &diag));
    mt_face_list back;
    mt_status status = mt_read_file(path, MT_FORMAT_AUTO, &back, &diag);
    if (status != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: read failed: %s", name, diag.message);
        return;
    }
    check_soup(list, &back, rounded);
    mt_face_list_free(&back);
    unsigned char *data;
    size_t size = 0;
    if (!io_test_slurp(path, &data, &size)) {
        mt_test_fail(__FILE__, __LINE__, "cannot read %s back", path);
        return;
    }
    /* an unnamed buffer too: the content alone tells */
    CHECK_OK(IO_TEST_READ_VARIANTS(data, size, MT_FORMAT_AUTO, NULL, &back, &diag));
    check_soup(list, &back, rounded);
    mt_face_list_free(&back);
    free(data);
}

static void test_stl_ascii_round_trip(void)
{
    mt_face_list list;
    make_mesh(&list);
    round_trip(&list, "mesh_ascii.stl", MT_FORMAT_STL_ASCII, 0);
    round_trip(&list, "mesh_ascii.stl.gz", MT_FORMAT_STL_ASCII, 0);
    /* the file reads as the format says */
    const char *path = io_test_path("mesh_ascii.stl");
    unsigned char *data;
    size_t size = 0;
    if (io_test_slurp(path, &data, &size)) {
        CHECK(size > 15 && memcmp(data, "solid meshtopo\n", 15) == 0);
        /* the quad's two triangles, in the xy plane */
        const char *quad = strstr((const char *)data, "facet normal 0 0 1\n");
        CHECK(quad != NULL && strstr(quad + 1, "facet normal 0 0 1\n") != NULL);
        free(data);
    }
    mt_face_list_free(&list);
}

static void test_stl_binary_round_trip(void)
{
    mt_face_list list;
    make_mesh(&list);
    round_trip(&list, "mesh_binary.stl", MT_FORMAT_STL_BINARY, 1);
    round_trip(&list, "mesh_auto.stl", MT_FORMAT_AUTO, 1); /* .stl: binary */
    round_trip(&list, "mesh_binary.stl.gz", MT_FORMAT_AUTO, 1);
    unsigned char *data;
    size_t size = 0;
    if (io_test_slurp(io_test_path("mesh_binary.stl"), &data, &size)) {
        CHECK_EQ(size, 84 + 50 * 6);
        CHECK_EQ(data[80], 6);
        for (size_t t = 0; t < 6; t++) { /* attribute byte counts are 0 */
            CHECK_EQ(data[84 + 50 * t + 48], 0);
            CHECK_EQ(data[84 + 50 * t + 49], 0);
        }
        /* the quad's first triangle (4, 5, 6) has the normal (0, 0, 1) */
        float n[3];
        memcpy(n, data + 84 + 50 * 4, sizeof n);
        CHECK(n[0] == 0 && n[1] == 0 && n[2] == 1);
        free(data);
    }
    mt_face_list_free(&list);
}

/* A binary STL file of `count` triangles declared, `present` written:
 * triangle t has corners (t, 0, 0), (t, 1, 0), (t, 0, 1) and attribute
 * byte count `attr` (two bytes, little endian). malloc'd. */
static unsigned char *binary_stl(const char *header, uint32_t count, uint32_t present,
                                 uint16_t attr, size_t *out_size)
{
    size_t size = 84 + 50 * (size_t)present;
    unsigned char *p = calloc(1, size);
    if (!p) return NULL;
    memset(p, ' ', 80);
    memcpy(p, header, strlen(header));
    for (int k = 0; k < 4; k++) p[80 + k] = (unsigned char)(count >> (8 * k));
    for (uint32_t t = 0; t < present; t++) {
        unsigned char *q = p + 84 + 50 * (size_t)t;
        float v[12] = {1, 0, 0, (float)t, 0, 0, (float)t, 1, 0, (float)t, 0, 1};
        memcpy(q, v, sizeof v); /* the tests run on little-endian machines */
        q[48] = (unsigned char)attr;
        q[49] = (unsigned char)(attr >> 8);
    }
    *out_size = size;
    return p;
}

static void check_binary_triangles(const mt_face_list *list, uint32_t count)
{
    CHECK_EQ(list->num_faces, count);
    CHECK_EQ(list->num_verts, 3 * count);
    for (uint32_t t = 0; t < count && t < list->num_faces; t++) {
        const double *p = list->positions + 9 * (size_t)t;
        CHECK(p[0] == t && p[1] == 0 && p[3] == t && p[4] == 1 && p[8] == 1);
        CHECK_EQ(list->face_indices[3 * t + 2], 3 * t + 2);
    }
}

static void test_stl_binary_attribute_count(void)
{
    /* 0x0001 and 0x0100 (and 0xffff): read and ignored, the same triangles */
    static const uint16_t attrs[] = {0, 1, 0x100, 0xffff};
    for (size_t a = 0; a < sizeof attrs / sizeof attrs[0]; a++) {
        size_t size;
        unsigned char *data = binary_stl("attributes", 4, 4, attrs[a], &size);
        mt_face_list list;
        mt_diag diag;
        CHECK_OK(IO_TEST_READ_VARIANTS(data, size, MT_FORMAT_AUTO, "a.stl", &list, &diag));
        check_binary_triangles(&list, 4);
        mt_face_list_free(&list);
        free(data);
    }
}

static void test_stl_binary_solid_header(void)
{
    /* A binary file whose header starts with "solid": its length tells. */
    size_t size = 0;
    unsigned char *data = binary_stl("solid exported by a CAD tool", 3, 3, 0, &size);
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(IO_TEST_READ_VARIANTS(data, size, MT_FORMAT_AUTO, NULL, &list, &diag));
    check_binary_triangles(&list, 3);
    mt_face_list_free(&list);
    /* Even with no triangle (84 bytes). */
    free(data);
    data = binary_stl("solid empty", 0, 0, 0, &size);
    CHECK_OK(IO_TEST_READ_VARIANTS(data, size, MT_FORMAT_AUTO, NULL, &list, &diag));
    CHECK_EQ(list.num_faces, 0);
    mt_face_list_free(&list);
    free(data);
    /* Truncated: "solid" but not text, so still binary, and the message says so. */
    data = binary_stl("solid cut short", 5, 2, 0, &size);
    EXPECT_PARSE_ERROR(data, size, MT_FORMAT_AUTO, "cut", 0, 84 + 100,
                       "binary STL ends after 2 of 5 triangles");
    free(data);
}

static void test_stl_binary_truncated(void)
{
    size_t size = 0;
    unsigned char *data = binary_stl("cut", 10, 7, 0, &size);
    EXPECT_PARSE_ERROR(data, size, MT_FORMAT_AUTO, "t.stl", 0, 84 + 350,
                       "binary STL ends after 7 of 10 triangles");
    EXPECT_PARSE_ERROR(data, size, MT_FORMAT_STL_BINARY, "t", 0, 84 + 350,
                       "binary STL ends after 7 of 10 triangles");
    /* a triangle cut in the middle: still 7 whole ones */
    EXPECT_PARSE_ERROR(data, size - 20, MT_FORMAT_STL_BINARY, "t", 0, 84 + 300,
                       "binary STL ends after 6 of 10 triangles");
    /* the header alone, cut */
    EXPECT_PARSE_ERROR(data, 50, MT_FORMAT_AUTO, "t.stl", 0, 50,
                       "binary STL ends in its 84-byte header (50 bytes)");
    free(data);
    /* more data than the count declares */
    data = binary_stl("long", 2, 3, 0, &size);
    EXPECT_PARSE_ERROR(data, size, MT_FORMAT_STL_BINARY, "t", 0, 84 + 100,
                       "binary STL goes on after the 2 triangles its count declares");
    free(data);
    /* a count past meshtopo's limits in a small file: the length speaks first */
    data = binary_stl("huge", 0xffffffffu, 1, 0, &size);
    EXPECT_PARSE_ERROR(data, size, MT_FORMAT_STL_BINARY, "t", 0, 84 + 50,
                       "binary STL ends after 1 of 4294967295 triangles");
    free(data);
}

static const char *const ascii_ok =
    "solid part\n"
    "  facet normal 0 0 1\n"
    "    outer loop\n"
    "      vertex 0 0 0\n"
    "      vertex 1 0 0\n"
    "      vertex 0 1 0\n"
    "    endloop\n"
    "  endfacet\n"
    "  FACET NORMAL 0 0 1\n" /* keywords in any case */
    "    OUTER LOOP\n"
    "      VERTEX 1e0 1 0\n"
    "      VERTEX 0 1 0\n"
    "      VERTEX 1 0 0\n"
    "      VERTEX 2 2 2\n" /* a quad loop: a face of 4 */
    "    ENDLOOP\n"
    "  ENDFACET\n"
    "endsolid part\n"
    "solid second\n" /* another solid, a facet without its normal */
    "facet outer loop vertex 5 5 5 vertex 6 5 5 vertex 5 6 5 endloop endfacet\n"
    "endsolid\n";

static void test_stl_ascii_forms(void)
{
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(IO_TEST_READ_VARIANTS(ascii_ok, strlen(ascii_ok), MT_FORMAT_AUTO, NULL, &list, &diag));
    CHECK_EQ(list.num_faces, 3);
    CHECK_EQ(list.num_verts, 10);
    CHECK_EQ(list.num_indices, 10);
    if (list.num_faces == 3) {
        CHECK_EQ(list.face_sizes[1], 4);
        CHECK_EQ(list.face_indices[9], 9);
        CHECK(list.positions[27] == 5 && list.positions[28] == 6);
    }
    mt_face_list_free(&list);
    /* empty solid */
    CHECK_OK(io_test_read_text("solid\nendsolid\n", MT_FORMAT_AUTO, NULL, &list, &diag));
    CHECK_EQ(list.num_faces, 0);
    mt_face_list_free(&list);
}

static void test_stl_ascii_errors(void)
{
    /* missing endloop */
    EXPECT_TEXT_ERROR(
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
        "vertex 0 1 0\nendfacet\nendsolid s\n",
        MT_FORMAT_AUTO, "a.stl", 7,
        "facet 0: expected 'vertex' or 'endloop', "
        "found 'endfacet'");
    /* missing endfacet, then the end of file */
    EXPECT_TEXT_ERROR(
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
        "vertex 0 1 0\nendloop\n",
        MT_FORMAT_AUTO, "a.stl", 8, "facet 0: expected 'endfacet', found the end of file");
    /* cut in a vertex */
    EXPECT_TEXT_ERROR("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0", MT_FORMAT_AUTO,
                      "a.stl", 4,
                      "facet 0: vertex 0: expected coordinate 2, found the end of file");
    /* no endsolid */
    EXPECT_TEXT_ERROR("solid s\n", MT_FORMAT_AUTO, "a.stl", 2,
                      "expected 'facet' or 'endsolid', found the end of file");
    /* garbage numbers */
    EXPECT_TEXT_ERROR("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 zero 0\n",
                      MT_FORMAT_AUTO, "a.stl", 5,
                      "facet 0: vertex 1: coordinate 1 is not a number, found 'zero'");
    EXPECT_TEXT_ERROR("solid s\nfacet normal 0 x 1\n", MT_FORMAT_AUTO, "a.stl", 2,
                      "facet 0: normal: coordinate 1 is not a number, found 'x'");
    EXPECT_TEXT_ERROR("solid s\nfacet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 1 1 endloop\n",
                      MT_FORMAT_AUTO, "a.stl", 2, "facet 0: 2 vertices in its loop (3 at least)");
    /* the second facet's number */
    EXPECT_TEXT_ERROR(
        "solid s\nfacet outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop "
        "endfacet\nfacet outer lop\n",
        MT_FORMAT_AUTO, "a.stl", 3, "facet 1: expected 'loop', found 'lop'");
    EXPECT_TEXT_ERROR("solid s\nendsolid s\nfacet\n", MT_FORMAT_AUTO, "a.stl", 3,
                      "expected 'solid' or the end of file after 'endsolid'");
    EXPECT_TEXT_ERROR("hello\n", MT_FORMAT_STL_ASCII, "a", 1, "expected 'solid' (ASCII STL)");
}

static void test_stl_formats(void)
{
    CHECK_EQ(mt_format_from_path("a.stl"), MT_FORMAT_STL_BINARY);
    CHECK_EQ(mt_format_from_path("A.STL.gz"), MT_FORMAT_STL_BINARY);
    CHECK(strcmp(mt_format_name(MT_FORMAT_STL_ASCII), "stl-ascii") == 0);
    CHECK(strcmp(mt_format_name(MT_FORMAT_STL_BINARY), "stl-binary") == 0);
    /* appended: the earlier values keep their numbers */
    CHECK_EQ((int)MT_FORMAT_PLY_BINARY_BE, 5);
    CHECK_EQ((int)MT_FORMAT_STL_ASCII, 6);
    CHECK_EQ((int)MT_FORMAT_STL_BINARY, 7);
    mt_face_list list;
    mt_diag diag;
    CHECK_STATUS(mt_read_memory("x", 1, (mt_format)8, NULL, &list, &diag), MT_ERR_INVALID_ARG);
}

static void test_stl_write_refusals(void)
{
    mt_face_list list;
    make_mesh(&list);
    mt_diag diag;
    const char *path = io_test_path("refused.stl");
    list.face_indices[4] = 8; /* face 1: out of range */
    CHECK_STATUS(mt_write_file(path, MT_FORMAT_AUTO, &list, &diag), MT_ERR_UNSUPPORTED);
    CHECK(strstr(diag.message, "face 1: index 8 is out of range") != NULL);
    list.face_indices[4] = 1;
    list.face_sizes[4] = 2; /* the quad becomes a 2-entry face (and 2 indices unused) */
    list.num_indices -= 2;
    CHECK_STATUS(mt_write_file(path, MT_FORMAT_STL_ASCII, &list, &diag), MT_ERR_UNSUPPORTED);
    CHECK(strstr(diag.message, "face 4 has 2 entries: STL stores triangles") != NULL);
    unsigned char *data;
    size_t size = 0;
    CHECK(!io_test_slurp(path, &data, &size)); /* no file was created */
    mt_face_list_free(&list);
}

/* ---- Welding ------------------------------------------------------------- */

static int compare_triple(const void *a, const void *b)
{
    const double *p = a, *q = b;
    for (int k = 0; k < 3; k++)
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    return 0;
}

static void test_weld_bunny_soup(void)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/npm_bunny.off", mt_test_corpus_dir());
    mt_face_list bunny, soup;
    mt_diag diag;
    mt_status status = mt_read_file(path, MT_FORMAT_AUTO, &bunny, &diag);
    if (status != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s", diag.message);
        return;
    }
    /* Expected: distinct float32-rounded positions among referenced vertices. */
    char *used = calloc(bunny.num_verts + 1, 1);
    double *distinct = malloc(3 * sizeof(double) * (bunny.num_verts + 1));
    size_t n = 0;
    for (uint64_t k = 0; k < bunny.num_indices; k++) used[bunny.face_indices[k]] = 1;
    for (uint32_t v = 0; v < bunny.num_verts; v++)
        if (used[v])
            for (int k = 0; k < 3; k++, n++) distinct[n] = (float)bunny.positions[3 * v + k];
    n /= 3;
    qsort(distinct, n, 3 * sizeof(double), compare_triple);
    size_t expected = n ? 1 : 0;
    for (size_t i = 1; i < n; i++)
        expected += compare_triple(distinct + 3 * i, distinct + 3 * i - 3) != 0;

    const char *stl = io_test_path("bunny.stl");
    CHECK_OK(mt_write_file(stl, MT_FORMAT_STL_BINARY, &bunny, &diag));
    CHECK_OK(mt_read_file(stl, MT_FORMAT_AUTO, &soup, &diag));
    CHECK_EQ(soup.num_verts, 3 * bunny.num_faces);
    uint32_t *map = malloc(sizeof(uint32_t) * soup.num_verts);
    mt_weld_stats stats;
    CHECK_OK(mt_face_list_weld(&soup, 0, map, &stats, &diag));
    CHECK_EQ(stats.vertices_before, 3 * bunny.num_faces);
    CHECK_EQ(stats.vertices_after, expected);
    CHECK_EQ(stats.vertices_after, bunny.num_verts); /* the bunny has no duplicates */
    CHECK_EQ(stats.merged, stats.vertices_before - stats.vertices_after);
    CHECK_EQ(soup.num_verts, expected);
    /* every face's corners are where the bunny's are */
    for (uint64_t k = 0; k < soup.num_indices && k < bunny.num_indices; k++)
        for (int c = 0; c < 3; c++)
            CHECK(soup.positions[3 * soup.face_indices[k] + (uint32_t)c] ==
                  (float)bunny.positions[3 * bunny.face_indices[k] + (uint32_t)c]);
    /* survivors keep their order: the first corner is vertex 0 */
    CHECK_EQ(map[0], 0);
    CHECK_EQ(soup.face_indices[0], 0);
    /* welding again merges nothing */
    CHECK_OK(mt_face_list_weld(&soup, 0, NULL, &stats, &diag));
    CHECK_EQ(stats.merged, 0);
    free(map);
    free(used);
    free(distinct);
    mt_face_list_free(&soup);
    mt_face_list_free(&bunny);
}

/* A face list of n vertices at pos and one face over all of them. */
static void make_points(mt_face_list *list, const double *pos, uint32_t n)
{
    CHECK_OK(mt_face_list_alloc(list, n, 1, n, NULL));
    memcpy(list->positions, pos, 3 * sizeof(double) * n);
    list->face_sizes[0] = n;
    for (uint32_t v = 0; v < n; v++) list->face_indices[v] = v;
}

static void test_weld_eps(void)
{
    /* near-duplicates 1e-7 apart merge with eps 1e-5; points 2e-5 apart do not */
    const double pos[] = {1,   1,   1,   1 + 1e-7, 1,          1 - 1e-7, 1,       1, 1.00002,
                          0.3, 0.3, 0.3, 0.3,      0.3 + 1e-7, 0.3,      1.00002, 1, 1};
    mt_face_list list;
    make_points(&list, pos, 6);
    uint32_t map[6];
    mt_weld_stats stats;
    mt_diag diag;
    CHECK_OK(mt_face_list_weld(&list, 1e-5, map, &stats, &diag));
    CHECK_EQ(stats.vertices_after, 4);
    CHECK_EQ(stats.merged, 2);
    static const uint32_t want[6] = {0, 0, 1, 2, 2, 3};
    for (int v = 0; v < 6; v++) CHECK_EQ(map[v], want[v]);
    for (int v = 0; v < 6; v++) CHECK_EQ(list.face_indices[v], want[v]);
    /* survivors keep their own positions */
    CHECK(list.positions[3] == 1 && list.positions[5] == 1.00002 && list.positions[6] == 0.3);
    CHECK(list.positions[9] == 1.00002);
    mt_face_list_free(&list);

    /* exact: the same points stay apart */
    make_points(&list, pos, 6);
    CHECK_OK(mt_face_list_weld(&list, 0, NULL, &stats, &diag));
    CHECK_EQ(stats.merged, 0);
    mt_face_list_free(&list);

    /* not transitive: a chain 0.6 eps apart merges into its survivors only */
    const double chain[] = {0, 0, 0, 0.6, 0, 0, 1.2, 0, 0, 1.8, 0, 0, 2.4, 0, 0};
    make_points(&list, chain, 5);
    CHECK_OK(mt_face_list_weld(&list, 1.0, map, &stats, &diag));
    static const uint32_t want_chain[5] = {0, 0, 1, 1, 2};
    for (int v = 0; v < 5; v++) CHECK_EQ(map[v], want_chain[v]);
    mt_face_list_free(&list);

    /* at exactly eps: merged; the lowest-numbered survivor wins */
    const double two[] = {0, 0, 0, 2, 0, 0, 1, 0, 0};
    make_points(&list, two, 3);
    CHECK_OK(mt_face_list_weld(&list, 1.0, map, &stats, &diag));
    CHECK_EQ(map[2], 0);
    mt_face_list_free(&list);
}

static void test_weld_special_values(void)
{
    const double pos[] = {NAN,      0, 0, NAN,      0, 0, 0,     -0.0,  0,     0,     0,     0,
                          INFINITY, 1, 1, INFINITY, 1, 1, 1e300, 1e300, 1e300, 1e300, 1e300, 1e300};
    mt_face_list list;
    make_points(&list, pos, 8);
    uint32_t map[8];
    mt_weld_stats stats;
    mt_diag diag;
    CHECK_OK(mt_face_list_weld(&list, 0, map, &stats, &diag));
    static const uint32_t want[8] = {0, 1, 2, 2, 3, 4, 5, 5}; /* NaN, inf never merged */
    for (int v = 0; v < 8; v++) CHECK_EQ(map[v], want[v]);
    mt_face_list_free(&list);
    make_points(&list, pos, 8);
    CHECK_OK(mt_face_list_weld(&list, 1e-300, map, &stats, &diag)); /* tiny cells, huge values */
    for (int v = 0; v < 8; v++) CHECK_EQ(map[v], want[v]);
    mt_face_list_free(&list);

    /* out-of-range indices stay out of range; empty list; errors leave it alone */
    make_points(&list, pos + 6, 2);
    list.face_indices[1] = 7;
    CHECK_OK(mt_face_list_weld(&list, 0, NULL, &stats, &diag));
    CHECK_EQ(list.num_verts, 1);
    CHECK_EQ(list.face_indices[0], 0);
    CHECK_EQ(list.face_indices[1], 7);
    CHECK_STATUS(mt_face_list_weld(&list, -1, NULL, &stats, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_list_weld(&list, NAN, NULL, &stats, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_list_weld(&list, INFINITY, NULL, &stats, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_list_weld(NULL, 0, NULL, &stats, &diag), MT_ERR_INVALID_ARG);
    CHECK_EQ(list.num_verts, 1);
    mt_face_list_free(&list);
    mt_face_list empty;
    memset(&empty, 0, sizeof empty);
    CHECK_OK(mt_face_list_weld(&empty, 0.5, NULL, &stats, &diag));
    CHECK_EQ(stats.vertices_after, 0);
}

static const mt_test_case cases[] = {
    {"stl_ascii_round_trip", test_stl_ascii_round_trip},
    {"stl_binary_round_trip", test_stl_binary_round_trip},
    {"stl_binary_attribute_count", test_stl_binary_attribute_count},
    {"stl_binary_solid_header", test_stl_binary_solid_header},
    {"stl_binary_truncated", test_stl_binary_truncated},
    {"stl_ascii_forms", test_stl_ascii_forms},
    {"stl_ascii_errors", test_stl_ascii_errors},
    {"stl_formats", test_stl_formats},
    {"stl_write_refusals", test_stl_write_refusals},
    {"weld_bunny_soup", test_weld_bunny_soup},
    {"weld_eps", test_weld_eps},
    {"weld_special_values", test_weld_special_values},
};

const mt_test_table mt_tests_io_stl = {cases, sizeof cases / sizeof cases[0]};
