/* OFF files (Geomview's Object File Format, ASCII): reading and writing.
 * Headers OFF, COFF, NOFF, CNOFF, STOFF and combinations (per-vertex
 * colours, normals and texture coordinates after x y z are skipped to the
 * end of the line); '#' comments anywhere; a face record "n i0 ... i(n-1)"
 * of any n, possibly over several lines, with any colour values after its
 * indices skipped to the end of the line. The counts are checked against
 * the bytes that follow (as soon as their number is known), arrays grow as
 * records are read, and after the last face reading stops: only
 * MT_READ_MAX_TRAILING_BYTES of whitespace and comments may follow. */
#include <stdio.h>

#include "io_internal.h"

/* Next token: skips whitespace and comments, moving the window on. Returns
 * 0 at the end of the input. */
static int next_token(mt__io_src *src, size_t *pos, size_t *start, size_t *len)
{
    size_t i = *pos;
    int in_comment = 0;
    for (;;) {
        const unsigned char *d = src->data;
        size_t n = src->size;
        for (;;) {
            if (in_comment) {
                const unsigned char *nl = i < n ? memchr(d + i, '\n', n - i) : NULL;
                if (!nl) {
                    i = n;
                    break;
                }
                i = (size_t)(nl - d);
                in_comment = 0;
            }
            while (i < n && mt__is_space(d[i])) i++;
            if (i < n && d[i] == '#') {
                in_comment = 1;
                i++;
                continue;
            }
            break;
        }
        if (i < n) {
            size_t s = i;
            while (i < n && !mt__is_space(d[i]) && d[i] != '#') i++;
            *start = s;
            *len = i - s;
            *pos = i;
            return 1;
        }
        if (!mt__src_more(src, &i)) {
            *pos = i;
            return 0;
        }
    }
}

/* Whitespace from i on (not comments), moving the window on. */
static size_t skip_space(mt__io_src *src, size_t i)
{
    for (;;) {
        const unsigned char *d = src->data;
        size_t n = src->size;
        while (i < n && mt__is_space(d[i])) i++;
        if (i < n || !mt__src_more(src, &i)) return i;
    }
}

/* The end of the line at i: its '\n' or '\r' (so that files with '\r'
 * line ends read too), or the end of the input. */
static size_t rest_of_line(mt__io_src *src, size_t i)
{
    for (;;) {
        const unsigned char *d = src->data;
        size_t n = src->size;
        while (i < n && d[i] != '\n' && d[i] != '\r') i++;
        if (i < n || !mt__src_more(src, &i)) return i;
    }
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
    const unsigned char *d = src->data;
    size_t n = src->size, i = 0;
    for (;;) {
        while (i < n && mt__is_space(d[i])) i++;
        if (i < n && d[i] == '#') {
            i = mt__line_end(d, n, i);
            if (i == n && !src->eof) return -1;
            continue;
        }
        break;
    }
    if (i >= n) return src->eof ? 0 : -1;
    size_t s = i;
    while (i < n && !mt__is_space(d[i]) && d[i] != '#') i++;
    int extras;
    return parse_header(d + s, i - s, &extras) != OFF_NOT;
}

/* Fails with the token at window index [start, start + len) quoted. */
static mt_status fail_token(mt_diag *diag, const mt__io_src *src, size_t start, size_t len,
                            uint32_t element, const char *what)
{
    char excerpt[64];
    mt__io_excerpt(excerpt, sizeof excerpt, src->data + start, len);
    return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->base + start, element,
                       "%s, found '%s'", what, excerpt);
}

/* The counts line "V F [E]". */
typedef struct off_counts {
    uint64_t verts, faces;
    uint64_t at, line; /* input offset and line of V */
    uint64_t after;    /* input offset just past the counts line */
} off_counts;

/* Reads "V F [E]": *pos ends past the counts line. */
static mt_status read_counts(mt__io_src *src, size_t *pos, off_counts *c, mt_diag *diag)
{
    static const char *const what[2] = {"vertex count", "face count"};
    uint64_t counts[2];
    for (int k = 0; k < 2; k++) {
        size_t start, len;
        if (!next_token(src, pos, &start, &len))
            return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->base + src->size,
                               MT_NONE, "missing the %s after the OFF header (end of file)",
                               what[k]);
        if (k == 0) {
            c->at = src->base + start;
            c->line = mt__src_line(src, c->at);
        }
        mt__num r = mt__parse_count(src->data + start, len, &counts[k]);
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
    c->verts = counts[0];
    c->faces = counts[1];
    *pos = rest_of_line(src, *pos); /* the edge count and anything else */
    if (*pos < src->size) (*pos)++;
    c->after = src->base + *pos;
    return MT_OK;
}

/* Every vertex is 3 tokens, every face at least 1, and tokens need a
 * separator: 2 bytes each, bar the last. Checked as soon as the input's
 * length is known: at once, or (gzip) when the input ends early. */
static mt_status check_counts(const mt__io_src *src, const off_counts *c, mt_diag *diag)
{
    uint64_t length = mt__src_length(src);
    if (length == MT__UNKNOWN) return MT_OK;
    uint64_t follow = length > c->after ? length - c->after : 0;
    uint64_t tokens = 3 * c->verts + c->faces;
    if (tokens > (follow + 1) / 2)
        return mt__io_fail_line(diag, MT_ERR_PARSE, src, c->at, c->line, MT_NONE,
                                "the header declares %llu vertices and %llu faces but only %llu "
                                "bytes follow",
                                (unsigned long long)c->verts, (unsigned long long)c->faces,
                                (unsigned long long)follow);
    return MT_OK;
}

/* Before the face list of input whose length is unknown grows large: the
 * length is learned (if it can be) and the counts checked against it. */
typedef struct off_confirm {
    mt__io_src *src;
    const off_counts *counts;
} off_confirm;

static mt_status confirm_counts(void *ctx, mt_diag *diag)
{
    off_confirm *c = ctx;
    mt__src_learn_length(c->src);
    return check_counts(c->src, c->counts, diag);
}

/* Bytes of input after window index i: all of them when the length is
 * known, else those in the window. */
static uint64_t bytes_after(const mt__io_src *src, size_t i)
{
    uint64_t length = mt__src_length(src), at = src->base + i;
    if (length == MT__UNKNOWN) return src->size - i;
    return length > at ? length - at : 0;
}

static mt_status read_verts(mt__io_src *src, size_t *pos, const off_counts *c, int extras,
                            mt__builder *b, mt_diag *diag)
{
    uint32_t num_verts = (uint32_t)c->verts;
    const unsigned char *d = src->data;
    size_t n = src->size;
    size_t i = *pos, cap = 0;
    double *p = NULL;
    mt__bulk_spec plain = {.ops = {MT__BULK_X, MT__BULK_Y, MT__BULK_Z, MT__BULK_REST},
                           .num_ops = extras ? 4 : 3};
    for (uint32_t v = 0; v < num_verts; v++) {
        if (v >= cap) {
            cap = mt__builder_ahead(v, num_verts);
            if (!mt__builder_reserve_verts(b, cap)) return mt__builder_fail(b, src, diag);
            p = b->positions;
        }
        /* A vertex starts at its first non-space byte: messages point there. */
        while (i < n && mt__is_space(d[i])) i++;
        if (i == n) {
            i = skip_space(src, i);
            d = src->data;
            n = src->size;
        }
        /* Lines of plain vertices from here on: io_bulk.c reads them. */
        if (i > 0 && i < n && d[i - 1] == '\n') {
            uint64_t got = mt__bulk_parse(src, &plain, &i, v, num_verts, b);
            if (got) {
                v += (uint32_t)got - 1;
                p = b->positions;
                cap = b->cap_verts;
                continue;
            }
        }
        src->mark = src->base + i;
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
            int found = next_token(src, &i, &start, &len);
            d = src->data;
            n = src->size;
            if (!found) {
                mt_status status = check_counts(src, c, diag);
                if (status != MT_OK) return status;
                return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->mark, v,
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
        if (extras) {
            i = rest_of_line(src, i);
            d = src->data;
            n = src->size;
        }
    }
    b->num_verts = num_verts;
    *pos = i;
    return MT_OK;
}

static mt_status read_faces(mt__io_src *src, size_t *pos, const off_counts *c, mt__builder *b,
                            mt_diag *diag)
{
    uint32_t num_faces = (uint32_t)c->faces;
    size_t i = *pos, cap = 0;
    mt__bulk_spec plain = {.ops = {MT__BULK_INDICES, MT__BULK_REST}, .num_ops = 2, .faces = 1};
    for (uint32_t f = 0; f < num_faces; f++) {
        if (f >= cap) {
            cap = mt__builder_ahead(f, num_faces);
            if (!mt__builder_reserve_faces(b, cap) ||
                !mt__builder_reserve_indices(b, b->num_indices + 3 * (cap - f)))
                return mt__builder_fail(b, src, diag);
        }
        /* Lines of plain faces from here on: io_bulk.c reads them. */
        while (i < src->size && mt__is_space(src->data[i])) i++;
        if (i > 0 && i < src->size && src->data[i - 1] == '\n') {
            uint64_t got = mt__bulk_parse(src, &plain, &i, f, num_faces, b);
            if (got) {
                f += (uint32_t)got - 1;
                cap = b->cap_faces;
                continue;
            }
        }
        size_t start, len;
        int found = next_token(src, &i, &start, &len);
        const unsigned char *d = src->data;
        size_t n = src->size;
        if (!found) {
            mt_status status = check_counts(src, c, diag);
            if (status != MT_OK) return status;
            return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->base + n, f,
                               "face %u: expected a face record, found the end of file (the "
                               "header declares %u faces)",
                               f, num_faces);
        }
        src->mark = src->base + start; /* the face's messages point at its count */
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
        /* Every index needs 2 bytes at least. A record longer than the rest
         * of the input can hold is read to its failure without being kept
         * (a long one makes the reader learn the input's length first). */
        if (size > MT__IO_BIG_LIST) mt__src_learn_length(src);
        uint64_t room = bytes_after(src, i) / 2;
        int keep = mt__src_length(src) == MT__UNKNOWN || size <= room;
        if (keep && !mt__builder_reserve_indices(
                        b, b->num_indices + (size_t)(size < room + 1 ? size : room + 1)))
            return mt__builder_fail(b, src, diag);
        for (uint32_t j = 0; j < (uint32_t)size; j++) {
            int64_t index;
            while (i < n && mt__is_space(d[i])) i++;
            if (mt__scan_index(d, n, &i, '#', &index)) { /* fast path */
                if (keep && !mt__builder_add_index(b, (uint32_t)index))
                    return mt__builder_fail(b, src, diag);
                continue;
            }
            found = next_token(src, &i, &start, &len);
            d = src->data;
            n = src->size;
            if (!found) {
                mt_status status = check_counts(src, c, diag);
                if (status != MT_OK) return status;
                return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->mark, f,
                                   "face %u: expected %u vertex indices, found %u", f,
                                   (uint32_t)size, j);
            }
            r = mt__parse_index(d + start, len, &index);
            if (r != MT__NUM_OK) {
                char msg[128];
                snprintf(
                    msg, sizeof msg, "face %u: vertex index %u %s", f, j,
                    r == MT__NUM_BAD ? "is not an integer" : "does not fit in a 32-bit integer");
                return fail_token(diag, src, start, len, f, msg);
            }
            if (keep && !mt__builder_add_index(b, (uint32_t)index))
                return mt__builder_fail(b, src, diag);
        }
        if (!keep) /* cannot be: the input was too short for the record */
            return mt__io_fail(diag, MT_ERR_IO, src, MT__POS_LINE, src->mark, f,
                               "face %u: the input grew while it was read", f);
        b->sizes[f] = (uint32_t)size;
        i = rest_of_line(src, i); /* colour values, if any */
    }
    b->num_faces = num_faces;
    *pos = i;
    return MT_OK;
}

static mt_status read_off(mt__io_src *src, mt__builder *b, mt_diag *diag)
{
    size_t pos = 0, start, len;
    int extras = 0;
    if (!next_token(src, &pos, &start, &len))
        return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->base + src->size, MT_NONE,
                           "empty file: expected an OFF header");
    off_header h = parse_header(src->data + start, len, &extras);
    if (h == OFF_NOT) return fail_token(diag, src, start, len, MT_NONE, "expected an OFF header");
    if (h == OFF_OTHER_DIM)
        return mt__io_fail(diag, MT_ERR_UNSUPPORTED, src, MT__POS_LINE, src->base + start, MT_NONE,
                           "OFF files of other than 3 dimensions are not supported");
    /* "BINARY" on the header line: enough of the line must be in view. */
    for (;;) {
        while (pos < src->size && (src->data[pos] == ' ' || src->data[pos] == '\t')) pos++;
        if (src->size - pos >= 6 || !mt__src_more(src, &pos)) break;
    }
    if (src->size - pos >= 6 && memcmp(src->data + pos, "BINARY", 6) == 0)
        return mt__io_fail(diag, MT_ERR_UNSUPPORTED, src, MT__POS_LINE, src->base + pos, MT_NONE,
                           "binary OFF is not supported");

    off_counts c;
    mt_status status = read_counts(src, &pos, &c, diag);
    if (status == MT_OK) status = check_counts(src, &c, diag);
    if (status == MT_OK && mt__src_length(src) != MT__UNKNOWN)
        mt__builder_reserve_declared(b, c.verts, c.faces, 3 * c.faces);
    off_confirm confirm = {src, &c};
    b->confirm = confirm_counts;
    b->confirm_ctx = &confirm;
    if (status == MT_OK) status = read_verts(src, &pos, &c, extras, b, diag);
    if (status == MT_OK) status = read_faces(src, &pos, &c, b, diag);
    /* confirm lives in this frame: the builder must not keep it (GCC's
     * -Wdangling-pointer checks it here). */
    b->confirm = NULL;
    b->confirm_ctx = NULL;
    if (status != MT_OK) return status;
    switch (mt__src_skip_trailer(src, &pos, 1)) {
        case MT__TRAIL_END:
            return MT_OK;
        case MT__TRAIL_DATA: {
            next_token(src, &pos, &start, &len);
            char msg[128];
            snprintf(msg, sizeof msg,
                     "unexpected data after the last face (the header declares %u)",
                     (uint32_t)c.faces);
            return fail_token(diag, src, start, len, MT_NONE, msg);
        }
        case MT__TRAIL_LONG:
            break;
    }
    return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->base + pos, MT_NONE,
                       "the input goes on for more than %llu bytes after the last face (the "
                       "header declares %u)",
                       (unsigned long long)MT_READ_MAX_TRAILING_BYTES, (uint32_t)c.faces);
}

mt_status mt__read_off(mt__io_src *src, mt_face_list *out, mt_diag *diag)
{
    return mt__builder_read(src, read_off, out, diag);
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
