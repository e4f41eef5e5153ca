/* OFF files (Geomview's Object File Format, ASCII): reading and writing.
 * Headers OFF, COFF, NOFF, CNOFF, STOFF and combinations (per-vertex
 * colours, normals and texture coordinates after x y z are skipped to the
 * end of the line); '#' comments anywhere; a face record "n i0 ... i(n-1)"
 * of any n, possibly over several lines, with any colour values after its
 * indices skipped to the end of the line. Counts are checked against the
 * bytes that follow before anything is allocated. */
#include <stdio.h>

#include "io_internal.h"

/* Next token: skips whitespace and comments. Returns 0 at the end. */
static inline int next_token(const unsigned char *d, size_t n, size_t *pos, size_t *start,
                             size_t *len)
{
    size_t i = *pos;
    for (;;) {
        while (i < n && mt__is_space(d[i])) i++;
        if (i < n && d[i] == '#') {
            i = mt__line_end(d, n, i);
            continue;
        }
        break;
    }
    *pos = i;
    if (i >= n) return 0;
    size_t s = i;
    while (i < n && !mt__is_space(d[i]) && d[i] != '#') i++;
    *start = s;
    *len = i - s;
    *pos = i;
    return 1;
}

/* The end of the line at i: its '\n' or '\r' (so that files with '\r'
 * line ends read too), or n. */
static inline size_t rest_of_line(const unsigned char *d, size_t n, size_t i)
{
    while (i < n && d[i] != '\n' && d[i] != '\r') i++;
    return i;
}

/* Recognises [ST][C][N]OFF; *extras is set when per-vertex values follow
 * x y z. 4OFF and nOFF (other dimensions) are reported as unsupported. */
typedef enum off_header { OFF_NOT, OFF_OK, OFF_OTHER_DIM } off_header;

static off_header parse_header(const unsigned char *t, size_t len, int *extras)
{
    size_t i = 0;
    if (len >= 2 && t[0] == 'S' && t[1] == 'T') i += 2;
    if (i < len && t[i] == 'C') i++;
    if (i < len && t[i] == 'N') i++;
    off_header ok = OFF_OK;
    if (i < len && (t[i] == '4' || t[i] == 'n')) {
        ok = OFF_OTHER_DIM;
        i++;
    }
    if (len - i != 3 || memcmp(t + i, "OFF", 3) != 0) return OFF_NOT;
    *extras = i > 0;
    return ok;
}

int mt__looks_like_off(const mt__io_src *src)
{
    size_t pos = 0, start, len;
    int extras;
    if (!next_token(src->data, src->size, &pos, &start, &len)) return 0;
    return parse_header(src->data + start, len, &extras) != OFF_NOT;
}

/* Fails with the token at [start, start + len) quoted. */
static mt_status fail_token(mt_diag *diag, const mt__io_src *src, size_t start, size_t len,
                            uint32_t element, const char *what)
{
    char excerpt[64];
    mt__io_excerpt(excerpt, sizeof excerpt, src->data + start, len);
    return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, start, element, "%s, found '%s'",
                       what, excerpt);
}

/* Reads "V F [E]": *pos ends past the counts line, *at is where V is. */
static mt_status read_counts(const mt__io_src *src, size_t *pos, size_t *at, uint64_t *counts,
                             mt_diag *diag)
{
    static const char *const what[2] = {"vertex count", "face count"};
    const unsigned char *d = src->data;
    *at = *pos;
    for (int k = 0; k < 2; k++) {
        size_t start, len;
        if (!next_token(d, src->size, pos, &start, &len))
            return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->size, MT_NONE,
                               "missing the %s after the OFF header (end of file)", what[k]);
        if (k == 0) *at = start;
        mt__num r = mt__parse_count(d + start, len, &counts[k]);
        if (r == MT__NUM_BAD) {
            char msg[64];
            snprintf(msg, sizeof msg, "expected the %s", what[k]);
            return fail_token(diag, src, start, len, MT_NONE, msg);
        }
        if (r == MT__NUM_RANGE || counts[k] > (k == 0 ? MT__IO_MAX_VERTS : UINT32_MAX)) {
            char msg[64];
            snprintf(msg, sizeof msg, "%s too large", what[k]);
            return fail_token(diag, src, start, len, MT_NONE, msg);
        }
    }
    *pos = rest_of_line(d, src->size, *pos); /* the edge count and anything else */
    if (*pos < src->size) (*pos)++;
    return MT_OK;
}

static mt_status read_verts(const mt__io_src *src, size_t *pos, uint32_t num_verts, int extras,
                            mt__builder *b, mt_diag *diag)
{
    const unsigned char *d = src->data;
    size_t n = src->size;
    size_t i = *pos;
    double *p = b->positions;
    for (uint32_t v = 0; v < num_verts; v++) {
        size_t first = i;
        for (int k = 0; k < 3; k++) {
            /* Fast path: a plain decimal after plain whitespace. */
            while (i < n && mt__is_space(d[i])) i++;
            double *x = &p[3 * (size_t)v + (size_t)k];
            size_t used = i < n ? mt__scan_decimal(d + i, d + n, x) : 0;
            if (used && (i + used == n || mt__is_space(d[i + used]) || d[i + used] == '#')) {
                i += used;
                continue;
            }
            size_t start, len;
            if (!next_token(d, n, &i, &start, &len)) {
                while (first < n && mt__is_space(d[first])) first++;
                return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, first, v,
                                   "vertex %u: expected 3 coordinates, found %d (end of file; "
                                   "the header declares %u vertices)",
                                   v, k, num_verts);
            }
            if (!mt__parse_double(d + start, len, x)) {
                char msg[96];
                snprintf(msg, sizeof msg, "vertex %u: coordinate %d is not a number", v, k);
                return fail_token(diag, src, start, len, v, msg);
            }
        }
        if (extras) i = rest_of_line(d, n, i);
    }
    b->num_verts = num_verts;
    *pos = i;
    return MT_OK;
}

static mt_status read_faces(const mt__io_src *src, size_t *pos, uint32_t num_faces, mt__builder *b,
                            mt_diag *diag)
{
    const unsigned char *d = src->data;
    size_t n = src->size;
    size_t i = *pos;
    for (uint32_t f = 0; f < num_faces; f++) {
        size_t start, len;
        if (!next_token(d, n, &i, &start, &len))
            return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, n, f,
                               "face %u: expected a face record, found the end of file (the "
                               "header declares %u faces)",
                               f, num_faces);
        size_t face_start = start;
        uint64_t size;
        mt__num r = mt__parse_count(d + start, len, &size);
        if (r == MT__NUM_BAD) {
            char msg[96];
            snprintf(msg, sizeof msg, "face %u: expected the number of vertex indices", f);
            return fail_token(diag, src, start, len, f, msg);
        }
        if (r == MT__NUM_RANGE || size > UINT32_MAX) {
            char msg[96];
            snprintf(msg, sizeof msg, "face %u: vertex count too large", f);
            return fail_token(diag, src, start, len, f, msg);
        }
        /* Room for what the rest of the file can hold (2 bytes an index at
         * least); a larger count runs into the end of the file below. */
        uint64_t room = (uint64_t)(n - i) / 2 + 1;
        if (!mt__builder_reserve_indices(b, b->num_indices + (size_t)(size < room ? size : room)))
            return mt__io_fail_nomem(diag, src);
        for (uint32_t j = 0; j < (uint32_t)size; j++) {
            int64_t index;
            while (i < n && mt__is_space(d[i])) i++;
            if (mt__scan_index(d, n, &i, '#', &index)) { /* fast path */
                if (!mt__builder_add_index(b, (uint32_t)index)) return mt__io_fail_nomem(diag, src);
                continue;
            }
            if (!next_token(d, n, &i, &start, &len))
                return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, face_start, f,
                                   "face %u: expected %u vertex indices, found %u", f,
                                   (uint32_t)size, j);
            r = mt__parse_index(d + start, len, &index);
            if (r != MT__NUM_OK) {
                char msg[128];
                snprintf(
                    msg, sizeof msg, "face %u: vertex index %u %s", f, j,
                    r == MT__NUM_BAD ? "is not an integer" : "does not fit in a 32-bit integer");
                return fail_token(diag, src, start, len, f, msg);
            }
            if (!mt__builder_add_index(b, (uint32_t)index)) return mt__io_fail_nomem(diag, src);
        }
        b->sizes[f] = (uint32_t)size;
        i = rest_of_line(d, n, i); /* colour values, if any */
    }
    b->num_faces = num_faces;
    *pos = i;
    return MT_OK;
}

static mt_status read_off(const mt__io_src *src, mt__builder *b, mt_diag *diag)
{
    const unsigned char *d = src->data;
    size_t n = src->size;
    size_t pos = 0, start, len;
    int extras = 0;
    if (!next_token(d, n, &pos, &start, &len))
        return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, n, MT_NONE,
                           "empty file: expected an OFF header");
    off_header h = parse_header(d + start, len, &extras);
    if (h == OFF_NOT) return fail_token(diag, src, start, len, MT_NONE, "expected an OFF header");
    if (h == OFF_OTHER_DIM)
        return mt__io_fail(diag, MT_ERR_UNSUPPORTED, src, MT__POS_LINE, start, MT_NONE,
                           "OFF files of other than 3 dimensions are not supported");
    size_t rest = pos;
    while (rest < n && (d[rest] == ' ' || d[rest] == '\t')) rest++;
    if (n - rest >= 6 && memcmp(d + rest, "BINARY", 6) == 0)
        return mt__io_fail(diag, MT_ERR_UNSUPPORTED, src, MT__POS_LINE, rest, MT_NONE,
                           "binary OFF is not supported");

    uint64_t counts[2];
    size_t counts_at;
    mt_status status = read_counts(src, &pos, &counts_at, counts, diag);
    if (status != MT_OK) return status;
    /* Every vertex is 3 tokens, every face at least 1, and tokens need a
     * separator: 2 bytes each, bar the last. */
    uint64_t tokens = 3 * counts[0] + counts[1];
    if (tokens > ((uint64_t)(n - pos) + 1) / 2)
        return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, counts_at, MT_NONE,
                           "the header declares %llu vertices and %llu faces but only %zu "
                           "bytes follow",
                           (unsigned long long)counts[0], (unsigned long long)counts[1], n - pos);
    uint64_t index_guess = 3 * counts[1];
    if (index_guess > ((uint64_t)(n - pos) + 1) / 2) index_guess = ((uint64_t)(n - pos) + 1) / 2;
    if (!mt__builder_reserve_verts(b, (size_t)counts[0]) ||
        !mt__builder_reserve_faces(b, (size_t)counts[1]) ||
        !mt__builder_reserve_indices(b, (size_t)index_guess))
        return mt__io_fail_nomem(diag, src);

    status = read_verts(src, &pos, (uint32_t)counts[0], extras, b, diag);
    if (status != MT_OK) return status;
    status = read_faces(src, &pos, (uint32_t)counts[1], b, diag);
    if (status != MT_OK) return status;
    if (next_token(d, n, &pos, &start, &len)) {
        char msg[128];
        snprintf(msg, sizeof msg, "unexpected data after the last face (the header declares %u)",
                 (uint32_t)counts[1]);
        return fail_token(diag, src, start, len, MT_NONE, msg);
    }
    return MT_OK;
}

mt_status mt__read_off(const mt__io_src *src, mt_face_list *out, mt_diag *diag)
{
    mt__builder b;
    memset(&b, 0, sizeof b);
    mt_status status = read_off(src, &b, diag);
    if (status == MT_OK) status = mt__builder_finish(&b, out, src, diag);
    mt__builder_free(&b);
    return status;
}

/* ---- Writing ----------------------------------------------------------- */

mt_status mt__write_off(mt__sink *s, const mt_face_list *list, mt_diag *diag)
{
    char *p = mt__sink_reserve(s, 64);
    int k = snprintf(p, 64, "OFF\n%u %u 0\n", list->num_verts, list->num_faces);
    mt__sink_commit(s, (size_t)k);
    for (uint32_t v = 0; v < list->num_verts; v++) {
        p = mt__sink_reserve(s, 100);
        size_t o = 0;
        for (int c = 0; c < 3; c++) {
            double x = list->positions ? list->positions[3 * (size_t)v + (size_t)c] : 0.0;
            o += mt__format_double(x, p + o);
            p[o++] = c < 2 ? ' ' : '\n';
        }
        mt__sink_commit(s, o);
    }
    const uint32_t *idx = list->face_indices;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        uint32_t size = list->face_sizes[f];
        p = mt__sink_reserve(s, 32);
        size_t o = mt__format_i64(size, p);
        mt__sink_commit(s, o);
        for (uint32_t j = 0; j < size; j++) {
            p = mt__sink_reserve(s, 32);
            p[0] = ' ';
            o = 1 + mt__format_i64(mt_index_as_signed(*idx++), p + 1);
            mt__sink_commit(s, o);
        }
        mt__sink_write(s, "\n", 1);
    }
    return MT_OK;
}
