/* Helpers shared by the meshtopo::io tests (see io_test_util.h). */
#include "io_test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness.h"

#define MAX_PATHS 256

static char dir[64];
static char *paths[MAX_PATHS];
static int num_paths;

static void cleanup(void)
{
    for (int i = 0; i < num_paths; i++) {
        unlink(paths[i]);
        free(paths[i]);
    }
    if (dir[0]) rmdir(dir);
}

const char *io_test_path(const char *name)
{
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/meshtopo-io-test.XXXXXX");
        if (!mkdtemp(dir)) {
            mt_test_fail(__FILE__, __LINE__, "mkdtemp failed");
            snprintf(dir, sizeof dir, "/tmp");
        }
        atexit(cleanup);
    }
    size_t n = strlen(dir) + strlen(name) + 2;
    char *p = malloc(n);
    if (!p || num_paths == MAX_PATHS) {
        mt_test_fail(__FILE__, __LINE__, "too many temporary paths");
        free(p);
        return "/nonexistent/meshtopo-io-test";
    }
    snprintf(p, n, "%s/%s", dir, name);
    paths[num_paths++] = p;
    return p;
}

int io_test_slurp(const char *path, unsigned char **data, size_t *size)
{
    *data = NULL;
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    size_t cap = 1 << 16, len = 0;
    unsigned char *buf = malloc(cap);
    while (buf) {
        if (len == cap) {
            unsigned char *p = realloc(buf, cap * 2);
            if (!p) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = p;
            cap *= 2;
        }
        size_t k = fread(buf + len, 1, cap - len, f);
        if (k == 0) break;
        len += k;
    }
    fclose(f);
    if (!buf) return 0;
    *data = buf;
    *size = len;
    return 1;
}

int io_test_spill(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    int ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

mt_status io_test_read_text(const char *text, mt_format format, const char *name, mt_face_list *out,
                            mt_diag *diag)
{
    return io_test_read_variants_at(__FILE__, __LINE__, text, strlen(text), format, name, out,
                                    diag);
}

void io_test_check_same(const mt_face_list *a, const mt_face_list *b, const char *what)
{
    if (a->num_verts != b->num_verts || a->num_faces != b->num_faces ||
        a->num_indices != b->num_indices) {
        mt_test_fail(__FILE__, __LINE__, "%s: counts differ: V %u/%u F %u/%u I %llu/%llu", what,
                     a->num_verts, b->num_verts, a->num_faces, b->num_faces,
                     (unsigned long long)a->num_indices, (unsigned long long)b->num_indices);
        return;
    }
    for (uint32_t f = 0; f < a->num_faces; f++) {
        if (a->face_sizes[f] != b->face_sizes[f]) {
            mt_test_fail(__FILE__, __LINE__, "%s: face %u has size %u vs %u", what, f,
                         a->face_sizes[f], b->face_sizes[f]);
            return;
        }
    }
    for (uint64_t k = 0; k < a->num_indices; k++) {
        if (a->face_indices[k] != b->face_indices[k]) {
            mt_test_fail(__FILE__, __LINE__, "%s: index %llu is %u vs %u", what,
                         (unsigned long long)k, a->face_indices[k], b->face_indices[k]);
            return;
        }
    }
    for (uint64_t k = 0; k < 3ull * a->num_verts; k++) {
        double x = a->positions ? a->positions[k] : 0.0;
        double y = b->positions ? b->positions[k] : 0.0;
        if (memcmp(&x, &y, sizeof x) != 0) {
            mt_test_fail(__FILE__, __LINE__, "%s: coordinate %llu is %.17g vs %.17g", what,
                         (unsigned long long)k, x, y);
            return;
        }
    }
}

/* ---- gzip with stored blocks -------------------------------------------- */

static uint32_t crc32_of(const unsigned char *p, size_t n)
{
    uint32_t crc = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int k = 0; k < 8; k++) crc = crc & 1 ? (crc >> 1) ^ 0xedb88320u : crc >> 1;
    }
    return ~crc;
}

static void put32(unsigned char *p, uint32_t v)
{
    for (int k = 0; k < 4; k++) p[k] = (unsigned char)(v >> (8 * k));
}

unsigned char *io_test_gzip_stored(const void *data, size_t size, size_t *out_size)
{
    const unsigned char *in = data;
    size_t blocks = size / 65535 + 1;
    unsigned char *out = malloc(size + 18 + 5 * blocks);
    if (!out) return NULL;
    static const unsigned char header[10] = {0x1f, 0x8b, 8, 0, 0, 0, 0, 0, 0, 0xff};
    memcpy(out, header, sizeof header);
    size_t o = sizeof header, i = 0;
    do {
        size_t len = size - i < 65535 ? size - i : 65535;
        out[o++] = i + len == size; /* BFINAL, BTYPE 00: stored */
        out[o++] = (unsigned char)len;
        out[o++] = (unsigned char)(len >> 8);
        out[o++] = (unsigned char)~len;
        out[o++] = (unsigned char)(~len >> 8);
        if (len) memcpy(out + o, in + i, len);
        o += len;
        i += len;
    } while (i < size);
    put32(out + o, size ? crc32_of(in, size) : 0);
    put32(out + o + 4, (uint32_t)size);
    *out_size = o + 8;
    return out;
}

/* ---- gzip of a repeated pattern ------------------------------------------- */

typedef struct bit_writer {
    unsigned char *p;
    size_t len;
    uint64_t acc;
    int n;
} bit_writer;

/* Appends the n low bits of v, least significant first (RFC 1951 3.1.1). */
static void put_bits(bit_writer *w, uint32_t v, int n)
{
    w->acc |= (uint64_t)v << w->n;
    w->n += n;
    while (w->n >= 8) {
        w->p[w->len++] = (unsigned char)w->acc;
        w->acc >>= 8;
        w->n -= 8;
    }
}

/* Appends an n-bit Huffman code, most significant bit first. */
static void put_code(bit_writer *w, uint32_t code, int n)
{
    uint32_t r = 0;
    for (int k = 0; k < n; k++) r |= ((code >> k) & 1u) << (n - 1 - k);
    put_bits(w, r, n);
}

/* A literal byte in the fixed code. */
static void put_literal(bit_writer *w, unsigned char c)
{
    if (c < 144)
        put_code(w, 0x30u + c, 8);
    else
        put_code(w, 0x190u + (c - 144u), 9);
}

unsigned char *io_test_gzip_repeat(const char *pattern, size_t pattern_len, uint64_t member_size,
                                   size_t members, size_t *out_size)
{
    if (pattern_len < 1 || pattern_len > 4) return NULL;
    /* one fixed-Huffman block: the pattern as literals, then 258-byte
     * matches at distance pattern_len (13 bits each), then literals */
    uint64_t matches = member_size > pattern_len ? (member_size - pattern_len) / 258 : 0;
    size_t deflate_max = (size_t)(matches * 13 / 8) + 2 * pattern_len + 2 * 258 + 16;
    size_t member_max = deflate_max + 18;
    unsigned char *out = malloc(member_max * members + 1);
    if (!out) return NULL;
    static const unsigned char header[10] = {0x1f, 0x8b, 8, 0, 0, 0, 0, 0, 0, 0xff};
    memcpy(out, header, sizeof header);
    bit_writer w = {out + sizeof header, 0, 0, 0};
    put_bits(&w, 1, 1); /* BFINAL */
    put_bits(&w, 1, 2); /* BTYPE 01: fixed codes */
    uint64_t done = 0;
    for (; done < member_size && done < pattern_len; done++)
        put_literal(&w, (unsigned char)pattern[done]);
    for (uint64_t m = 0; m < matches; m++, done += 258) {
        put_code(&w, 0xc5, 8);                        /* length code 285: 258 */
        put_code(&w, (uint32_t)(pattern_len - 1), 5); /* distance 1 to 4 */
    }
    for (; done < member_size; done++) put_literal(&w, (unsigned char)pattern[done % pattern_len]);
    put_code(&w, 0, 7); /* end of block */
    if (w.n) put_bits(&w, 0, 8 - w.n);
    size_t o = sizeof header + w.len;
    /* CRC-32 of the content, a table at a time */
    uint32_t table[256];
    for (uint32_t k = 0; k < 256; k++) {
        uint32_t c = k;
        for (int j = 0; j < 8; j++) c = c & 1 ? (c >> 1) ^ 0xedb88320u : c >> 1;
        table[k] = c;
    }
    uint32_t crc = 0xffffffffu;
    size_t j = 0;
    for (uint64_t k = 0; k < member_size; k++) {
        crc = table[(crc ^ (unsigned char)pattern[j]) & 0xff] ^ (crc >> 8);
        if (++j == pattern_len) j = 0;
    }
    put32(out + o, ~crc);
    put32(out + o + 4, (uint32_t)member_size);
    o += 8;
    for (size_t m = 1; m < members; m++) memcpy(out + m * o, out, o);
    *out_size = o * members;
    return out;
}

/* ---- The same bytes read in several ways --------------------------------- */

/* 1 when a message reports a check of counts against the bytes that follow. */
static int is_size_check(const char *message)
{
    return strstr(message, "bytes follow") || strstr(message, "bytes of data but only") ||
           strstr(message, "larger than the rest of the file") ||
           strstr(message, "runs past the end of the data");
}

/* 1 when a message reports damaged gzip data: found when the window reaches
 * the damage, so a smaller window may meet a parse error in the bytes
 * inflated before it first. */
static int is_gzip_error(const char *message)
{
    return strstr(message, "gzip data") || strstr(message, "gzip stream");
}

/* CHECKs that reading data with `options` (or, with gzip, its stored-gzip
 * form) gives what the whole read gave. */
static void check_variant(const char *file, int line_no, const void *data, size_t size,
                          mt_format format, const char *name, const mt_read_options *options,
                          int gzip, mt_status want, const mt_face_list *want_list,
                          const mt_diag *want_diag)
{
    char what[64];
    snprintf(what, sizeof what, gzip ? "as gzip" : "through a window of %zu bytes",
             options->window_bytes);
    unsigned char *gz = NULL;
    if (gzip) {
        gz = io_test_gzip_stored(data, size, &size);
        if (!gz) return;
        data = gz;
    }
    mt_face_list list;
    mt_diag diag;
    mt_status status = mt_read_memory_with(data, size, format, name, options, &list, &diag);
    int loose = want == MT_ERR_PARSE &&
                ((gzip && is_size_check(want_diag->message)) || is_gzip_error(want_diag->message));
    if (status != want && !(loose && status != MT_OK)) {
        mt_test_fail(file, line_no, "%s: status %d (%s), whole: %d (%s)", what, (int)status,
                     diag.message, (int)want, want_diag->message);
    } else if (status == MT_OK) {
        io_test_check_same(want_list, &list, what);
    } else if (!loose &&
               (strcmp(diag.message, want_diag->message) != 0 || diag.line != want_diag->line ||
                diag.byte_offset != want_diag->byte_offset || diag.element != want_diag->element)) {
        mt_test_fail(file, line_no, "%s: '%s' (line %llu, offset %llu), whole: '%s' (%llu, %llu)",
                     what, diag.message, (unsigned long long)diag.line,
                     (unsigned long long)diag.byte_offset, want_diag->message,
                     (unsigned long long)want_diag->line,
                     (unsigned long long)want_diag->byte_offset);
    }
    if (status == MT_OK) mt_face_list_free(&list);
    free(gz);
}

mt_status io_test_read_variants_at(const char *file, int line_no, const void *data, size_t size,
                                   mt_format format, const char *name, mt_face_list *out,
                                   mt_diag *diag)
{
    mt_diag local;
    if (!diag) diag = &local;
    mt_status status = mt_read_memory(data, size, format, name, out, diag);
    static const size_t windows[] = {1, 2, 3, 5, 8, 13, 64};
    for (size_t k = 0; k < sizeof windows / sizeof windows[0]; k++) {
        mt_read_options options;
        memset(&options, 0, sizeof options);
        options.window_bytes = windows[k];
        check_variant(file, line_no, data, size, format, name, &options, 0, status, out, diag);
    }
    if (!(size >= 2 && ((const unsigned char *)data)[0] == 0x1f &&
          ((const unsigned char *)data)[1] == 0x8b)) {
        mt_read_options options;
        memset(&options, 0, sizeof options);
        for (size_t w = 0; w < 2; w++) {
            options.window_bytes = w ? 3 : 0;
            check_variant(file, line_no, data, size, format, name, &options, 1, status, out, diag);
        }
    }
    return status;
}

void io_test_expect_parse_error_at(const char *file, int line_no, const void *data, size_t size,
                                   mt_format format, const char *name, uint64_t line,
                                   uint64_t offset, const char *fragment)
{
    mt_face_list list;
    memset(&list, 0xab, sizeof list);
    mt_diag diag;
    mt_status status =
        io_test_read_variants_at(file, line_no, data, size, format, name, &list, &diag);
    if (status != MT_ERR_PARSE) {
        mt_test_fail(file, line_no, "expected MT_ERR_PARSE, got %d (%s): %s", (int)status,
                     mt_strerror(status), status == MT_OK ? "" : diag.message);
        if (status == MT_OK) mt_face_list_free(&list);
        return;
    }
    if (list.num_verts || list.num_faces || list.num_indices || list.positions || list.face_sizes ||
        list.face_indices)
        mt_test_fail(file, line_no, "the output list is not zeroed after a failure");
    if (diag.status != MT_ERR_PARSE) mt_test_fail(file, line_no, "diag.status is not set");
    char where[160];
    if (line > 0) {
        snprintf(where, sizeof where, "%s:%llu: ", name, (unsigned long long)line);
        if (diag.line != line)
            mt_test_fail(file, line_no, "diag.line is %llu, expected %llu (%s)",
                         (unsigned long long)diag.line, (unsigned long long)line, diag.message);
    } else if (offset == UINT64_MAX) {
        snprintf(where, sizeof where, "%s: byte offset ", name);
        if (diag.byte_offset == UINT64_MAX || diag.line != 0)
            mt_test_fail(file, line_no, "diag.byte_offset is not set, or diag.line is (%s)",
                         diag.message);
    } else {
        snprintf(where, sizeof where, "%s: byte offset %llu: ", name, (unsigned long long)offset);
        if (diag.byte_offset != offset)
            mt_test_fail(file, line_no, "diag.byte_offset is %llu, expected %llu (%s)",
                         (unsigned long long)diag.byte_offset, (unsigned long long)offset,
                         diag.message);
    }
    if (strncmp(diag.message, where, strlen(where)) != 0)
        mt_test_fail(file, line_no, "message '%s' does not start with '%s'", diag.message, where);
    if (!strstr(diag.message, fragment))
        mt_test_fail(file, line_no, "message '%s' does not contain '%s'", diag.message, fragment);
}
