/* PLY (Stanford polygon file format, http://paulbourke.net/dataformats/ply/)
 * reader for the ascii, binary_little_endian and binary_big_endian
 * encodings: x y z of the vertex element (any numeric types, any order,
 * other properties skipped), the vertex_indices (or vertex_index) list of
 * the face element (integer count and index types), every other element
 * skipped. Element counts are checked against the bytes that follow the
 * header (as soon as their number is known), arrays grow as items are
 * read, binary data is read bounds-checked, and after the last element
 * reading stops: only MT_READ_MAX_TRAILING_BYTES of whitespace may follow. */
#include <stdio.h>
#include <stdlib.h>

#include "io_internal.h"

typedef enum ply_type {
    PT_NONE,
    PT_I8,
    PT_U8,
    PT_I16,
    PT_U16,
    PT_I32,
    PT_U32,
    PT_F32,
    PT_F64
} ply_type;

static const unsigned char type_size[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};

static const struct {
    const char *name;
    ply_type type;
} type_names[] = {
    {"char", PT_I8},   {"int8", PT_I8},     {"uchar", PT_U8},   {"uint8", PT_U8},
    {"short", PT_I16}, {"int16", PT_I16},   {"ushort", PT_U16}, {"uint16", PT_U16},
    {"int", PT_I32},   {"int32", PT_I32},   {"uint", PT_U32},   {"uint32", PT_U32},
    {"float", PT_F32}, {"float32", PT_F32}, {"double", PT_F64}, {"float64", PT_F64},
};

static int type_is_integer(ply_type t)
{
    return t >= PT_I8 && t <= PT_U32;
}

typedef enum ply_role { ROLE_NONE, ROLE_X, ROLE_Y, ROLE_Z, ROLE_INDICES } ply_role;
typedef enum ply_kind { KIND_OTHER, KIND_VERTEX, KIND_FACE } ply_kind;
typedef enum ply_encoding { ENC_NONE, ENC_ASCII, ENC_LE, ENC_BE } ply_encoding;

typedef struct ply_prop {
    ply_type type;       /* scalar type, or the list's index type */
    ply_type count_type; /* PT_NONE for a scalar */
    ply_role role;
    char name[40];
} ply_prop;

typedef struct ply_elem {
    ply_kind kind;
    uint64_t count;
    size_t first_prop, num_props;
    size_t header_offset; /* its "element" line, for messages */
    char name[40];
} ply_elem;

typedef struct ply_header {
    ply_encoding encoding;
    ply_elem *elems;
    size_t num_elems, cap_elems;
    ply_prop *props;
    size_t num_props, cap_props;
    size_t data_start;         /* input offset of the data (the header is read whole: base 0) */
    uint64_t min_bytes;        /* the least data the element counts need */
    uint64_t end_at, end_line; /* the end_header line, for the size check */
} ply_header;

static void header_free(ply_header *h)
{
    free(h->elems);
    free(h->props);
}

/* ---- Header ------------------------------------------------------------ */

typedef struct tok {
    size_t start, len;
} tok;

static int tok_is(const mt__io_src *src, tok t, const char *s)
{
    size_t n = strlen(s);
    return t.len == n && memcmp(src->data + t.start, s, n) == 0;
}

static ply_type type_of(const mt__io_src *src, tok t)
{
    for (size_t i = 0; i < sizeof type_names / sizeof type_names[0]; i++)
        if (tok_is(src, t, type_names[i].name)) return type_names[i].type;
    return PT_NONE;
}

static const char *type_name(ply_type t)
{
    for (size_t i = 0; i < sizeof type_names / sizeof type_names[0]; i++)
        if (type_names[i].type == t) return type_names[i].name;
    return "?";
}

static mt_status header_fail(mt_diag *diag, const mt__io_src *src, size_t offset, const char *fmt,
                             const char *arg)
{
    return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->base + offset, MT_NONE, fmt,
                       arg);
}

static mt_status fail_tok(mt_diag *diag, const mt__io_src *src, tok t, const char *fmt)
{
    char excerpt[64];
    mt__io_excerpt(excerpt, sizeof excerpt, src->data + t.start, t.len);
    return header_fail(diag, src, t.start, fmt, excerpt);
}

static int push_elem(ply_header *h)
{
    if (h->num_elems == h->cap_elems) {
        size_t cap = h->cap_elems ? 2 * h->cap_elems : 8;
        ply_elem *p = realloc(h->elems, cap * sizeof *p);
        if (!p) return 0;
        h->elems = p;
        h->cap_elems = cap;
    }
    memset(&h->elems[h->num_elems++], 0, sizeof(ply_elem));
    return 1;
}

static int push_prop(ply_header *h)
{
    if (h->num_props == h->cap_props) {
        size_t cap = h->cap_props ? 2 * h->cap_props : 16;
        ply_prop *p = realloc(h->props, cap * sizeof *p);
        if (!p) return 0;
        h->props = p;
        h->cap_props = cap;
    }
    memset(&h->props[h->num_props++], 0, sizeof(ply_prop));
    return 1;
}

static void copy_name(char *dst, size_t size, const mt__io_src *src, tok t)
{
    mt__io_excerpt(dst, size, src->data + t.start, t.len);
}

static mt_status parse_property(const mt__io_src *src, ply_header *h, const tok *t, size_t nt,
                                size_t line, mt_diag *diag)
{
    if (h->num_elems == 0) return header_fail(diag, src, line, "%s", "property before any element");
    ply_elem *e = &h->elems[h->num_elems - 1];
    ply_type type, count_type = PT_NONE;
    tok name;
    if (nt >= 2 && tok_is(src, t[1], "list")) {
        if (nt != 5)
            return header_fail(diag, src, line, "%s",
                               "expected 'property list COUNT_TYPE INDEX_TYPE NAME'");
        count_type = type_of(src, t[2]);
        if (count_type == PT_NONE) return fail_tok(diag, src, t[2], "unknown type '%s'");
        if (!type_is_integer(count_type))
            return fail_tok(diag, src, t[2], "list count type must be an integer type, not '%s'");
        type = type_of(src, t[3]);
        if (type == PT_NONE) return fail_tok(diag, src, t[3], "unknown type '%s'");
        name = t[4];
    } else {
        if (nt != 3) return header_fail(diag, src, line, "%s", "expected 'property TYPE NAME'");
        type = type_of(src, t[1]);
        if (type == PT_NONE) return fail_tok(diag, src, t[1], "unknown type '%s'");
        name = t[2];
    }
    if (!push_prop(h)) return mt__io_fail_nomem(diag, src);
    e = &h->elems[h->num_elems - 1];
    ply_prop *p = &h->props[h->num_props - 1];
    p->type = type;
    p->count_type = count_type;
    copy_name(p->name, sizeof p->name, src, name);
    e->num_props++;
    /* Roles: the first x, y, z of the vertex element, the first
     * vertex_indices / vertex_index of the face element. */
    ply_role role = ROLE_NONE;
    if (e->kind == KIND_VERTEX) {
        if (tok_is(src, name, "x")) role = ROLE_X;
        if (tok_is(src, name, "y")) role = ROLE_Y;
        if (tok_is(src, name, "z")) role = ROLE_Z;
        if (role != ROLE_NONE && count_type != PT_NONE)
            return fail_tok(diag, src, name, "vertex property '%s' must not be a list");
    } else if (e->kind == KIND_FACE) {
        if (tok_is(src, name, "vertex_indices") || tok_is(src, name, "vertex_index")) {
            role = ROLE_INDICES;
            if (count_type == PT_NONE)
                return fail_tok(diag, src, name, "face property '%s' must be a list");
            if (!type_is_integer(type))
                return header_fail(diag, src, line,
                                   "face vertex indices must have an integer type, not '%s'",
                                   type_name(type));
        }
    }
    for (size_t i = e->first_prop; role != ROLE_NONE && i + 1 < h->num_props; i++)
        if (h->props[i].role == role) role = ROLE_NONE; /* a second one is just skipped */
    p->role = role;
    return MT_OK;
}

static mt_status parse_element(const mt__io_src *src, ply_header *h, const tok *t, size_t nt,
                               size_t line, mt_diag *diag)
{
    if (nt != 3) return header_fail(diag, src, line, "%s", "expected 'element NAME COUNT'");
    uint64_t count;
    mt__num r = mt__parse_count(src->data + t[2].start, t[2].len, &count);
    if (r != MT__NUM_OK) return fail_tok(diag, src, t[2], "bad element count '%s'");
    ply_kind kind = tok_is(src, t[1], "vertex") ? KIND_VERTEX
                    : tok_is(src, t[1], "face") ? KIND_FACE
                                                : KIND_OTHER;
    for (size_t i = 0; kind != KIND_OTHER && i < h->num_elems; i++)
        if (h->elems[i].kind == kind) return fail_tok(diag, src, t[1], "second '%s' element");
    if (kind == KIND_VERTEX && count > MT__IO_MAX_VERTS)
        return fail_tok(diag, src, t[2], "vertex count %s too large");
    if (kind == KIND_FACE && count > UINT32_MAX)
        return fail_tok(diag, src, t[2], "face count %s too large");
    if (!push_elem(h)) return mt__io_fail_nomem(diag, src);
    ply_elem *e = &h->elems[h->num_elems - 1];
    e->kind = kind;
    e->count = count;
    e->first_prop = h->num_props;
    e->header_offset = line;
    copy_name(e->name, sizeof e->name, src, t[1]);
    return MT_OK;
}

/* The element counts against the bytes that follow the header, once their
 * number is known: at once, or (gzip) when the input ends early. */
static mt_status check_size(const mt__io_src *src, const ply_header *h, mt_diag *diag)
{
    uint64_t length = mt__src_length(src);
    if (length == MT__UNKNOWN) return MT_OK;
    uint64_t follow = length > h->data_start ? length - h->data_start : 0;
    uint64_t rest = follow + (h->encoding != ENC_ASCII ? 0 : 1);
    if (h->min_bytes > rest)
        return mt__io_fail_line(diag, MT_ERR_PARSE, src, h->end_at, h->end_line, MT_NONE,
                                "the header's element counts need at least %llu bytes of data "
                                "but only %llu follow",
                                (unsigned long long)h->min_bytes, (unsigned long long)follow);
    return MT_OK;
}

/* Checks what the data parser relies on: encoding given, x y z present,
 * face indices present, counts the remaining bytes can hold. */
static mt_status check_header(const mt__io_src *src, ply_header *h, size_t end_line, mt_diag *diag)
{
    if (h->encoding == ENC_NONE)
        return header_fail(diag, src, end_line, "%s", "no 'format' line in the header");
    uint64_t min_bytes = 0;
    int binary = h->encoding != ENC_ASCII;
    for (size_t i = 0; i < h->num_elems; i++) {
        ply_elem *e = &h->elems[i];
        int have[5] = {0};
        uint64_t item = 0;
        for (size_t k = 0; k < e->num_props; k++) {
            const ply_prop *p = &h->props[e->first_prop + k];
            have[p->role] = 1;
            item += binary ? type_size[p->count_type != PT_NONE ? p->count_type : p->type] : 2;
        }
        if (e->kind == KIND_VERTEX && !(have[ROLE_X] && have[ROLE_Y] && have[ROLE_Z]))
            return header_fail(diag, src, e->header_offset, "%s",
                               "the vertex element lacks one of the properties x, y, z");
        if (e->kind == KIND_FACE && !have[ROLE_INDICES])
            return header_fail(diag, src, e->header_offset, "%s",
                               "the face element has no vertex_indices list");
        if (item && e->count > (UINT64_MAX - min_bytes) / item) {
            min_bytes = UINT64_MAX;
            break;
        }
        min_bytes += e->count * item;
    }
    h->min_bytes = min_bytes;
    h->end_at = src->base + end_line;
    h->end_line = mt__src_line(src, h->end_at);
    return check_size(src, h, diag);
}

/* Parses the header, which must be in the window whole: *need_more is set
 * (and nothing reported) when the window ends before it does. */
static mt_status parse_header(const mt__io_src *src, ply_header *h, int *need_more, mt_diag *diag)
{
    const unsigned char *d = src->data;
    size_t n = src->size, i = 0;
    int first = 1;
    *need_more = 0;
    while (i < n) {
        size_t line = i, e = mt__line_end(d, n, i);
        if (e == n && !src->eof) {
            *need_more = 1;
            return MT_OK;
        }
        tok t[6];
        size_t nt = 0;
        while (i < e) {
            while (i < e && mt__is_space(d[i])) i++;
            if (i >= e) break;
            size_t s = i;
            while (i < e && !mt__is_space(d[i])) i++;
            if (nt < 6) t[nt] = (tok){s, i - s};
            nt++;
        }
        i = e < n ? e + 1 : n;
        if (first) {
            if (nt != 1 || !tok_is(src, t[0], "ply"))
                return header_fail(diag, src, line, "%s", "expected the 'ply' magic line");
            first = 0;
            continue;
        }
        if (nt == 0) continue;
        if (tok_is(src, t[0], "comment") || tok_is(src, t[0], "obj_info")) continue;
        if (nt > 6) nt = 6;
        mt_status status = MT_OK;
        if (tok_is(src, t[0], "format")) {
            if (nt != 3)
                return header_fail(diag, src, line, "%s", "expected 'format ENCODING 1.0'");
            if (h->encoding != ENC_NONE)
                return header_fail(diag, src, line, "%s", "second 'format' line");
            if (tok_is(src, t[1], "ascii"))
                h->encoding = ENC_ASCII;
            else if (tok_is(src, t[1], "binary_little_endian"))
                h->encoding = ENC_LE;
            else if (tok_is(src, t[1], "binary_big_endian"))
                h->encoding = ENC_BE;
            else
                return fail_tok(diag, src, t[1], "unknown PLY encoding '%s'");
        } else if (tok_is(src, t[0], "element")) {
            status = parse_element(src, h, t, nt, line, diag);
        } else if (tok_is(src, t[0], "property")) {
            status = parse_property(src, h, t, nt, line, diag);
        } else if (tok_is(src, t[0], "end_header")) {
            h->data_start = i;
            return check_header(src, h, line, diag);
        } else {
            return fail_tok(diag, src, t[0], "unknown PLY header keyword '%s'");
        }
        if (status != MT_OK) return status;
    }
    if (!src->eof) {
        *need_more = 1;
        return MT_OK;
    }
    if (first) return header_fail(diag, src, 0, "%s", "empty file: expected the 'ply' magic line");
    return header_fail(diag, src, n, "%s", "the header has no 'end_header' line");
}

int mt__looks_like_ply(const mt__io_src *src)
{
    if (src->size < 4) return src->eof ? 0 : -1;
    return memcmp(src->data, "ply", 3) == 0 && (src->data[3] == '\n' || src->data[3] == '\r');
}

/* ---- Messages about data ----------------------------------------------- */

/* "vertex 12 of 40", "face 7 of 9" or "element 'edge' item 3 of 5" */
static void item_label(char *buf, size_t size, const ply_elem *e, uint64_t item)
{
    unsigned long long i = item, n = e->count;
    if (e->kind == KIND_VERTEX)
        snprintf(buf, size, "vertex %llu of %llu", i, n);
    else if (e->kind == KIND_FACE)
        snprintf(buf, size, "face %llu of %llu", i, n);
    else
        snprintf(buf, size, "element '%s' item %llu of %llu", e->name, i, n);
}

static uint32_t item_element(const ply_elem *e, uint64_t item)
{
    return e->kind != KIND_OTHER && item < UINT32_MAX ? (uint32_t)item : MT_NONE;
}

/* ---- ASCII data -------------------------------------------------------- */

/* "LABEL: property 'NAME': WHAT: 'EXCERPT'" at an input offset (line 0:
 * computed from it). */
static mt_status ascii_fail_at(mt_diag *diag, const mt__io_src *src, const ply_elem *e,
                               uint64_t item, const ply_prop *p, uint64_t offset, uint64_t line,
                               const char *what, const char *excerpt)
{
    char label[96];
    item_label(label, sizeof label, e, item);
    if (!line) line = mt__src_line(src, offset);
    return mt__io_fail_line(diag, MT_ERR_PARSE, src, offset, line, item_element(e, item),
                            "%s: property '%s': %s: '%s'", label, p->name, what, excerpt);
}

/* The same for the token at window index [start, start + len). */
static mt_status ascii_fail(mt_diag *diag, const mt__io_src *src, const ply_elem *e, uint64_t item,
                            const ply_prop *p, size_t start, size_t len, const char *what)
{
    char excerpt[64];
    mt__io_excerpt(excerpt, sizeof excerpt, src->data + start, len);
    return ascii_fail_at(diag, src, e, item, p, src->base + start, 0, what, excerpt);
}

/* A list count that could not be checked against the rest of the input
 * when it was read (the length of gzip data is known at its end only). */
typedef struct list_check {
    int pending;
    uint64_t count, after; /* the count, and the input offset just past it */
    uint64_t at, line;     /* where the count is */
    char excerpt[64];
} list_check;

/* The input ended inside item `item`, property p: the header's size check
 * and a pending list check come first, as they would have with the input's
 * length known from the start. */
static mt_status ascii_end(mt_diag *diag, const mt__io_src *src, const ply_header *h,
                           const ply_elem *e, uint64_t item, const ply_prop *p,
                           const list_check *lc)
{
    mt_status status = check_size(src, h, diag);
    if (status != MT_OK) return status;
    uint64_t length = mt__src_length(src);
    if (lc && lc->pending && length != MT__UNKNOWN &&
        lc->count > (length > lc->after ? length - lc->after : 0) / 2)
        return ascii_fail_at(diag, src, e, item, p, lc->at, lc->line,
                             "list count larger than the rest of the file", lc->excerpt);
    char label[96];
    item_label(label, sizeof label, e, item);
    return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_LINE, src->base + src->size,
                       item_element(e, item), "%s: property '%s': unexpected end of file", label,
                       p->name);
}

/* Room for the next items of a vertex or face element. */
static int reserve_items(mt__builder *b, const ply_elem *e, uint64_t item, size_t *cap)
{
    if (e->kind == KIND_OTHER || item < *cap) return 1;
    *cap = mt__builder_ahead((size_t)item, e->count);
    return e->kind == KIND_VERTEX ? mt__builder_reserve_verts(b, *cap)
                                  : mt__builder_reserve_faces(b, *cap);
}

/* The lines of a vertex or face element that io_bulk.c may read: 1 with
 * *spec filled, 0 when its items are left to ascii_element alone. */
static int bulk_spec_of(const ply_elem *e, const ply_prop *props, mt__bulk_spec *spec)
{
    if (e->kind == KIND_OTHER || e->num_props > MT__BULK_MAX_OPS) return 0;
    memset(spec, 0, sizeof *spec);
    spec->faces = e->kind == KIND_FACE;
    size_t lists = 0;
    for (size_t k = 0; k < e->num_props; k++) {
        const ply_prop *p = &props[k];
        unsigned char op = MT__BULK_TOKEN;
        if (p->count_type != PT_NONE) {
            op = p->role == ROLE_INDICES ? MT__BULK_INDICES : MT__BULK_LIST;
            lists += op == MT__BULK_INDICES;
        } else if (p->role >= ROLE_X && p->role <= ROLE_Z) {
            op = (unsigned char)(MT__BULK_X + (p->role - ROLE_X));
        }
        spec->ops[spec->num_ops++] = op;
    }
    return spec->faces ? lists == 1 : lists == 0;
}

static mt_status ascii_element(mt__io_src *src, const ply_header *h, const ply_elem *e, size_t *pos,
                               mt__builder *b, mt_diag *diag)
{
    const unsigned char *d = src->data;
    size_t n = src->size, i = *pos, cap = 0;
    const ply_prop *props = h->props + e->first_prop;
    list_check lc;
    lc.pending = 0;
    mt__bulk_spec plain;
    int bulk = bulk_spec_of(e, props, &plain);
    for (uint64_t item = 0; item < e->count; item++) {
        if (!reserve_items(b, e, item, &cap)) return mt__builder_fail(b, src, diag);
        /* Lines of plain items from here on: io_bulk.c reads them. */
        while (bulk && i < n && mt__is_space(d[i])) i++;
        if (bulk && i > 0 && i < n && d[i - 1] == '\n') {
            uint64_t got = mt__bulk_parse(src, &plain, &i, item, e->count, b);
            if (got) {
                item += got - 1;
                cap = e->kind == KIND_VERTEX ? b->cap_verts : b->cap_faces;
                continue;
            }
        }
        double xyz[3] = {0, 0, 0};
        for (size_t k = 0; k < e->num_props; k++) {
            const ply_prop *p = &props[k];
            size_t start, len;
            if (p->role >= ROLE_X && p->role <= ROLE_Z) { /* fast path: a plain decimal */
                while (i < n && mt__is_space(d[i])) i++;
                size_t used = i < n ? mt__scan_decimal(d + i, d + n, &xyz[p->role - ROLE_X]) : 0;
                if (used && (i + used == n || mt__is_space(d[i + used]))) {
                    i += used;
                    continue;
                }
            }
            int found = mt__src_token(src, &i, &start, &len);
            d = src->data;
            n = src->size;
            if (!found) return ascii_end(diag, src, h, e, item, p, NULL);
            if (p->count_type == PT_NONE) {
                if (p->role >= ROLE_X && p->role <= ROLE_Z &&
                    !mt__parse_double(d + start, len, &xyz[p->role - ROLE_X]))
                    return ascii_fail(diag, src, e, item, p, start, len, "not a number");
                continue;
            }
            uint64_t count;
            mt__num r = mt__parse_count(d + start, len, &count);
            if (r != MT__NUM_OK)
                return ascii_fail(diag, src, e, item, p, start, len, "bad list count");
            if (count > MT__IO_BIG_LIST) mt__src_learn_length(src);
            uint64_t length = mt__src_length(src), after = src->base + i;
            int known = length != MT__UNKNOWN;
            uint64_t rest = !known ? n - i : length > after ? length - after : 0;
            if ((known && count > rest / 2) || count > UINT32_MAX)
                return ascii_fail(diag, src, e, item, p, start, len,
                                  "list count larger than the rest of the file");
            lc.pending = !known && count > rest / 2;
            if (lc.pending) {
                lc.count = count;
                lc.after = after;
                lc.at = src->base + start;
                lc.line = mt__src_line(src, lc.at);
                mt__io_excerpt(lc.excerpt, sizeof lc.excerpt, d + start, len);
            }
            if (p->role == ROLE_INDICES) {
                uint64_t room = count < rest / 2 + 1 ? count : rest / 2 + 1;
                if (!mt__builder_reserve_indices(b, b->num_indices + (size_t)room))
                    return mt__builder_fail(b, src, diag);
                for (uint64_t j = 0; j < count; j++) {
                    int64_t index;
                    while (i < n && mt__is_space(d[i])) i++;
                    if (!mt__scan_index(d, n, &i, ' ', &index)) { /* not the fast path */
                        found = mt__src_token(src, &i, &start, &len);
                        d = src->data;
                        n = src->size;
                        if (!found) return ascii_end(diag, src, h, e, item, p, &lc);
                        r = mt__parse_index(d + start, len, &index);
                        if (r != MT__NUM_OK)
                            return ascii_fail(diag, src, e, item, p, start, len,
                                              r == MT__NUM_BAD ? "vertex index is not an integer"
                                                               : "vertex index does not fit in a "
                                                                 "32-bit integer");
                    }
                    if (!mt__builder_add_index(b, (uint32_t)index))
                        return mt__builder_fail(b, src, diag);
                }
                b->sizes[item] = (uint32_t)count;
            } else {
                for (uint64_t j = 0; j < count; j++) {
                    found = mt__src_token(src, &i, &start, &len);
                    d = src->data;
                    n = src->size;
                    if (!found) return ascii_end(diag, src, h, e, item, p, &lc);
                }
            }
            lc.pending = 0;
        }
        if (e->kind == KIND_VERTEX) {
            double *q = b->positions + 3 * item;
            q[0] = xyz[0];
            q[1] = xyz[1];
            q[2] = xyz[2];
        }
    }
    *pos = i;
    return MT_OK;
}

/* ---- Binary data ------------------------------------------------------- */

static inline uint16_t load16(const unsigned char *p, int be)
{
    return be ? (uint16_t)(p[0] << 8 | p[1]) : (uint16_t)(p[1] << 8 | p[0]);
}

static inline uint32_t load32(const unsigned char *p, int be)
{
    return be ? (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]
              : (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

static inline uint64_t load64(const unsigned char *p, int be)
{
    uint64_t a = load32(p, be), c = load32(p + 4, be);
    return be ? a << 32 | c : c << 32 | a;
}

static inline double load_double(const unsigned char *p, ply_type t, int be)
{
    switch (t) {
        case PT_I8:
            return (int8_t)p[0];
        case PT_U8:
            return p[0];
        case PT_I16:
            return (int16_t)load16(p, be);
        case PT_U16:
            return load16(p, be);
        case PT_I32:
            return (int32_t)load32(p, be);
        case PT_U32:
            return load32(p, be);
        case PT_F32: {
            uint32_t u = load32(p, be);
            float f;
            memcpy(&f, &u, sizeof f);
            return f;
        }
        case PT_F64: {
            uint64_t u = load64(p, be);
            double v;
            memcpy(&v, &u, sizeof v);
            return v;
        }
        default:
            return 0;
    }
}

/* An integer-typed value as a signed 64-bit number (exact for every type). */
static inline int64_t load_int(const unsigned char *p, ply_type t, int be)
{
    switch (t) {
        case PT_I8:
            return (int8_t)p[0];
        case PT_U8:
            return p[0];
        case PT_I16:
            return (int16_t)load16(p, be);
        case PT_U16:
            return load16(p, be);
        case PT_I32:
            return (int32_t)load32(p, be);
        default:
            return load32(p, be);
    }
}

/* Indices of type t at p as stored indices: signed types sign-extended
 * (negative ones as two's complement), unsigned ones as they are. */
static void load_indices(const unsigned char *p, ply_type t, int be, uint32_t count, uint32_t *out)
{
    switch (t) {
        case PT_I8:
            for (uint32_t j = 0; j < count; j++) out[j] = (uint32_t)(int32_t)(int8_t)p[j];
            break;
        case PT_U8:
            for (uint32_t j = 0; j < count; j++) out[j] = p[j];
            break;
        case PT_I16:
            for (uint32_t j = 0; j < count; j++)
                out[j] = (uint32_t)(int32_t)(int16_t)load16(p + 2 * (size_t)j, be);
            break;
        case PT_U16:
            for (uint32_t j = 0; j < count; j++) out[j] = load16(p + 2 * (size_t)j, be);
            break;
        default: /* 32-bit, signed or not: the same bits */
            for (uint32_t j = 0; j < count; j++) out[j] = load32(p + 4 * (size_t)j, be);
            break;
    }
}

static mt_status binary_fail(mt_diag *diag, const mt__io_src *src, const ply_elem *e, uint64_t item,
                             const ply_prop *p, uint64_t offset, const char *what)
{
    char label[96];
    item_label(label, sizeof label, e, item);
    return mt__io_fail(diag, MT_ERR_PARSE, src, MT__POS_BYTE, offset, item_element(e, item),
                       "%s: property '%s': %s", label, p->name, what);
}

/* The input ended early: the header's size check comes first (ascii_end). */
static mt_status binary_end(mt_diag *diag, const mt__io_src *src, const ply_header *h,
                            const ply_elem *e, uint64_t item, const ply_prop *p, uint64_t offset,
                            const char *what)
{
    mt_status status = check_size(src, h, diag);
    if (status != MT_OK) return status;
    return binary_fail(diag, src, e, item, p, offset, what);
}

/* How runs of binary items are read without the general loop: vertices
 * whose properties are all scalars (a fixed stride, x y z at fixed
 * offsets), faces whose only property is the index list. */
typedef struct binary_run {
    int fixed;        /* vertices: every property a scalar */
    size_t stride;    /* their bytes */
    size_t offset[3]; /* of x, y, z */
    ply_type type[3]; /* PT_NONE: absent (0) */
    int list;         /* faces: only the index list */
    ply_type count_type, index_type;
} binary_run;

static void binary_run_of(const ply_elem *e, const ply_prop *props, binary_run *r)
{
    memset(r, 0, sizeof *r);
    if (e->kind == KIND_VERTEX) {
        r->fixed = 1;
        for (size_t k = 0; k < e->num_props; k++) {
            const ply_prop *p = &props[k];
            if (p->count_type != PT_NONE) r->fixed = 0;
            if (p->role >= ROLE_X && p->role <= ROLE_Z) {
                r->offset[p->role - ROLE_X] = r->stride;
                r->type[p->role - ROLE_X] = p->type;
            }
            r->stride += type_size[p->type];
        }
    } else if (e->kind == KIND_FACE && e->num_props == 1 && props[0].role == ROLE_INDICES) {
        r->list = 1;
        r->count_type = props[0].count_type;
        r->index_type = props[0].type;
    }
}

/* The data's byte order is this machine's: values can be copied as they are. */
static int native_order(int be)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    return !be;
#elif defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    return be;
#else
    (void)be;
    return 0;
#endif
}

/* Vertices [*item, *item + k) from the window: as many whole ones as it
 * holds, up to `limit`. Vertices of x, y, z doubles only, in this machine's
 * byte order, are the positions array's own layout: copied at once. */
static void binary_run_verts(const binary_run *r, const unsigned char *d, size_t n, size_t *pos,
                             int be, uint64_t *item, uint64_t limit, double *positions)
{
    size_t i = *pos;
    uint64_t k = (n - i) / r->stride;
    if (k > limit - *item) k = limit - *item;
    double *q = positions + 3 * *item;
    if (r->stride == 3 * sizeof(double) && r->offset[1] == 8 && r->offset[2] == 16 &&
        r->type[0] == PT_F64 && r->type[1] == PT_F64 && r->type[2] == PT_F64 && native_order(be)) {
        if (k) memcpy(q, d + i, (size_t)k * r->stride);
        *item += k;
        *pos = i + (size_t)k * r->stride;
        return;
    }
    for (uint64_t j = 0; j < k; j++, i += r->stride, q += 3) {
        for (int c = 0; c < 3; c++)
            q[c] = r->type[c] == PT_NONE ? 0.0 : load_double(d + i + r->offset[c], r->type[c], be);
    }
    *item += k;
    *pos = i;
}

/* Triangles with a one-byte count and 32-bit indices in this machine's
 * byte order, from window index i, while the index array has room: their
 * indices are copied as they are (a signed index keeps its bits, as
 * load_indices stores it). Returns the faces read; *pos moves past them. */
static uint64_t binary_run_triangles(const unsigned char *d, size_t n, size_t *pos, uint64_t f,
                                     uint64_t limit, mt__builder *b)
{
    enum { BYTES = 1 + 3 * 4 };
    size_t i = *pos;
    uint64_t k = (n - i) / BYTES, room = (b->cap_indices - b->num_indices) / 3;
    if (k > limit - f) k = limit - f;
    if (k > room) k = room;
    uint32_t *out = b->indices ? b->indices + b->num_indices : NULL;
    uint64_t j = 0;
    for (; j < k && d[i] == 3; j++, i += BYTES) {
        memcpy(out + 3 * j, d + i + 1, 3 * sizeof(uint32_t));
        b->sizes[f + j] = 3;
    }
    b->num_indices += 3 * (size_t)j;
    *pos = i;
    return j;
}

/* Faces from the window, while whole ones of at most 2^16 entries are in
 * it, up to `limit`; anything else is left to the general loop. Returns 0
 * when the index array cannot grow. */
static int binary_run_faces(const binary_run *r, const unsigned char *d, size_t n, size_t *pos,
                            int be, uint64_t *item, uint64_t limit, mt__builder *b)
{
    size_t i = *pos, csize = type_size[r->count_type], isize = type_size[r->index_type];
    const int triangles = csize == 1 && isize == 4 && native_order(be);
    uint64_t f = *item;
    while (f < limit && n - i >= csize) {
        if (triangles) {
            f += binary_run_triangles(d, n, &i, f, limit, b);
            if (f == limit || n - i < csize) break;
        }
        int64_t count = load_int(d + i, r->count_type, be);
        if (count < 0 || count > (1 << 16) || (n - i - csize) / isize < (uint64_t)count) break;
        if (b->cap_indices - b->num_indices < (size_t)count &&
            !mt__builder_reserve_indices(b, b->num_indices + (size_t)count)) {
            *pos = i;
            *item = f;
            return 0;
        }
        if (count > 0) /* an empty face may come before any index array exists */
            load_indices(d + i + csize, r->index_type, be, (uint32_t)count,
                         b->indices + b->num_indices);
        b->num_indices += (size_t)count;
        b->sizes[f++] = (uint32_t)count;
        i += csize + (size_t)count * isize;
    }
    *pos = i;
    *item = f;
    return 1;
}

static mt_status binary_element(mt__io_src *src, const ply_header *h, const ply_elem *e,
                                size_t *pos, mt__builder *b, mt_diag *diag)
{
    static const char *const past_end = "the list runs past the end of the data";
    const unsigned char *d = src->data;
    size_t n = src->size, i = *pos, cap = 0;
    int be = h->encoding == ENC_BE;
    const ply_prop *props = h->props + e->first_prop;
    binary_run run;
    binary_run_of(e, props, &run);
    for (uint64_t item = 0; item < e->count; item++) {
        if (!reserve_items(b, e, item, &cap)) return mt__builder_fail(b, src, diag);
        /* Whole items in the window: a run without the general loop. */
        uint64_t from = item;
        if (run.fixed)
            binary_run_verts(&run, d, n, &i, be, &item, cap, b->positions);
        else if (run.list && !binary_run_faces(&run, d, n, &i, be, &item, cap, b))
            return mt__builder_fail(b, src, diag);
        if (item != from) {
            item--;
            continue;
        }
        double xyz[3] = {0, 0, 0};
        for (size_t k = 0; k < e->num_props; k++) {
            const ply_prop *p = &props[k];
            size_t size = type_size[p->count_type != PT_NONE ? p->count_type : p->type];
            if (n - i < size) {
                int ok = mt__src_need(src, &i, size);
                d = src->data;
                n = src->size;
                if (!ok)
                    return binary_end(diag, src, h, e, item, p, src->base + i,
                                      "unexpected end of data");
            }
            if (p->count_type == PT_NONE) {
                if (p->role >= ROLE_X && p->role <= ROLE_Z)
                    xyz[p->role - ROLE_X] = load_double(d + i, p->type, be);
                i += size;
                continue;
            }
            int64_t count = load_int(d + i, p->count_type, be);
            if (count < 0)
                return binary_fail(diag, src, e, item, p, src->base + i, "negative list count");
            i += size;
            if ((uint64_t)count > MT__IO_BIG_LIST) mt__src_learn_length(src);
            uint64_t after = src->base + i, length = mt__src_length(src);
            size_t isize = type_size[p->type];
            if (length != MT__UNKNOWN &&
                (uint64_t)count > (length > after ? length - after : 0) / isize)
                return binary_fail(diag, src, e, item, p, after, past_end);
            /* The list, a window at a time: indices stored, anything else skipped. */
            uint64_t left = (uint64_t)count;
            while (left) {
                size_t avail = (n - i) / isize;
                if (avail == 0) {
                    int ok = mt__src_need(src, &i, isize);
                    d = src->data;
                    n = src->size;
                    if (!ok) return binary_end(diag, src, h, e, item, p, after, past_end);
                    continue;
                }
                size_t take = avail < left ? avail : (size_t)left;
                if (p->role == ROLE_INDICES) {
                    if (!mt__builder_reserve_indices(b, b->num_indices + take))
                        return mt__builder_fail(b, src, diag);
                    load_indices(d + i, p->type, be, (uint32_t)take, b->indices + b->num_indices);
                    b->num_indices += take;
                }
                i += take * isize;
                left -= take;
            }
            if (p->role == ROLE_INDICES) b->sizes[item] = (uint32_t)count;
        }
        if (e->kind == KIND_VERTEX) {
            double *q = b->positions + 3 * item;
            q[0] = xyz[0];
            q[1] = xyz[1];
            q[2] = xyz[2];
        }
    }
    *pos = i;
    return MT_OK;
}

/* ---- The whole file ---------------------------------------------------- */

/* Before the face list of input whose length is unknown grows large: the
 * length is learned (if it can be) and the element counts checked. */
typedef struct ply_confirm {
    mt__io_src *src;
    const ply_header *h;
} ply_confirm;

static mt_status confirm_size(void *ctx, mt_diag *diag)
{
    ply_confirm *c = ctx;
    mt__src_learn_length(c->src);
    return check_size(c->src, c->h, diag);
}

static mt_status read_ply(mt__io_src *src, ply_header *h, mt__builder *b, mt_diag *diag)
{
    /* The header is read whole: the window widens (from the input's start)
     * until it holds it. */
    for (;;) {
        int need_more;
        mt_status status = parse_header(src, h, &need_more, diag);
        if (status != MT_OK) return status;
        if (!need_more) break;
        header_free(h);
        memset(h, 0, sizeof *h);
        size_t keep = 0;
        mt__src_more(src, &keep);
    }
    if (mt__src_length(src) != MT__UNKNOWN) { /* parse_header checked the counts against it */
        uint64_t verts = 0, faces = 0;
        for (size_t k = 0; k < h->num_elems; k++) {
            if (h->elems[k].kind == KIND_VERTEX) verts = h->elems[k].count;
            if (h->elems[k].kind == KIND_FACE) faces = h->elems[k].count;
        }
        mt__builder_reserve_declared(b, verts, faces, 3 * faces);
    }
    size_t pos = h->data_start;
    int binary = h->encoding != ENC_ASCII;
    if (binary) mt__src_binary(src);
    ply_confirm confirm = {src, h};
    b->confirm = confirm_size;
    b->confirm_ctx = &confirm;
    for (size_t k = 0; k < h->num_elems; k++) {
        const ply_elem *e = &h->elems[k];
        if (e->num_props == 0) continue; /* items without properties take no bytes */
        mt_status status = binary ? binary_element(src, h, e, &pos, b, diag)
                                  : ascii_element(src, h, e, &pos, b, diag);
        if (status != MT_OK) return status;
        if (e->kind == KIND_VERTEX) b->num_verts = (size_t)e->count;
        if (e->kind == KIND_FACE) b->num_faces = (size_t)e->count;
    }
    mt__io_pos where = binary ? MT__POS_BYTE : MT__POS_LINE;
    switch (mt__src_skip_trailer(src, &pos, 0)) {
        case MT__TRAIL_END:
            return MT_OK;
        case MT__TRAIL_DATA:
            return mt__io_fail(diag, MT_ERR_PARSE, src, where, src->base + pos, MT_NONE,
                               "unexpected data after the last element");
        case MT__TRAIL_LONG:
            break;
    }
    return mt__io_fail(diag, MT_ERR_PARSE, src, where, src->base + pos, MT_NONE,
                       "the input goes on for more than %llu bytes after the last element",
                       (unsigned long long)MT_READ_MAX_TRAILING_BYTES);
}

mt_status mt__read_ply(mt__io_src *src, mt_face_list *out, mt_diag *diag)
{
    ply_header h;
    memset(&h, 0, sizeof h);
    mt__builder b;
    memset(&b, 0, sizeof b);
    mt_status status = read_ply(src, &h, &b, diag);
    if (status == MT_OK) status = mt__builder_finish(&b, out, src, diag);
    mt__builder_free(&b);
    header_free(&h);
    return status;
}
