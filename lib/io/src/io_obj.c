/* Wavefront OBJ: reading v and f lines (every other line is skipped) and
 * writing them. Face entries a, a/b, a/b/c and a//c give the vertex a;
 * indices are 1-based, negative ones count back from the vertices defined
 * so far, 0 is stored as -1 (out of range). A backslash at the end of a
 * line continues it. All objects and groups go into one mesh in file order.
 * OBJ declares no counts: the input limit (max_input_bytes) bounds a read.
 * Runs of plain v and f lines are read by io_bulk.c, which leaves every
 * other line, and so every message, to the loop here. */
#include <stdio.h>

#include "io_internal.h"

static inline int is_hspace(unsigned char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* 1 when d[i] is a backslash that ends its line (continuation). */
static inline int is_continuation(const unsigned char *d, size_t n, size_t i)
{
    if (d[i] != '\\') return 0;
    size_t j = i + 1;
    if (j < n && d[j] == '\r') j++;
    return j >= n || d[j] == '\n';
}

/* Skips spaces, tabs, '\r' and line continuations (not '\n'). */
static inline size_t skip_hspace(const unsigned char *d, size_t n, size_t i)
{
    for (;;) {
        while (i < n && is_hspace(d[i])) i++;
        if (i < n && is_continuation(d, n, i)) {
            i = mt__line_end(d, n, i);
            if (i < n) i++;
            continue;
        }
        return i;
    }
}

/* The index just past the '\n' ending the logical line at i (or the end of
 * the input), moving the window on. The window never ends between a '\\'
 * and the '\r' '\n' that make it a continuation (io_internal.h), so the
 * check of the bytes before a '\n' in view is exact. */
static size_t skip_line(mt__io_src *src, size_t i)
{
    for (;;) {
        const unsigned char *d = src->data;
        size_t n = src->size;
        size_t e = mt__line_end(d, n, i);
        if (e >= n) {
            i = n;
            if (!mt__src_more(src, &i)) return i;
            continue;
        }
        size_t b = e;
        if (b > i && d[b - 1] == '\r') b--;
        if (b > i && d[b - 1] == '\\') {
            i = e + 1;
            continue;
        }
        return e + 1;
    }
}

/* Next token on the current logical line; 0 at its end or at a comment
 * (*pos is then at the '\n', the '#' or the end of the input). */
static int line_token(mt__io_src *src, size_t *pos, size_t *start, size_t *len)
{
    for (;;) {
        const unsigned char *d = src->data;
        size_t n = src->size;
        size_t i = skip_hspace(d, n, *pos);
        *pos = i;
        if (i >= n) {
            if (mt__src_more(src, pos)) continue;
            return 0;
        }
        if (d[i] == '\n' || d[i] == '#') return 0;
        size_t s = i;
        while (i < n && !mt__is_space(d[i]) && !is_continuation(d, n, i)) i++;
        *start = s;
        *len = i - s;
        *pos = i;
        return 1;
    }
}

/* 1 when the keyword at i is exactly the letter k. */
static inline int keyword_is(const unsigned char *d, size_t n, size_t i, unsigned char k)
{
    if (d[i] != k) return 0;
    return i + 1 >= n || mt__is_space(d[i + 1]) || d[i + 1] == '#' || is_continuation(d, n, i + 1);
}

int mt__looks_like_obj(const mt__io_src *src)
{
    static const char *const keywords[] = {"v", "vt", "vn", "vp", "f",      "l",
                                           "p", "o",  "g",  "s",  "mtllib", "usemtl"};
    const unsigned char *d = src->data;
    size_t n = src->size, i = 0;
    while (i < n) {
        while (i < n && mt__is_space(d[i])) i++;
        if (i >= n) break;
        if (d[i] == '#') {
            /* a comment line, continued by a '\\' before its end */
            for (;;) {
                size_t e = mt__line_end(d, n, i);
                if (e >= n) return src->eof ? 0 : -1;
                size_t b = e;
                if (b > i && d[b - 1] == '\r') b--;
                if (b > i && d[b - 1] == '\\') {
                    i = e + 1;
                    continue;
                }
                i = e + 1;
                break;
            }
            continue;
        }
        size_t s = i;
        while (i < n && !mt__is_space(d[i])) i++;
        for (size_t k = 0; k < sizeof keywords / sizeof keywords[0]; k++)
            if (strlen(keywords[k]) == i - s && memcmp(keywords[k], d + s, i - s) == 0) return 1;
        return 0;
    }
    return src->eof ? 0 : -1;
}

static mt_status fail_token(mt_diag *diag, const mt__io_src *src, size_t start, size_t len,
                            uint32_t element, const char *what)
{
    char excerpt[64];
    mt__io_excerpt(excerpt, sizeof excerpt, src->data + start, len);
    return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->base + start, element,
                       "%s: '%s'", what, excerpt);
}

/* 1 when [p, end) is "/[vt]" or "/[vt]/[vn]" with optional signed integers. */
static int entry_rest_ok(const unsigned char *p, const unsigned char *end)
{
    for (int part = 0; part < 2 && p < end; part++) {
        if (*p != '/') return 0;
        p++;
        if (p < end && (*p == '-' || *p == '+')) p++;
        while (p < end && (unsigned)*p - '0' <= 9) p++;
    }
    return p == end;
}

/* Messages about a line point at its start: src->mark. */
static mt_status read_vertex_line(mt__io_src *src, size_t *pos, mt__builder *b, mt_diag *diag)
{
    double xyz[3];
    uint32_t v = (uint32_t)b->num_verts;
    for (int k = 0; k < 3; k++) {
        /* Fast path: a plain decimal ended by whitespace. */
        const unsigned char *d = src->data;
        size_t n = src->size;
        size_t i = skip_hspace(d, n, *pos);
        size_t used = i < n ? mt__scan_decimal(d + i, d + n, &xyz[k]) : 0;
        if (used && (i + used == n || mt__is_space(d[i + used]))) {
            *pos = i + used;
            continue;
        }
        size_t start, len;
        if (!line_token(src, pos, &start, &len))
            return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->mark, v,
                               "vertex %u: expected 3 coordinates, found %d", v, k);
        if (!mt__parse_double(src->data + start, len, &xyz[k])) {
            char msg[96];
            snprintf(msg, sizeof msg, "vertex %u: coordinate %d is not a number", v, k);
            return fail_token(diag, src, start, len, v, msg);
        }
    }
    if (b->num_verts >= MT__IO_MAX_VERTS)
        return mt__io_fail(diag, MT_ERR_TOO_LARGE, src, MT__POS_LINE, src->mark, MT_NONE,
                           "more than %u vertices", MT__IO_MAX_VERTS);
    if (!mt__builder_add_vert(b, xyz[0], xyz[1], xyz[2])) return mt__builder_fail(b, src, diag);
    return MT_OK;
}

static mt_status read_face_line(mt__io_src *src, size_t *pos, mt__builder *b, mt_diag *diag)
{
    if (b->num_faces >= UINT32_MAX)
        return mt__io_fail(diag, MT_ERR_TOO_LARGE, src, MT__POS_LINE, src->mark, MT_NONE,
                           "more than %u faces", UINT32_MAX);
    uint32_t f = (uint32_t)b->num_faces;
    int64_t defined = (int64_t)b->num_verts;
    size_t first = b->num_indices;
    size_t start, len;
    while (line_token(src, pos, &start, &len)) {
        const unsigned char *tok = src->data + start;
        const unsigned char *slash = memchr(tok, '/', len);
        size_t ilen = slash ? (size_t)(slash - tok) : len;
        int64_t index;
        mt__num r = mt__parse_index(tok, ilen, &index);
        if (r != MT__NUM_OK || (slash && !entry_rest_ok(slash, tok + len))) {
            char msg[96];
            snprintf(msg, sizeof msg, "face %u: %s", f,
                     r == MT__NUM_RANGE ? "vertex index does not fit in a 32-bit integer"
                                        : "bad face entry (expected v, v/vt, v/vt/vn or v//vn)");
            return fail_token(diag, src, start, len, f, msg);
        }
        uint32_t stored;
        if (index > 0)
            stored = (uint32_t)(index - 1);
        else if (index == 0)
            stored = UINT32_MAX; /* -1: OBJ has no vertex 0 */
        else
            stored = (uint32_t)(defined + index); /* two's complement when before vertex 0 */
        if (b->num_indices - first >= UINT32_MAX)
            return mt__io_fail(diag, MT_ERR_TOO_LARGE, src, MT__POS_LINE, src->mark, f,
                               "face %u: more than %u vertices", f, UINT32_MAX);
        if (!mt__builder_add_index(b, stored)) return mt__builder_fail(b, src, diag);
    }
    if (!mt__builder_add_face(b, (uint32_t)(b->num_indices - first)))
        return mt__builder_fail(b, src, diag);
    return MT_OK;
}

static mt_status read_obj(mt__io_src *src, mt__builder *b, mt_diag *diag)
{
    /* A first guess from the size (at most a million of each), refined by
     * doubling. */
    uint64_t length = mt__src_length(src);
    uint64_t guess = length != MT__UNKNOWN ? length : src->size;
    if (guess > ((uint64_t)64 << 20)) guess = (uint64_t)64 << 20;
    if (!mt__builder_reserve_verts(b, (size_t)guess / 64) ||
        !mt__builder_reserve_faces(b, (size_t)guess / 64) ||
        !mt__builder_reserve_indices(b, (size_t)guess / 16))
        return mt__builder_fail(b, src, diag);
    /* Lines of plain v or f records: io_bulk.c reads them, on several
     * threads when they are many. Where it reads few (comments after
     * records, v lines between vt and vn lines), the loop here takes the
     * next PAUSE_LINES lines before it is asked again. */
    static const mt__bulk_spec plain_verts = {
        .ops = {MT__BULK_KEYWORD, MT__BULK_X, MT__BULK_Y, MT__BULK_Z, MT__BULK_REST},
        .num_ops = 5,
        .keyword = 'v'};
    mt__bulk_spec plain_faces = {
        .ops = {MT__BULK_KEYWORD, MT__BULK_ENTRIES}, .num_ops = 2, .faces = 1, .keyword = 'f'};
    enum { FEW_RECORDS = 64, PAUSE_LINES = 256 };
    size_t pause = 0;
    size_t i = 0;
    for (;;) {
        const unsigned char *d = src->data;
        size_t n = src->size;
        if (pause > 0) {
            pause--;
        } else if (i > 0 && i + 1 < n && d[i - 1] == '\n') {
            size_t k = i;
            while (k + 1 < n && (d[k] == ' ' || d[k] == '\t')) k++;
            const mt__bulk_spec *plain = NULL;
            if (k + 1 < n && (d[k + 1] == ' ' || d[k + 1] == '\t'))
                plain = d[k] == 'v' ? &plain_verts : d[k] == 'f' ? &plain_faces : NULL;
            if (plain) {
                plain_faces.defined = (uint32_t)b->num_verts; /* for relative indices */
                size_t *records = plain->faces ? &b->num_faces : &b->num_verts;
                uint64_t got = mt__bulk_parse(src, plain, &i, *records,
                                              plain->faces ? UINT32_MAX : MT__IO_MAX_VERTS, b);
                *records += got;
                if (got < FEW_RECORDS) pause = PAUSE_LINES;
                if (got) continue;
            }
        }
        i = skip_hspace(d, n, i);
        if (i >= n) {
            if (!mt__src_more(src, &i)) break;
            continue;
        }
        if (d[i] == '\n') {
            i++;
            continue;
        }
        mt_status status = MT_OK;
        if (keyword_is(d, n, i, 'v')) {
            src->mark = src->base + i;
            i++;
            status = read_vertex_line(src, &i, b, diag);
        } else if (keyword_is(d, n, i, 'f')) {
            src->mark = src->base + i;
            i++;
            status = read_face_line(src, &i, b, diag);
        }
        if (status != MT_OK) return status;
        i = skip_line(src, i); /* the rest: w, colours, comments, other keywords */
    }
    return MT_OK;
}

mt_status mt__read_obj(mt__io_src *src, mt_face_list *out, mt_diag *diag)
{
    return mt__builder_read(src, read_obj, out, diag);
}

/* ---- Writing ----------------------------------------------------------- */

/* The OBJ token for a stored index: 1-based; -1 as 0; other negative
 * values as the relative index that reads back to them after all V
 * vertices. Returns 0 when that does not fit in 32 bits. */
static int obj_index(uint32_t index, int64_t num_verts, int64_t *out)
{
    int64_t s = mt_index_as_signed(index);
    if (s >= 0)
        *out = s + 1;
    else if (s == -1)
        *out = 0;
    else
        *out = s - num_verts;
    return *out >= INT32_MIN;
}

mt_status mt__obj_check_writable(const mt_face_list *list, const char *path, mt_diag *diag)
{
    uint64_t k = 0;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        for (uint32_t j = 0; j < list->face_sizes[f]; j++, k++) {
            int64_t token;
            if (!obj_index(list->face_indices[k], list->num_verts, &token)) {
                mt__io_src src = {.name = path};
                return mt__io_fail(diag, MT_ERR_UNSUPPORTED, &src, MT__POS_NONE, 0, f,
                                   "face %u: index %lld has no OBJ form (a relative index "
                                   "past 2^31 vertices back)",
                                   f, (long long)mt_index_as_signed(list->face_indices[k]));
            }
        }
    }
    return MT_OK;
}

mt_status mt__write_obj(mt__sink *s, const mt_face_list *list, mt_diag *diag)
{
    for (uint32_t v = 0; v < list->num_verts; v++) {
        char *p = mt__sink_reserve(s, 112);
        p[0] = 'v';
        size_t o = 1;
        for (int c = 0; c < 3; c++) {
            double x = list->positions ? list->positions[3 * (size_t)v + (size_t)c] : 0.0;
            p[o++] = ' ';
            o += mt__format_double(x, p + o);
        }
        p[o++] = '\n';
        mt__sink_commit(s, o);
    }
    const uint32_t *idx = list->face_indices;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        mt__sink_write(s, "f", 1);
        for (uint32_t j = 0; j < list->face_sizes[f]; j++) {
            int64_t token;
            obj_index(*idx++, list->num_verts, &token); /* checked before writing */
            char *p = mt__sink_reserve(s, 32);
            p[0] = ' ';
            mt__sink_commit(s, 1 + mt__format_i64(token, p + 1));
        }
        mt__sink_write(s, "\n", 1);
    }
    return MT_OK;
}
