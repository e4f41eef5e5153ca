/* meshtopo::io in bounded memory: data past what an OFF or PLY header
 * declares is refused after MT_READ_MAX_TRAILING_BYTES, headers declaring
 * gigabytes are refused without memory spent on them (gzip data that
 * inflates to gigabytes too), the input limit (max_input_bytes), tokens
 * longer than the window can widen to, and files read through windows of
 * any size giving what a whole read gives. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "harness.h"
#include "io_test_util.h"
#include "meshtopo/generate.h"
#include "meshtopo/io.h"

#define MESH "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
#define MIB ((uint64_t)1 << 20)

/* AddressSanitizer keeps freed memory in quarantine: peaks say nothing. */
#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif

/* ThreadSanitizer's shadow memory takes address space as ASan's does. */
#if defined(__SANITIZE_THREAD__)
#define UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define UNDER_TSAN 1
#endif
#endif

/* Peak resident memory of this process so far, in MiB (0 under ASan). */
static long peak_rss_mib(void)
{
#ifdef UNDER_ASAN
    return 0;
#else
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return 0;
    return ru.ru_maxrss / 1024; /* Linux: kilobytes */
#endif
}

/* head (as stored gzip) followed by `tail` (gzip members): one buffer. */
static unsigned char *gzip_join(const char *head, size_t head_len, const unsigned char *tail,
                                size_t tail_len, size_t *out_size)
{
    size_t n;
    unsigned char *h = io_test_gzip_stored(head, head_len, &n);
    unsigned char *out = h ? malloc(n + tail_len) : NULL;
    if (out) {
        memcpy(out, h, n);
        memcpy(out + n, tail, tail_len);
        *out_size = n + tail_len;
    }
    free(h);
    return out;
}

/* Reads data (name gives the format) and CHECKs the status and that the
 * message contains `fragment`; returns the diag for more checks. */
static mt_diag expect_status(const void *data, size_t size, const char *name,
                             const mt_read_options *options, mt_status want, const char *fragment)
{
    mt_face_list list;
    mt_diag diag;
    mt_status status = mt_read_memory_with(data, size, MT_FORMAT_AUTO, name, options, &list, &diag);
    CHECK_STATUS(status, want);
    if (status == MT_OK) mt_face_list_free(&list);
    if (fragment && !strstr(diag.message, fragment))
        mt_test_fail(__FILE__, __LINE__, "%s: message '%s' lacks '%s'", name, diag.message,
                     fragment);
    return diag;
}

static void test_bounded_gzip_generator(void)
{
    /* The generator's members inflate to what they say (CRC and length
     * checked by zlib): a mesh, then 3 x 100000 newlines. */
    size_t tail_size, size;
    unsigned char *tail = io_test_gzip_repeat("\n", 1, 100000, 3, &tail_size);
    CHECK(tail != NULL);
    unsigned char *gz = gzip_join(MESH, strlen(MESH), tail, tail_size, &size);
    CHECK(gz != NULL);
    if (gz) expect_status(gz, size, "gen.off.gz", NULL, MT_OK, NULL);
    free(gz);
    free(tail);
    /* A two-byte pattern of coordinates: 3 vertices of "0 " x 9. */
    static const char head[] = "OFF\n3 0 0\n";
    tail = io_test_gzip_repeat("0 ", 2, 18, 1, &tail_size);
    gz = tail ? gzip_join(head, strlen(head), tail, tail_size, &size) : NULL;
    CHECK(gz != NULL);
    if (gz) {
        mt_face_list list;
        mt_diag diag;
        CHECK_OK(mt_read_memory(gz, size, MT_FORMAT_AUTO, "zeros.off.gz", &list, &diag));
        CHECK_EQ(list.num_verts, 3);
        mt_face_list_free(&list);
    }
    free(gz);
    free(tail);
}

static void test_bounded_trailing_data(void)
{
    size_t mesh_len = strlen(MESH);
    uint64_t allowed = MT_READ_MAX_TRAILING_BYTES;
    /* The allowance counts from the end of the last face's values: its line
     * end, then exactly the allowance of newlines in all, is read. */
    size_t end = mesh_len - 1;
    char *text = malloc(end + allowed + 1);
    if (!text) return;
    memcpy(text, MESH, mesh_len);
    memset(text + end, '\n', allowed + 1);
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(IO_TEST_READ_VARIANTS(text, end + allowed, MT_FORMAT_OFF, "t.off", &list, &diag));
    CHECK_EQ(list.num_faces, 1);
    mt_face_list_free(&list);
    /* One byte more: refused at that byte, on its line. */
    EXPECT_PARSE_ERROR(text, end + allowed + 1, MT_FORMAT_OFF, "t.off", 6 + allowed, UINT64_MAX,
                       "the input goes on for more than 1048576 bytes after the last face (the "
                       "header declares 1)");
    /* Comments count as trailing bytes too. */
    uint64_t lines = 6;
    for (size_t k = mesh_len; k + 4 <= end + allowed + 1; k += 4, lines++)
        memcpy(text + k, "#c \n", 4);
    EXPECT_PARSE_ERROR(text, end + allowed + 1, MT_FORMAT_OFF, "c.off", lines, UINT64_MAX,
                       "the input goes on for more than");
    CHECK_OK(mt_read_memory(text, end + allowed, MT_FORMAT_OFF, "c.off", &list, &diag));
    mt_face_list_free(&list);
    free(text);

    /* Binary PLY: the same allowance of whitespace after the last element. */
    static const char ply[] =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n";
    size_t ply_len = strlen(ply) + 12;
    unsigned char *bin = calloc(1, ply_len + allowed + 1);
    if (!bin) return;
    memcpy(bin, ply, strlen(ply));
    memset(bin + ply_len, ' ', allowed + 1);
    expect_status(bin, ply_len + allowed, "t.ply", NULL, MT_OK, NULL);
    EXPECT_PARSE_ERROR(bin, ply_len + allowed + 1, MT_FORMAT_AUTO, "t.ply", 0, ply_len + allowed,
                       "the input goes on for more than 1048576 bytes after the last element");
    free(bin);

    /* Gigabytes of gzip'd newlines after a valid mesh: refused at the same
     * byte, having inflated little more than the allowance. */
    size_t tail_size, size;
    unsigned char *tail = io_test_gzip_repeat("\n", 1, 64 * MIB, 32, &tail_size); /* 2 GiB */
    unsigned char *gz = tail ? gzip_join(MESH, mesh_len, tail, tail_size, &size) : NULL;
    CHECK(gz != NULL);
    if (gz) {
        diag = expect_status(gz, size, "nl.off.gz", NULL, MT_ERR_PARSE,
                             "the input goes on for more than 1048576 bytes after the last face");
        CHECK_EQ(diag.line, 6 + allowed);
        CHECK_EQ(diag.byte_offset, mesh_len - 1 + allowed);
        /* the same through a file */
        const char *path = io_test_path("nl.off.gz");
        CHECK(io_test_spill(path, gz, size));
        CHECK_STATUS(mt_read_file(path, MT_FORMAT_AUTO, &list, &diag), MT_ERR_PARSE);
        CHECK_EQ(diag.line, 6 + allowed);
    }
    free(gz);
    free(tail);
    CHECK(peak_rss_mib() < 150);
}

/* A binary PLY header declaring `count` float vertices (and no faces). */
static size_t vertex_header(char *buf, size_t size, const char *count)
{
    return (size_t)snprintf(buf, size,
                            "ply\nformat binary_little_endian 1.0\nelement vertex %s\n"
                            "property float x\nproperty float y\nproperty float z\nend_header\n",
                            count);
}

static void test_bounded_declared_counts(void)
{
    char head[512];
    /* 2^31 vertices: past meshtopo's limit, whatever follows. */
    size_t n = vertex_header(head, sizeof head, "2147483648");
    EXPECT_PARSE_ERROR(head, n, MT_FORMAT_AUTO, "big.ply", 3, UINT64_MAX,
                       "vertex count 2147483648 too large");
    /* 2^31 - 1 vertices in a tiny file: refused by the size check. */
    n = vertex_header(head, sizeof head, "2147483647");
    EXPECT_PARSE_ERROR(head, n, MT_FORMAT_AUTO, "big.ply", 7, UINT64_MAX,
                       "need at least 25769803764 bytes of data but only 0 follow");

    /* ... followed by 256 MiB of gzip'd zero bytes (valid floats): the
     * reader learns the length of the gzip data before the face list grows
     * past its bound, and refuses with the same message. */
    size_t tail_size, size;
    unsigned char *tail = io_test_gzip_repeat("\0", 1, 64 * MIB, 4, &tail_size);
    unsigned char *gz = tail ? gzip_join(head, n, tail, tail_size, &size) : NULL;
    CHECK(gz != NULL);
    if (gz) {
        mt_diag diag = expect_status(gz, size, "zeros.ply.gz", NULL, MT_ERR_PARSE,
                                     "need at least 25769803764 bytes of data but only "
                                     "268435456 follow");
        CHECK_EQ(diag.line, 7);
        /* from a file: the length is learned with a second reader */
        const char *path = io_test_path("zeros.ply.gz");
        CHECK(io_test_spill(path, gz, size));
        mt_face_list list;
        CHECK_STATUS(mt_read_file(path, MT_FORMAT_AUTO, &list, &diag), MT_ERR_PARSE);
        CHECK(strstr(diag.message, "only 268435456 follow") != NULL);
    }
    free(gz);
    free(tail);

    /* OFF declaring 2^31 - 1 vertices, then 256 MiB of "0 " (coordinates). */
    static const char off[] = "OFF\n2147483647 0 0\n";
    tail = io_test_gzip_repeat("0 ", 2, 64 * MIB, 4, &tail_size);
    gz = tail ? gzip_join(off, strlen(off), tail, tail_size, &size) : NULL;
    if (gz)
        expect_status(gz, size, "zeros.off.gz", NULL, MT_ERR_PARSE,
                      "the header declares 2147483647 vertices and 0 faces but only 268435456 "
                      "bytes follow");
    free(gz);

    /* A face record declaring 4e9 indices, then 128 MiB of "0 ": read to
     * its end without keeping the indices the input cannot complete. */
    static const char face[] = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 ";
    gz = tail ? gzip_join(face, strlen(face), tail, tail_size / 2, &size) : NULL;
    if (gz) {
        mt_diag diag = expect_status(gz, size, "face.off.gz", NULL, MT_ERR_PARSE,
                                     "face 0: expected 4000000000 vertex indices, found 67108864");
        CHECK_EQ(diag.line, 6);
    }
    free(gz);

    /* A PLY list declaring 4e9 entries: refused at its count. */
    static const char ascii[] =
        "ply\nformat ascii 1.0\nelement face 1\nproperty list uint int vertex_indices\n"
        "end_header\n4000000000 ";
    gz = tail ? gzip_join(ascii, strlen(ascii), tail, tail_size / 2, &size) : NULL;
    if (gz)
        expect_status(gz, size, "list.ply.gz", NULL, MT_ERR_PARSE,
                      "face 0 of 1: property 'vertex_indices': list count larger than the rest "
                      "of the file: '4000000000'");
    free(gz);
    free(tail);
    unsigned char bin[256];
    n = (size_t)snprintf((char *)bin, sizeof bin,
                         "ply\nformat binary_little_endian 1.0\nelement face 1\n"
                         "property list uint int vertex_indices\nend_header\n");
    memcpy(bin + n, "\x00\x28\x6b\xee", 4); /* 4e9 */
    tail = io_test_gzip_repeat("\0", 1, 64 * MIB, 2, &tail_size);
    gz = tail ? gzip_join((const char *)bin, n + 4, tail, tail_size, &size) : NULL;
    if (gz) {
        mt_diag diag = expect_status(gz, size, "list.ply.gz", NULL, MT_ERR_PARSE,
                                     "face 0 of 1: property 'vertex_indices': the list runs past "
                                     "the end of the data");
        CHECK_EQ(diag.byte_offset, n + 4);
    }
    free(gz);
    free(tail);
    CHECK(peak_rss_mib() < 150);
}

static void test_bounded_input_limit(void)
{
    size_t len = strlen(MESH);
    mt_read_options options;
    memset(&options, 0, sizeof options);
    options.max_input_bytes = len;
    expect_status(MESH, len, "l.off", &options, MT_OK, NULL);
    options.max_input_bytes = len - 1;
    char want[128];
    snprintf(want, sizeof want, "l.off: %zu bytes: more than the input limit of %zu bytes", len,
             len - 1);
    expect_status(MESH, len, "l.off", &options, MT_ERR_TOO_LARGE, want);
    options.window_bytes = 5;
    expect_status(MESH, len, "l.off", &options, MT_ERR_TOO_LARGE, want);
    options.window_bytes = 0;

    /* gzip: the limit counts inflated bytes. */
    size_t size;
    unsigned char *gz = io_test_gzip_stored(MESH, len, &size);
    if (!gz) return;
    options.max_input_bytes = len;
    expect_status(gz, size, "l.off.gz", &options, MT_OK, NULL);
    options.max_input_bytes = len - 1;
    snprintf(want, sizeof want, "gzip data inflates to more than the input limit of %zu bytes",
             len - 1);
    expect_status(gz, size, "l.off.gz", &options, MT_ERR_TOO_LARGE, want);

    /* Files, plain (refused before reading) and gzip. */
    const char *plain = io_test_path("l.off"), *packed = io_test_path("l.off.gz");
    CHECK(io_test_spill(plain, MESH, len));
    CHECK(io_test_spill(packed, gz, size));
    mt_face_list list;
    mt_diag diag;
    CHECK_STATUS(mt_read_file_with(plain, MT_FORMAT_AUTO, &options, &list, &diag),
                 MT_ERR_TOO_LARGE);
    CHECK(strstr(diag.message, "more than the input limit of") != NULL);
    CHECK_STATUS(mt_read_file_with(packed, MT_FORMAT_AUTO, &options, &list, &diag),
                 MT_ERR_TOO_LARGE);
    CHECK(strstr(diag.message, want) != NULL);
    options.max_input_bytes = 0; /* the default */
    CHECK_OK(mt_read_file_with(packed, MT_FORMAT_AUTO, &options, &list, &diag));
    mt_face_list_free(&list);
    CHECK_OK(mt_read_file_with(plain, MT_FORMAT_AUTO, NULL, &list, &diag));
    mt_face_list_free(&list);
    free(gz);

    /* A gigabyte of gzip'd newlines between the counts and the vertices
     * (whitespace OFF allows): the limit stops it. */
    static const char head[] = "OFF\n3 1 0\n";
    size_t tail_size;
    unsigned char *tail = io_test_gzip_repeat("\n", 1, 64 * MIB, 16, &tail_size);
    gz = tail ? gzip_join(head, strlen(head), tail, tail_size, &size) : NULL;
    if (gz) {
        options.max_input_bytes = 32 * MIB;
        expect_status(gz, size, "ws.off.gz", &options, MT_ERR_TOO_LARGE,
                      "gzip data inflates to more than the input limit of 33554432 bytes");
    }
    free(gz);
    free(tail);
}

/* Reads text from a pipe (a length not known) as OFF. */
static mt_status read_piped(const char *text, size_t len, const mt_read_options *options,
                            mt_diag *diag)
{
    int fds[2];
    if (pipe(fds) != 0) return MT_ERR_IO;
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        size_t done = 0;
        while (done < len) {
            ssize_t k = write(fds[1], text + done, len - done);
            if (k <= 0) break; /* the reader stopped */
            done += (size_t)k;
        }
        _exit(0);
    }
    close(fds[1]);
    mt_face_list list;
    mt_status status =
        pid < 0 ? MT_ERR_IO
                : mt_read_fd_with(fds[0], "piped.off", MT_FORMAT_OFF, options, &list, diag);
    if (status == MT_OK) mt_face_list_free(&list);
    close(fds[0]);
    if (pid > 0) waitpid(pid, NULL, 0);
    return status;
}

/* The next window is read ahead while threads parse the current one; the
 * input limit met that far ahead must not hide an error before it. Each
 * limit after a bad face gives what one thread, which reads nothing ahead,
 * gives: the face's error, or the limit where the window holding the face
 * reaches it. */
static void test_bounded_limit_read_ahead(void)
{
    size_t cap = 8 * MIB, len = 0;
    char *text = malloc(cap);
    CHECK(text != NULL);
    if (!text) return;
    const uint32_t verts = 1000, faces = 400000, bad = 200000;
    len += (size_t)snprintf(text, cap, "OFF\n%u %u 0\n", verts, faces);
    for (uint32_t v = 0; v < verts; v++)
        len += (size_t)snprintf(text + len, cap - len, "%u 0 0\n", v);
    size_t bad_at = 0;
    for (uint32_t f = 0; f < faces; f++) {
        if (f == bad) {
            bad_at = len;
            len += (size_t)snprintf(text + len, cap - len, "3 1 2 x\n");
            continue;
        }
        len += (size_t)snprintf(text + len, cap - len, "3 %u %u %u\n", f % verts, (f + 1) % verts,
                                (f + 2) % verts);
    }
    mt_read_options options;
    memset(&options, 0, sizeof options);
    options.window_bytes = (size_t)3 << 19;
    int parse_errors = 0;
    for (size_t limit = bad_at + MIB / 4; limit < len; limit += MIB / 4) {
        options.max_input_bytes = limit;
        mt_diag one, two;
        options.threads = 1;
        mt_status want = read_piped(text, len, &options, &one);
        options.threads = 2;
        CHECK_STATUS(read_piped(text, len, &options, &two), want);
        if (strcmp(one.message, two.message) != 0)
            mt_test_fail(__FILE__, __LINE__, "limit %zu: '%s' != '%s'", limit, two.message,
                         one.message);
        parse_errors += want == MT_ERR_PARSE;
    }
    CHECK(parse_errors > 0); /* some limits lie past the bad face's window */
    free(text);
}

static void test_bounded_long_token(void)
{
    /* In streamed input a token may widen the window up to
     * MT_READ_MAX_HELD_BYTES; past that it is refused. */
    static const char head[] = "OFF\n1 0 0\n";
    size_t tail_size, size;
    unsigned char *tail = io_test_gzip_repeat("7", 1, 2 * MT_READ_MAX_HELD_BYTES, 1, &tail_size);
    unsigned char *gz = tail ? gzip_join(head, strlen(head), tail, tail_size, &size) : NULL;
    if (gz) {
        mt_diag diag = expect_status(gz, size, "long.off.gz", NULL, MT_ERR_TOO_LARGE,
                                     "more than 4194304 bytes without whitespace");
        CHECK_EQ(diag.line, 3);
    }
    free(gz);
    free(tail);
    /* A long token and a long PLY header within that are read. */
    size_t comments = 300000;
    size_t cap = comments * 10 + 200000;
    char *text = malloc(cap);
    if (!text) return;
    size_t o = (size_t)snprintf(text, cap, "ply\nformat ascii 1.0\n");
    for (size_t k = 0; k < comments; k++)
        o += (size_t)snprintf(text + o, cap - o, "comment %zu\n", k % 10);
    o += (size_t)snprintf(text + o, cap - o,
                          "element vertex 1\nproperty double x\nproperty double y\n"
                          "property double z\nend_header\n1 2 1");
    memset(text + o, '0', 100000); /* 1e100000: a coordinate of 100001 characters */
    o += 100000;
    text[o++] = '\n';
    mt_read_options options;
    memset(&options, 0, sizeof options);
    options.window_bytes = 4096;
    mt_face_list list;
    mt_diag diag;
    CHECK_OK(mt_read_memory_with(text, o, MT_FORMAT_AUTO, "h.ply", &options, &list, &diag));
    CHECK_EQ(list.num_verts, 1);
    if (list.num_verts == 1) CHECK(list.positions[2] > 1e99);
    mt_face_list_free(&list);
    free(text);
}

/* Writes `list` to NAME in its format and reads it back through windows of
 * several sizes (and whole): all the same. */
static void check_windows(const mt_face_list *list, const char *name, mt_format format)
{
    const char *path = io_test_path(name);
    mt_diag diag;
    CHECK_OK(mt_write_file(path, format, list, &diag));
    static const size_t windows[] = {1, 7, 4096, 0};
    for (size_t k = 0; k < sizeof windows / sizeof windows[0]; k++) {
        mt_read_options options;
        memset(&options, 0, sizeof options);
        options.window_bytes = windows[k];
        mt_face_list back;
        mt_status status = mt_read_file_with(path, MT_FORMAT_AUTO, &options, &back, &diag);
        if (status != MT_OK) {
            mt_test_fail(__FILE__, __LINE__, "%s, window %zu: %s", name, windows[k], diag.message);
            continue;
        }
        char what[96];
        snprintf(what, sizeof what, "%s through a window of %zu", name, windows[k]);
        io_test_check_same(list, &back, what);
        mt_face_list_free(&back);
    }
}

static void test_bounded_windows_match_whole(void)
{
    mt_face_list list;
    CHECK_OK(mt_gen_grid(60, 40, true, &list));
    for (uint64_t k = 0; k < 3ull * list.num_verts; k++) list.positions[k] += 0.1 * (double)k;
    static const struct {
        const char *name;
        mt_format format;
    } files[] = {
        {"w.off", MT_FORMAT_AUTO},           {"w.obj", MT_FORMAT_AUTO},
        {"w.ply", MT_FORMAT_AUTO},           {"wa.ply", MT_FORMAT_PLY_ASCII},
        {"wb.ply", MT_FORMAT_PLY_BINARY_BE}, {"w.off.gz", MT_FORMAT_AUTO},
        {"w.obj.gz", MT_FORMAT_AUTO},        {"w.ply.gz", MT_FORMAT_AUTO},
        {"wa.ply.gz", MT_FORMAT_PLY_ASCII},
    };
    for (size_t f = 0; f < sizeof files / sizeof files[0]; f++)
        check_windows(&list, files[f].name, files[f].format);
    mt_face_list_free(&list);
}

#if !defined(UNDER_ASAN) && !defined(UNDER_TSAN)
/* Reads `text` as short.off in a child process limited to 64 MiB of
 * address space more than it has, and expects the error of a header that
 * declares more vertices than the text holds. Returns 0 when it got it.
 * Not under the sanitizers, whose shadow memory takes the address space. */
static int short_off_in_little_memory(const char *text, size_t size)
{
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        int before = mt_test_failures();
        long pages = 0;
        FILE *statm = fopen("/proc/self/statm", "r");
        CHECK(statm && fscanf(statm, "%ld", &pages) == 1);
        if (statm) fclose(statm);
        rlim_t bytes = (rlim_t)pages * (rlim_t)sysconf(_SC_PAGESIZE) + 64 * MIB;
        struct rlimit lim = {bytes, bytes};
        CHECK(setrlimit(RLIMIT_AS, &lim) == 0);
        void *probe = malloc(96 * MIB); /* the room the header asks for */
        CHECK(probe == NULL);
        free(probe);
        expect_status(text, size, "short.off", NULL, MT_ERR_PARSE,
                      "vertex 3: expected 3 coordinates, found 0 (end of file; the header "
                      "declares 4194304 vertices)");
        fflush(stdout);
        fflush(stderr);
        _exit(mt_test_failures() > before ? 1 : 0);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
    return WEXITSTATUS(status);
}
#endif

/* The counts a header declares, once checked against a known length, get
 * their room at once; where that room is not to be had (an address-space
 * limit here), the arrays grow as they are read, and a header declaring
 * more than the file holds gets the error it always got. */
static void test_bounded_room_for_declared(void)
{
    /* 4 Mi vertices declared (96 MiB of positions), 3 given, then spaces:
     * the counts fit the 24 MiB that follow, the vertices are not there */
    size_t size = 25 * MIB;
    char *text = malloc(size);
    CHECK(text != NULL);
    if (!text) return;
    int head = snprintf(text, size, "OFF\n4194304 0 0\n0 0 0\n1 0 0\n0 1 0\n");
    memset(text + head, ' ', size - (size_t)head);
    text[size - 1] = '\n';
    expect_status(text, size, "short.off", NULL, MT_ERR_PARSE,
                  "vertex 3: expected 3 coordinates, found 0 (end of file; the header declares "
                  "4194304 vertices)");
#if !defined(UNDER_ASAN) && !defined(UNDER_TSAN)
    CHECK_EQ(short_off_in_little_memory(text, size), 0);
#endif
    free(text);
}

static const mt_test_case cases[] = {
    {"bounded_gzip_generator", test_bounded_gzip_generator},
    {"bounded_trailing_data", test_bounded_trailing_data},
    {"bounded_declared_counts", test_bounded_declared_counts},
    {"bounded_input_limit", test_bounded_input_limit},
    {"bounded_long_token", test_bounded_long_token},
    {"bounded_windows_match_whole", test_bounded_windows_match_whole},
    {"bounded_room_for_declared", test_bounded_room_for_declared},
    {"bounded_limit_read_ahead", test_bounded_limit_read_ahead},
};
const mt_test_table mt_tests_io_bounded = {cases, sizeof cases / sizeof cases[0]};
