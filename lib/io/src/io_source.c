/* The input of the readers, held a window at a time: raw bytes from a file
 * descriptor or a buffer (io_raw.c), inflated when they are gzip
 * (io_inflate.c), appended to a window the parser moves on (mt__src_more).
 * Holds at most the window (widened only for a token or PLY header longer
 * than it, up to MT_READ_MAX_HELD_BYTES) and, for plain text parsed on
 * several threads, one window more read ahead while the threads parse the
 * first (mt__src_read_ahead), whatever the input's size; counts
 * the input against max_input_bytes, learns the length of gzip data on
 * demand (mt__src_learn_length), and counts the lines of the bytes it drops
 * so that messages keep exact line numbers. */
#include <stdio.h>
#include <stdlib.h>

#include "io_internal.h"

/* Bytes of raw input read at once from a file descriptor. */
#define RAW_CHUNK ((size_t)64 << 10)

/* Room before the bytes read ahead for the bytes the window keeps (the
 * partial line at its end), so that the two join without moving either. */
#define AHEAD_ROOM ((size_t)64 << 10)

struct mt__io_stream {
    mt__io_raw raw;
    mt__inflater *gz;   /* NULL: plain input */
    unsigned char *mem; /* the window's block, mem_size bytes */
    size_t mem_size;
    unsigned char *buf; /* the window: at mem, or inside it once bytes read ahead were taken in */
    size_t len;         /* bytes in buf: the window, then (text) a partial token */
    size_t cap;         /* bytes from buf to the end of mem */
    size_t max_cap;     /* largest block allowed */
    size_t window;      /* mt_read_options.window_bytes: the block's size until it widens */
    /* Input read ahead (mt__src_read_ahead): `ahead` bytes at spare +
     * AHEAD_ROOM and whether the input ended there (finished, status,
     * diag kept aside), taken in by the next mt__src_more: until then
     * the window's owner sees the input as it was. */
    unsigned char *spare;
    size_t spare_size;
    int ahead_held;
    size_t ahead;
    int ahead_finished;
    mt_status ahead_status;
    mt_diag ahead_diag;
    int text;          /* cut the window after whitespace */
    int finished;      /* nothing more to append (end of input, or a failure) */
    int rereadable;    /* the raw input can be read again (a buffer, a regular file) */
    uint64_t produced; /* input bytes appended so far */
    uint64_t limit;    /* max_input_bytes */
    mt_status status;  /* the failure that finished the input, else MT_OK */
    mt_diag diag;
};

/* ---- Failures ------------------------------------------------------------ */

/* Ends the input with a failure, kept for mt__src_status (the first one). */
static void stream_fail(mt__io_stream *s, mt_status status, const mt_diag *diag)
{
    s->finished = 1;
    if (s->status != MT_OK) return;
    s->status = status;
    s->diag = *diag;
}

mt_status mt__src_status(const mt__io_src *src, mt_diag *diag)
{
    mt__io_stream *s = src->stream;
    if (!s || s->status == MT_OK) return MT_OK;
    if (diag) *diag = s->diag;
    return s->status;
}

static void fail_read_error(const mt__io_src *src, mt__io_stream *s)
{
    char text[256];
    if (strerror_r(s->raw.err, text, sizeof text) != 0)
        snprintf(text, sizeof text, "error %d", s->raw.err);
    mt_diag diag;
    mt_status status =
        mt__io_fail(&diag, MT_ERR_IO, src, MT__POS_NONE, 0, MT_NONE, "cannot read: %s", text);
    stream_fail(s, status, &diag);
}

/* The input limit passed; `compressed`: gzip bytes read until then. */
static void fail_too_long(const mt__io_src *src, mt__io_stream *s, uint64_t compressed)
{
    mt_diag diag;
    mt_status status;
    if (s->gz)
        status = mt__io_fail(&diag, MT_ERR_TOO_LARGE, src, MT__POS_NONE, 0, MT_NONE,
                             "gzip data inflates to more than the input limit of %llu bytes "
                             "(after %llu compressed bytes)",
                             (unsigned long long)s->limit, (unsigned long long)compressed);
    else
        status = mt__io_fail(&diag, MT_ERR_TOO_LARGE, src, MT__POS_NONE, 0, MT_NONE,
                             "the input is longer than the input limit of %llu bytes",
                             (unsigned long long)s->limit);
    stream_fail(s, status, &diag);
}

/* ---- The window ---------------------------------------------------------- */

/* Appends input to buf (*len bytes of cap) until it is full or the input
 * ends: after `limit` bytes, or after `total` (a plain file is read as
 * long as it was when opened; gzip data that inflates past the length
 * learned before has changed under the reader). */
static void fill_into(const mt__io_src *src, mt__io_stream *s, unsigned char *buf, size_t *len,
                      size_t cap)
{
    while (!s->finished && *len < cap) {
        size_t room = cap - *len;
        uint64_t left = s->limit - s->produced;
        if (left < room) room = (size_t)left + 1; /* one byte past the limit tells */
        if (src->total != MT__UNKNOWN) {
            left = src->total > s->produced ? src->total - s->produced : 0;
            if (!s->gz && left < room) room = (size_t)left;
            if (!s->gz && room == 0) {
                s->finished = 1;
                break;
            }
        }
        size_t got;
        if (s->gz) {
            int done = 0;
            mt_status status = MT_OK;
            mt_diag diag;
            got = mt__inflate(s->gz, &s->raw, buf + *len, room, src, &done, &status, &diag);
            if (status != MT_OK)
                stream_fail(s, status, &diag);
            else if (done)
                s->finished = 1;
        } else {
            got = mt__raw_read(&s->raw, buf + *len, room);
            if (got < room) {
                if (s->raw.err)
                    fail_read_error(src, s);
                else
                    s->finished = 1;
            }
        }
        *len += got;
        s->produced += got;
        if (s->produced > s->limit) {
            *len -= (size_t)(s->produced - s->limit);
            s->produced = s->limit;
            fail_too_long(src, s, s->raw.offset);
        } else if (s->gz && src->total != MT__UNKNOWN && s->produced > src->total) {
            mt_diag diag;
            mt_status status = mt__io_fail(&diag, MT_ERR_IO, src, MT__POS_NONE, 0, MT_NONE,
                                           "the file changed while it was read");
            stream_fail(s, status, &diag);
        }
    }
}

static void fill(const mt__io_src *src, mt__io_stream *s)
{
    fill_into(src, s, s->buf, &s->len, s->cap);
}

/* The end of the window in a text buffer: just after its last whitespace
 * byte past `from` (a '\r' after a '\\' does not count: an OBJ continuation
 * must be seen whole), or `from` when there is none. */
static size_t text_cut(const unsigned char *b, size_t from, size_t len)
{
    for (size_t k = len; k > from; k--) {
        unsigned char c = b[k - 1];
        if (c == ' ' || c == '\n' || c == '\t' || c == '\v' || c == '\f') return k;
        if (c == '\r' && !(k >= 2 && b[k - 2] == '\\')) return k;
    }
    return from;
}

/* Doubles the window's block (up to max_cap). Returns 0 after recording
 * the failure. */
static int grow(mt__io_src *src, mt__io_stream *s)
{
    mt_diag diag;
    if (s->buf != s->mem) {
        memmove(s->mem, s->buf, s->len);
        s->buf = s->mem;
        s->cap = s->mem_size;
        src->data = s->mem;
    }
    if (s->cap >= s->max_cap) {
        mt_status status = mt__io_fail(
            &diag, MT_ERR_TOO_LARGE, src, s->text ? MT__POS_LINE : MT__POS_BYTE, src->base, MT_NONE,
            "more than %zu bytes without whitespace (a token or PLY header this long "
            "is not read)",
            s->max_cap);
        stream_fail(s, status, &diag);
        return 0;
    }
    size_t cap = s->cap > s->max_cap / 2 ? s->max_cap : 2 * s->cap;
    unsigned char *p = realloc(s->mem, cap);
    if (!p) {
        stream_fail(s, mt__io_fail_nomem(&diag, src), &diag);
        return 0;
    }
    s->mem = s->buf = p;
    s->mem_size = s->cap = cap;
    src->data = p;
    return 1;
}

/* ---- Reading ahead ------------------------------------------------------- */

int mt__src_reads_ahead(const mt__io_src *src)
{
    const mt__io_stream *s = src->stream;
    return s && s->text && !s->gz && !s->finished && !s->ahead_held;
}

void mt__src_read_ahead(mt__io_src *src)
{
    mt__io_stream *s = src->stream;
    if (!mt__src_reads_ahead(src)) return;
    /* A window's size at most; after the first swap the spare block is the
     * window's first, which holds a little less than that after the room
     * (a window too small even for the room gets a block of its own). */
    size_t most = AHEAD_ROOM + s->window;
    if (s->spare_size <= AHEAD_ROOM) {
        free(s->spare);
        s->spare = malloc(most);
        s->spare_size = s->spare ? most : 0;
        if (!s->spare) return;
    }
    size_t len = AHEAD_ROOM;
    fill_into(src, s, s->spare, &len, s->spare_size < most ? s->spare_size : most);
    s->ahead = len - AHEAD_ROOM;
    s->ahead_held = 1;
    s->ahead_finished = s->finished;
    s->ahead_status = s->status;
    if (s->status != MT_OK) s->ahead_diag = s->diag;
    s->finished = 0;
    s->status = MT_OK;
}

/* The bytes read ahead are all in the window: the input is now where the
 * read ahead left it. */
static void end_ahead(mt__io_stream *s)
{
    s->ahead_held = 0;
    s->ahead = 0;
    if (s->ahead_status != MT_OK)
        stream_fail(s, s->ahead_status, &s->ahead_diag);
    else if (s->ahead_finished)
        s->finished = 1;
}

/* Drops the window's first `drop` bytes and takes in the bytes read ahead
 * without moving them: the kept bytes (at most AHEAD_ROOM) go just before
 * them, and the two blocks change places. */
static void swap_in_ahead(mt__io_stream *s, size_t drop)
{
    size_t kept = s->len - drop;
    unsigned char *start = s->spare + AHEAD_ROOM - kept;
    memcpy(start, s->buf + drop, kept);
    unsigned char *mem = s->mem;
    size_t mem_size = s->mem_size;
    s->mem = s->spare;
    s->mem_size = s->spare_size;
    s->spare = mem;
    s->spare_size = mem_size;
    s->buf = start;
    s->cap = s->mem_size - (size_t)(start - s->mem);
    s->len = kept + s->ahead;
    end_ahead(s);
}

/* Appends what fits of the bytes read ahead to the window. */
static void copy_in_ahead(mt__io_stream *s)
{
    size_t n = s->cap - s->len < s->ahead ? s->cap - s->len : s->ahead;
    memcpy(s->buf + s->len, s->spare + AHEAD_ROOM, n);
    s->len += n;
    s->ahead -= n;
    if (s->ahead)
        memmove(s->spare + AHEAD_ROOM, s->spare + AHEAD_ROOM + n, s->ahead);
    else
        end_ahead(s);
}

int mt__src_more(mt__io_src *src, size_t *pos)
{
    mt__io_stream *s = src->stream;
    if (!s || src->eof) return 0;
    size_t drop = *pos;
    if (drop && s->text) {
        if (src->mark >= src->base && src->mark - src->base < drop)
            src->mark_line =
                1 + src->lines + mt__count_newlines(s->buf, (size_t)(src->mark - src->base));
        src->lines += mt__count_newlines(s->buf, drop);
    }
    if (s->ahead_held && s->len - drop <= AHEAD_ROOM) {
        swap_in_ahead(s, drop);
    } else if (drop) {
        memmove(s->mem, s->buf + drop, s->len - drop);
        s->buf = s->mem;
        s->cap = s->mem_size;
        s->len -= drop;
    }
    src->base += drop;
    *pos = 0;
    size_t old = src->size - drop; /* bytes shown before, still shown */
    for (;;) {
        if (!s->ahead_held)
            fill(src, s);
        else if (s->finished) /* widening the window failed: the input ends there */
            s->ahead_held = 0;
        else
            copy_in_ahead(s);
        size_t end = s->text && !s->finished ? text_cut(s->buf, old, s->len) : s->len;
        if (end > old || s->finished) {
            src->data = s->buf;
            src->size = end;
            src->eof = s->finished && end == s->len;
            return end > old;
        }
        /* buf is full and holds no break past what was shown: widen it */
        grow(src, s);
    }
}

void mt__src_binary(mt__io_src *src)
{
    mt__io_stream *s = src->stream;
    if (!s) return;
    s->text = 0;
    src->size = s->len;
    src->eof = s->finished && !s->ahead_held;
}

mt__trail mt__src_skip_trailer(mt__io_src *src, size_t *pos, int comments)
{
    uint64_t stop = src->base + *pos + MT_READ_MAX_TRAILING_BYTES; /* first byte not allowed */
    size_t i = *pos;
    int in_comment = 0;
    for (;;) {
        const unsigned char *d = src->data;
        size_t n = src->size;
        size_t lim = stop - src->base < n ? (size_t)(stop - src->base) : n;
        for (; i < lim; i++) {
            if (in_comment) {
                in_comment = d[i] != '\n';
            } else if (comments && d[i] == '#') {
                in_comment = 1;
            } else if (!mt__is_space(d[i])) {
                *pos = i;
                return MT__TRAIL_DATA;
            }
        }
        if (i < n) {
            *pos = i;
            return MT__TRAIL_LONG;
        }
        if (!mt__src_more(src, &i)) {
            *pos = i;
            return MT__TRAIL_END;
        }
    }
}

/* ---- Learning the length ------------------------------------------------- */

/* Inflated bytes are counted RAW_CHUNK at a time. */
int mt__src_learn_length(mt__io_src *src)
{
    mt__io_stream *s = src->stream;
    if (src->total != MT__UNKNOWN || !s) return 1;
    if (s->finished) {
        if (s->status == MT_OK) src->total = s->produced;
        return s->status == MT_OK;
    }
    if (!s->gz || !s->rereadable) return 0;
    mt__io_raw ahead = s->raw;
    ahead.chunk = NULL;
    if (ahead.fd >= 0) {
        /* a second reader of the file, from where the first one is */
        size_t unused = (size_t)(s->raw.end - s->raw.p);
        ahead.chunk = malloc(RAW_CHUNK);
        if (!ahead.chunk) return 0;
        memcpy(ahead.chunk, s->raw.p, unused);
        ahead.p = ahead.chunk;
        ahead.end = ahead.chunk + unused;
        ahead.positioned = 1;
    }
    mt__inflater *z = mt__inflater_dup(s->gz);
    unsigned char *scratch = malloc(RAW_CHUNK);
    uint64_t produced = s->produced;
    while (z && scratch) {
        size_t room = RAW_CHUNK;
        uint64_t left = s->limit - produced;
        if (left < room) room = (size_t)left + 1;
        int done = 0;
        mt_status status = MT_OK;
        mt_diag diag;
        produced += mt__inflate(z, &ahead, scratch, room, src, &done, &status, &diag);
        if (status != MT_OK) {
            stream_fail(s, status, &diag);
            break;
        }
        if (produced > s->limit) {
            fail_too_long(src, s, ahead.offset);
            break;
        }
        if (done) {
            src->total = produced;
            break;
        }
    }
    free(scratch);
    mt__inflater_free(z);
    free(ahead.chunk);
    return src->total != MT__UNKNOWN;
}

/* ---- Opening and closing ------------------------------------------------- */

void mt__src_init_buffer(mt__io_src *src, const char *name, const void *data, size_t size)
{
    memset(src, 0, sizeof *src);
    src->name = name;
    src->data = size ? data : (const unsigned char *)"";
    src->size = size;
    src->eof = 1;
    src->total = size;
}

static void stream_free(mt__io_stream *s)
{
    if (!s) return;
    mt__inflater_free(s->gz);
    free(s->raw.chunk);
    free(s->mem);
    free(s->spare);
    free(s);
}

void mt__src_close(mt__io_src *src)
{
    stream_free(src->stream);
    src->stream = NULL;
    src->data = NULL;
    src->size = 0;
}

mt_status mt__src_open(mt__io_src *src, const char *name, int fd, const void *data, size_t size,
                       uint64_t total, const mt_read_options *options, mt_diag *diag)
{
    memset(src, 0, sizeof *src);
    src->name = name;
    src->data = (const unsigned char *)"";
    src->total = MT__UNKNOWN;
    mt__io_stream *s = calloc(1, sizeof *s);
    if (!s) return mt__io_fail_nomem(diag, src);
    size_t window =
        options && options->window_bytes ? options->window_bytes : MT_READ_DEFAULT_WINDOW_BYTES;
    s->max_cap = window > MT_READ_MAX_HELD_BYTES ? window : MT_READ_MAX_HELD_BYTES;
    s->cap = s->window = window;
    s->limit = options && options->max_input_bytes ? options->max_input_bytes
                                                   : MT_READ_DEFAULT_MAX_INPUT_BYTES;
    s->text = 1;
    s->rereadable = fd < 0 || total != MT__UNKNOWN; /* a buffer, or a regular file */
    s->raw.fd = fd;
    if (fd >= 0) {
        s->raw.chunk_cap = RAW_CHUNK;
        s->raw.chunk = malloc(RAW_CHUNK);
        s->raw.p = s->raw.end = s->raw.chunk;
    } else {
        s->raw.p = size ? data : (const unsigned char *)"";
        s->raw.end = s->raw.p + size;
        s->raw.at_end = 1;
    }
    s->mem = s->buf = malloc(s->cap);
    s->mem_size = s->cap;
    if (!s->buf || (fd >= 0 && !s->raw.chunk)) {
        stream_free(s);
        return mt__io_fail_nomem(diag, src);
    }
    /* gzip or not: the first two bytes tell */
    while (s->raw.end - s->raw.p < 2 && mt__raw_more(&s->raw)) continue;
    if (mt__is_gzip(s->raw.p, (size_t)(s->raw.end - s->raw.p))) {
        s->gz = mt__inflater_new();
        if (!s->gz) {
            stream_free(s);
            return mt__io_fail_nomem(diag, src);
        }
    } else {
        src->total = total;
    }
    src->stream = s;
    src->data = s->buf;
    if (s->raw.err) {
        fail_read_error(src, s);
    } else if (src->total != MT__UNKNOWN && src->total > s->limit) {
        mt_diag d;
        mt_status status =
            mt__io_fail(&d, MT_ERR_TOO_LARGE, src, MT__POS_NONE, 0, MT_NONE,
                        "%llu bytes: more than the input limit of %llu bytes",
                        (unsigned long long)src->total, (unsigned long long)s->limit);
        stream_fail(s, status, &d);
    }
    size_t zero = 0;
    mt__src_more(src, &zero);
    mt_status status = mt__src_status(src, diag);
    if (status != MT_OK) mt__src_close(src);
    return status;
}
