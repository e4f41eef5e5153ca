/* Archive file names: a mesh id is user input and never becomes a path as
 * it is. Every byte outside [A-Za-z0-9_-] is percent-encoded (so '.', '/',
 * '%', '~' and ' ' never appear raw) and long ids are shortened with a hash
 * so every name fits NAME_MAX. Also the small helpers every file uses:
 * failure messages (with the system's reason and the limit it hit), paths,
 * fault names. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/statvfs.h>
#include <time.h>

#include "archive_internal.h"

/* Escaped ids longer than this are shortened to a prefix plus a hash. */
#define ESCAPED_MAX 160
#define ESCAPED_PREFIX 140

mt_status mt__archive_fail(mt_diag *diag, mt_status status, const char *fmt, ...)
{
    if (!diag) return status;
    diag->status = status;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(diag->message, sizeof diag->message, fmt, ap);
    va_end(ap);
    return status;
}

_Thread_local int mt__archive_last_errno;

void mt__archive_errno_text(int err, const char *path, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%s", strerror(err));
    if (n < 0 || (size_t)n >= size) return;
    struct statvfs vfs;
    struct rlimit lim;
    if ((err == ENOSPC || err == EDQUOT) && path && statvfs(path, &vfs) == 0)
        snprintf(buf + n, size - (size_t)n, " (%llu bytes free on the file system of %s)",
                 (unsigned long long)vfs.f_bavail * (unsigned long long)vfs.f_frsize, path);
    else if (err == EFBIG && getrlimit(RLIMIT_FSIZE, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY)
        snprintf(buf + n, size - (size_t)n, " (the file size limit, RLIMIT_FSIZE, is %llu bytes)",
                 (unsigned long long)lim.rlim_cur);
}

mt_status mt__archive_fail_os(mt_diag *diag, mt_status status, int err, const char *path,
                              const char *fmt, ...)
{
    mt__archive_last_errno = err;
    if (!diag) return status;
    char what[sizeof diag->message], why[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    mt__archive_errno_text(err, path, why, sizeof why);
    /* The reason comes first when the message is long: it is what a
     * message cut to fit must not lose. */
    if (strlen(what) + strlen(why) + 2 >= sizeof diag->message)
        return mt__archive_fail(diag, status, "%s: %.*s", why,
                                (int)(sizeof diag->message - strlen(why) - 3), what);
    return mt__archive_fail(diag, status, "%s: %s", what, why);
}

const char *mt_archive_fault_name(mt_archive_fault fault)
{
    switch (fault) {
        case MT_ARCHIVE_FAULT_NONE:
            return "none";
        case MT_ARCHIVE_FAULT_DERIVED:
            return "derived";
        case MT_ARCHIVE_FAULT_VTK:
            return "vtk";
        case MT_ARCHIVE_FAULT_CONTENT:
            return "content";
        case MT_ARCHIVE_FAULT_NEWER:
            return "newer";
        case MT_ARCHIVE_FAULT_UNSAFE:
            return "unsafe";
        case MT_ARCHIVE_FAULT_SYSTEM:
            return "system";
    }
    return "unknown";
}

char *mt__archive_strdup(const char *text)
{
    size_t n = strlen(text) + 1;
    char *copy = malloc(n);
    if (copy) memcpy(copy, text, n);
    return copy;
}

char *mt__archive_path(const mt_archive *archive, const char *name)
{
    size_t a = strlen(archive->dir), b = strlen(name);
    char *path = malloc(a + b + 2);
    if (!path) return NULL;
    memcpy(path, archive->dir, a);
    path[a] = '/';
    memcpy(path + a + 1, name, b + 1);
    return path;
}

double mt__archive_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

static bool byte_is_plain(unsigned char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
}

size_t mt_archive_file_name(const char *mesh_id, uint32_t version, char *buf, size_t size)
{
    if (size > 0) buf[0] = '\0';
    if (version == 0 || mt_mesh_id_check(mesh_id, NULL) != MT_OK) return 0;
    static const char hex[] = "0123456789ABCDEF";
    char escaped[3 * MT_MESH_ID_MAX + 1];
    size_t n = 0, cut = 0;
    for (const unsigned char *p = (const unsigned char *)mesh_id; *p; p++) {
        if (byte_is_plain(*p)) {
            escaped[n++] = (char)*p;
        } else {
            escaped[n++] = '%';
            escaped[n++] = hex[*p >> 4];
            escaped[n++] = hex[*p & 15];
        }
        if (n <= ESCAPED_PREFIX) cut = n; /* whole escapes only */
    }
    escaped[n] = '\0';
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    int len;
    if (n <= ESCAPED_MAX) {
        len = snprintf(name, sizeof name, "%s.v%u" MT_ARCHIVE_SUFFIX, escaped, version);
    } else {
        uint64_t h = 0xcbf29ce484222325ull; /* FNV-1a of the id itself */
        for (const unsigned char *p = (const unsigned char *)mesh_id; *p; p++) {
            h ^= *p;
            h *= 0x100000001b3ull;
        }
        len = snprintf(name, sizeof name, "%.*s~%016llx.v%u" MT_ARCHIVE_SUFFIX, (int)cut, escaped,
                       (unsigned long long)h, version);
    }
    if (len < 0) return 0;
    if (size > 0) snprintf(buf, size, "%s", name);
    return (size_t)len;
}

size_t mt__archive_suffix_len(const char *name)
{
    static const char *const suffixes[] = {MT_ARCHIVE_SUFFIX, MT_ARCHIVE_SUFFIX_LEGACY};
    size_t len = strlen(name);
    for (size_t i = 0; i < sizeof suffixes / sizeof suffixes[0]; i++) {
        size_t n = strlen(suffixes[i]);
        if (len > n && strcmp(name + len - n, suffixes[i]) == 0) return n;
    }
    return 0;
}

bool mt__archive_name_matches(const char *file_name, const char *mesh_id, uint32_t version)
{
    char expected[MT_ARCHIVE_FILE_NAME_MAX + 1];
    size_t len = mt_archive_file_name(mesh_id, version, expected, sizeof expected);
    if (len == 0 || len > MT_ARCHIVE_FILE_NAME_MAX) return false;
    size_t stem = len - strlen(MT_ARCHIVE_SUFFIX), suffix = mt__archive_suffix_len(file_name);
    return suffix > 0 && strlen(file_name) == stem + suffix &&
           memcmp(file_name, expected, stem) == 0;
}

bool mt__archive_name_parse(const char *name, size_t *out_stem_len, uint32_t *out_version)
{
    size_t len = strlen(name), suffix = mt__archive_suffix_len(name);
    if (suffix == 0) return false;
    size_t end = len - suffix; /* one past the version's last digit */
    size_t start = end;
    while (start > 0 && name[start - 1] >= '0' && name[start - 1] <= '9') start--;
    if (start == end || end - start > 10 || name[start] == '0') return false;
    if (start < 3 || name[start - 1] != 'v' || name[start - 2] != '.') return false;
    uint64_t v = 0;
    for (size_t i = start; i < end; i++) v = v * 10 + (uint64_t)(name[i] - '0');
    if (v > UINT32_MAX) return false;
    *out_stem_len = start - 2;
    *out_version = (uint32_t)v;
    return true;
}
