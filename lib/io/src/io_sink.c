/* Output files: a buffered writer, gzip-compressing when asked, that writes
 * to PATH.tmp.XXXXXX beside PATH, then fsyncs, closes and renames it onto
 * PATH, so PATH is never seen half-written. The first write error sticks
 * and is reported by mt__sink_close as MT_ERR_IO naming the path; the
 * temporary file is then removed. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

#include "io_internal.h"

#define SINK_BUFFER (1u << 20)

struct mt__sink {
    int fd;
    char *path;
    char *tmp_path;
    unsigned char *buf;
    size_t len;
    int gzip;
    z_stream zs;
    unsigned char *zbuf;
    int err;          /* errno of the first failure, 0 while all is well */
    const char *what; /* what failed: "write", "fsync", ... */
};

static void sink_free(mt__sink *s)
{
    if (s->gzip) deflateEnd(&s->zs);
    free(s->buf);
    free(s->zbuf);
    free(s->path);
    free(s->tmp_path);
    free(s);
}

static mt_status sink_error(mt_diag *diag, const char *path, const char *what, int err)
{
    char text[256];
    if (strerror_r(err, text, sizeof text) != 0) snprintf(text, sizeof text, "error %d", err);
    mt__io_src src = {.name = path};
    return mt__io_fail(diag, MT_ERR_IO, &src, MT__POS_NONE, 0, MT_NONE, "cannot %s: %s", what,
                       text);
}

static uint64_t mix(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* Creates PATH.tmp.XXXXXX with a fresh suffix; returns the fd or -1. */
static int create_temp(mt__sink *s)
{
    static const char chars[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    size_t n = strlen(s->path);
    s->tmp_path = malloc(n + 12);
    if (!s->tmp_path) {
        errno = ENOMEM;
        return -1;
    }
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t seed = mix((uint64_t)ts.tv_nsec ^ (uint64_t)ts.tv_sec << 32) ^
                    mix((uint64_t)getpid()) ^ mix((uint64_t)(uintptr_t)s);
    for (int attempt = 0; attempt < 100; attempt++) {
        uint64_t r = mix(seed + (uint64_t)attempt);
        memcpy(s->tmp_path, s->path, n);
        memcpy(s->tmp_path + n, ".tmp.", 5);
        for (int k = 0; k < 6; k++) s->tmp_path[n + 5 + k] = chars[(r >> (6 * k)) % 62];
        s->tmp_path[n + 11] = '\0';
        int fd;
        do fd = open(s->tmp_path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        while (fd < 0 && errno == EINTR);
        if (fd >= 0 || errno != EEXIST) return fd;
    }
    return -1;
}

mt_status mt__sink_open(mt__sink **out, const char *path, int gzip, mt_diag *diag)
{
    *out = NULL;
    mt__sink *s = calloc(1, sizeof *s);
    mt__io_src src = {.name = path};
    if (!s) return mt__io_fail(diag, MT_ERR_NOMEM, &src, MT__POS_NONE, 0, MT_NONE, "out of memory");
    s->fd = -1;
    s->path = malloc(strlen(path) + 1);
    s->buf = malloc(SINK_BUFFER);
    if (gzip) s->zbuf = malloc(SINK_BUFFER);
    if (!s->path || !s->buf || (gzip && !s->zbuf)) {
        sink_free(s);
        return mt__io_fail(diag, MT_ERR_NOMEM, &src, MT__POS_NONE, 0, MT_NONE, "out of memory");
    }
    memcpy(s->path, path, strlen(path) + 1);
    if (gzip) {
        if (deflateInit2(&s->zs, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
            sink_free(s);
            return mt__io_fail(diag, MT_ERR_NOMEM, &src, MT__POS_NONE, 0, MT_NONE,
                               "cannot start gzip compression");
        }
        s->gzip = 1;
    }
    s->fd = create_temp(s);
    if (s->fd < 0) {
        int err = errno;
        sink_free(s);
        return sink_error(diag, path, "create a temporary file beside it", err);
    }
    *out = s;
    return MT_OK;
}

static void write_all(mt__sink *s, const unsigned char *p, size_t n)
{
    while (n > 0 && !s->err) {
        ssize_t k = write(s->fd, p, n);
        if (k < 0) {
            if (errno == EINTR) continue;
            s->err = errno;
            s->what = "write";
            return;
        }
        p += k;
        n -= (size_t)k;
    }
}

/* Runs deflate over the pending input with flush, writing what it makes. */
static void deflate_out(mt__sink *s, int flush)
{
    for (;;) {
        s->zs.next_out = s->zbuf;
        s->zs.avail_out = SINK_BUFFER;
        int ret = deflate(&s->zs, flush);
        write_all(s, s->zbuf, SINK_BUFFER - s->zs.avail_out);
        if (ret == Z_STREAM_ERROR) {
            if (!s->err) {
                s->err = EIO;
                s->what = "compress";
            }
            return;
        }
        if (flush == Z_FINISH ? ret == Z_STREAM_END : s->zs.avail_out != 0) return;
    }
}

static void flush_buffer(mt__sink *s)
{
    if (s->len == 0 || s->err) {
        s->len = 0;
        return;
    }
    if (s->gzip) {
        s->zs.next_in = s->buf;
        s->zs.avail_in = (uInt)s->len;
        deflate_out(s, Z_NO_FLUSH);
    } else {
        write_all(s, s->buf, s->len);
    }
    s->len = 0;
}

char *mt__sink_reserve(mt__sink *s, size_t n)
{
    if (SINK_BUFFER - s->len < n) flush_buffer(s);
    return (char *)s->buf + s->len;
}

void mt__sink_commit(mt__sink *s, size_t n)
{
    s->len += n;
}

void mt__sink_write(mt__sink *s, const void *data, size_t n)
{
    const unsigned char *p = data;
    while (n > 0) {
        if (s->len == SINK_BUFFER) flush_buffer(s);
        size_t k = SINK_BUFFER - s->len < n ? SINK_BUFFER - s->len : n;
        memcpy(s->buf + s->len, p, k);
        s->len += k;
        p += k;
        n -= k;
    }
}

/* Syncs the directory holding path so the rename is durable (best effort:
 * some file systems refuse fsync on directories). */
static void sync_directory(const char *path)
{
    const char *slash = strrchr(path, '/');
    char *dir;
    if (!slash) {
        dir = malloc(2);
        if (dir) memcpy(dir, ".", 2);
    } else {
        size_t n = slash == path ? 1 : (size_t)(slash - path);
        dir = malloc(n + 1);
        if (dir) {
            memcpy(dir, path, n);
            dir[n] = '\0';
        }
    }
    if (!dir) return;
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    free(dir);
    if (fd < 0) return;
    (void)fsync(fd);
    close(fd);
}

mt_status mt__sink_close(mt__sink *s, mt_diag *diag)
{
    flush_buffer(s);
    if (s->gzip && !s->err) {
        s->zs.next_in = s->buf;
        s->zs.avail_in = 0;
        deflate_out(s, Z_FINISH);
    }
    if (!s->err && fsync(s->fd) != 0) {
        s->err = errno;
        s->what = "fsync";
    }
    if (close(s->fd) != 0 && !s->err) {
        s->err = errno;
        s->what = "close";
    }
    s->fd = -1;
    if (!s->err && rename(s->tmp_path, s->path) != 0) {
        s->err = errno;
        s->what = "rename the temporary file onto it";
    }
    if (s->err) {
        unlink(s->tmp_path);
        mt_status status = sink_error(diag, s->path, s->what, s->err);
        sink_free(s);
        return status;
    }
    sync_directory(s->path);
    sink_free(s);
    return MT_OK;
}

void mt__sink_abort(mt__sink *s)
{
    if (!s) return;
    if (s->fd >= 0) close(s->fd);
    if (s->tmp_path) unlink(s->tmp_path);
    sink_free(s);
}
