/* STL files (the StereoLithography format of 3D Systems), ASCII and
 * binary: reading and writing. STL stores each triangle by its corners'
 * positions, so a file reads as a soup: facet f gives vertices 3f, 3f+1,
 * 3f+2 (more for an ASCII loop of more than 3 vertices) and welding is left
 * to mt_face_list_weld. Binary data is read through the window a triangle
 * at a time, its count checked against the input's length as soon as that
 * is known; ASCII is read token by token, arrays growing as facets come. */
#include <math.h>
#include <stdio.h>

#include "io_internal.h"

/* Bytes before the first triangle of binary STL, and per triangle. */
#define STL_HEADER 84
#define STL_TRIANGLE 50
/* Bytes of the start of a file that must be text for it to be ASCII STL. */
#define STL_TEXT_PROBE 256

static inline uint32_t load32(const unsigned char *p)
{
    return (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

static inline double load_float(const unsigned char *p)
{
    uint32_t u = load32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* 1 when [s, s + len) is the keyword `kw` (lower case), in any case; with
 * `prefix`, when it starts with it. */
static int keyword(const unsigned char *s, size_t len, const char *kw, int prefix)
{
    size_t m = strlen(kw);
    if (len < m || (!prefix && len != m)) return 0;
    for (size_t k = 0; k < m; k++) {
        unsigned char c = s[k];
        if (c >= 'A' && c <= 'Z') c = (unsigned char)(c - 'A' + 'a');
        if (c != (unsigned char)kw[k]) return 0;
    }
    return 1;
}

/* ---- Detection ---------------------------------------------------------- */

int mt__looks_like_stl(mt__io_src *src, int learn, mt_format *format)
{
    *format = MT_FORMAT_AUTO;
    const unsigned char *d = src->data;
    size_t n = src->size;
    if (n < STL_TEXT_PROBE && !src->eof) return -1;
    size_t i = 0;
    while (i < n && mt__is_space(d[i])) i++;
    int solid = keyword(d + i, n - i, "solid", 1);
    if (n >= STL_HEADER) {
        uint64_t length = mt__src_length(src);
        if (length == MT__UNKNOWN && (learn || solid) && mt__src_learn_length(src))
            length = src->total;
        if (length == STL_HEADER + (uint64_t)STL_TRIANGLE * load32(d + 80)) {
            *format = MT_FORMAT_STL_BINARY;
            return 1;
        }
    }
    if (!solid) return 0;
    size_t probe = n < STL_TEXT_PROBE ? n : STL_TEXT_PROBE;
    int text = 1;
    for (size_t k = 0; k < probe && text; k++)
        text = d[k] >= 0x20 ? d[k] != 0x7f : mt__is_space(d[k]);
    *format = text ? MT_FORMAT_STL_ASCII : MT_FORMAT_STL_BINARY;
    return 1;
}

/* ---- Binary ------------------------------------------------------------- */

/* Data after the last triangle the count declares (at its input offset,
 * 84 + 50 * count, whether the length was known or not). */
static mt_status fail_trailing(const mt__io_src *src, uint32_t count, mt_diag *diag)
{
    return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE,
                       STL_HEADER + (uint64_t)STL_TRIANGLE * count, MT_NONE,
                       "binary STL goes on after the %u triangles its count declares", count);
}

/* The declared count against the input's length, once that is known. */
static mt_status check_length(const mt__io_src *src, uint32_t count, mt_diag *diag)
{
    uint64_t length = mt__src_length(src);
    if (length == MT__UNKNOWN) return MT_OK;
    uint64_t want = STL_HEADER + (uint64_t)STL_TRIANGLE * count;
    if (length < want) {
        uint64_t have = (length - STL_HEADER) / STL_TRIANGLE;
        return mt__io_fail(
            diag, MT_ERR_PARSE, src, MT__POS_BYTE, STL_HEADER + have * STL_TRIANGLE, (uint32_t)have,
            "binary STL ends after %llu of %u triangles (%llu bytes; the count "
            "needs %llu)",
            (unsigned long long)have, count, (unsigned long long)length, (unsigned long long)want);
    }
    if (length > want) return fail_trailing(src, count, diag);
    return MT_OK;
}

typedef struct stl_confirm {
    mt__io_src *src;
    uint32_t count;
} stl_confirm;

/* Before the face list of input whose length is unknown grows large. */
static mt_status confirm_count(void *ctx, mt_diag *diag)
{
    stl_confirm *c = ctx;
    mt__src_learn_length(c->src);
    return check_length(c->src, c->count, diag);
}

/* The count triangles of a binary STL after its header, into b. */
static mt_status read_triangles(mt__io_src *src, mt__builder *b, uint32_t count, mt_diag *diag)
{
    size_t i = STL_HEADER;
    mt_status status = MT_OK;
    size_t cap = 0;
    for (uint32_t t = 0; t < count; t++) {
        if (t == cap) {
            cap = mt__builder_ahead(t, count);
            if (!mt__builder_reserve_verts(b, 3 * cap) || !mt__builder_reserve_faces(b, cap) ||
                !mt__builder_reserve_indices(b, 3 * cap))
                return mt__builder_fail(b, src, diag);
        }
        if (src->size - i < STL_TRIANGLE && !mt__src_need(src, &i, STL_TRIANGLE)) {
            status = check_length(src, count, diag);
            if (status != MT_OK) return status;
            return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE, src->base + i, t,
                               "binary STL ends after %u of %u triangles", t, count);
        }
        /* normal (12 bytes), 3 corners (36), attribute byte count (2): skipped */
        const unsigned char *p = src->data + i + 12;
        double *q = b->positions + 3 * b->num_verts;
        for (int k = 0; k < 9; k++) q[k] = load_float(p + 4 * k);
        uint32_t v = (uint32_t)b->num_verts;
        b->indices[b->num_indices++] = v;
        b->indices[b->num_indices++] = v + 1;
        b->indices[b->num_indices++] = v + 2;
        b->sizes[b->num_faces++] = 3;
        b->num_verts += 3;
        i += STL_TRIANGLE;
    }
    if (mt__src_need(src, &i, 1)) return fail_trailing(src, count, diag);
    return MT_OK;
}

static mt_status read_binary(mt__io_src *src, mt__builder *b, mt_diag *diag)
{
    mt__src_binary(src);
    size_t i = 0;
    if (!mt__src_need(src, &i, STL_HEADER))
        return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE, src->base + src->size, MT_NONE,
                           "binary STL ends in its 84-byte header (%llu bytes)",
                           (unsigned long long)(src->base + src->size));
    uint32_t count = load32(src->data + 80);
    /* A count past the limits is judged against the length first, as it
     * is when the length is known from the start. */
    if ((uint64_t)count * 3 > MT__IO_MAX_VERTS) mt__src_learn_length(src);
    mt_status status = check_length(src, count, diag);
    if (status != MT_OK) return status;
    if ((uint64_t)count * 3 > MT__IO_MAX_VERTS)
        return mt__io_fail(diag, MT_ERR_TOO_LARGE, src, MT__POS_BYTE, 80, MT_NONE,
                           "%u triangles: more than meshtopo's limit of %u vertices", count,
                           MT__IO_MAX_VERTS);
    if (mt__src_length(src) != MT__UNKNOWN) /* check_length held the count to it */
        mt__builder_reserve_declared(b, 3 * (uint64_t)count, count, 3 * (uint64_t)count);
    /* The builder asks confirm_count, with the count, before growing large;
     * the pointer to this frame's confirmation is taken back before return. */
    stl_confirm confirm = {src, count};
    b->confirm = confirm_count;
    b->confirm_ctx = &confirm;
    status = read_triangles(src, b, count, diag);
    b->confirm = NULL;
    b->confirm_ctx = NULL;
    return status;
}

mt_status mt__read_stl_binary(mt__io_src *src, mt_face_list *out, mt_diag *diag)
{
    return mt__builder_read(src, read_binary, out, diag);
}

/* ---- ASCII -------------------------------------------------------------- */

/* Skips to the end of the line (a solid's name). */
static size_t rest_of_line(mt__io_src *src, size_t i)
{
    for (;;) {
        const unsigned char *d = src->data;
        size_t n = src->size;
        while (i < n && d[i] != '\n' && d[i] != '\r') i++;
        if (i < n || !mt__src_more(src, &i)) return i;
    }
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

static mt_status fail_end(mt_diag *diag, const mt__io_src *src, uint32_t element, const char *what)
{
    return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->base + src->size, element,
                       "%s, found the end of file", what);
}

/* Expects the keyword kw as the next token; `facet` names the facet in
 * messages (MT_NONE: outside a facet). */
static mt_status expect(mt__io_src *src, size_t *pos, const char *kw, uint32_t facet, mt_diag *diag)
{
    size_t start, len;
    char what[64];
    if (facet == MT_NONE)
        snprintf(what, sizeof what, "expected '%s'", kw);
    else
        snprintf(what, sizeof what, "facet %u: expected '%s'", facet, kw);
    if (!mt__src_token(src, pos, &start, &len)) return fail_end(diag, src, facet, what);
    if (!keyword(src->data + start, len, kw, 0))
        return fail_token(diag, src, start, len, facet, what);
    return MT_OK;
}

/* Three numbers (a normal or a vertex) into xyz. */
static mt_status read_xyz(mt__io_src *src, size_t *pos, uint32_t facet, const char *what,
                          double *xyz, mt_diag *diag)
{
    for (int k = 0; k < 3; k++) {
        size_t start, len;
        char msg[96];
        snprintf(msg, sizeof msg, "facet %u: %s: expected coordinate %d", facet, what, k);
        if (!mt__src_token(src, pos, &start, &len)) return fail_end(diag, src, facet, msg);
        if (!mt__parse_double(src->data + start, len, &xyz[k])) {
            snprintf(msg, sizeof msg, "facet %u: %s: coordinate %d is not a number", facet, what,
                     k);
            return fail_token(diag, src, start, len, facet, msg);
        }
    }
    return MT_OK;
}

/* One facet, after its "facet" keyword: "[normal n n n] outer loop (vertex
 * x y z)+ endloop endfacet". */
static mt_status read_facet(mt__io_src *src, size_t *pos, uint32_t f, mt__builder *b, mt_diag *diag)
{
    size_t start, len;
    double xyz[3];
    char what[96];
    snprintf(what, sizeof what, "facet %u: expected 'normal' or 'outer'", f);
    if (!mt__src_token(src, pos, &start, &len)) return fail_end(diag, src, f, what);
    if (keyword(src->data + start, len, "normal", 0)) {
        mt_status status = read_xyz(src, pos, f, "normal", xyz, diag);
        if (status != MT_OK) return status;
        if (!mt__src_token(src, pos, &start, &len)) return fail_end(diag, src, f, what);
    }
    if (!keyword(src->data + start, len, "outer", 0))
        return fail_token(diag, src, start, len, f, what);
    mt_status status = expect(src, pos, "loop", f, diag);
    if (status != MT_OK) return status;
    size_t first = b->num_verts;
    snprintf(what, sizeof what, "facet %u: expected 'vertex' or 'endloop'", f);
    for (;;) {
        if (!mt__src_token(src, pos, &start, &len)) return fail_end(diag, src, f, what);
        if (keyword(src->data + start, len, "endloop", 0)) break;
        if (!keyword(src->data + start, len, "vertex", 0))
            return fail_token(diag, src, start, len, f, what);
        char label[32];
        snprintf(label, sizeof label, "vertex %zu", b->num_verts - first);
        status = read_xyz(src, pos, f, label, xyz, diag);
        if (status != MT_OK) return status;
        if (b->num_verts >= MT__IO_MAX_VERTS)
            return mt__io_fail(diag, MT_ERR_TOO_LARGE, src, MT__POS_LINE, src->base + start, f,
                               "facet %u: more than meshtopo's limit of %u vertices", f,
                               MT__IO_MAX_VERTS);
        if (!mt__builder_add_vert(b, xyz[0], xyz[1], xyz[2])) return mt__builder_fail(b, src, diag);
    }
    size_t corners = b->num_verts - first;
    if (corners < 3) {
        snprintf(what, sizeof what, "facet %u: %zu %s in its loop (3 at least)", f, corners,
                 corners == 1 ? "vertex" : "vertices");
        return fail_token(diag, src, start, len, f, what);
    }
    if (!mt__builder_add_face(b, (uint32_t)corners)) return mt__builder_fail(b, src, diag);
    for (size_t k = 0; k < corners; k++)
        if (!mt__builder_add_index(b, (uint32_t)(first + k))) return mt__builder_fail(b, src, diag);
    return expect(src, pos, "endfacet", f, diag);
}

static mt_status read_ascii(mt__io_src *src, mt__builder *b, mt_diag *diag)
{
    size_t pos = 0, start, len;
    if (!mt__src_token(src, &pos, &start, &len))
        return fail_end(diag, src, MT_NONE, "expected 'solid' (ASCII STL)");
    if (!keyword(src->data + start, len, "solid", 1))
        return fail_token(diag, src, start, len, MT_NONE, "expected 'solid' (ASCII STL)");
    pos = rest_of_line(src, pos); /* the solid's name */
    uint32_t f = 0;
    for (;;) {
        static const char *const what = "expected 'facet' or 'endsolid'";
        if (!mt__src_token(src, &pos, &start, &len)) return fail_end(diag, src, f, what);
        if (keyword(src->data + start, len, "facet", 0)) {
            if (f == UINT32_MAX)
                return mt__io_fail(diag, MT_ERR_TOO_LARGE, src, MT__POS_LINE, src->base + start, f,
                                   "more than meshtopo's limit of %u faces", UINT32_MAX - 1);
            src->mark = src->base + start;
            mt_status status = read_facet(src, &pos, f, b, diag);
            if (status != MT_OK) return status;
            f++;
            continue;
        }
        if (!keyword(src->data + start, len, "endsolid", 1))
            return fail_token(diag, src, start, len, f, what);
        pos = rest_of_line(src, pos);
        /* the end, or another solid */
        if (!mt__src_token(src, &pos, &start, &len)) return MT_OK;
        if (!keyword(src->data + start, len, "solid", 1))
            return fail_token(diag, src, start, len, MT_NONE,
                              "expected 'solid' or the end of file after 'endsolid'");
        pos = rest_of_line(src, pos);
    }
}

mt_status mt__read_stl_ascii(mt__io_src *src, mt_face_list *out, mt_diag *diag)
{
    return mt__builder_read(src, read_ascii, out, diag);
}

/* ---- Writing ------------------------------------------------------------ */

mt_status mt__stl_check_writable(const mt_face_list *list, mt_format format, const char *path,
                                 mt_diag *diag)
{
    mt__io_src src = {.name = path};
    uint64_t k = 0, triangles = 0;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        uint32_t size = list->face_sizes[f];
        if (size < 3)
            return mt__io_fail(diag, MT_ERR_UNSUPPORTED, &src, MT__POS_NONE, 0, f,
                               "face %u has %u %s: STL stores triangles", f, size,
                               size == 1 ? "entry" : "entries");
        for (uint32_t j = 0; j < size; j++, k++)
            if (list->face_indices[k] >= list->num_verts)
                return mt__io_fail(diag, MT_ERR_UNSUPPORTED, &src, MT__POS_NONE, 0, f,
                                   "face %u: index %lld is out of range: STL stores positions, "
                                   "not indices",
                                   f, (long long)mt_index_as_signed(list->face_indices[k]));
        triangles += size - 2;
    }
    if (format == MT_FORMAT_STL_BINARY && triangles > UINT32_MAX)
        return mt__io_fail(diag, MT_ERR_UNSUPPORTED, &src, MT__POS_NONE, 0, MT_NONE,
                           "%llu triangles: more than binary STL's count holds",
                           (unsigned long long)triangles);
    return MT_OK;
}

/* The unit normal of triangle abc (right-handed), zero when it is
 * degenerate or not finite. */
static void triangle_normal(const double *a, const double *b, const double *c, double *n)
{
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    /* + 0.0: no -0 in the output */
    for (int k = 0; k < 3; k++) n[k] = len > 0 && isfinite(len) ? n[k] / len + 0.0 : 0.0;
}

static void store_float(unsigned char *p, double x)
{
    float f = (float)x;
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    for (int k = 0; k < 4; k++) p[k] = (unsigned char)(u >> (8 * k));
}

/* "PREFIX x y z\n" with the shortest round-tripping decimals. */
static void write_xyz(mt__sink *s, const char *prefix, const double *xyz)
{
    char *p = mt__sink_reserve(s, 128);
    size_t o = strlen(prefix);
    memcpy(p, prefix, o);
    for (int c = 0; c < 3; c++) {
        p[o++] = ' ';
        o += mt__format_double(xyz[c], p + o);
    }
    p[o++] = '\n';
    mt__sink_commit(s, o);
}

mt_status mt__write_stl(mt__sink *s, const mt_face_list *list, mt_format format, mt_diag *diag)
{
    (void)diag;
    static const double zero[3] = {0, 0, 0};
    int binary = format == MT_FORMAT_STL_BINARY;
    if (binary) {
        uint64_t triangles = 0;
        for (uint32_t f = 0; f < list->num_faces; f++) triangles += list->face_sizes[f] - 2;
        unsigned char header[STL_HEADER];
        memset(header, ' ', 80);
        memcpy(header, "binary STL written by meshtopo", 30);
        for (int k = 0; k < 4; k++) header[80 + k] = (unsigned char)(triangles >> (8 * k));
        mt__sink_write(s, header, sizeof header);
    } else {
        mt__sink_write(s, "solid meshtopo\n", 15);
    }
    const uint32_t *idx = list->face_indices;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        uint32_t size = list->face_sizes[f];
        for (uint32_t j = 1; j + 1 < size; j++) {
            const double *c[3];
            uint32_t corner[3] = {idx[0], idx[j], idx[j + 1]};
            for (int k = 0; k < 3; k++)
                c[k] = list->positions ? list->positions + 3 * (size_t)corner[k] : zero;
            double n[3];
            triangle_normal(c[0], c[1], c[2], n);
            if (binary) {
                unsigned char *q = (unsigned char *)mt__sink_reserve(s, STL_TRIANGLE);
                for (int k = 0; k < 3; k++) store_float(q + 4 * k, n[k]);
                for (int v = 0; v < 3; v++)
                    for (int k = 0; k < 3; k++) store_float(q + 12 + 12 * v + 4 * k, c[v][k]);
                q[48] = q[49] = 0;
                mt__sink_commit(s, STL_TRIANGLE);
                continue;
            }
            write_xyz(s, "  facet normal", n);
            mt__sink_write(s, "    outer loop\n", 15);
            for (int v = 0; v < 3; v++) write_xyz(s, "      vertex", c[v]);
            mt__sink_write(s, "    endloop\n  endfacet\n", 23);
        }
        idx += size;
    }
    if (!binary) mt__sink_write(s, "endsolid meshtopo\n", 18);
    return MT_OK;
}
