/* Files of the archive opened so that nothing planted in the directory can
 * redirect them: a name is checked with lstat, opened with O_NOFOLLOW (and
 * O_NONBLOCK, so a FIFO swapped in cannot block), and the open file must be
 * the regular file, owned by the effective user, that lstat saw. HDF5 then
 * opens that file through /proc/self/fd (mt__fd_proc_path), never the name
 * again. Also the random part of temporary names (getrandom(2)). */
#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <time.h>
#include <unistd.h>

#include "archive_internal.h"

bool mt__fd_proc_path(int fd, char *buf, size_t size)
{
    struct stat via_proc, direct;
    int n = snprintf(buf, size, "/proc/self/fd/%d", fd);
    if (n < 0 || (size_t)n >= size) return false;
    /* stat follows the magic link to the open file: the same device and
     * inode prove /proc is mounted and names this very file. */
    return stat(buf, &via_proc) == 0 && fstat(fd, &direct) == 0 &&
           via_proc.st_dev == direct.st_dev && via_proc.st_ino == direct.st_ino;
}

void mt__archive_random_hex(char out[17])
{
    static atomic_uint fallback_counter;
    uint64_t r = 0;
    if (getrandom(&r, sizeof r, GRND_NONBLOCK) != (ssize_t)sizeof r) {
        /* No entropy yet (early boot) or no getrandom: a mix of the clock,
         * the pid and a counter. Exclusive creation keeps the name safe; it
         * is only less hard to guess. */
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        r = (uint64_t)ts.tv_nsec * 0x9e3779b97f4a7c15ull ^ (uint64_t)ts.tv_sec << 20 ^
            (uint64_t)getpid() << 40 ^ atomic_fetch_add(&fallback_counter, 1u);
        r ^= r >> 29;
        r *= 0xbf58476d1ce4e5b9ull;
        r ^= r >> 32;
    }
    static const char hex[] = "0123456789abcdef";
    for (int i = 0; i < 16; i++) out[i] = hex[(r >> (60 - 4 * i)) & 15];
    out[16] = '\0';
}

/* What kind of file a mode is, for the messages. */
static const char *kind_of(mode_t mode)
{
    if (S_ISLNK(mode)) return "a symbolic link";
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    return "not a regular file";
}

/* Refuses what lstat or fstat found unless it is a regular file owned by
 * the effective user. */
static mt_status check_kind(const char *path, const struct stat *sb, mt_archive_fault *fault,
                            mt_diag *diag)
{
    if (S_ISLNK(sb->st_mode)) {
        char target[256];
        ssize_t n = readlink(path, target, sizeof target - 1);
        target[n > 0 ? n : 0] = '\0';
        *fault = MT_ARCHIVE_FAULT_UNSAFE;
        return mt__archive_fail(diag, MT_ERR_IO,
                                "%s: refused: a symbolic link (to '%s'), not a regular file; "
                                "archive files are never followed through links",
                                path, target);
    }
    if (!S_ISREG(sb->st_mode)) {
        *fault = MT_ARCHIVE_FAULT_UNSAFE;
        return mt__archive_fail(diag, MT_ERR_IO, "%s: refused: %s, not a regular file", path,
                                kind_of(sb->st_mode));
    }
    if (sb->st_uid != geteuid()) {
        *fault = MT_ARCHIVE_FAULT_UNSAFE;
        return mt__archive_fail(diag, MT_ERR_IO,
                                "%s: refused: owned by uid %lu, not by this process's user "
                                "(uid %lu)",
                                path, (unsigned long)sb->st_uid, (unsigned long)geteuid());
    }
    return MT_OK;
}

mt_status mt__archive_open_fd(const mt_archive *archive, const char *file_name, int *out_fd,
                              struct stat *out_sb, mt_archive_fault *out_fault, mt_diag *diag)
{
    *out_fd = -1;
    mt_archive_fault fault = MT_ARCHIVE_FAULT_NONE;
    char *path = mt__archive_path(archive, file_name);
    if (!path) {
        *out_fault = MT_ARCHIVE_FAULT_SYSTEM;
        return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    }
    struct stat seen, opened;
    mt_status st = MT_OK;
    /* lstat first, so that nothing but a regular file is ever opened (a
     * device's open may act on the device). */
    if (lstat(path, &seen) != 0) {
        int err = errno;
        fault = MT_ARCHIVE_FAULT_SYSTEM;
        st = mt__archive_fail_os(diag, err == ENOENT ? MT_ERR_NOT_FOUND : MT_ERR_IO, err, path,
                                 "%s", path);
    }
    if (st == MT_OK) st = check_kind(path, &seen, &fault, diag);
    int fd = -1;
    if (st == MT_OK) {
        fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
        if (fd < 0) {
            int err = errno;
            if (err == ELOOP) { /* made a link since lstat */
                fault = MT_ARCHIVE_FAULT_UNSAFE;
                st = mt__archive_fail(diag, MT_ERR_IO,
                                      "%s: refused: a symbolic link, not a regular file", path);
            } else {
                fault = MT_ARCHIVE_FAULT_SYSTEM;
                st = mt__archive_fail_os(diag, err == ENOENT ? MT_ERR_NOT_FOUND : MT_ERR_IO, err,
                                         path, "%s: cannot open", path);
            }
        }
    }
    if (st == MT_OK && fstat(fd, &opened) != 0) {
        fault = MT_ARCHIVE_FAULT_SYSTEM;
        st = mt__archive_fail_os(diag, MT_ERR_IO, errno, path, "%s: fstat", path);
    }
    if (st == MT_OK) st = check_kind(path, &opened, &fault, diag);
    if (st == MT_OK && (opened.st_dev != seen.st_dev || opened.st_ino != seen.st_ino)) {
        fault = MT_ARCHIVE_FAULT_UNSAFE;
        st = mt__archive_fail(diag, MT_ERR_IO,
                              "%s: refused: replaced by another file while being opened", path);
    }
    free(path);
    *out_fault = fault;
    if (st != MT_OK) {
        if (fd >= 0) close(fd);
        return st;
    }
    *out_fd = fd;
    *out_sb = opened;
    return MT_OK;
}
