/* Shared internals of meshtopo::io: the input being parsed, error reporting
 * with file name and line or byte offset, number parsing, the growable face
 * list the readers fill, and the output sink the writers use. Parsers never
 * read outside [data, data + size) and never trust a count for allocation
 * before checking it against the bytes that remain. */
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

typedef struct mt__io_src {
    const char *name; /* for messages; never NULL */
    const unsigned char *data;
    size_t size;
} mt__io_src;

/* How a failure position is shown: "name:LINE: " for text (the line is
 * computed from the offset) or "name: byte offset N: " for binary data. */
typedef enum mt__io_pos { MT__POS_NONE, MT__POS_LINE, MT__POS_BYTE } mt__io_pos;

/* Fills diag with status, element, the position (line and/or byte_offset)
 * and "name:position: message"; returns status. */
mt_status mt__io_fail(mt_diag *diag, mt_status status, const mt__io_src *src, mt__io_pos pos,
                      size_t offset, uint32_t element, const char *fmt, ...)
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
 * significant digits, or too large an exponent for one exact operation). */
size_t mt__scan_decimal(const unsigned char *s, const unsigned char *end, double *out);

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

/* Arrays that grow geometrically; counts are checked against the face list
 * limits (MT__IO_MAX_VERTS vertices, 2^32 - 1 faces) by the readers. */
typedef struct mt__builder {
    double *positions;
    size_t num_verts, cap_verts;
    uint32_t *sizes;
    size_t num_faces, cap_faces;
    uint32_t *indices;
    size_t num_indices, cap_indices;
} mt__builder;

/* Make room for at least n vertices / faces / indices in total. Return 0
 * when memory runs out (or the size overflows). */
int mt__builder_reserve_verts(mt__builder *b, size_t n);
int mt__builder_reserve_faces(mt__builder *b, size_t n);
int mt__builder_reserve_indices(mt__builder *b, size_t n);

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

/* The failure every reader reports when an array cannot grow. */
mt_status mt__io_fail_nomem(mt_diag *diag, const mt__io_src *src);

/* ---- gzip -------------------------------------------------------------- */

static inline int mt__is_gzip(const unsigned char *data, size_t size)
{
    return size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
}

/* Inflates the gzip data of src (all members) into a new buffer (free()).
 * Refuses output larger than 16 GiB or than fits in memory. */
mt_status mt__inflate(const mt__io_src *src, unsigned char **out, size_t *out_size, mt_diag *diag);

/* ---- Readers (src is already decompressed) ----------------------------- */

mt_status mt__read_off(const mt__io_src *src, mt_face_list *out, mt_diag *diag);
mt_status mt__read_obj(const mt__io_src *src, mt_face_list *out, mt_diag *diag);
/* Any PLY encoding: the header says which. */
mt_status mt__read_ply(const mt__io_src *src, mt_face_list *out, mt_diag *diag);

/* 1 when the first non-comment line of src starts with an OBJ keyword. */
int mt__looks_like_obj(const mt__io_src *src);
/* 1 when the first token of src is an OFF header keyword (OFF, COFF, ...). */
int mt__looks_like_off(const mt__io_src *src);

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
mt_status mt__write_ply(mt__sink *s, const mt_face_list *list, mt_format format, mt_diag *diag);
/* OBJ cannot express every negative index; checked before a file is created. */
mt_status mt__obj_check_writable(const mt_face_list *list, const char *path, mt_diag *diag);

#endif
