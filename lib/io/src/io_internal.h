/* Shared internals of meshtopo::io: the input being parsed, error reporting
 * with file name and line or byte offset, number parsing, the growable face
 * list the readers fill, and the output sink the writers use. Parsers never
 * read outside [data, data + size) of their window and never allocate by a
 * count a file declares: arrays grow as elements are read. */
#ifndef MESHTOPO_IO_INTERNAL_H
#define MESHTOPO_IO_INTERNAL_H

#include <locale.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "meshtopo/io.h"

/* The largest vertex count meshtopo::io accepts (reading and writing), so
 * that every index stored as a negative two's complement (>= 2^31) is out of
 * range by construction. */
#define MT__IO_MAX_VERTS 0x7fffffffu

/* ---- The input --------------------------------------------------------- */

/* An input length not known yet (gzip data, a pipe). */
#define MT__UNKNOWN UINT64_MAX

typedef struct mt__io_stream mt__io_stream;
typedef struct mt__bulk mt__bulk;

/* The bytes being parsed. A plain buffer read whole: data/size is all of it
 * and base 0. Any other input (a file, gzip data): data/size is a window on
 * it, the bytes at input offsets [base, base + size), moved on by
 * mt__src_more as the parser advances. While the window is on text it ends
 * just after a whitespace byte (never after a '\r' that follows a '\\'),
 * unless it ends the input: so a token, a number or an OBJ continuation
 * never straddles its end, and parsers treat the end of the window as the
 * end of a token; they call mt__src_more only where they need bytes past it.
 * Messages give input offsets (base + index into data). */
typedef struct mt__io_src {
    const char *name; /* for messages; never NULL */
    const unsigned char *data;
    size_t size;
    uint64_t base;      /* input offset of data[0] */
    int eof;            /* data + size is the end of the input */
    uint64_t total;     /* the input's length when known (buffers, plain files), else MT__UNKNOWN */
    uint64_t lines;     /* '\n' bytes before base (text windows) */
    uint64_t mark;      /* input offset of the record being read: its line is kept when the */
    uint64_t mark_line; /* window moves past it, so a message can still point there */
    mt__io_stream *stream; /* NULL when data is all the input */
    unsigned threads;      /* mt_read_options.threads */
    mt__bulk *bulk;        /* the bulk parser's scratch (io_bulk.c), freed with mt__bulk_free */
} mt__io_src;

/* A source over all of [data, data + size). */
void mt__src_init_buffer(mt__io_src *src, const char *name, const void *data, size_t size);

/* Moves the window on: drops the bytes before *pos (*pos then indexes the
 * same byte as before), keeps the others and appends more input. Returns 1
 * when the window shows bytes past those it kept, 0 at the end of the input
 * (src->eof is then set) or when reading failed (mt__src_status has the
 * failure). A buffer read whole always gives 0. data may move: reload it. */
int mt__src_more(mt__io_src *src, size_t *pos);

/* Makes at least k bytes available at *pos (mt__src_more as needed).
 * Returns 0 when the input ends first. */
static inline int mt__src_need(mt__io_src *src, size_t *pos, size_t k)
{
    while (src->size - *pos < k)
        if (!mt__src_more(src, pos)) return 0;
    return 1;
}

/* From here on the window is on binary data: it shows every byte read. */
void mt__src_binary(mt__io_src *src);

/* The number of '\n' bytes in [p, p + n). */
uint64_t mt__count_newlines(const unsigned char *p, size_t n);

/* The 1-based line of an input offset in the window or at the mark. */
uint64_t mt__src_line(const mt__io_src *src, uint64_t offset);

/* The input's length: known at once for buffers and plain files, else
 * when the window has reached the end of the input; MT__UNKNOWN before. */
static inline uint64_t mt__src_length(const mt__io_src *src)
{
    if (src->total != MT__UNKNOWN) return src->total;
    return src->eof ? src->base + src->size : MT__UNKNOWN;
}

/* What follows the last element of an OFF or PLY file. */
typedef enum mt__trail {
    MT__TRAIL_END,  /* only whitespace (and comments) up to the end of the input */
    MT__TRAIL_DATA, /* something else, at *pos */
    MT__TRAIL_LONG  /* MT_READ_MAX_TRAILING_BYTES of whitespace and more input after them,
                       the first of which is at *pos */
} mt__trail;

/* Skips whitespace (and '#' comments to the end of their line when
 * `comments`) from *pos, but no more than MT_READ_MAX_TRAILING_BYTES. */
mt__trail mt__src_skip_trailer(mt__io_src *src, size_t *pos, int comments);

/* How a failure position is shown: "name:LINE: " for text (the line is
 * computed from the offset) or "name: byte offset N: " for binary data. */
typedef enum mt__io_pos { MT__POS_NONE, MT__POS_LINE, MT__POS_BYTE } mt__io_pos;

/* Fills diag with status, element, the position (line and/or byte_offset)
 * and "name:position: message"; returns status. `offset` is an input offset
 * (base + index); a line position must be in the window or at the mark. */
mt_status mt__io_fail(mt_diag *diag, mt_status status, const mt__io_src *src, mt__io_pos pos,
                      uint64_t offset, uint32_t element, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 7, 8)))
#endif
    ;

/* The same at a text offset whose line is already known. */
mt_status mt__io_fail_line(mt_diag *diag, mt_status status, const mt__io_src *src, uint64_t offset,
                           uint64_t line, uint32_t element, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 7, 8)))
#endif
    ;

/* Writes a printable, quoted-safe excerpt of [s, s + len) into buf (at most
 * a few dozen characters, non-printable bytes as \xNN, "..." when cut). */
void mt__io_excerpt(char *buf, size_t bufsize, const unsigned char *s, size_t len);

/* ---- Text scanning ------------------------------------------------------ */

static inline int mt__is_space(unsigned char c)
{
    return c == ' ' || (c >= '\t' && c <= '\r');
}

/* The next whitespace-separated token from *pos on, moving the window on:
 * 1 with [*start, *start + *len) in the window and *pos past it, 0 at the
 * end of the input (*pos then at the end). Inline: the ASCII parsers call
 * it once per number. */
static inline int mt__src_token(mt__io_src *src, size_t *pos, size_t *start, size_t *len)
{
    size_t i = *pos;
    for (;;) {
        const unsigned char *d = src->data;
        size_t n = src->size;
        while (i < n && mt__is_space(d[i])) i++;
        if (i < n) {
            size_t s = i;
            while (i < n && !mt__is_space(d[i])) i++;
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

/* Index of the first '\n' at or after i, or n. */
static inline size_t mt__line_end(const unsigned char *d, size_t n, size_t i)
{
    if (i >= n) return n;
    const unsigned char *nl = memchr(d + i, '\n', n - i);
    return nl ? (size_t)(nl - d) : n;
}

/* ---- Numbers ----------------------------------------------------------- */

typedef enum mt__num { MT__NUM_OK, MT__NUM_BAD, MT__NUM_RANGE } mt__num;

/* Parses all of [s, s + len) as a floating-point number: decimal with
 * optional sign, fraction and exponent (exactly rounded), or anything else
 * strtod accepts (inf, nan, hex). Always '.' as the decimal point: callers
 * run it under the C locale (mt__c_locale_enter). Returns 1, or 0 when the
 * text is not a number. */
int mt__parse_double(const unsigned char *s, size_t len, double *out);

/* The fast, exact part of mt__parse_double: reads the longest plain
 * decimal ([+-]digits[.digits][e[+-]digits]) at s and returns how many bytes
 * it took, or 0 when there is none or its value needs strtod (more than 19
 * significant digits, a subnormal or out-of-range value, or one of the rare
 * roundings the Eisel-Lemire algorithm leaves open). The value is
 * bit-identical to strtod's. */
size_t mt__scan_decimal(const unsigned char *s, const unsigned char *end, double *out);
/* 10^0 to 10^22, each exact in a double: Clinger's fast path, where one
 * multiplication or division by them rounds correctly. */
extern const double mt__pow10_exact[23];
/* The double nearest to w * 10^q (w != 0) by the Eisel-Lemire algorithm
 * (negated when neg), as mt__scan_decimal computes it; 0 when it cannot
 * tell the rounding cheaply or the result is subnormal, zero or infinite. */
int mt__eisel_lemire(uint64_t w, int64_t q, int neg, double *out);

/* Eight digits at a time (Lemire's SWAR): 8 bytes as a little-endian word
 * (byte 0 the first), which bytes are not ASCII digits, and the value of 8
 * digits. */
static inline uint64_t mt__load8(const unsigned char *p)
{
    uint64_t v;
    memcpy(&v, p, sizeof v);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap64(v);
#endif
    return v;
}

/* 0x80 in each byte that is not '0'..'9' and in no byte before the first
 * such one (borrows and carries only run towards later bytes). */
static inline uint64_t mt__nondigits8(uint64_t v)
{
    return ((v - 0x3030303030303030ull) | (v + 0x4646464646464646ull)) & 0x8080808080808080ull;
}

static inline int mt__is_8digits(uint64_t v)
{
    return mt__nondigits8(v) == 0;
}

/* The value of 8 digit values (0..9, not ASCII) in bytes 0 (most
 * significant) to 7. */
static inline uint32_t mt__digits8_value(uint64_t v)
{
    v = v * 10 + (v >> 8);
    v = ((v & 0x000000ff000000ffull) * 0x000f424000000064ull +
         ((v >> 16) & 0x000000ff000000ffull) * 0x0000271000000001ull) >>
        32;
    return (uint32_t)v;
}

static inline uint32_t mt__parse_8digits(uint64_t v)
{
    return mt__digits8_value(v - 0x3030303030303030ull);
}

/* 5^q for q in [MT__POW5_SMALLEST, MT__POW5_LARGEST], each scaled by a power
 * of two into [2^127, 2^128), high 64 bits first (io_pow5.c): the table of
 * the Eisel-Lemire conversion in mt__scan_decimal. */
#define MT__POW5_SMALLEST (-342)
#define MT__POW5_LARGEST 308
extern const uint64_t mt__pow5_128[MT__POW5_LARGEST - MT__POW5_SMALLEST + 1][2];

/* Reads a plain index token at d[*pos]: [-]digits in 32-bit range followed
 * by whitespace, `stop` or the end. Returns 1 and moves *pos past it, or 0
 * without moving (anything unusual: the caller's slow path diagnoses it). */
static inline int mt__scan_index(const unsigned char *d, size_t n, size_t *pos, unsigned char stop,
                                 int64_t *out)
{
    size_t k = *pos;
    int neg = k < n && d[k] == '-';
    k += (size_t)neg;
    size_t s = k;
    uint64_t v = 0;
    while (k < n && (unsigned)d[k] - '0' <= 9 && k - s < 10) v = v * 10 + (d[k++] - '0');
    if (k == s || (k < n && !mt__is_space(d[k]) && d[k] != stop)) return 0;
    if (neg ? v > 0x80000000ull : v > 0xffffffffull) return 0;
    *out = neg ? -(int64_t)v : (int64_t)v;
    *pos = k;
    return 1;
}

/* Parses all of [s, s + len) as an optional sign and decimal digits with a
 * value in [-2^31, 2^32 - 1]. */
static inline mt__num mt__parse_index(const unsigned char *s, size_t len, int64_t *out)
{
    const unsigned char *p = s, *end = s + len;
    int neg = 0;
    if (p < end && (*p == '-' || *p == '+')) neg = *p++ == '-';
    if (p == end) return MT__NUM_BAD;
    uint64_t v = 0;
    int big = 0;
    for (; p < end; p++) {
        unsigned d = (unsigned)*p - '0';
        if (d > 9) return MT__NUM_BAD;
        if (v > 0xffffffffull)
            big = 1; /* keep scanning: a later non-digit makes it BAD */
        else
            v = v * 10 + d;
    }
    if (big || (!neg && v > 0xffffffffull) || (neg && v > 0x80000000ull)) return MT__NUM_RANGE;
    *out = neg ? -(int64_t)v : (int64_t)v;
    return MT__NUM_OK;
}

/* Parses all of [s, s + len) as unsigned decimal digits (a leading '+' is
 * allowed) with a value that fits in 64 bits. */
mt__num mt__parse_count(const unsigned char *s, size_t len, uint64_t *out);

/* Shortest of %.15g, %.16g, %.17g that reads back to v; "nan", "inf" and
 * "-inf" for non-finite values. Writes a NUL-terminated string of at most
 * 31 characters into buf and returns its length. Needs the C locale. */
size_t mt__format_double(double v, char *buf);
/* Decimal text of v into buf (at least 21 bytes); returns its length. */
size_t mt__format_i64(int64_t v, char *buf);

/* Locale: number text is always read and written with '.' as the decimal
 * point, whatever the process locale, by switching this thread to the C
 * locale for the duration of a call. */
typedef struct mt__locale_state {
    locale_t c_locale; /* 0 when the switch failed */
    locale_t saved;
} mt__locale_state;
void mt__c_locale_enter(mt__locale_state *state);
void mt__c_locale_leave(mt__locale_state *state);

/* ---- The face list being read ------------------------------------------ */

/* The most the face list may hold (bytes, all arrays) while the input's
 * length is unknown, before the reader confirms the counts it declares
 * against that length (mt__builder.confirm): 64 MiB. */
#define MT__IO_BLIND_BYTES ((size_t)64 << 20)

/* A list (a face record, a PLY list) declaring more entries than this
 * makes a reader learn the input's length before reading it. */
#define MT__IO_BIG_LIST ((uint64_t)1 << 20)

/* Arrays that grow geometrically; counts are checked against the face list
 * limits (MT__IO_MAX_VERTS vertices, 2^32 - 1 faces) by the readers. */
typedef struct mt__builder {
    double *positions;
    size_t num_verts, cap_verts;
    uint32_t *sizes;
    size_t num_faces, cap_faces;
    uint32_t *indices;
    size_t num_indices, cap_indices;
    /* When set, called once before the arrays would hold more than
     * MT__IO_BLIND_BYTES: MT_OK lets them grow; another status refuses the
     * growth, and mt__builder_fail reports it (from `refusal`). */
    mt_status (*confirm)(void *ctx, mt_diag *diag);
    void *confirm_ctx;
    int confirmed;
    mt_status refused;
    mt_diag refusal;
} mt__builder;

/* Make room for at least n vertices / faces / indices in total. Return 0
 * when memory runs out (or the size overflows) or confirm refused. */
int mt__builder_reserve_verts(mt__builder *b, size_t n);
int mt__builder_reserve_faces(mt__builder *b, size_t n);
int mt__builder_reserve_indices(mt__builder *b, size_t n);

/* Room at once for the counts a reader's header declares, once they were
 * checked against the input's length (known when the header was read):
 * memory in proportion to the input, and none of the copies growth makes.
 * Where that room is not to be had, the arrays grow as they are read. */
void mt__builder_reserve_declared(mt__builder *b, uint64_t verts, uint64_t faces, uint64_t indices);

/* The failure a reader reports when the builder refused to grow: confirm's
 * refusal, else out of memory. */
mt_status mt__builder_fail(const mt__builder *b, const mt__io_src *src, mt_diag *diag);

/* The element count to make room for when `done` of `declared` elements
 * are read and the arrays are full: all of them when few remain, else a
 * batch as large as what was read so far (at least 64 Ki). So arrays grow
 * with what a file holds, never with what its header declares (but for
 * mt__builder_reserve_declared: what the input's length can hold). */
static inline size_t mt__builder_ahead(size_t done, uint64_t declared)
{
    size_t step = done > ((size_t)1 << 16) ? done : ((size_t)1 << 16);
    return declared - done <= step ? (size_t)declared : done + step;
}

static inline int mt__builder_add_vert(mt__builder *b, double x, double y, double z)
{
    if (b->num_verts == b->cap_verts && !mt__builder_reserve_verts(b, b->num_verts + 1)) return 0;
    double *p = b->positions + 3 * b->num_verts++;
    p[0] = x;
    p[1] = y;
    p[2] = z;
    return 1;
}

static inline int mt__builder_add_face(mt__builder *b, uint32_t size)
{
    if (b->num_faces == b->cap_faces && !mt__builder_reserve_faces(b, b->num_faces + 1)) return 0;
    b->sizes[b->num_faces++] = size;
    return 1;
}

static inline int mt__builder_add_index(mt__builder *b, uint32_t index)
{
    if (b->num_indices == b->cap_indices && !mt__builder_reserve_indices(b, b->num_indices + 1))
        return 0;
    b->indices[b->num_indices++] = index;
    return 1;
}

/* Moves the arrays into *out (trimmed to size; never NULL) and empties b. */
mt_status mt__builder_finish(mt__builder *b, mt_face_list *out, const mt__io_src *src,
                             mt_diag *diag);
void mt__builder_free(mt__builder *b);

/* Runs a reader that fills a builder, then moves the builder's arrays into
 * *out (mt__builder_finish); the builder is freed whatever happens. */
typedef mt_status (*mt__builder_reader)(mt__io_src *src, mt__builder *b, mt_diag *diag);
mt_status mt__builder_read(mt__io_src *src, mt__builder_reader read, mt_face_list *out,
                           mt_diag *diag);

/* The failure every reader reports when an array cannot grow. */
mt_status mt__io_fail_nomem(mt_diag *diag, const mt__io_src *src);

/* ---- Runs of plain records (io_bulk.c) ---------------------------------- */

/* What a line holds, in order, each item after spaces or tabs. */
enum {
    MT__BULK_X = 1, /* a number: the vertex's x, y, z */
    MT__BULK_Y,
    MT__BULK_Z,
    MT__BULK_TOKEN,   /* any token, skipped */
    MT__BULK_INDICES, /* a count and that many vertex indices: the face */
    MT__BULK_LIST,    /* a count and that many tokens, skipped */
    MT__BULK_REST,    /* anything up to the end of the line (OFF's colours) */
    MT__BULK_KEYWORD, /* the spec's keyword letter alone (OBJ's v, f) */
    MT__BULK_ENTRIES  /* OBJ face entries to the line's end: v, v/vt, v/vt/vn, v//vn */
};

#define MT__BULK_MAX_OPS 16
/* Longer lists (faces) are left to the general loop. */
#define MT__BULK_MAX_LIST 255u
#define MT__BULK_MAX_THREADS 4u

/* One record per line: a vertex (positions) or a face (sizes, indices; then
 * exactly one MT__BULK_INDICES or MT__BULK_ENTRIES). */
typedef struct mt__bulk_spec {
    unsigned char ops[MT__BULK_MAX_OPS];
    size_t num_ops;
    int faces;
    unsigned char keyword; /* MT__BULK_KEYWORD's letter */
    uint32_t defined;      /* MT__BULK_ENTRIES: vertices before the run (relative indices) */
} mt__bulk_spec;

/* Parses the plain records of the lines at window index *pos on (the
 * start of a line; *pos must follow a '\n' or the start of the data) into
 * b: vertex or face `first` on, `declared` in all (a format that declares
 * no counts passes its limit), growing b as the reader would. Stops before
 * the first line the general loop must read (see io_bulk.c), at the
 * window's last '\n' or before record declared - 1 (the last, whose end or
 * refusal the general loop must know); on several threads (src->threads)
 * when the lines are many. Returns how many
 * records it read, *pos past them: the same records, bit for bit, that the
 * general loop would have read. */
uint64_t mt__bulk_parse(mt__io_src *src, const mt__bulk_spec *spec, size_t *pos, uint64_t first,
                        uint64_t declared, mt__builder *b);
void mt__bulk_free(mt__bulk *bulk);

/* ---- Streamed input: raw bytes, gzip, the window ------------------------ */

/* Raw input bytes, from a file descriptor (read a chunk at a time) or a
 * buffer: [p, end) are bytes read and not used yet, `offset` the input
 * offset of p. */
typedef struct mt__io_raw {
    int fd; /* -1 for a buffer */
    const unsigned char *p, *end;
    uint64_t offset;
    unsigned char *chunk; /* fd: where chunks are read */
    size_t chunk_cap;
    int at_end;        /* nothing follows end */
    int err;           /* errno of a failed read, else 0 */
    int positioned;    /* read with pread at file_pos (a second reader of the file) */
    uint64_t file_pos; /* fd: file offset of end */
} mt__io_raw;

/* Reads another chunk after the unused bytes (moved to the chunk's start).
 * Returns 1 when bytes arrived, 0 at the end or on a read error (err). */
int mt__raw_more(mt__io_raw *raw);

/* Copies up to n bytes into dst: the unused ones first, then straight from
 * the file. Returns fewer than n only at the end of the input or on a read
 * error (err). */
size_t mt__raw_read(mt__io_raw *raw, unsigned char *dst, size_t n);

static inline int mt__is_gzip(const unsigned char *data, size_t size)
{
    return size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
}

/* gzip data (RFC 1952) being inflated: every member of a multi-member
 * file, then nothing but zero bytes. */
typedef struct mt__inflater mt__inflater;

mt__inflater *mt__inflater_new(void);
/* A copy that goes on from the same place (for a read ahead). */
mt__inflater *mt__inflater_dup(const mt__inflater *z);
void mt__inflater_free(mt__inflater *z);

/* Inflates up to `room` bytes into out from raw; returns how many. Sets
 * *done at the clean end of the gzip data; on corrupt or truncated data or
 * a read error fills diag (offsets in the compressed bytes, name from src)
 * and *status. */
size_t mt__inflate(mt__inflater *z, mt__io_raw *raw, unsigned char *out, size_t room,
                   const mt__io_src *src, int *done, mt_status *status, mt_diag *diag);

/* Opens src on the file descriptor fd (not closed) or, with fd < 0, on the
 * buffer [data, data + size), through a window (gzip recognised by its
 * magic bytes and inflated as the window moves on). `total` is the plain
 * input's length when known. The first window is read. On failure src
 * holds nothing to close. */
mt_status mt__src_open(mt__io_src *src, const char *name, int fd, const void *data, size_t size,
                       uint64_t total, const mt_read_options *options, mt_diag *diag);
/* Learns the input's length when it is not known yet and the input can be
 * read again (gzip data from a buffer or a regular file): the rest is
 * inflated once, ahead of the window, and not kept. A failure met on the
 * way (corrupt data, the input limit) ends the input at once, as it would
 * be met later. Returns 1 when the length is known (src->total). */
int mt__src_learn_length(mt__io_src *src);
/* Reads the next window's input ahead, into a block of its own, while
 * other threads parse the window (which stays as it is): the next
 * mt__src_more takes it in, and until then a failure or the end of the
 * input met ahead is not seen. Plain text only (inflating ahead would keep
 * the parsing threads waiting); does nothing for other input, nor when
 * bytes read ahead are already waiting: mt__src_reads_ahead tells. */
int mt__src_reads_ahead(const mt__io_src *src);
void mt__src_read_ahead(mt__io_src *src);
/* MT_OK, or the failure met while reading the input (copied into diag). */
mt_status mt__src_status(const mt__io_src *src, mt_diag *diag);
/* Frees the window (NULL-safe for a buffer read whole). */
void mt__src_close(mt__io_src *src);

/* ---- Readers ------------------------------------------------------------- */

/* Each parses src to its end; input failures are left in src for the
 * caller (mt__src_status), which reports them instead of the parser's. */
mt_status mt__read_off(mt__io_src *src, mt_face_list *out, mt_diag *diag);
mt_status mt__read_obj(mt__io_src *src, mt_face_list *out, mt_diag *diag);
/* Any PLY encoding: the header says which. */
mt_status mt__read_ply(mt__io_src *src, mt_face_list *out, mt_diag *diag);
mt_status mt__read_stl_ascii(mt__io_src *src, mt_face_list *out, mt_diag *diag);
mt_status mt__read_stl_binary(mt__io_src *src, mt_face_list *out, mt_diag *diag);

/* Format detection on the start of the window: 1 yes, 0 no, -1 cannot tell
 * before the window shows more of the input. */
/* the first non-comment line of src starts with an OBJ keyword */
int mt__looks_like_obj(const mt__io_src *src);
/* the first token of src is an OFF header keyword (OFF, COFF, ...) */
int mt__looks_like_off(const mt__io_src *src);
/* src starts with the PLY magic line */
int mt__looks_like_ply(const mt__io_src *src);
/* src is STL: *format set to MT_FORMAT_STL_BINARY (its length is 84 + 50 *
 * the count at byte 80, or it starts with "solid" but is not text) or
 * MT_FORMAT_STL_ASCII (it starts with "solid" and its first 256 bytes are
 * text), else MT_FORMAT_AUTO. The length of gzip data is learned first when
 * `learn` (it inflates the data once) or the input starts with "solid". */
int mt__looks_like_stl(mt__io_src *src, int learn, mt_format *format);

/* 1 when path ends in ".gz" (any case). */
int mt__path_is_gzip(const char *path);

/* ---- Output ------------------------------------------------------------ */

/* A file being written: buffered, optionally gzip-compressed, created as
 * PATH.tmp.XXXXXX in the same directory and renamed onto PATH by
 * mt__sink_close after fsync. Write errors are sticky and reported by
 * mt__sink_close. */
typedef struct mt__sink mt__sink;

mt_status mt__sink_open(mt__sink **out, const char *path, int gzip, mt_diag *diag);
/* Room for n more bytes (n <= 4096) at the returned pointer; commit what was used. */
char *mt__sink_reserve(mt__sink *s, size_t n);
void mt__sink_commit(mt__sink *s, size_t n);
void mt__sink_write(mt__sink *s, const void *data, size_t n);
/* Flushes, syncs and renames into place, then frees the sink. On failure
 * the temporary file is removed and MT_ERR_IO names the path. */
mt_status mt__sink_close(mt__sink *s, mt_diag *diag);
/* Removes the temporary file and frees the sink. */
void mt__sink_abort(mt__sink *s);

/* Writers: list is checked (mt_face_list_check) and has at most
 * MT__IO_MAX_VERTS vertices. */
mt_status mt__write_off(mt__sink *s, const mt_face_list *list, mt_diag *diag);
mt_status mt__write_obj(mt__sink *s, const mt_face_list *list, mt_diag *diag);
mt_status mt__write_ply(mt__sink *s, const mt_face_list *list, mt_format format,
                        const mt_write_options *options, mt_diag *diag);
/* OBJ cannot express every negative index; checked before a file is created. */
mt_status mt__obj_check_writable(const mt_face_list *list, const char *path, mt_diag *diag);
/* STL needs faces of 3 entries or more with indices in range (and, in
 * binary, at most 2^32 - 1 triangles); checked before a file is created. */
mt_status mt__stl_check_writable(const mt_face_list *list, mt_format format, const char *path,
                                 mt_diag *diag);
mt_status mt__write_stl(mt__sink *s, const mt_face_list *list, mt_format format, mt_diag *diag);

#endif
