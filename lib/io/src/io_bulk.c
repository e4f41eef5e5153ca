/* Runs of plain records, one per line, parsed ahead of a reader's general
 * loop and split across threads: an OFF or ASCII PLY vertex ("x y z") or
 * face ("3 i j k") line of numbers separated by spaces or tabs, or an OBJ
 * "v x y z" or "f i j k" (entries i, i/t, i/t/n, i//n) line. A line that
 * is anything else (a comment, a blank line, a record over several lines, a
 * malformed number, the window's unfinished last line) stops the run before
 * it, and the reader's general loop, which owns every message and line
 * number, takes it from there; so results, errors and their positions are
 * those of the general loop alone. Numbers: mt__scan_decimal, else
 * mt__parse_double (strtod), the general loop's own functions. A run large
 * enough is cut at line ends into parts; part 0 is parsed on the calling
 * thread into the face list, the others on threads of their own. Where the
 * face list already has room, each part writes straight into its own
 * region of it: a line is a record, so a part's first record follows the
 * lines before it, and its first index is guessed from the faces read just
 * before (exact for meshes of one face size; a gap left by a wrong guess is
 * closed afterwards, and an index region too small stops the part there).
 * Otherwise a part parses into scratch arrays appended in order once part 0
 * ends where part 1 starts. A part's thread starts on another CPU than the
 * calling thread's, as core's parallel.c starts its parts and for the same
 * reason (said there). */
#define _GNU_SOURCE /* cpu_set_t, sched_getcpu, pthread_attr_setaffinity_np */
#include <float.h>
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <unistd.h>

#include "io_internal.h"

/* Bytes each thread gets at least (smaller runs are parsed on one), and
 * bytes parsed on the calling thread before any other starts. The fuzz
 * build makes both tiny, so that its small inputs are cut into parts too. */
#ifdef MESHTOPO_FUZZ_SMALL_PARTS
#define THREAD_MIN_BYTES ((size_t)64)
#define PROBE_BYTES ((size_t)32)
#else
#define THREAD_MIN_BYTES ((size_t)512 << 10)
#define PROBE_BYTES ((size_t)64 << 10)
#endif
/* A worker checks whether its part is still wanted every this many lines. */
#define CANCEL_LINES 1024u
/* When the calling thread reads the next window ahead after its part, its
 * part is smaller by 1/READ_AHEAD_SHARE of the run's bytes, so that it
 * ends with the others': it reads while they finish. */
#define READ_AHEAD_SHARE 12

/* Where a part's records go: arrays with room for cap_* elements. */
typedef struct bulk_out {
    double *positions; /* 3 per vertex */
    size_t num_verts, cap_verts;
    uint32_t *sizes;
    size_t num_faces, cap_faces;
    uint32_t *indices;
    size_t num_indices, cap_indices;
} bulk_out;

/* Why a part stopped. */
typedef enum part_end {
    END_DONE,  /* its bytes are all read, or `max` records */
    END_ROOM,  /* the output is full */
    END_OTHER, /* a line the bulk parser leaves to the general loop, or cancelled */
} part_end;

typedef struct bulk_part {
    const mt__bulk_spec *spec;
    const unsigned char *d;
    size_t begin, end; /* [begin, end): whole lines */
    size_t pos;        /* where parsing is */
    uint64_t max;      /* records wanted at most */
    bulk_out out;      /* where records go: a region of the face list, or scratch */
    bulk_out scratch;  /* workers: arrays of their own, kept from run to run */
    int direct;        /* out is a region of the face list */
    part_end why;
    int nomem;
    atomic_int *cancel;
    pthread_t thread;
    int started;
    const cpu_set_t *allowed; /* where its thread may go once it runs; NULL: anywhere */
} bulk_part;

struct mt__bulk {
    bulk_part parts[MT__BULK_MAX_THREADS]; /* parts[0].scratch is unused */
};

/* ---- One line ----------------------------------------------------------- */

static inline int is_hspace(unsigned char c)
{
    return c == ' ' || c == '\t';
}

/* Ends a token: a separator, or the line's end. */
static inline int ends_token(unsigned char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

/* The digits at p when fewer than 8 are (8 bytes are read): their count,
 * and their value in *value; 8 when there are 8 or more. No branch on the
 * count, which varies from number to number. */
static inline unsigned short_digits(const unsigned char *p, uint64_t *value)
{
    uint64_t w = mt__load8(p), nd = mt__nondigits8(w);
    if (!nd) return 8;
    unsigned len = (unsigned)__builtin_ctzll(nd) / 8;
    *value = len ? mt__digits8_value((w - 0x3030303030303030ull) << (8 * (8 - len))) : 0;
    return len;
}

/* Up to 10 digits at d[k] (8 at a time where 8 bytes are in the window):
 * their value, and k past them. More than 10 digits: *k moves past 11. */
static inline uint64_t scan_digits(const unsigned char *d, size_t n, size_t *k)
{
    size_t i = *k;
    uint64_t v = 0;
    if (n - i >= 8) {
        unsigned len = short_digits(d + i, &v);
        if (len < 8) {
            *k = i + len;
            return v;
        }
    }
    size_t s = i;
    while (i < n && (unsigned)d[i] - '0' <= 9 && i - s < 11) v = v * 10 + (d[i++] - '0');
    *k = i;
    return v;
}

/* A plain count: 1 to 3 digits. */
static inline int scan_count(const unsigned char *d, size_t n, size_t *pos, uint32_t *out)
{
    size_t k = *pos;
    uint64_t v = scan_digits(d, n, &k);
    if (k == *pos || k - *pos > 3 || k >= n || !ends_token(d[k])) return 0;
    *out = (uint32_t)v;
    *pos = k;
    return 1;
}

/* An index as the general loop's fast path reads it (mt__scan_index),
 * followed by a separator or the line's end. */
static inline int scan_index(const unsigned char *d, size_t n, size_t *pos, uint32_t *out)
{
    size_t k = *pos;
    int neg = d[k] == '-';
    k += (size_t)neg;
    size_t s = k;
    uint64_t v = scan_digits(d, n, &k);
    if (k == s || k - s > 10 || k >= n || !ends_token(d[k])) return 0;
    if (neg ? v > 0x80000000ull : v > 0xffffffffull) return 0;
    *out = neg ? (uint32_t) - (int64_t)v : (uint32_t)v;
    *pos = k;
    return 1;
}

/* An OBJ face entry as io_obj.c reads it: a signed vertex index (1-based,
 * negative ones counting back from the `defined` vertices before the line;
 * 0 is stored as -1, out of range), then optionally "/[vt]" and "/[vn]" of
 * signed digits, followed by a separator or the line's end. */
static inline int scan_entry(const unsigned char *d, size_t n, size_t *pos, uint32_t defined,
                             uint32_t *out)
{
    size_t k = *pos;
    int neg = d[k] == '-';
    k += (size_t)(neg || d[k] == '+');
    const size_t first = k;
    uint64_t v = scan_digits(d, n, &k);
    if (k == first || k - first > 10 || v > (neg ? 0x80000000ull : 0xffffffffull)) return 0;
    for (int part = 0; part < 2 && k < n && d[k] == '/'; part++) {
        k++;
        if (k < n && (d[k] == '-' || d[k] == '+')) k++;
        while (k < n && (unsigned)d[k] - '0' <= 9) k++;
    }
    if (k >= n || !ends_token(d[k])) return 0;
    if (v == 0)
        *out = UINT32_MAX;
    else
        *out = neg ? defined - (uint32_t)v : (uint32_t)(v - 1); /* wraps as io_obj.c's does */
    *pos = k;
    return 1;
}

/* A token's end as the general loop finds it (any whitespace), which must
 * be a separator or the line's end here (not '\v' or '\f'); n when the
 * window ends first. */
static inline size_t token_end(const unsigned char *d, size_t n, size_t i)
{
    while (i < n && !mt__is_space(d[i])) i++;
    return i < n && ends_token(d[i]) ? i : n;
}

/* A number, as the general loop reads one. */
static inline int scan_number(const unsigned char *d, size_t n, size_t *pos, double *out)
{
    size_t k = *pos;
    size_t used = mt__scan_decimal(d + k, d + n, out);
    if (used && k + used < n && ends_token(d[k + used])) {
        *pos = k + used;
        return 1;
    }
    size_t e = token_end(d, n, k);
    if (e == k || e >= n || !mt__parse_double(d + k, e - k, out)) return 0;
    *pos = e;
    return 1;
}

/* The end of the rest of a line at i (i < n, after spaces and tabs): where
 * its '\n' or "\r\n" starts. Anything may come before it, but only '\n'
 * or "\r\n" may end it (the general loop stops at a lone '\r'); most
 * lines have nothing left. n when the line has a lone '\r', ends in a
 * backslash (OBJ continues such a line) or has no '\n' in the window. */
static size_t rest_end(const unsigned char *d, size_t n, size_t i)
{
    if (d[i] == '\n' || d[i] == '\r') return i;
    const unsigned char *nl = memchr(d + i, '\n', n - i);
    if (!nl) return n;
    size_t e = (size_t)(nl - d);
    const unsigned char *cr = memchr(d + i, '\r', e - i);
    if (cr && cr != nl - 1) return n;
    i = cr ? e - 1 : e;
    return d[i - 1] == '\\' ? n : i;
}

/* ---- The common lines, before the general shapes ----------------------- */

/* Most lines are "x y z" of short decimals or "3 i j k", optionally after a
 * keyword letter: fast_line reads those alone, without parse_line's walk
 * over the spec's ops, and leaves every other line to parse_line, which
 * reads it as before. It reads only lines that start FAST_SPAN bytes or
 * more before the part's end, and looks at most that far. */
#define FAST_SPAN ((size_t)192)
/* Where a line's separators must end: a number or an index after them
 * reads at most 46 bytes (a sign, 20 digits, '.', 16 digits and 8 more
 * read). */
#define FAST_ITEMS_END ((size_t)128)

typedef enum line_shape {
    SHAPE_OTHER,    /* parse_line alone */
    SHAPE_XYZ,      /* [keyword] x y z: ops X Y Z, then REST or nothing */
    SHAPE_FACE,     /* count and indices: ops INDICES, then REST or nothing */
    SHAPE_OBJ_FACE, /* keyword and OBJ face entries: ops KEYWORD ENTRIES */
} line_shape;

/* What fast_line reads of a spec's lines. */
typedef struct line_form {
    line_shape shape;
    unsigned char keyword; /* the letter before the items, or 0 */
    int rest;              /* anything may follow them (MT__BULK_REST) */
} line_form;

static line_form form_of(const mt__bulk_spec *spec)
{
    line_form form = {SHAPE_OTHER, 0, 0};
    const unsigned char *op = spec->ops;
    size_t n = spec->num_ops;
    if (n && op[0] == MT__BULK_KEYWORD) {
        form.keyword = spec->keyword;
        op++;
        n--;
    }
    form.rest = n && op[n - 1] == MT__BULK_REST;
    n -= (size_t)form.rest;
    if (n == 3 && op[0] == MT__BULK_X && op[1] == MT__BULK_Y && op[2] == MT__BULK_Z)
        form.shape = SHAPE_XYZ;
    else if (n == 1 && op[0] == MT__BULK_INDICES)
        form.shape = SHAPE_FACE;
    else if (n == 1 && op[0] == MT__BULK_ENTRIES && form.keyword)
        form.shape = SHAPE_OBJ_FACE;
    return form;
}

/* Past spaces and tabs at p, not beyond lim. */
static inline const unsigned char *skip_hspace(const unsigned char *p, const unsigned char *lim)
{
    while (p < lim && is_hspace(*p)) p++;
    return p;
}

/* The digits at *q, up to `most` of them (8 bytes are read): their value
 * in *value (0 before), *q past them, and their count; fewer than 8 at
 * once (short_digits), more one at a time. */
static inline size_t leading_digits(const unsigned char **q, size_t most, uint64_t *value)
{
    size_t n = short_digits(*q, value);
    if (n < 8) {
        *q += n;
        return n;
    }
    const unsigned char *p = *q;
    unsigned c;
    while ((size_t)(p - *q) < most && (c = (unsigned)*p - '0') <= 9) {
        *value = *value * 10 + c;
        p++;
    }
    n = (size_t)(p - *q);
    *q = p;
    return n;
}

static const uint64_t pow10_u64[8] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000};

/* A number ending a token, as scan_number reads it: a plain decimal of at
 * most 19 digits without an exponent here, as mt__scan_decimal would read
 * it (Clinger's fast path, else Eisel-Lemire), others by mt__scan_decimal.
 * 0 when neither reads it: parse_line then reads the line. */
static inline int fast_number(const unsigned char **at, const unsigned char *end, double *out)
{
    const unsigned char *p = *at;
#if FLT_EVAL_METHOD == 0
    int neg = *p == '-';
    const unsigned char *q = p + neg;
    uint64_t mant = 0;
    size_t digits = leading_digits(&q, 20, &mant);
    size_t frac = 0;
    if (*q == '.') {
        const unsigned char *f = ++q;
        uint64_t chunk, tail = 0;
        while (q - f < 16 && mt__is_8digits(chunk = mt__load8(q))) {
            mant = mant * 100000000 + mt__parse_8digits(chunk);
            q += 8;
        }
        size_t t = short_digits(q, &tail);
        if (t < 8) {
            mant = mant * pow10_u64[t] + tail;
            q += t;
        }
        frac = t < 8 ? (size_t)(q - f) : 24; /* 24 or more: not read here */
    }
    if (digits + frac - 1 < 19 && ends_token(*q)) {
        if (mant <= (1ull << 53)) {
            double v = (double)mant;
            if (frac) v /= mt__pow10_exact[frac];
            *out = neg ? -v : v;
            *at = q;
            return 1;
        }
        if (mt__eisel_lemire(mant, -(int64_t)frac, neg, out)) {
            *at = q;
            return 1;
        }
    }
#endif
    size_t used = mt__scan_decimal(p, end, out);
    if (!used || (size_t)(end - p) <= used || !ends_token(p[used])) return 0;
    *at = p + used;
    return 1;
}

/* 1 to 10 digits at *at of a value that fits 32 bits, as scan_digits
 * reads them for an index (without a sign). */
static inline int fast_u32(const unsigned char **at, uint32_t *out)
{
    const unsigned char *p = *at;
    uint64_t v = 0;
    size_t len = leading_digits(&p, 11, &v);
    if (len == 0 || len > 10 || v > 0xffffffffull) return 0;
    *out = (uint32_t)v;
    *at = p;
    return 1;
}

/* An OBJ face entry as scan_entry reads it, when its vertex index has no
 * sign, not looking past lim (and the few bytes of a number after it). */
static inline int fast_entry(const unsigned char **at, const unsigned char *lim, uint32_t *out)
{
    const unsigned char *p = *at;
    uint32_t v;
    if (!fast_u32(&p, &v)) return 0;
    for (int part = 0; part < 2 && *p == '/'; part++) {
        p++;
        if (*p == '-' || *p == '+') p++;
        while (p < lim && (unsigned)*p - '0' <= 9) p++;
    }
    if (p >= lim || !ends_token(*p)) return 0;
    *out = v ? v - 1 : UINT32_MAX;
    *at = p;
    return 1;
}

/* Past the end of a line's items at p (p < lim): spaces and tabs, then,
 * where the form allows a rest, anything up to '\n' or "\r\n" (rest_end),
 * else only '\n' or "\r\n" before lim; NULL where the line ends otherwise. */
static inline const unsigned char *line_end(const unsigned char *d, size_t n,
                                            const unsigned char *p, const unsigned char *lim,
                                            int rest)
{
    p = skip_hspace(p, lim);
    if (p >= lim) return NULL;
    if (rest && *p != '\r' && *p != '\n') {
        const size_t e = rest_end(d, n, (size_t)(p - d));
        if (e >= n) return NULL;
        p = d + e;
    }
    if (*p == '\r') p++;
    return *p == '\n' ? p + 1 : NULL;
}

/* Reads the line at *pos (at least FAST_SPAN bytes before n) into out as
 * parse_line would, when it has the common shape: returns 1 with *pos past
 * its '\n'. Otherwise 0, with out and *pos unchanged. */
static int fast_line(line_form form, const mt__bulk_spec *spec, const unsigned char *d, size_t n,
                     size_t *pos, bulk_out *out)
{
    const unsigned char *p = d + *pos, *lim = p + FAST_ITEMS_END;
    if (form.keyword) {
        if (p[0] != form.keyword || !is_hspace(p[1])) return 0;
        p = skip_hspace(p + 2, lim);
    }
    if (form.shape == SHAPE_XYZ) {
        double xyz[3];
        for (int k = 0; k < 3; k++) {
            if (k) {
                if (!is_hspace(*p)) return 0;
                p = skip_hspace(p + 1, lim);
            }
            if (p >= lim || !fast_number(&p, d + n, &xyz[k])) return 0;
        }
        if (p >= lim || !(p = line_end(d, n, p, lim, form.rest))) return 0;
        double *xyz_out = out->positions + 3 * out->num_verts++;
        xyz_out[0] = xyz[0];
        xyz_out[1] = xyz[1];
        xyz_out[2] = xyz[2];
    } else if (form.shape == SHAPE_OBJ_FACE) {
        uint32_t *idx = out->indices + out->num_indices;
        size_t room = out->cap_indices - out->num_indices;
        uint32_t size = 0;
        do {
            if (size == MT__BULK_MAX_LIST || size == room || p >= lim) return 0;
            if (*p == '-' || *p == '+') { /* relative, or signed: scan_entry */
                size_t i = (size_t)(p - d);
                if (!scan_entry(d, n, &i, spec->defined, &idx[size])) return 0;
                p = d + i;
            } else if (!fast_entry(&p, lim, &idx[size])) {
                return 0;
            }
            size++;
            p = skip_hspace(p, lim);
        } while (p < lim && *p != '\r' && *p != '\n');
        if (p >= lim || !(p = line_end(d, n, p, lim, 0))) return 0;
        out->sizes[out->num_faces++] = size;
        out->num_indices += size;
    } else {
        unsigned count = (unsigned)*p - '0';
        if (count - 1 > 8 || !is_hspace(p[1]) || count > out->cap_indices - out->num_indices)
            return 0;
        uint32_t *idx = out->indices + out->num_indices;
        p++;
        for (unsigned j = 0; j < count; j++) {
            if (!is_hspace(*p)) return 0;
            p = skip_hspace(p + 1, lim);
            if (p >= lim || !fast_u32(&p, &idx[j]) || !ends_token(*p)) return 0;
        }
        if (p >= lim || !(p = line_end(d, n, p, lim, form.rest))) return 0;
        out->sizes[out->num_faces++] = count;
        out->num_indices += count;
    }
    *pos = (size_t)(p - d);
    return 1;
}

/* What parse_line found. */
typedef enum line_result {
    LINE_OTHER,   /* a line the bulk parser leaves to the general loop */
    LINE_READ,    /* a record, now in out */
    LINE_NO_ROOM, /* a face with more indices than out has room for */
} line_result;

/* Parses the line at *pos (the start of a line) into out, which has room
 * for one vertex, or one face. Returns LINE_READ with *pos past its '\n';
 * otherwise out's counts are unchanged. */
static line_result parse_line(const mt__bulk_spec *spec, const unsigned char *d, size_t n,
                              size_t *pos, bulk_out *out)
{
    size_t i = *pos;
    double xyz[3] = {0, 0, 0};
    uint32_t size = 0;
    uint32_t *idx = out->indices ? out->indices + out->num_indices : NULL;
    for (size_t o = 0; o < spec->num_ops; o++) {
        unsigned char op = spec->ops[o];
        while (i < n && is_hspace(d[i])) i++;
        if (i >= n || (op != MT__BULK_REST && mt__is_space(d[i])))
            return LINE_OTHER; /* the line ends before the item, or '\v' '\f' */
        switch (op) {
            case MT__BULK_X:
            case MT__BULK_Y:
            case MT__BULK_Z:
                if (!scan_number(d, n, &i, &xyz[op - MT__BULK_X])) return LINE_OTHER;
                break;
            case MT__BULK_TOKEN:
                i = token_end(d, n, i);
                if (i >= n) return LINE_OTHER;
                break;
            case MT__BULK_INDICES:
            case MT__BULK_LIST: {
                uint32_t count;
                if (!scan_count(d, n, &i, &count) || count > MT__BULK_MAX_LIST) return LINE_OTHER;
                if (op == MT__BULK_INDICES && count > out->cap_indices - out->num_indices)
                    return LINE_NO_ROOM;
                for (uint32_t j = 0; j < count; j++) {
                    while (i < n && is_hspace(d[i])) i++;
                    if (i >= n || mt__is_space(d[i])) return LINE_OTHER;
                    if (op == MT__BULK_INDICES) {
                        if (!scan_index(d, n, &i, &idx[j])) return LINE_OTHER;
                    } else {
                        i = token_end(d, n, i);
                        if (i >= n) return LINE_OTHER;
                    }
                }
                if (op == MT__BULK_INDICES) size = count;
                break;
            }
            case MT__BULK_KEYWORD:
                if (d[i] != spec->keyword || i + 1 >= n || !is_hspace(d[i + 1])) return LINE_OTHER;
                i++;
                break;
            case MT__BULK_ENTRIES:
                for (;;) {
                    if (size == MT__BULK_MAX_LIST) return LINE_OTHER;
                    if (size == out->cap_indices - out->num_indices) return LINE_NO_ROOM;
                    if (!scan_entry(d, n, &i, spec->defined, &idx[size])) return LINE_OTHER;
                    size++;
                    while (i < n && is_hspace(d[i])) i++;
                    if (i >= n || d[i] == '\r' || d[i] == '\n') break;
                }
                break;
            case MT__BULK_REST:
                i = rest_end(d, n, i);
                if (i >= n) return LINE_OTHER;
                break;
            default:
                return LINE_OTHER;
        }
    }
    /* the end of the line: only spaces and tabs, then '\n' or "\r\n" */
    while (i < n && is_hspace(d[i])) i++;
    if (i < n && d[i] == '\r') i++;
    if (i >= n || d[i] != '\n') return LINE_OTHER;
    *pos = i + 1;
    if (spec->faces) {
        out->sizes[out->num_faces++] = size;
        out->num_indices += size;
    } else {
        double *p = out->positions + 3 * out->num_verts++;
        p[0] = xyz[0];
        p[1] = xyz[1];
        p[2] = xyz[2];
    }
    return LINE_READ;
}

/* ---- A part: lines until its end, `max` records or full output --------- */

/* Room for one more record (a face's indices are checked once its count
 * is read). */
static int has_room(const mt__bulk_spec *spec, const bulk_out *out)
{
    if (!spec->faces) return out->num_verts < out->cap_verts;
    return out->num_faces < out->cap_faces;
}

static void parse_part(bulk_part *p)
{
    const mt__bulk_spec *spec = p->spec;
    size_t records = spec->faces ? p->out.num_faces : p->out.num_verts;
    uint32_t lines = 0;
    const line_form form = form_of(spec);
    for (;;) {
        if (p->pos >= p->end || records >= p->max) {
            p->why = END_DONE;
            return;
        }
        if (!has_room(spec, &p->out)) {
            p->why = END_ROOM;
            return;
        }
        if (p->cancel && ++lines % CANCEL_LINES == 0 &&
            atomic_load_explicit(p->cancel, memory_order_relaxed)) {
            p->why = END_OTHER;
            return;
        }
        if (form.shape != SHAPE_OTHER && p->end - p->pos >= FAST_SPAN &&
            fast_line(form, spec, p->d, p->end, &p->pos, &p->out)) {
            records++;
            continue;
        }
        line_result r = parse_line(spec, p->d, p->end, &p->pos, &p->out);
        if (r != LINE_READ) {
            p->why = r == LINE_NO_ROOM ? END_ROOM : END_OTHER;
            return;
        }
        records++;
    }
}

/* Scratch arrays of a worker grow with what it parses. */
static int scratch_grow(const mt__bulk_spec *spec, bulk_out *out)
{
    if (!spec->faces) {
        size_t cap = out->cap_verts < 4096 ? 8192 : 2 * out->cap_verts;
        double *p = realloc(out->positions, cap * 3 * sizeof(double));
        if (!p) return 0;
        out->positions = p;
        out->cap_verts = cap;
        return 1;
    }
    if (out->num_faces == out->cap_faces) {
        size_t cap = out->cap_faces < 4096 ? 8192 : 2 * out->cap_faces;
        uint32_t *p = realloc(out->sizes, cap * sizeof(uint32_t));
        if (!p) return 0;
        out->sizes = p;
        out->cap_faces = cap;
    }
    if (out->cap_indices - out->num_indices < MT__BULK_MAX_LIST) { /* room for any face */
        size_t cap = out->cap_indices < 16384 ? 32768 : 2 * out->cap_indices;
        uint32_t *p = realloc(out->indices, cap * sizeof(uint32_t));
        if (!p) return 0;
        out->indices = p;
        out->cap_indices = cap;
    }
    return 1;
}

static void *worker_main(void *arg)
{
    bulk_part *p = arg;
    /* strtod reads '.' as the decimal point on this thread too */
    mt__locale_state locale;
    mt__c_locale_enter(&locale);
    for (;;) {
        parse_part(p);
        if (p->why != END_ROOM || p->direct) break; /* a region of the face list cannot grow */
        if (!scratch_grow(p->spec, &p->out)) {
            p->nomem = 1;
            p->why = END_OTHER;
            break;
        }
    }
    mt__c_locale_leave(&locale);
    return NULL;
}

/* A part on a thread of its own, started elsewhere than the calling thread. */
static void *part_thread(void *arg)
{
    bulk_part *p = arg;
    if (p->allowed) pthread_setaffinity_np(pthread_self(), sizeof *p->allowed, p->allowed);
    return worker_main(p);
}

/* The CPUs the calling thread may use (*allowed) and those of them it is
 * not on (*elsewhere); 0 when there is no other, or they are not known.
 * (Core's parallel.c has its own: io does not reach into core's insides.) */
static int cpus_elsewhere(cpu_set_t *allowed, cpu_set_t *elsewhere)
{
    if (sched_getaffinity(0, sizeof *allowed, allowed) != 0) return 0;
    int here = sched_getcpu();
    if (here < 0 || here >= CPU_SETSIZE || !CPU_ISSET(here, allowed)) return 0;
    *elsewhere = *allowed;
    CPU_CLR(here, elsewhere);
    return CPU_COUNT(elsewhere) > 0;
}

/* Starts parts 1 and later on threads of their own (kept off this thread's
 * CPU until they run); returns whether they were so kept. */
static int start_parts(bulk_part *pp, unsigned parts, cpu_set_t *allowed)
{
    cpu_set_t elsewhere;
    pthread_attr_t attr;
    int spread = cpus_elsewhere(allowed, &elsewhere) && pthread_attr_init(&attr) == 0;
    if (spread && pthread_attr_setaffinity_np(&attr, sizeof elsewhere, &elsewhere) != 0) {
        pthread_attr_destroy(&attr);
        spread = 0;
    }
    for (unsigned t = 1; t < parts; t++) {
        pp[t].allowed = spread ? allowed : NULL;
        pp[t].started =
            pthread_create(&pp[t].thread, spread ? &attr : NULL, part_thread, &pp[t]) == 0;
    }
    if (spread) pthread_attr_destroy(&attr);
    return spread;
}

/* ---- Part 0: into the face list ----------------------------------------- */

/* out as a view of the builder's arrays from record `rec` and index `index`
 * on, up to record rec_end and index index_end or the arrays' ends. */
static void alias_builder(const mt__bulk_spec *spec, const mt__builder *b, size_t rec, size_t index,
                          size_t rec_end, size_t index_end, bulk_out *out)
{
    memset(out, 0, sizeof *out); /* no room where an array is not there yet */
    if (!spec->faces) {
        size_t cap = rec_end < b->cap_verts ? rec_end : b->cap_verts;
        if (!b->positions || rec >= cap) return;
        out->positions = b->positions + 3 * rec;
        out->cap_verts = cap - rec;
    } else {
        size_t cap = rec_end < b->cap_faces ? rec_end : b->cap_faces;
        size_t index_cap = index_end < b->cap_indices ? index_end : b->cap_indices;
        if (!b->sizes || !b->indices || rec >= cap || index > index_cap) return;
        out->sizes = b->sizes + rec;
        out->cap_faces = cap - rec;
        out->indices = b->indices + index;
        out->cap_indices = index_cap - index;
    }
}

/* Grows the builder for the records after `done` of `declared`; 0 when it
 * refuses (the general loop then meets and reports the same refusal). */
static int builder_grow(const mt__bulk_spec *spec, mt__builder *b, uint64_t done, uint64_t declared)
{
    size_t want = mt__builder_ahead((size_t)done, declared);
    if (want <= done) want = (size_t)done + 1;
    if (!spec->faces) return mt__builder_reserve_verts(b, want);
    return mt__builder_reserve_faces(b, want) &&
           mt__builder_reserve_indices(
               b, b->num_indices + 3 * (want - (size_t)done) + MT__BULK_MAX_LIST);
}

/* Part 0 on the calling thread, writing into the builder from record
 * `first` on, up to record rec_end and index index_end when other parts
 * write after it (the builder then must not move: part 0 stops when its
 * region is full); returns the records it parsed. */
static uint64_t parse_first(bulk_part *p, mt__builder *b, uint64_t first, uint64_t declared,
                            size_t rec_end, size_t index_end)
{
    int may_grow = rec_end == SIZE_MAX;
    uint64_t done = 0, limit = p->max;
    for (;;) {
        alias_builder(p->spec, b, (size_t)(first + done), b->num_indices, rec_end, index_end,
                      &p->out);
        p->max = limit - done;
        parse_part(p);
        done += p->spec->faces ? p->out.num_faces : p->out.num_verts;
        if (p->spec->faces) b->num_indices += p->out.num_indices;
        if (p->why != END_ROOM || !may_grow) break;
        if (!builder_grow(p->spec, b, first + done, declared)) {
            p->why = END_OTHER;
            break;
        }
    }
    p->max = limit;
    return done;
}

/* ---- The other parts: straight into the face list, or into scratch ------ */

/* Indices in `lines` faces after record `first`, guessed from the faces
 * before it: exactly their size times `lines` when they all have one size,
 * else their mean with some slack (a gap is closed once the parts end). */
static size_t guess_indices(const mt__builder *b, uint64_t first, uint64_t lines)
{
    size_t seen = first < 256 ? (size_t)first : 256;
    if (seen == 0) return 3 * (size_t)lines;
    uint64_t sum = 0;
    uint32_t lo = UINT32_MAX, hi = 0;
    for (size_t r = (size_t)first - seen; r < first; r++) {
        uint32_t size = b->sizes[r];
        sum += size;
        lo = size < lo ? size : lo;
        hi = size > hi ? size : hi;
    }
    if (lo == hi) return (size_t)(lo * lines);
    return (size_t)(sum * lines / seen + lines / 8 + MT__BULK_MAX_LIST);
}

/* Makes parts 1 and later write straight into b, each at its place, when b has
 * (or grows as the reader would to) room for them; returns 1 then. A part's
 * first record follows the lines of the parts before it: when those are
 * whole, each line was a record. *rec_end, *index_end: part 0's region. */
static int place_parts(const mt__bulk_spec *spec, mt__builder *b, bulk_part *pp, unsigned parts,
                       uint64_t first, uint64_t declared, size_t *rec_end, size_t *index_end)
{
    size_t rec[MT__BULK_MAX_THREADS + 1], index[MT__BULK_MAX_THREADS + 1];
    uint64_t lines = 0;
    for (unsigned t = 1; t < parts; t++) {
        lines += mt__count_newlines(pp[t - 1].d + pp[t - 1].begin, pp[t - 1].end - pp[t - 1].begin);
        rec[t] = (size_t)(first + lines);
    }
    /* the lines of the last part, about those of the others */
    uint64_t all_lines = lines + lines / (parts - 1);
    if (!builder_grow(spec, b, first + lines, declared)) return 0;
    if (spec->faces &&
        !mt__builder_reserve_indices(b, b->num_indices + guess_indices(b, first, all_lines)))
        return 0;
    rec[parts] = spec->faces ? b->cap_faces : b->cap_verts;
    index[parts] = b->cap_indices;
    for (unsigned t = 1; t < parts; t++) {
        if (rec[t] >= rec[parts]) return 0;
        index[t] = spec->faces ? b->num_indices + guess_indices(b, first, rec[t] - first) : 0;
        if (index[t] > index[parts]) return 0;
    }
    for (unsigned t = 1; t < parts; t++) {
        alias_builder(spec, b, rec[t], index[t], rec[t + 1], index[t + 1], &pp[t].out);
        pp[t].direct = 1;
    }
    *rec_end = rec[1];
    *index_end = index[1];
    return 1;
}

/* Appends k records of a worker's scratch to the builder from record
 * `first` on. Returns 0 when the builder refuses to grow. */
static int append_part(const bulk_part *p, uint64_t k, mt__builder *b, uint64_t first,
                       uint64_t declared)
{
    if (k == 0) return 1; /* its arrays may not be there */
    if (!p->spec->faces) {
        if (first + k > b->cap_verts && !mt__builder_reserve_verts(b, (size_t)(first + k)))
            return 0;
        memcpy(b->positions + 3 * first, p->out.positions, (size_t)k * 3 * sizeof(double));
        return 1;
    }
    size_t nidx = 0;
    for (uint64_t r = 0; r < k; r++) nidx += p->out.sizes[r];
    size_t want_faces = (size_t)(first + k);
    if (want_faces > b->cap_faces) {
        size_t ahead = mt__builder_ahead((size_t)first, declared);
        if (!mt__builder_reserve_faces(b, ahead > want_faces ? ahead : want_faces)) return 0;
    }
    if (!mt__builder_reserve_indices(b, b->num_indices + nidx)) return 0;
    memcpy(b->sizes + first, p->out.sizes, (size_t)k * sizeof(uint32_t));
    memcpy(b->indices + b->num_indices, p->out.indices, nidx * sizeof(uint32_t));
    b->num_indices += nidx;
    return 1;
}

/* Takes the first k records of a part that wrote straight into b: they are
 * in place but for a gap before their indices, closed here. */
static void take_direct(const bulk_part *p, uint64_t k, mt__builder *b)
{
    if (!p->spec->faces) return;
    size_t nidx = 0;
    for (uint64_t r = 0; r < k; r++) nidx += p->out.sizes[r];
    uint32_t *at = b->indices + b->num_indices;
    if (nidx && p->out.indices != at) memmove(at, p->out.indices, nidx * sizeof(uint32_t));
    b->num_indices += nidx;
}

/* The index just past the k-th '\n' of [i, end) (there are k or more). */
static size_t after_lines(const unsigned char *d, size_t i, size_t end, uint64_t k)
{
    while (k--) i = (size_t)((const unsigned char *)memchr(d + i, '\n', end - i) - d) + 1;
    return i;
}

/* ---- The run ------------------------------------------------------------- */

static unsigned threads_for(unsigned wanted)
{
    if (wanted == 0) {
        long cores = sysconf(_SC_NPROCESSORS_ONLN);
        wanted = cores > 1 ? (unsigned)cores : 1;
    }
    return wanted < MT__BULK_MAX_THREADS ? wanted : MT__BULK_MAX_THREADS;
}

/* Lines [start, end) in `parts` parts (parts[0] on this thread, into b
 * from record `first` on), at most `max` records. Returns the records read;
 * *at is where reading stopped. */
static uint64_t run_parts(mt__io_src *src, const mt__bulk_spec *spec, bulk_part *pp, unsigned parts,
                          size_t start, size_t end, uint64_t first, uint64_t max, uint64_t declared,
                          mt__builder *b, size_t *at)
{
    const unsigned char *d = src->data;
    size_t bytes = end - start, cut = start;
    int ahead = parts > 1 && mt__src_reads_ahead(src);
    size_t less = ahead ? bytes / READ_AHEAD_SHARE : 0; /* taken from part 0, given to the others */
    atomic_int cancel;
    atomic_init(&cancel, 0);
    for (unsigned t = 0; t < parts; t++) {
        bulk_part *p = &pp[t];
        p->spec = spec;
        p->d = d;
        p->pos = p->begin = cut;
        if (t + 1 == parts) {
            cut = end; /* an unfinished last line stops the part */
        } else {
            cut = start + bytes / parts * (t + 1) - less * (parts - 1 - t) / (parts - 1);
            if (cut < p->pos) cut = p->pos;
            const unsigned char *nl = memchr(d + cut, '\n', end - cut);
            cut = nl ? (size_t)(nl - d) + 1 : end;
        }
        p->end = cut;
        p->max = max;
        p->why = END_DONE;
        p->nomem = 0;
        p->cancel = parts > 1 ? &cancel : NULL;
        p->started = 0;
        p->direct = 0;
    }
    size_t rec_end = SIZE_MAX, index_end = SIZE_MAX;
    if (parts > 1 && !place_parts(spec, b, pp, parts, first, declared, &rec_end, &index_end)) {
        for (unsigned t = 1; t < parts; t++) {
            pp[t].out = pp[t].scratch;
            pp[t].out.num_verts = pp[t].out.num_faces = pp[t].out.num_indices = 0;
        }
    }
    cpu_set_t allowed;
    int spread = parts > 1 && start_parts(pp, parts, &allowed);
    uint64_t done = parse_first(&pp[0], b, first, declared, rec_end, index_end);
    if (ahead) mt__src_read_ahead(src); /* while the other parts are parsed */
    int whole = pp[0].why == END_DONE && pp[0].pos == pp[0].end && done < max;
    if (!whole) atomic_store(&cancel, 1);
    *at = pp[0].pos;
    for (unsigned t = 1; t < parts; t++) {
        bulk_part *p = &pp[t];
        if (p->started && spread) /* one not running yet may now run anywhere (parallel.c) */
            pthread_setaffinity_np(p->thread, sizeof allowed, &allowed);
        if (p->started)
            pthread_join(p->thread, NULL);
        else if (whole)
            worker_main(p);
        if (!p->direct) p->scratch = p->out; /* keeps what its arrays grew to */
        if (!whole) continue;
        uint64_t parsed = spec->faces ? p->out.num_faces : p->out.num_verts;
        uint64_t got = parsed < max - done ? parsed : max - done;
        if (p->direct) {
            take_direct(p, got, b);
        } else if (!append_part(p, got, b, first + done, declared)) {
            whole = 0;
            continue;
        }
        done += got;
        /* when the declared count ends inside this part, after its got-th line */
        *at = got < parsed ? after_lines(d, p->begin, p->end, got) : p->pos;
        whole = got == parsed && p->why == END_DONE && p->pos == p->end && done < max;
        if (!whole) atomic_store(&cancel, 1);
    }
    return done;
}

uint64_t mt__bulk_parse(mt__io_src *src, const mt__bulk_spec *spec, size_t *pos, uint64_t first,
                        uint64_t declared, mt__builder *b)
{
    const unsigned char *d = src->data;
    size_t n = src->size, start = *pos;
    /* The last record is left to the general loop: where it stops reading
     * counts (the allowance of trailing bytes starts there). */
    if (first + 1 >= declared || start >= n) return 0;
    uint64_t max = declared - first - 1;
    /* First a few lines on this thread: threads only for runs that start well. */
    size_t probe_end = n;
    if (n - start > PROBE_BYTES) {
        const unsigned char *nl = memchr(d + start + PROBE_BYTES, '\n', n - start - PROBE_BYTES);
        probe_end = nl ? (size_t)(nl - d) + 1 : n;
    }
    size_t at;
    bulk_part solo;
    uint64_t done = run_parts(src, spec, &solo, 1, start, probe_end, first, max, declared, b, &at);
    if (probe_end == n || at != probe_end || solo.why != END_DONE || done >= max) {
        *pos = at;
        return done;
    }
    unsigned threads = threads_for(src->threads);
    size_t bytes = n - at;
    unsigned parts =
        bytes / THREAD_MIN_BYTES < threads ? (unsigned)(bytes / THREAD_MIN_BYTES) : threads;
    if (parts < 1) parts = 1;
    if (parts > 1 && !src->bulk) {
        src->bulk = calloc(1, sizeof *src->bulk);
        if (!src->bulk) parts = 1;
    }
    bulk_part *pp = parts > 1 ? src->bulk->parts : &solo;
    done += run_parts(src, spec, pp, parts, at, n, first + done, max - done, declared, b, &at);
    *pos = at;
    return done;
}

void mt__bulk_free(mt__bulk *bulk)
{
    if (!bulk) return;
    for (unsigned t = 1; t < MT__BULK_MAX_THREADS; t++) { /* parts[0] writes into the builder */
        free(bulk->parts[t].scratch.positions);
        free(bulk->parts[t].scratch.sizes);
        free(bulk->parts[t].scratch.indices);
    }
    free(bulk);
}
