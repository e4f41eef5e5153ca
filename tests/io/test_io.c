/* meshtopo::io: the shared corpus read against its reference counts, and
 * write/read round trips in every format, gzip included, plus the format
 * helpers and I/O errors. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "harness.h"
#include "io_test_util.h"
#include "meshtopo/io.h"

/* ---- A tiny scan of NAME.expected.json --------------------------------- */

/* Value of the first `"key": <integer>` in json; 0 when absent. */
static int json_int(const char *json, const char *key, long long *out)
{
    char pattern[64];
    snprintf(pattern, sizeof pattern, "\"%s\":", key);
    const char *p = strstr(json, pattern);
    if (!p) return 0;
    char *end;
    *out = strtoll(p + strlen(pattern), &end, 10);
    return end != p + strlen(pattern);
}

/* face_size_histogram as (size, count) pairs; returns the number of pairs
 * or -1 when it cannot be read. */
static int json_histogram(const char *json, long long sizes[], long long counts[], int max)
{
    const char *p = strstr(json, "\"face_size_histogram\":");
    if (!p) return -1;
    p = strchr(p, '{');
    if (!p) return -1;
    p++;
    int n = 0;
    for (;;) {
        while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t' || *p == ',') p++;
        if (*p == '}') return n;
        if (*p != '"' || n == max) return -1;
        char *end;
        sizes[n] = strtoll(p + 1, &end, 10);
        if (*end != '"') return -1;
        p = end + 1;
        while (*p == ' ' || *p == ':') p++;
        counts[n] = strtoll(p, &end, 10);
        if (end == p) return -1;
        p = end;
        n++;
    }
}

/* Checks one corpus mesh (path) against its JSON text. */
static void check_corpus_mesh(const char *path, const char *json)
{
    long long V, F, half_edges;
    long long sizes[64], counts[64];
    int hist = json_histogram(json, sizes, counts, 64);
    if (!json_int(json, "V", &V) || !json_int(json, "F", &F) ||
        !json_int(json, "half_edges", &half_edges) || hist < 0) {
        mt_test_fail(__FILE__, __LINE__, "%s: cannot read the expected counts", path);
        return;
    }
    mt_face_list list;
    mt_diag diag;
    mt_status status = mt_read_file(path, MT_FORMAT_AUTO, &list, &diag);
    if (status != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: %s", path, diag.message);
        return;
    }
    CHECK_EQ(diag.status, MT_OK);
    CHECK_EQ(diag.message[0], '\0');
    CHECK_OK(mt_face_list_check(&list, NULL));
    if (list.num_verts != V || list.num_faces != F || (long long)list.num_indices != half_edges)
        mt_test_fail(__FILE__, __LINE__, "%s: V %u F %u half-edges %llu, expected %lld %lld %lld",
                     path, list.num_verts, list.num_faces, (unsigned long long)list.num_indices, V,
                     F, half_edges);
    long long total = 0;
    for (int h = 0; h < hist; h++) {
        long long found = 0;
        for (uint32_t f = 0; f < list.num_faces; f++) found += list.face_sizes[f] == sizes[h];
        if (found != counts[h])
            mt_test_fail(__FILE__, __LINE__, "%s: %lld faces of size %lld, expected %lld", path,
                         found, sizes[h], counts[h]);
        total += counts[h];
    }
    CHECK_EQ(total, F); /* so no face has a size the histogram lacks */

    /* The same bytes through mt_read_memory (gzip inflated in memory). */
    unsigned char *data;
    size_t size;
    CHECK(io_test_slurp(path, &data, &size));
    mt_face_list again;
    CHECK_OK(mt_read_memory(data, size, MT_FORMAT_OFF, path, &again, &diag));
    io_test_check_same(&list, &again, path);
    mt_face_list_free(&again);
    free(data);
    mt_face_list_free(&list);
}

static void test_corpus_counts(void)
{
    const char *dir = mt_test_corpus_dir();
    DIR *d = opendir(dir);
    if (!d) {
        mt_test_fail(__FILE__, __LINE__, "cannot open the corpus %s", dir);
        return;
    }
    int meshes = 0, gz = 0;
    struct dirent *entry;
    while ((entry = readdir(d)) != NULL) {
        const char *name = entry->d_name;
        size_t n = strlen(name);
        size_t stem;
        if (n > 4 && strcmp(name + n - 4, ".off") == 0)
            stem = n - 4;
        else if (n > 7 && strcmp(name + n - 7, ".off.gz") == 0)
            stem = n - 7, gz++;
        else
            continue;
        char path[1024], json_path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, name);
        snprintf(json_path, sizeof json_path, "%s/%.*s.expected.json", dir, (int)stem, name);
        unsigned char *json;
        size_t json_size;
        if (!io_test_slurp(json_path, &json, &json_size)) {
            mt_test_fail(__FILE__, __LINE__, "%s: no %s", path, json_path);
            continue;
        }
        char *text = realloc(json, json_size + 1);
        if (!text) {
            free(json);
            continue;
        }
        text[json_size] = '\0';
        check_corpus_mesh(path, text);
        free(text);
        meshes++;
    }
    closedir(d);
    CHECK(meshes >= 20);
    CHECK(gz >= 1);
}

/* A known corpus mesh, entry by entry: out-of-range -1 and 11, a repeated index. */
static void test_corpus_assimp_malformed_contents(void)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/assimp_malformed.off", mt_test_corpus_dir());
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(mt_read_file(path, MT_FORMAT_AUTO, &list, &diag));
    if (list.num_faces != 6) {
        mt_face_list_free(&list);
        return;
    }
    static const uint32_t expected[24] = {3, 11, 1, 0, 1, 5, 4, 0, 7,          6, 5, 1,
                                          7, 6,  2, 3, 4, 7, 7, 0, UINT32_MAX, 6, 7, 4};
    CHECK_EQ(list.num_indices, 24);
    for (int k = 0; k < 24; k++) CHECK_EQ(list.face_indices[k], expected[k]);
    CHECK_EQ(mt_index_as_signed(list.face_indices[20]), -1);
    CHECK(list.positions[0] == -0.5 && list.positions[2] == 0.5);
    CHECK(list.positions[3 * 7 + 1] == 0.5);
    mt_face_list_free(&list);
}

/* ---- Round trips ------------------------------------------------------- */

/* A face list with every awkward case: faces of 0, 1, 2 and many vertices,
 * out-of-range indices of both signs, and doubles that need 17 digits. */
static void make_awkward(mt_face_list *list, uint32_t big_face)
{
    static const uint32_t sizes[] = {3, 4, 0, 1, 2, 3, 5, 3};
    uint32_t num_faces = sizeof sizes / sizeof sizes[0] + 1;
    uint64_t num_indices = big_face;
    for (size_t f = 0; f < sizeof sizes / sizeof sizes[0]; f++) num_indices += sizes[f];
    const uint32_t V = 12;
    CHECK_OK(mt_face_list_alloc(list, V, num_faces, num_indices, NULL));
    static const double coords[] = {0.1,
                                    1.0 / 3.0,
                                    -0.0,
                                    1e-300,
                                    4.9406564584124654e-324,
                                    1.7976931348623157e308,
                                    123456789.123456789,
                                    3.141592653589793,
                                    1e15,
                                    -2.5,
                                    9007199254740993.0,
                                    0.30000000000000004,
                                    -1e-5,
                                    6.02214076e23,
                                    100.0,
                                    -7.0};
    for (uint32_t k = 0; k < 3 * V; k++)
        list->positions[k] = coords[k % 16] * (k < 16 ? 1.0 : 1.0 + k / 1024.0);
    static const uint32_t indices[] = {0, 1, 2,    /* triangle */
                                       3, 4, 5, 6, /* quad */
                                       /* empty face */
                                       7,                 /* 1-face */
                                       8, 8,              /* 2-face */
                                       UINT32_MAX, 1, 12, /* -1 and V */
                                       11, 10, 9, 0xfffffffbu /* -5 */, 3000000000u, 2, 2, 2};
    size_t k = 0;
    for (; k < sizeof indices / sizeof indices[0]; k++) list->face_indices[k] = indices[k];
    for (size_t f = 0; f < sizeof sizes / sizeof sizes[0]; f++) list->face_sizes[f] = sizes[f];
    list->face_sizes[num_faces - 1] = big_face;
    for (uint32_t j = 0; j < big_face; j++) list->face_indices[k++] = j % V;
    CHECK_OK(mt_face_list_check(list, NULL));
}

static void round_trip(const mt_face_list *list, const char *name, mt_format format)
{
    const char *path = io_test_path(name);
    mt_diag diag;
    mt_status status = mt_write_file(path, format, list, &diag);
    if (status != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: write failed: %s", name, diag.message);
        return;
    }
    mt_face_list back;
    status = mt_read_file(path, MT_FORMAT_AUTO, &back, &diag);
    if (status != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: read failed: %s", name, diag.message);
        return;
    }
    io_test_check_same(list, &back, name);
    mt_face_list_free(&back);
    /* The explicit format reads it too, and gzip files start with the magic. */
    mt_format explicit_format = format != MT_FORMAT_AUTO ? format : mt_format_from_path(path);
    CHECK_OK(mt_read_file(path, explicit_format, &back, &diag));
    io_test_check_same(list, &back, name);
    mt_face_list_free(&back);
    unsigned char *data;
    size_t size;
    if (io_test_slurp(path, &data, &size)) {
        size_t n = strlen(name);
        int gz = n > 3 && strcmp(name + n - 3, ".gz") == 0;
        CHECK_EQ(size >= 2 && data[0] == 0x1f && data[1] == 0x8b, gz);
        free(data);
    }
}

static void round_trip_all(const mt_face_list *list, const char *stem)
{
    static const struct {
        const char *suffix;
        mt_format format;
    } cases[] = {
        {".off", MT_FORMAT_AUTO},
        {".obj", MT_FORMAT_AUTO},
        {".ply", MT_FORMAT_AUTO},
        {".ascii.ply", MT_FORMAT_PLY_ASCII},
        {".be.ply", MT_FORMAT_PLY_BINARY_BE},
        {".off.gz", MT_FORMAT_AUTO},
        {".obj.gz", MT_FORMAT_AUTO},
        {".ply.gz", MT_FORMAT_PLY_BINARY_LE},
        {".ascii.ply.gz", MT_FORMAT_PLY_ASCII},
        {".be.ply.gz", MT_FORMAT_PLY_BINARY_BE},
        {".mesh", MT_FORMAT_OFF},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char name[128];
        snprintf(name, sizeof name, "%s%s", stem, cases[i].suffix);
        round_trip(list, name, cases[i].format);
    }
}

static void test_round_trip_awkward(void)
{
    mt_face_list list;
    make_awkward(&list, 6);
    round_trip_all(&list, "awkward");
    mt_face_list_free(&list);
}

/* Faces over 255 and over 65535 vertices need wider PLY list counts. */
static void test_round_trip_huge_faces(void)
{
    mt_face_list list;
    make_awkward(&list, 300);
    round_trip_all(&list, "face300");
    mt_face_list_free(&list);
    make_awkward(&list, 70000);
    round_trip_all(&list, "face70000");
    mt_face_list_free(&list);
}

static void test_round_trip_empty_and_no_positions(void)
{
    mt_face_list empty;
    memset(&empty, 0, sizeof empty);
    round_trip_all(&empty, "empty");

    /* No positions: zeros are written. */
    mt_face_list list;
    make_awkward(&list, 3);
    double *positions = list.positions;
    list.positions = NULL;
    mt_face_list zeros = list;
    zeros.positions = calloc(3 * list.num_verts, sizeof(double));
    const char *path = io_test_path("nopos.ply");
    mt_diag diag;
    CHECK_OK(mt_write_file(path, MT_FORMAT_AUTO, &list, &diag));
    mt_face_list back;
    CHECK_OK(mt_read_file(path, MT_FORMAT_AUTO, &back, &diag));
    io_test_check_same(&zeros, &back, "no positions");
    mt_face_list_free(&back);
    free(zeros.positions);
    list.positions = positions;
    mt_face_list_free(&list);
}

/* A corpus mesh written and read back in every format. */
static void test_round_trip_corpus(void)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/npm_conway_djmeD.off", mt_test_corpus_dir());
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(mt_read_file(path, MT_FORMAT_AUTO, &list, &diag));
    CHECK_EQ(list.num_faces, 722);
    round_trip_all(&list, "conway");
    mt_face_list_free(&list);
}

/* Non-finite coordinates survive text formats as nan/inf. */
static void test_round_trip_nonfinite(void)
{
    mt_face_list list;
    CHECK_OK(mt_face_list_alloc(&list, 2, 0, 0, NULL));
    list.positions[0] = INFINITY;
    list.positions[1] = -INFINITY;
    list.positions[2] = NAN;
    static const char *const names[] = {"nf.off", "nf.obj", "nf.ply", "nf.ascii.ply"};
    for (int i = 0; i < 4; i++) {
        const char *path = io_test_path(names[i]);
        mt_diag diag;
        CHECK_OK(mt_write_file(path, i == 3 ? MT_FORMAT_PLY_ASCII : MT_FORMAT_AUTO, &list, &diag));
        mt_face_list back;
        CHECK_OK(mt_read_file(path, MT_FORMAT_AUTO, &back, &diag));
        CHECK_EQ(back.num_verts, 2);
        if (back.num_verts == 2) {
            CHECK(isinf(back.positions[0]) && back.positions[0] > 0);
            CHECK(isinf(back.positions[1]) && back.positions[1] < 0);
            CHECK(isnan(back.positions[2]));
            CHECK(back.positions[3] == 0 && back.positions[5] == 0);
        }
        mt_face_list_free(&back);
    }
    mt_face_list_free(&list);
}

/* Writing leaves no temporary file behind, and replaces an existing file. */
static void test_write_replaces_atomically(void)
{
    mt_face_list list;
    make_awkward(&list, 3);
    const char *path = io_test_path("replace.off");
    CHECK(io_test_spill(path, "old contents", 12));
    mt_diag diag;
    CHECK_OK(mt_write_file(path, MT_FORMAT_AUTO, &list, &diag));
    mt_face_list back;
    CHECK_OK(mt_read_file(path, MT_FORMAT_AUTO, &back, &diag));
    io_test_check_same(&list, &back, "replaced");
    mt_face_list_free(&back);
    /* The directory holds no PATH.tmp.* file. */
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", path);
    *strrchr(dir, '/') = '\0';
    DIR *d = opendir(dir);
    CHECK(d != NULL);
    struct dirent *entry;
    while (d && (entry = readdir(d)) != NULL) CHECK(strstr(entry->d_name, ".tmp.") == NULL);
    if (d) closedir(d);
    mt_face_list_free(&list);
}

/* Colours in PLY (ascii, both binaries, gzip): the header names them after
 * the positions and the indices, they are read back by our reader as
 * properties it skips (the face list is unchanged), the bytes are where a
 * PLY reader finds them, and other formats refuse them. */
static void test_write_ply_colors(void)
{
    mt_face_list list;
    make_awkward(&list, 3);
    uint8_t *vc = malloc(3 * (size_t)list.num_verts + 1),
            *fc = malloc(3 * (size_t)list.num_faces + 1);
    for (uint32_t i = 0; i < 3 * list.num_verts; i++) vc[i] = (uint8_t)(i * 7);
    for (uint32_t i = 0; i < 3 * list.num_faces; i++) fc[i] = (uint8_t)(255 - i);
    mt_write_options options = {.vertex_colors = vc, .face_colors = fc};
    static const char *const names[] = {"c.ply", "c.ascii.ply", "c.be.ply", "c.ply.gz"};
    static const mt_format formats[] = {MT_FORMAT_AUTO, MT_FORMAT_PLY_ASCII,
                                        MT_FORMAT_PLY_BINARY_BE, MT_FORMAT_AUTO};
    mt_diag diag;
    for (int i = 0; i < 4; i++) {
        const char *path = io_test_path(names[i]);
        CHECK_OK(mt_write_file_with(path, formats[i], &list, &options, &diag));
        mt_face_list back;
        CHECK_OK(mt_read_file(path, MT_FORMAT_AUTO, &back, &diag));
        io_test_check_same(&list, &back, names[i]);
        mt_face_list_free(&back);
    }
    /* The ascii file: "x y z r g b" and "n i... r g b". */
    FILE *f = fopen(io_test_path("c.ascii.ply"), "r");
    char text[65536] = "";
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f) fclose(f);
    text[n] = '\0';
    CHECK(strstr(text,
                 "property double z\nproperty uchar red\nproperty uchar green\n"
                 "property uchar blue\nelement face") != NULL);
    CHECK(strstr(text,
                 "vertex_indices\nproperty uchar red\nproperty uchar green\n"
                 "property uchar blue\nend_header\n") != NULL);
    char line[64];
    snprintf(line, sizeof line, " %u %u %u\n", fc[0], fc[1], fc[2]);
    CHECK(strstr(text, line) != NULL);
    snprintf(line, sizeof line, " %u %u %u\n", vc[3], vc[4], vc[5]);
    CHECK(strstr(text, line) != NULL);
    /* Vertex colours alone, then other formats. */
    options.face_colors = NULL;
    CHECK_OK(mt_write_file_with(io_test_path("v.ply"), MT_FORMAT_AUTO, &list, &options, &diag));
    mt_face_list back;
    CHECK_OK(mt_read_file(io_test_path("v.ply"), MT_FORMAT_AUTO, &back, &diag));
    io_test_check_same(&list, &back, "vertex colours only");
    mt_face_list_free(&back);
    CHECK_STATUS(mt_write_file_with(io_test_path("c.off"), MT_FORMAT_AUTO, &list, &options, &diag),
                 MT_ERR_UNSUPPORTED);
    CHECK(strstr(diag.message, "PLY") != NULL);
    CHECK_OK(mt_write_file_with(io_test_path("c.off"), MT_FORMAT_AUTO, &list, NULL, &diag));
    free(vc);
    free(fc);
    mt_face_list_free(&list);
}

static void test_write_errors(void)
{
    mt_face_list list;
    make_awkward(&list, 3);
    mt_diag diag;
    /* A directory that does not exist: MT_ERR_IO naming the path. */
    const char *missing = "/nonexistent-meshtopo-dir/out.off";
    CHECK_STATUS(mt_write_file(missing, MT_FORMAT_AUTO, &list, &diag), MT_ERR_IO);
    CHECK(strstr(diag.message, missing) != NULL);
    CHECK(strstr(diag.message, strerror(ENOENT)) != NULL);
    /* A name with no known suffix and no format. */
    CHECK_STATUS(mt_write_file(io_test_path("out.mesh"), MT_FORMAT_AUTO, &list, &diag),
                 MT_ERR_INVALID_ARG);
    /* An inconsistent list is refused before any file is made. */
    list.num_indices++;
    CHECK_STATUS(mt_write_file(io_test_path("bad.off"), MT_FORMAT_AUTO, &list, &diag),
                 MT_ERR_INVALID_ARG);
    list.num_indices--;
    struct stat st;
    CHECK(stat(io_test_path("bad.off"), &st) != 0);
    CHECK_STATUS(mt_write_file(NULL, MT_FORMAT_OFF, &list, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_write_file(io_test_path("x.off"), MT_FORMAT_OFF, NULL, &diag),
                 MT_ERR_INVALID_ARG);
    mt_face_list_free(&list);
}

/* ---- Entry points ------------------------------------------------------ */

static void test_read_missing_file(void)
{
    mt_face_list list;
    memset(&list, 0xab, sizeof list);
    mt_diag diag;
    const char *path = "/nonexistent-meshtopo-dir/mesh.off";
    CHECK_STATUS(mt_read_file(path, MT_FORMAT_AUTO, &list, &diag), MT_ERR_IO);
    CHECK_EQ(diag.status, MT_ERR_IO);
    CHECK(strstr(diag.message, path) != NULL);
    CHECK(strstr(diag.message, strerror(ENOENT)) != NULL);
    CHECK(list.num_verts == 0 && list.positions == NULL && list.face_indices == NULL);
    /* A directory cannot be read as a mesh either. */
    CHECK_STATUS(mt_read_file("/tmp", MT_FORMAT_AUTO, &list, &diag), MT_ERR_IO);
    CHECK(strstr(diag.message, "/tmp") != NULL);
}

static void test_format_names(void)
{
    CHECK(strcmp(mt_format_name(MT_FORMAT_AUTO), "auto") == 0);
    CHECK(strcmp(mt_format_name(MT_FORMAT_OFF), "off") == 0);
    CHECK(strcmp(mt_format_name(MT_FORMAT_OBJ), "obj") == 0);
    CHECK(strcmp(mt_format_name(MT_FORMAT_PLY_ASCII), "ply-ascii") == 0);
    CHECK(strcmp(mt_format_name(MT_FORMAT_PLY_BINARY_LE), "ply-le") == 0);
    CHECK(strcmp(mt_format_name(MT_FORMAT_PLY_BINARY_BE), "ply-be") == 0);
    CHECK_EQ(mt_format_from_path("a/b/mesh.off"), MT_FORMAT_OFF);
    CHECK_EQ(mt_format_from_path("mesh.off.gz"), MT_FORMAT_OFF);
    CHECK_EQ(mt_format_from_path("MESH.OBJ"), MT_FORMAT_OBJ);
    CHECK_EQ(mt_format_from_path("mesh.obj.gz"), MT_FORMAT_OBJ);
    CHECK_EQ(mt_format_from_path("scan.ply"), MT_FORMAT_PLY_BINARY_LE);
    CHECK_EQ(mt_format_from_path("scan.ply.gz"), MT_FORMAT_PLY_BINARY_LE);
    CHECK_EQ(mt_format_from_path("scan.stl"), MT_FORMAT_STL_BINARY);
    CHECK_EQ(mt_format_from_path("scan.vtk"), MT_FORMAT_AUTO);
    CHECK_EQ(mt_format_from_path("scan.gz"), MT_FORMAT_AUTO);
    CHECK_EQ(mt_format_from_path("off"), MT_FORMAT_AUTO);
    CHECK_EQ(mt_format_from_path(NULL), MT_FORMAT_AUTO);
}

/* AUTO reads by content first (OFF and PLY headers), then by name, then by
 * OBJ keywords; bad arguments are refused. */
static void test_read_auto_detection(void)
{
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(io_test_read_text("# c\nOFF\n1 0 0\n1 2 3\n", MT_FORMAT_AUTO, "x.obj", &list, &diag));
    CHECK_EQ(list.num_verts, 1);
    mt_face_list_free(&list);
    CHECK_OK(io_test_read_text("v 1 2 3\nv 4 5 6\n", MT_FORMAT_AUTO, NULL, &list, &diag));
    CHECK_EQ(list.num_verts, 2);
    mt_face_list_free(&list);
    CHECK_OK(io_test_read_text("# only\n\nf 1 2 3\n", MT_FORMAT_AUTO, "data.txt", &list, &diag));
    CHECK_EQ(list.num_faces, 1);
    mt_face_list_free(&list);
    CHECK_OK(
        io_test_read_text("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n1 2 3\n",
                          MT_FORMAT_AUTO, NULL, &list, &diag));
    CHECK_EQ(list.num_verts, 1);
    mt_face_list_free(&list);
    /* By name only: an empty OBJ is an empty mesh. */
    CHECK_OK(io_test_read_text("", MT_FORMAT_AUTO, "empty.obj", &list, &diag));
    CHECK_EQ(list.num_verts, 0);
    CHECK_EQ(list.num_faces, 0);
    mt_face_list_free(&list);
    EXPECT_TEXT_ERROR("hello world\n", MT_FORMAT_AUTO, "mystery", 1, "cannot tell the format");
    CHECK_STATUS(mt_read_memory("OFF", 3, (mt_format)42, NULL, &list, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_read_memory("OFF", 3, MT_FORMAT_OFF, NULL, NULL, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_read_memory(NULL, 3, MT_FORMAT_OFF, NULL, &list, &diag), MT_ERR_INVALID_ARG);
    /* NULL diag is fine. */
    CHECK_STATUS(mt_read_memory("OFF\n", 4, MT_FORMAT_OFF, NULL, &list, NULL), MT_ERR_PARSE);
}

static const mt_test_case cases[] = {
    {"corpus_counts", test_corpus_counts},
    {"corpus_assimp_malformed_contents", test_corpus_assimp_malformed_contents},
    {"round_trip_awkward", test_round_trip_awkward},
    {"round_trip_huge_faces", test_round_trip_huge_faces},
    {"round_trip_empty_and_no_positions", test_round_trip_empty_and_no_positions},
    {"round_trip_corpus", test_round_trip_corpus},
    {"round_trip_nonfinite", test_round_trip_nonfinite},
    {"write_replaces_atomically", test_write_replaces_atomically},
    {"write_ply_colors", test_write_ply_colors},
    {"write_errors", test_write_errors},
    {"read_missing_file", test_read_missing_file},
    {"format_names", test_format_names},
    {"read_auto_detection", test_read_auto_detection},
};
const mt_test_table mt_tests_io = {cases, sizeof cases / sizeof cases[0]};
