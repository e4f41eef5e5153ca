/* The text readers' answers do not depend on how fast they are read:
 * coordinates are bit-identical to strtod of the same tokens (an
 * independent slow path: the C library, under the C locale), on tricky
 * numbers and on many random ones; one thread, several threads and any
 * window give the same arrays, the same errors and the same line numbers,
 * on generated files large enough to be split across threads (OFF, PLY
 * and OBJ, whose arrays are known from their writing) and on the corpus. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "io_test_util.h"
#include "meshtopo/generate.h"
#include "meshtopo/io.h"

/* Tokens the fast number paths must read as strtod does (or leave to it). */
static const char *const tricky[] = {
    "0",
    "-0",
    "-0.0",
    "+0.000",
    "00012",
    "1",
    "-1",
    "+1.5",
    ".5",
    "5.",
    "0.1",
    "0.3",
    "1e22",
    "1e23",
    "1E5",
    "1e+05",
    "1e-05",
    "9007199254740992",
    "9007199254740993",
    "9007199254740995",
    "18446744073709551615",
    "18446744073709551616",
    "1234567890123456789",
    "12345678901234567890",
    "0.0027762372488338645",
    "1.2499969169988934",
    "3.14159265358979323846264338327950288",
    "123456789012345678901234567890",
    "0.000000000000000000000000000001",
    "1.7976931348623157e308",
    "1.7976931348623159e308",
    "1e308",
    "1e309",
    "-1e309",
    "2.2250738585072014e-308",
    "2.2250738585072011e-308",
    "2.2250738585072012e-308",
    "4.9406564584124654e-324",
    "2.4703282292062328e-324",
    "2.4703282292062327e-324",
    "1e-400",
    "-1e-400",
    "8.98846567431158e307",
    "0x1p3",
    "-0x1.8p-2",
    "inf",
    "-inf",
    "infinity",
    "nan",
    "1.00000000000000011102230246251565404236316680908203125",
    "1.00000000000000011102230246251565404236316680908203124",
    "7.2057594037927933e16",
    "4503599627370496.5",
    "4503599627370497.5",
    "1e-22",
    "1e-23",
    "123e-25",
    "9.999999999999999e22",
    "5e-324",
};

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static uint64_t next_rand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

/* A random number token into buf (shortest, long, integer, exponent ...). */
static void random_token(char *buf, size_t size)
{
    double v;
    uint64_t bits = next_rand();
    switch (next_rand() % 4) {
        case 0:
            memcpy(&v, &bits, sizeof v);
            if (!isfinite(v)) v = 1.0 / 3.0;
            snprintf(buf, size, "%.*g", 1 + (int)(next_rand() % 17), v);
            break;
        case 1:
            v = (double)(bits >> 11) / 9007199254740992.0 * pow(10, (int)(next_rand() % 40) - 20);
            snprintf(buf, size, "%.17g", v);
            break;
        case 2: {
            size_t n = 0;
            if (next_rand() & 1) buf[n++] = '-';
            int digits = 1 + (int)(next_rand() % 24);
            int point = (int)(next_rand() % (unsigned)(digits + 1));
            for (int k = 0; k < digits; k++) {
                if (k == point && k > 0) buf[n++] = '.';
                buf[n++] = (char)('0' + next_rand() % 10);
            }
            if (next_rand() % 3 == 0)
                n += (size_t)snprintf(buf + n, size - n, "e%d", (int)(next_rand() % 700) - 350);
            buf[n] = '\0';
            break;
        }
        default:
            snprintf(buf, size, "%d", (int)(next_rand() % 2000000) - 1000000);
            break;
    }
}

/* Tokens: the tricky ones, then `count` random ones. */
static char **make_tokens(size_t count, size_t *out_n)
{
    size_t ntricky = sizeof tricky / sizeof tricky[0];
    size_t n = ntricky + count;
    n += (3 - n % 3) % 3; /* whole vertices */
    char **tokens = malloc(n * sizeof *tokens);
    if (!tokens) return NULL;
    for (size_t i = 0; i < n; i++) {
        tokens[i] = malloc(64);
        if (!tokens[i]) return NULL;
        if (i < ntricky)
            snprintf(tokens[i], 64, "%s", tricky[i]);
        else
            random_token(tokens[i], 64);
    }
    *out_n = n;
    return tokens;
}

static void free_tokens(char **tokens, size_t n)
{
    for (size_t i = 0; i < n; i++) free(tokens[i]);
    free(tokens);
}

/* An OFF (ply = 0) or ASCII PLY file of the tokens as vertices, one per
 * line, and triangles of them. */
static char *make_text(char **tokens, size_t n, int ply, size_t *out_len)
{
    size_t verts = n / 3, faces = verts >= 3 ? verts - 2 : 0;
    size_t cap = 256 + n * 66 + faces * 40, len = 0;
    char *text = malloc(cap);
    if (!text) return NULL;
    if (ply)
        len += (size_t)snprintf(text, cap,
                                "ply\nformat ascii 1.0\nelement vertex %zu\nproperty double x\n"
                                "property double y\nproperty double z\nelement face %zu\n"
                                "property list uchar int vertex_indices\nend_header\n",
                                verts, faces);
    else
        len += (size_t)snprintf(text, cap, "OFF\n%zu %zu 0\n", verts, faces);
    for (size_t v = 0; v < verts; v++)
        len += (size_t)snprintf(text + len, cap - len, "%s %s\t%s\n", tokens[3 * v],
                                tokens[3 * v + 1], tokens[3 * v + 2]);
    for (size_t f = 0; f < faces; f++)
        len += (size_t)snprintf(text + len, cap - len, "3 %zu %zu %zu\n", f, f + 1, f + 2);
    *out_len = len;
    return text;
}

/* A way to read a file: threads and window size (0: the defaults). */
typedef struct read_way {
    unsigned threads;
    size_t window;
} read_way;

static mt_read_options options_for(read_way way)
{
    mt_read_options options;
    memset(&options, 0, sizeof options);
    options.threads = way.threads;
    options.window_bytes = way.window;
    return options;
}

static int same_lists(const mt_face_list *a, const mt_face_list *b)
{
    return a->num_verts == b->num_verts && a->num_faces == b->num_faces &&
           a->num_indices == b->num_indices &&
           memcmp(a->positions, b->positions, 3 * sizeof(double) * a->num_verts) == 0 &&
           memcmp(a->face_sizes, b->face_sizes, sizeof(uint32_t) * a->num_faces) == 0 &&
           memcmp(a->face_indices, b->face_indices, sizeof(uint32_t) * a->num_indices) == 0;
}

/* Reads with one thread, 2 and 4 threads, small windows, and windows
 * large enough for several threads, each next one read ahead while they
 * parse: the same status, arrays, message and line each time. */
static void expect_same_every_way(const char *text, size_t len, const char *name)
{
    static const read_way ways[] = {{1, 0},
                                    {2, 0},
                                    {4, 0},
                                    {2, 4096},
                                    {1, 7},
                                    {2, (size_t)1 << 20},
                                    {2, (size_t)3 << 19},
                                    {4, (size_t)4 << 20}};
    mt_face_list first, list;
    mt_diag first_diag, diag;
    mt_status first_status = MT_OK;
    for (size_t w = 0; w < sizeof ways / sizeof ways[0]; w++) {
        mt_read_options options = options_for(ways[w]);
        mt_face_list *out = w == 0 ? &first : &list;
        mt_diag *d = w == 0 ? &first_diag : &diag;
        mt_status st = mt_read_memory_with(text, len, MT_FORMAT_AUTO, name, &options, out, d);
        if (w == 0) {
            first_status = st;
            continue;
        }
        CHECK_EQ(st, first_status);
        if (st == MT_OK && first_status == MT_OK) {
            if (!same_lists(&first, &list))
                mt_test_fail(__FILE__, __LINE__, "%s: threads %u window %zu: other arrays", name,
                             ways[w].threads, ways[w].window);
            mt_face_list_free(&list);
        } else if (st != MT_OK && first_status != MT_OK) {
            CHECK_EQ(diag.line, first_diag.line);
            CHECK_EQ(diag.element, first_diag.element);
            if (strcmp(diag.message, first_diag.message) != 0)
                mt_test_fail(__FILE__, __LINE__, "%s: '%s' != '%s'", name, diag.message,
                             first_diag.message);
        }
    }
    if (first_status == MT_OK) mt_face_list_free(&first);
}

static void test_exact_numbers_match_strtod(void)
{
    size_t n;
    char **tokens = make_tokens(200000, &n); /* several MB: split across threads */
    CHECK(tokens != NULL);
    if (!tokens) return;
    for (int ply = 0; ply < 2; ply++) {
        size_t len;
        char *text = make_text(tokens, n, ply, &len);
        CHECK(text != NULL);
        if (!text) break;
        mt_face_list list;
        mt_diag diag;
        const char *name = ply ? "numbers.ply" : "numbers.off";
        CHECK_OK(mt_read_memory(text, len, MT_FORMAT_AUTO, name, &list, &diag));
        if (list.num_verts == n / 3) {
            size_t wrong = 0;
            for (size_t i = 0; i < n; i++) {
                double want = strtod(tokens[i], NULL);
                if (memcmp(&want, &list.positions[i], sizeof want) != 0 && wrong++ < 5)
                    mt_test_fail(__FILE__, __LINE__, "%s: '%s' read as %.17g, strtod %.17g", name,
                                 tokens[i], list.positions[i], want);
            }
            CHECK_EQ(wrong, 0);
        } else {
            CHECK_EQ(list.num_verts, n / 3);
        }
        mt_face_list_free(&list);
        expect_same_every_way(text, len, name);
        free(text);
    }
    free_tokens(tokens, n);
}

/* Large files with something for the general loop here and there (a
 * comment, a blank line, a vertex over two lines, colours, CRLF) and an
 * error deep inside: every way of reading agrees on all of it. */
static void test_exact_threads_errors_and_lines(void)
{
    size_t n;
    char **tokens = make_tokens(150000, &n);
    CHECK(tokens != NULL);
    if (!tokens) return;
    size_t len;
    char *text = make_text(tokens, n, 0, &len);
    free_tokens(tokens, n);
    CHECK(text != NULL);
    if (!text) return;
    expect_same_every_way(text, len, "plain.off");
    /* irregular lines: a comment, a blank line, CRLF */
    char *mixed = malloc(len + 64);
    CHECK(mixed != NULL);
    if (!mixed) {
        free(text);
        return;
    }
    size_t cut = len / 3;
    while (text[cut - 1] != '\n') cut++;
    memcpy(mixed, text, cut);
    size_t m = cut;
    m += (size_t)sprintf(mixed + m, "# a comment\n\n");
    memcpy(mixed + m, text + cut, len - cut);
    m += len - cut;
    expect_same_every_way(mixed, m, "mixed.off");
    /* errors deep in the vertices and in the faces, found at their lines */
    const double where[] = {0.3, 0.7, 0.95};
    for (size_t k = 0; k < sizeof where / sizeof where[0]; k++) {
        memcpy(mixed, text, len);
        size_t at = (size_t)(where[k] * (double)len);
        while (mixed[at - 1] != '\n') at++;
        mixed[at] = 'x'; /* the first character of a line */
        uint64_t line = 1;
        for (size_t i = 0; i < at; i++) line += mixed[i] == '\n';
        mt_face_list list;
        mt_diag diag;
        mt_read_options one;
        memset(&one, 0, sizeof one);
        one.threads = 1;
        mt_status st =
            mt_read_memory_with(mixed, len, MT_FORMAT_OFF, "bad.off", &one, &list, &diag);
        CHECK_EQ(st, MT_ERR_PARSE);
        CHECK_EQ(diag.line, line);
        expect_same_every_way(mixed, len, "bad.off");
    }
    free(mixed);
    free(text);
}

/* Every corpus file: the same with one thread as with several, and
 * through a small window. */
static void test_exact_corpus_every_way(void)
{
    const char *dir = mt_test_corpus_dir();
    DIR *d = dir ? opendir(dir) : NULL;
    if (!d) return; /* no corpus here: test_io.corpus_* say so */
    struct dirent *e;
    size_t files = 0;
    while ((e = readdir(d))) {
        const char *dot = strrchr(e->d_name, '.');
        if (!dot || (strcmp(dot, ".off") && strcmp(dot, ".obj") && strcmp(dot, ".ply"))) continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        FILE *f = fopen(path, "rb");
        if (!f) continue;
        fseek(f, 0, SEEK_END);
        long size = ftell(f);
        fseek(f, 0, SEEK_SET);
        char *data = size > 0 ? malloc((size_t)size) : NULL;
        if (data && fread(data, 1, (size_t)size, f) == (size_t)size) {
            expect_same_every_way(data, (size_t)size, e->d_name);
            files++;
        }
        free(data);
        fclose(f);
    }
    closedir(d);
    CHECK(files > 0);
}

/* Binary PLY read by its fast paths (x y z doubles copied whole, triangles
 * with a one-byte count and 32-bit indices copied as they are) gives the
 * arrays the ASCII PLY of the same list gives through the text reader, and
 * those the big-endian file gives through the per-value loop: with a quad
 * and a 16-gon (65 bytes, five triangles' worth) among the triangles, a
 * negative and an out-of-range index, coordinates that are not integers,
 * one thread or two, and windows that cut records anywhere. */
static void test_exact_binary_ply_fast_paths(void)
{
    mt_face_list grid, list;
    CHECK_OK(mt_gen_grid(160, 160, true, &grid));
    const uint32_t q = grid.num_faces / 4;
    /* before grid face `at`: the face `size` [v...] */
    const struct {
        uint32_t at, size, v[16];
    } extra[] = {
        {0, 4, {0, 1, 162, 161}},
        {q, 16, {2, 3, 4, 5, 6, 7, 8, 9, 170, 169, 168, 167, 166, 165, 164, 163}},
        {3 * q, 3, {7, 0xffffffffu, 8}},
        {grid.num_faces, 3, {9, 10, grid.num_verts + 3}},
        {grid.num_faces, 4, {11, 12, 173, 172}},
    };
    const size_t num_extra = sizeof extra / sizeof extra[0];
    uint64_t extra_indices = 0;
    for (size_t e = 0; e < num_extra; e++) extra_indices += extra[e].size;
    CHECK_OK(mt_face_list_alloc(&list, grid.num_verts, grid.num_faces + (uint32_t)num_extra,
                                grid.num_indices + extra_indices, NULL));
    for (uint32_t i = 0; i < 3 * grid.num_verts; i++)
        list.positions[i] = grid.positions[i] + 0.1 * i - 1e-3 / (i + 1);
    uint32_t f = 0;
    uint64_t k = 0;
    size_t e = 0;
    for (uint32_t g = 0; g <= grid.num_faces; g++) {
        for (; e < num_extra && extra[e].at == g; e++) {
            list.face_sizes[f++] = extra[e].size;
            for (uint32_t j = 0; j < extra[e].size; j++) list.face_indices[k++] = extra[e].v[j];
        }
        if (g == grid.num_faces) break;
        list.face_sizes[f++] = 3;
        for (uint32_t j = 0; j < 3; j++) list.face_indices[k++] = grid.face_indices[3 * g + j];
    }
    CHECK_EQ(f, list.num_faces);
    CHECK_EQ(k, list.num_indices);
    static const mt_format formats[] = {MT_FORMAT_PLY_ASCII, MT_FORMAT_PLY_BINARY_LE,
                                        MT_FORMAT_PLY_BINARY_BE};
    static const read_way ways[] = {{0, 0}, {1, 0}, {2, (size_t)1 << 20}, {2, 4096}, {2, 100}};
    mt_face_list ascii;
    memset(&ascii, 0, sizeof ascii);
    for (size_t i = 0; i < 3; i++) {
        const char *path = io_test_path(i == 0   ? "fast.ascii.ply"
                                        : i == 1 ? "fast.le.ply"
                                                 : "fast.be.ply");
        mt_diag diag;
        CHECK_OK(mt_write_file(path, formats[i], &list, &diag));
        unsigned char *data = NULL;
        size_t size = 0;
        CHECK(io_test_slurp(path, &data, &size));
        for (size_t w = 0; w < sizeof ways / sizeof ways[0] && data; w++) {
            mt_read_options options = options_for(ways[w]);
            mt_face_list read;
            CHECK_OK(mt_read_memory_with(data, size, MT_FORMAT_AUTO, path, &options, &read, &diag));
            if (i == 0 && w == 0) {
                ascii = read;
                CHECK_EQ(ascii.num_faces, list.num_faces);
                CHECK(ascii.num_indices == list.num_indices &&
                      memcmp(ascii.face_indices, list.face_indices,
                             list.num_indices * sizeof(uint32_t)) == 0);
                continue;
            }
            if (!same_lists(&ascii, &read))
                mt_test_fail(__FILE__, __LINE__,
                             "%s, threads %u, window %zu: not the ASCII file's arrays", path,
                             ways[w].threads, ways[w].window);
            mt_face_list_free(&read);
        }
        free(data);
    }
    mt_face_list_free(&ascii);
    mt_face_list_free(&list);
    mt_face_list_free(&grid);
}

/* The size of face f in the mixed file: runs of triangles, of quads, of
 * random sizes 3 to 6, and of triangles with a rare octagon, so that the
 * parts of a window meet faces of other sizes than those just before them. */
static uint32_t mixed_face_size(uint32_t f)
{
    if (f < 100000) return 3;
    if (f < 150000) return 4;
    if (f < 220000) return 3 + (uint32_t)(next_rand() % 4);
    if (f < 260000) return 3;
    return f % 1000 == 999 ? 8 : 3;
}

/* Faces of many sizes in files large enough to be cut into parts: every
 * part that writes straight into the face list at a guessed index (too
 * far: a gap closed afterwards; too near: the part stops and the rest is
 * read again) gives the written arrays exactly, as OFF and as ASCII PLY,
 * on one to four threads. */
static void test_exact_mixed_face_sizes(void)
{
    const uint32_t num_verts = 1000, num_faces = 300000;
    uint32_t *sizes = malloc(num_faces * sizeof *sizes);
    CHECK(sizes != NULL);
    if (!sizes) return;
    uint64_t num_indices = 0;
    for (uint32_t f = 0; f < num_faces; f++) num_indices += sizes[f] = mixed_face_size(f);
    mt_face_list list;
    CHECK_OK(mt_face_list_alloc(&list, num_verts, num_faces, num_indices, NULL));
    for (uint32_t i = 0; i < 3 * num_verts; i++) list.positions[i] = (double)(i % 97) - 48;
    uint64_t k = 0;
    for (uint32_t f = 0; f < num_faces; f++) {
        list.face_sizes[f] = sizes[f];
        for (uint32_t j = 0; j < sizes[f]; j++)
            list.face_indices[k++] = (f * 7 + j * 13) % num_verts;
    }
    free(sizes);
    static const mt_format formats[] = {MT_FORMAT_OFF, MT_FORMAT_PLY_ASCII};
    static const read_way ways[] = {{1, 0}, {2, 0}, {3, 0}, {4, 0}, {2, (size_t)3 << 20}};
    for (size_t i = 0; i < 2; i++) {
        const char *path = io_test_path(i == 0 ? "mixed.off" : "mixed.ply");
        mt_diag diag;
        CHECK_OK(mt_write_file(path, formats[i], &list, &diag));
        for (size_t w = 0; w < sizeof ways / sizeof ways[0]; w++) {
            mt_read_options options = options_for(ways[w]);
            mt_face_list read;
            CHECK_OK(mt_read_file_with(path, MT_FORMAT_AUTO, &options, &read, &diag));
            if (!same_lists(&list, &read))
                mt_test_fail(__FILE__, __LINE__, "%s, threads %u, window %zu: other arrays", path,
                             ways[w].threads, ways[w].window);
            mt_face_list_free(&read);
        }
    }
    mt_face_list_free(&list);
}

/* OFF lines the fast path for common lines must read as the general loop
 * does, or leave to it: vertices of three tokens (their values: strtod's)
 * and faces with the indices they hold. */
static const char *const odd_off_vertex_lines[] = {
    "-.5 5. +1\n",
    "  1 2 3\n",
    "1\t\t2  3 \r\n",
    "-0 0.1 1e3\n",
    "00000000000000000001 2.50000000000000000000 3\n",
    "9007199254740993 0.1234567890123456789 1234567890123456789\n",
    "0.12345678901234567 -0.0000000000000000001 12345678.12345678\n",
};

typedef struct odd_face_line {
    const char *text;
    uint32_t size, indices[4];
} odd_face_line;

static const odd_face_line odd_off_face_lines[] = {
    {"3 1 2 00000000002\n", 3, {1, 2, 2}}, {"3 1 2 4294967295\n", 3, {1, 2, UINT32_MAX}},
    {"3 1 2 -1\n", 3, {1, 2, UINT32_MAX}}, {"3\t1 2 3 \r\n", 3, {1, 2, 3}},
    {" 3 1 2 3\n", 3, {1, 2, 3}},          {"4 1 2 3 4\n", 4, {1, 2, 3, 4}},
    {"03 1  2 3\n", 3, {1, 2, 3}},         {"0\n", 0, {0}},
};

#define ODD_EVERY 997u /* one line in this many is odd */

/* Splits a vertex line into its three tokens' values by strtod. */
static void strtod_line(const char *line, double xyz[3])
{
    const char *p = line;
    for (int k = 0; k < 3; k++) {
        char *end;
        xyz[k] = strtod(p, &end);
        p = end;
    }
}

/* A text buffer of 16 MiB starting with an OFF header of `kind` (OFF,
 * COFF) and the counts, and want: a face list of those counts (and room for
 * max_indices) for the test to fill; NULL (and want freed) when either is
 * not there. *len: the header's length. */
static char *off_text_begin(const char *kind, uint32_t verts, uint32_t faces, uint64_t max_indices,
                            mt_face_list *want, size_t *len)
{
    char *text = malloc((size_t)16 << 20);
    CHECK(text != NULL);
    mt_status st = mt_face_list_alloc(want, verts, faces, max_indices, NULL);
    CHECK_OK(st);
    if (!text || st != MT_OK) {
        free(text);
        if (st == MT_OK) mt_face_list_free(want);
        return NULL;
    }
    *len = (size_t)sprintf(text, "%s\n%u %u 0\n", kind, (unsigned)verts, (unsigned)faces);
    return text;
}

/* The text read (OFF) as want holds it, and the same every way. */
static void expect_off_as(const char *text, size_t len, const char *name, const mt_face_list *want)
{
    mt_face_list read;
    mt_diag diag;
    CHECK_OK(mt_read_memory(text, len, MT_FORMAT_OFF, name, &read, &diag));
    if (!same_lists(want, &read)) mt_test_fail(__FILE__, __LINE__, "%s: other arrays", name);
    mt_face_list_free(&read);
    expect_same_every_way(text, len, name);
}

/* OFF files with odd lines deep inside their runs of vertices and faces:
 * read as the lines say on one to four threads and through small windows;
 * an index past 32 bits there is an error at its line every way. */
static void test_exact_off_odd_lines(void)
{
    enum { VERTS = 60000, FACES = 200000 };
    size_t len;
    mt_face_list want;
    char *text = off_text_begin("OFF", VERTS, FACES, 4 * (uint64_t)FACES, &want, &len);
    if (!text) return;
    size_t lines = 2, bad_at = 0, bad_line = 0;
    size_t num_odd_v = sizeof odd_off_vertex_lines / sizeof odd_off_vertex_lines[0];
    size_t num_odd_f = sizeof odd_off_face_lines / sizeof odd_off_face_lines[0];
    for (uint32_t v = 0; v < VERTS; v++, lines++) {
        double *xyz = want.positions + 3 * (size_t)v;
        if (v % ODD_EVERY == ODD_EVERY - 1) {
            const char *line = odd_off_vertex_lines[v / ODD_EVERY % num_odd_v];
            len += (size_t)sprintf(text + len, "%s", line);
            strtod_line(line, xyz);
        } else {
            xyz[0] = v % 1000, xyz[1] = -(double)(v / 1000) / 8, xyz[2] = 0.25 * (v % 7);
            len += (size_t)sprintf(text + len, "%.17g %.17g %.17g\n", xyz[0], xyz[1], xyz[2]);
        }
    }
    want.num_indices = 0;
    for (uint32_t f = 0; f < FACES; f++, lines++) {
        uint32_t *idx = want.face_indices + want.num_indices;
        if (f % ODD_EVERY == ODD_EVERY - 1) {
            const odd_face_line *odd = &odd_off_face_lines[f / ODD_EVERY % num_odd_f];
            len += (size_t)sprintf(text + len, "%s", odd->text);
            want.face_sizes[f] = odd->size;
            memcpy(idx, odd->indices, odd->size * sizeof *idx);
        } else {
            if (f == FACES / 2) {
                bad_at = len;
                bad_line = lines + 1;
            }
            want.face_sizes[f] = 3;
            idx[0] = f % VERTS, idx[1] = (f * 7 + 1) % VERTS, idx[2] = (f * 13 + 2) % VERTS;
            len += (size_t)sprintf(text + len, "3 %u %u %u\n", idx[0], idx[1], idx[2]);
        }
        want.num_indices += want.face_sizes[f];
    }
    expect_off_as(text, len, "odd.off", &want);
    /* the middle face's last index one past 32 bits, then 11 digits */
    static const char *const too_big[] = {"4294967296", "99999999999"};
    mt_face_list read;
    mt_diag diag;
    for (size_t k = 0; k < 2; k++) {
        char *nl = memchr(text + bad_at, '\n', 64);
        char *sp = nl;
        while (sp[-1] != ' ') sp--;
        char *copy = malloc(len + 16);
        CHECK(copy != NULL);
        if (!copy) break;
        size_t head = (size_t)(sp - text);
        memcpy(copy, text, head);
        size_t m = head + (size_t)sprintf(copy + head, "%s", too_big[k]);
        memcpy(copy + m, nl, len - (size_t)(nl - text));
        m += len - (size_t)(nl - text);
        mt_status st = mt_read_memory(copy, m, MT_FORMAT_OFF, "big.off", &read, &diag);
        CHECK_EQ(st, MT_ERR_PARSE);
        CHECK_EQ(diag.line, bad_line);
        CHECK(strstr(diag.message, "does not fit in a 32-bit integer") != NULL);
        if (st == MT_OK) mt_face_list_free(&read);
        expect_same_every_way(copy, m, "big.off");
        free(copy);
    }
    mt_face_list_free(&want);
    free(text);
}

/* COFF: colours follow x y z on every vertex line and some face lines,
 * and the common-line path reads past them as the general loop does. Odd
 * rests deep in the run (none, CRLF, a backslash at the end, a comment,
 * a lone '\r' inside) read the same every way, and the coordinates and
 * faces are those written. A lone '\r' ends a line (old Mac text): the
 * two numbers after it and the first of the next line are the next
 * vertex, whose line's rest is skipped. */
static void test_exact_coff_rests(void)
{
    enum { VERTS = 80000, FACES = 120000 };
    static const char *const odd_rests[] = {"", " 0.5 0.5 0.5 1\r", " 9 \\", " # c",
                                            " 255 0\r0 255"};
    const size_t num_odd = sizeof odd_rests / sizeof odd_rests[0];
    size_t len;
    mt_face_list want;
    char *text = off_text_begin("COFF", VERTS, FACES, 3 * (uint64_t)FACES, &want, &len);
    if (!text) return;
    bool after_cr = false;
    for (uint32_t v = 0; v < VERTS; v++) {
        double *xyz = want.positions + 3 * (size_t)v;
        xyz[0] = v % 1000, xyz[1] = -(double)(v / 1000) / 4, xyz[2] = 0.5 * (v % 5);
        const char *rest =
            v % ODD_EVERY == ODD_EVERY - 1 ? odd_rests[v / ODD_EVERY % num_odd] : " 255 128 0 255";
        len += (size_t)sprintf(text + len, "%.17g %.17g %.17g%s\n", xyz[0], xyz[1], xyz[2], rest);
        if (after_cr) xyz[2] = xyz[0], xyz[0] = 0, xyz[1] = 255;
        after_cr = strstr(rest, "\r0") != NULL;
    }
    for (uint32_t f = 0; f < FACES; f++) {
        uint32_t *idx = want.face_indices + 3 * (size_t)f;
        want.face_sizes[f] = 3;
        idx[0] = f % VERTS, idx[1] = (f * 3 + 1) % VERTS, idx[2] = (f * 11 + 5) % VERTS;
        len += (size_t)sprintf(text + len, "3 %u %u %u%s\n", idx[0], idx[1], idx[2],
                               f % 3 == 0 ? " 255 0 0" : "");
    }
    expect_off_as(text, len, "rests.off", &want);
    mt_face_list_free(&want);
    free(text);
}

/* An OBJ text written together with the face list it holds. */
typedef struct obj_writer {
    char *text;
    size_t len, cap;
    mt_face_list want; /* arrays of fixed capacity; counts grow */
    size_t lines;      /* '\n' written so far */
    unsigned odd;      /* odd lines written so far */
} obj_writer;

static void obj_put(obj_writer *o, const char *s)
{
    size_t n = strlen(s);
    if (o->len + n > o->cap) return; /* the capacities below are ample */
    memcpy(o->text + o->len, s, n);
    o->len += n;
    for (size_t i = 0; i < n; i++) o->lines += s[i] == '\n';
}

static void obj_want_vert(obj_writer *o, double x, double y, double z)
{
    double *p = o->want.positions + 3 * (size_t)o->want.num_verts++;
    p[0] = x;
    p[1] = y;
    p[2] = z;
}

static void obj_want_face(obj_writer *o, uint32_t size, const uint32_t *indices)
{
    o->want.face_sizes[o->want.num_faces++] = size;
    memcpy(o->want.face_indices + o->want.num_indices, indices, size * sizeof *indices);
    o->want.num_indices += size;
}

/* Lines inside a run of plain v lines, each with what it adds: the bulk
 * parser must leave them to the general loop, or read them as it would. */
static void obj_odd_vertex_line(obj_writer *o)
{
    switch (o->odd++ % 6) {
        case 0: /* a backslash continues the line: the second v is not a vertex */
            obj_put(o, "v 1 2 3 \\\nv 4 5 6\n");
            obj_want_vert(o, 1, 2, 3);
            break;
        case 1: /* w and colours */
            obj_put(o, "v 1 2 3 4 5 6\n");
            obj_want_vert(o, 1, 2, 3);
            break;
        case 2:
            obj_put(o, "# a comment\n\nvt 0.5 0.5\nvn 0 0 1\nv1 2 3\n"); /* no vertex */
            break;
        case 3:
            obj_put(o, "v 0.5 0.25 -1 # a comment\n");
            obj_want_vert(o, 0.5, 0.25, -1);
            break;
        case 4:
            obj_put(o, "  v\t7\t8\t9  \n");
            obj_want_vert(o, 7, 8, 9);
            break;
        default:
            obj_put(o, "v 1e2 -2.5e-1 +3\r\n");
            obj_want_vert(o, 100, -0.25, 3);
            break;
    }
}

/* The same inside a run of plain f lines (after at least 3 vertices). */
static void obj_odd_face_line(obj_writer *o)
{
    const uint32_t nv = o->want.num_verts;
    uint32_t f[3] = {0, 1, 2};
    switch (o->odd++ % 7) {
        case 0: /* relative indices */
            obj_put(o, "f -1 -2 -3\n");
            f[0] = nv - 1, f[1] = nv - 2, f[2] = nv - 3;
            break;
        case 1: /* OBJ has no vertex 0, signed or not: stored as -1 */
            obj_put(o, "f 0 -0 +1\n");
            f[0] = UINT32_MAX, f[1] = UINT32_MAX, f[2] = 0;
            break;
        case 2:
            obj_put(o, "f 1 2 3 # a comment\n");
            break;
        case 3:
            obj_put(o, "f 1 2 \\\n 3\n");
            break;
        case 4:
            obj_put(o, "f 1/2/3 4//6 7/8\r\n");
            f[1] = 3, f[2] = 6;
            break;
        case 5:
            obj_put(o, "f 4294967295 +1 2\n");
            f[0] = 4294967294u, f[1] = 0, f[2] = 1;
            break;
        default:
            obj_put(o, "g part\nusemtl metal\ns off\nf1 2 3\n"); /* no face */
            return;
    }
    obj_want_face(o, 3, f);
}

/* OBJ files large enough to be split across threads, in blocks of v and f
 * lines with texture and normal lines between them, entries of all four
 * forms (one block's relative), tabs, CRLF, and odd lines deep inside the
 * runs: the arrays they
 * were written from, on one to four threads and through small windows;
 * and a bad line inside a run is reported at its line every way. */
static void test_exact_obj_runs(void)
{
    enum { BLOCKS = 4, VERTS = 10000, FACES = 25000, ODD = 7 };
    obj_writer o = {.cap = (size_t)16 << 20};
    o.text = malloc(o.cap);
    CHECK(o.text != NULL);
    const uint32_t max_verts = BLOCKS * (VERTS + ODD), max_faces = BLOCKS * (FACES + ODD);
    CHECK_OK(mt_face_list_alloc(&o.want, max_verts, max_faces, 5 * (uint64_t)max_faces, NULL));
    if (!o.text) return;
    o.want.num_verts = o.want.num_faces = 0;
    o.want.num_indices = 0;
    obj_put(&o, "# meshtopo test\nmtllib test.mtl\no test\n");
    size_t error_at[2] = {0, 0}, error_line[2] = {0, 0};
    for (unsigned block = 0; block < BLOCKS; block++) {
        const char *end = block == 2 ? "\r\n" : "\n";
        for (uint32_t k = 0; k < VERTS; k++) {
            if (k % (VERTS / ODD) == VERTS / ODD / 2) obj_odd_vertex_line(&o);
            if (block == 1 && k == VERTS * 3 / 10) {
                error_at[0] = o.len;
                error_line[0] = o.lines + 1;
            }
            const uint32_t v = o.want.num_verts;
            const double x = (v % 1000) / 8.0, y = -(double)(v % 333) * 0.001, z = v * 1e-3 + 0.5;
            char line[128];
            const char *sep = v % 7 == 0 ? "\t" : " ";
            snprintf(line, sizeof line, "v%s%.17g%s%.17g%s%.17g%s%s", sep, x, sep, y, sep, z,
                     v % 11 == 0 ? " 1.0" : "", end);
            obj_put(&o, line);
            obj_want_vert(&o, x, y, z);
        }
        obj_put(&o, "vt 0 0\nvt 1 0\nvn 0 0 1\n");
        for (uint32_t k = 0; k < FACES; k++) {
            if (k % (FACES / ODD) == FACES / ODD / 2) obj_odd_face_line(&o);
            if (block == 3 && k == FACES * 7 / 10) {
                error_at[1] = o.len;
                error_line[1] = o.lines + 1;
            }
            const uint32_t f = o.want.num_faces, nv = o.want.num_verts;
            const uint32_t size = 3 + (f % 5 == 0) + (f % 17 == 0);
            uint32_t idx[5];
            char line[256];
            size_t n = (size_t)snprintf(line, sizeof line, "f");
            for (uint32_t j = 0; j < size; j++) {
                idx[j] = (f * 7 + j * 13) % nv;
                /* block 1 counts back from the vertices defined so far */
                const long entry = block == 1 ? (long)idx[j] - (long)nv : (long)idx[j] + 1;
                static const char *const forms[] = {" %ld", " %ld/%ld", " %ld/%ld/%ld",
                                                    " %ld//%ld"};
                n += (size_t)snprintf(line + n, sizeof line - n, forms[(f + j) % 4], entry, entry,
                                      entry);
            }
            snprintf(line + n, sizeof line - n, "%s", end);
            obj_put(&o, line);
            obj_want_face(&o, size, idx);
        }
    }
    static const read_way ways[] = {
        {1, 0}, {2, 0}, {3, 0}, {4, 0}, {2, (size_t)1 << 20}, {1, 4096}, {2, (size_t)3 << 19}};
    for (size_t w = 0; w < sizeof ways / sizeof ways[0]; w++) {
        mt_read_options options = options_for(ways[w]);
        mt_face_list read;
        mt_diag diag;
        CHECK_OK(
            mt_read_memory_with(o.text, o.len, MT_FORMAT_AUTO, "runs.obj", &options, &read, &diag));
        if (!same_lists(&o.want, &read))
            mt_test_fail(__FILE__, __LINE__,
                         "threads %u, window %zu: other arrays (%u vertices, "
                         "%u faces; want %u, %u)",
                         ways[w].threads, ways[w].window, read.num_verts, read.num_faces,
                         o.want.num_verts, o.want.num_faces);
        mt_face_list_free(&read);
        /* a vertex short of a coordinate, then a face entry that is not a
         * number and one past 32 bits, at the same place */
        for (int e = 0; e < 3; e++) {
            char *bad = malloc(o.len + 32);
            CHECK(bad != NULL);
            if (!bad) break;
            static const char *const lines[] = {"v 1 2\n", "f 1 2 x\n", "f 1 2 4294967297\n"};
            const int place = e == 0 ? 0 : 1;
            const size_t at = error_at[place], add = strlen(lines[e]);
            memcpy(bad, o.text, at);
            memcpy(bad + at, lines[e], add);
            memcpy(bad + at + add, o.text + at, o.len - at);
            CHECK_STATUS(mt_read_memory_with(bad, o.len + add, MT_FORMAT_OBJ, "bad.obj", &options,
                                             &read, &diag),
                         MT_ERR_PARSE);
            if (diag.line != error_line[place])
                mt_test_fail(__FILE__, __LINE__,
                             "threads %u, window %zu: '%s' at line %llu, "
                             "reported at %llu (%s)",
                             ways[w].threads, ways[w].window, lines[e],
                             (unsigned long long)error_line[place], (unsigned long long)diag.line,
                             diag.message);
            free(bad);
        }
    }
    mt_face_list_free(&o.want);
    free(o.text);
}

static const mt_test_case cases[] = {
    {"exact_numbers_match_strtod", test_exact_numbers_match_strtod},
    {"exact_threads_errors_and_lines", test_exact_threads_errors_and_lines},
    {"exact_corpus_every_way", test_exact_corpus_every_way},
    {"exact_binary_ply_fast_paths", test_exact_binary_ply_fast_paths},
    {"exact_mixed_face_sizes", test_exact_mixed_face_sizes},
    {"exact_off_odd_lines", test_exact_off_odd_lines},
    {"exact_coff_rests", test_exact_coff_rests},
    {"exact_obj_runs", test_exact_obj_runs},
};
const mt_test_table mt_tests_io_exact = {cases, sizeof cases / sizeof cases[0]};
