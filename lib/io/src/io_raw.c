/* Raw input bytes for the readers: from a file descriptor, a chunk at a
 * time (read, or pread by a second reader of the same file), or from a
 * buffer in place. Nothing here interprets the bytes; a failed read is
 * kept in `err` for the caller to report. */
#include <errno.h>
#include <unistd.h>

#include "io_internal.h"

int mt__raw_more(mt__io_raw *raw)
{
    if (raw->at_end) return 0;
    if (raw->fd < 0) {
        raw->at_end = 1;
        return 0;
    }
    size_t keep = (size_t)(raw->end - raw->p);
    if (keep) memmove(raw->chunk, raw->p, keep);
    raw->p = raw->chunk;
    raw->end = raw->chunk + keep;
    for (;;) {
        size_t room = raw->chunk_cap - keep;
        ssize_t got = raw->positioned
                          ? pread(raw->fd, raw->chunk + keep, room, (off_t)raw->file_pos)
                          : read(raw->fd, raw->chunk + keep, room);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) {
            if (got < 0) raw->err = errno;
            raw->at_end = 1;
            return 0;
        }
        raw->end += got;
        raw->file_pos += (uint64_t)got;
        return 1;
    }
}

size_t mt__raw_read(mt__io_raw *raw, unsigned char *dst, size_t n)
{
    size_t done = 0;
    while (done < n) {
        if (raw->p < raw->end) {
            size_t k = (size_t)(raw->end - raw->p);
            if (k > n - done) k = n - done;
            memcpy(dst + done, raw->p, k);
            raw->p += k;
            raw->offset += k;
            done += k;
            continue;
        }
        if (raw->at_end || raw->fd < 0) {
            raw->at_end = 1;
            break;
        }
        ssize_t got = read(raw->fd, dst + done, n - done);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) {
            if (got < 0) raw->err = errno;
            raw->at_end = 1;
            break;
        }
        done += (size_t)got;
        raw->offset += (uint64_t)got;
        raw->file_pos += (uint64_t)got;
    }
    return done;
}
