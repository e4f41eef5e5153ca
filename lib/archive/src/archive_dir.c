/* The archive directory: opening it (and removing leftovers of interrupted
 * writes whose writer is gone), listing its files, finding a mesh's
 * versions by file name, removing versions durably and setting damaged
 * files aside. Only names this library makes are touched: "*.hdf" files
 * (and "*.vtkhdf", as earlier versions named them) and ".mt-tmp-*" leftovers, and of the latter
 * only regular files of ours: whatever else is planted under such a name is never followed, opened
 * or removed. */
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "archive_internal.h"

void mt__archive_host(char *out, size_t size)
{
    char host[256] = "";
    gethostname(host, sizeof host - 1);
    size_t n = 0;
    /* Host names are [A-Za-z0-9.-]; anything else is not put in a name. */
    for (const char *p = host; *p && n + 1 < size && n < MT__ARCHIVE_HOST_MAX; p++)
        out[n++] = (isalnum((unsigned char)*p) || *p == '.' || *p == '-') ? *p : '_';
    if (n == 0 && size > 1) out[n++] = '_';
    if (size > 0) out[n] = '\0';
}

/* Whether a temporary file's writer (the pid in its name, on the host its
 * name gives) is gone. A file of another host is never judged here: its
 * writer may be running there (a directory shared by several machines). */
static bool leftover_is_stale(const char *name)
{
    const char *p = name + strlen(MT__ARCHIVE_TMP_PREFIX);
    char *end = NULL;
    long pid = strtol(p, &end, 10);
    if (end == p || *end != '-' || pid <= 0) return true; /* not one of ours in progress */
    /* "-<16 hex>" then ".<host>.part" (names written before hosts were
     * named end with ".part" right after the digits: this host's). */
    if (strlen(end + 1) > 16 && end[1 + 16] == '.') {
        const char *host = end + 1 + 16;
        char here[MT__ARCHIVE_HOST_MAX + 1];
        mt__archive_host(here, sizeof here);
        size_t len = strlen(here);
        if (strncmp(host + 1, here, len) != 0 || strcmp(host + 1 + len, ".part") != 0) return false;
    }
    if (pid == (long)getpid()) return false; /* another handle of this process */
    return kill((pid_t)pid, 0) != 0 && errno == ESRCH;
}

mt_status mt__archive_fsync_dir(const mt_archive *archive, mt_diag *diag)
{
    int fd = open(archive->dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0 || fsync(fd) != 0) {
        int err = errno;
        if (fd >= 0) close(fd);
        return mt__archive_fail_os(diag, MT_ERR_IO, err, archive->dir,
                                   "%s: fsync of the directory failed", archive->dir);
    }
    close(fd);
    return MT_OK;
}

static mt_status remove_leftovers(mt_archive *archive, mt_diag *diag)
{
    DIR *d = opendir(archive->dir);
    if (!d)
        return mt__archive_fail_os(diag, MT_ERR_IO, errno, NULL, "%s: cannot read the directory",
                                   archive->dir);
    size_t removed = 0;
    struct dirent *ent;
    while ((ent = readdir(d)) != NULL) {
        if (strncmp(ent->d_name, MT__ARCHIVE_TMP_PREFIX, strlen(MT__ARCHIVE_TMP_PREFIX)) != 0)
            continue;
        /* Only a regular file of ours is a leftover of ours: a symbolic link
         * (unlinking would remove only the link, but it is not ours to
         * tidy), a directory or another user's file is left alone. */
        struct stat sb;
        if (fstatat(dirfd(d), ent->d_name, &sb, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(sb.st_mode) ||
            sb.st_uid != geteuid())
            continue;
        if (!leftover_is_stale(ent->d_name)) continue;
        if (unlinkat(dirfd(d), ent->d_name, 0) == 0) removed++;
    }
    closedir(d);
    if (removed > 0) {
        int fd = open(archive->dir, O_RDONLY | O_DIRECTORY);
        if (fd >= 0) {
            fsync(fd);
            close(fd);
        }
    }
    archive->leftovers_removed = removed;
    return MT_OK;
}

mt_status mt_archive_open(const char *dir, const mt_archive_options *options,
                          mt_archive **out_archive, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!out_archive) return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_open: NULL");
    *out_archive = NULL;
    if (!dir || !dir[0])
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "no archive directory given");
    static const mt_archive_options defaults;
    if (!options) options = &defaults;
    struct stat sb;
    if (stat(dir, &sb) != 0 && errno == ENOENT && options->create && !options->read_only &&
        mkdir(dir, 0777) != 0 && errno != EEXIST)
        return mt__archive_fail_os(diag, MT_ERR_IO, errno, NULL, "%s: cannot create the directory",
                                   dir);
    if (stat(dir, &sb) != 0) return mt__archive_fail_os(diag, MT_ERR_IO, errno, NULL, "%s", dir);
    if (!S_ISDIR(sb.st_mode)) return mt__archive_fail(diag, MT_ERR_IO, "%s: not a directory", dir);
    mt_archive *a = calloc(1, sizeof *a);
    if (!a || !(a->dir = mt__archive_strdup(dir))) {
        free(a);
        return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    }
    size_t n = strlen(a->dir);
    while (n > 1 && a->dir[n - 1] == '/') a->dir[--n] = '\0';
    a->read_only = options->read_only;
    mt_status st = a->read_only ? MT_OK : remove_leftovers(a, diag);
    if (st == MT_OK && access(a->dir, a->read_only ? R_OK | X_OK : R_OK | W_OK | X_OK) != 0)
        st = mt__archive_fail_os(diag, MT_ERR_IO, errno, NULL, "%s", a->dir);
    if (st != MT_OK) {
        mt_archive_close(a);
        return st;
    }
    *out_archive = a;
    return MT_OK;
}

void mt_archive_set_content_hash(mt_archive *archive, mt_archive_hash_fn hash, void *ctx)
{
    if (!archive) return;
    archive->content_hash = hash;
    archive->content_hash_ctx = ctx;
}

void mt_archive_close(mt_archive *archive)
{
    if (!archive) return;
    free(archive->dir);
    free(archive);
}

const char *mt_archive_dir(const mt_archive *archive)
{
    return archive ? archive->dir : NULL;
}

size_t mt_archive_leftovers_removed(const mt_archive *archive)
{
    return archive ? archive->leftovers_removed : 0;
}

/* Whether the directory has an entry named `name` (not followed). */
static bool entry_exists(const mt_archive *archive, const char *name)
{
    char *path = mt__archive_path(archive, name);
    struct stat sb;
    bool found = path && lstat(path, &sb) == 0;
    free(path);
    return found;
}

/* name (from mt_archive_file_name, room for MT_ARCHIVE_FILE_NAME_MAX + 1
 * bytes) with its suffix replaced by the legacy one. */
static void name_to_legacy(char *name)
{
    size_t stem = strlen(name) - strlen(MT_ARCHIVE_SUFFIX);
    snprintf(name + stem, MT_ARCHIVE_FILE_NAME_MAX + 1 - stem, "%s", MT_ARCHIVE_SUFFIX_LEGACY);
}

mt_status mt_archive_file_find(const mt_archive *archive, const char *mesh_id, uint32_t version,
                               char *buf, size_t size, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (size > 0) buf[0] = '\0';
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    if (!archive || mt_archive_file_name(mesh_id, version, name, sizeof name) == 0)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                "no archive file name for mesh '%s' version %u",
                                mesh_id ? mesh_id : "(null)", version);
    mt_status st = MT_OK;
    if (!entry_exists(archive, name)) {
        char legacy[MT_ARCHIVE_FILE_NAME_MAX + 1];
        memcpy(legacy, name, sizeof legacy);
        name_to_legacy(legacy);
        if (entry_exists(archive, legacy))
            memcpy(name, legacy, sizeof name);
        else
            st = mt__archive_fail(diag, MT_ERR_NOT_FOUND,
                                  "%s: version %u of mesh '%s' is not archived (no file %s)",
                                  archive->dir, version, mesh_id, name);
    }
    if (size > 0) snprintf(buf, size, "%s", name);
    return st;
}

bool mt_archive_contains(const mt_archive *archive, const char *mesh_id, uint32_t version)
{
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    return mt_archive_file_find(archive, mesh_id, version, name, sizeof name, NULL) == MT_OK;
}

static int entry_compare(const void *pa, const void *pb)
{
    const mt_archive_entry *a = pa, *b = pb;
    bool ga = a->status == MT_OK, gb = b->status == MT_OK;
    if (ga != gb) return ga ? -1 : 1;
    if (ga) {
        int c = strcmp(a->mesh_id, b->mesh_id);
        if (c != 0) return c;
        if (a->version != b->version) return a->version < b->version ? -1 : 1;
    }
    return strcmp(a->file_name, b->file_name);
}

/* Whether a directory entry is an archive file (not hidden, ".hdf" or
 * the legacy ".vtkhdf"). */
static bool is_archive_name(const char *name)
{
    return name[0] != '.' && mt__archive_suffix_len(name) > 0;
}

mt_status mt_archive_list(const mt_archive *archive, mt_archive_listing *out, mt_diag *diag)
{
    return mt_archive_list_filtered(archive, NULL, NULL, out, diag);
}

mt_status mt_archive_list_filtered(const mt_archive *archive, mt_archive_name_filter wanted,
                                   void *ctx, mt_archive_listing *out, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!out) return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_list: NULL");
    memset(out, 0, sizeof *out);
    if (!archive) return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_list: NULL");
    DIR *d = opendir(archive->dir);
    if (!d)
        return mt__archive_fail_os(diag, MT_ERR_IO, errno, NULL, "%s: cannot read the directory",
                                   archive->dir);
    mt_archive_listing l = {NULL, 0};
    size_t capacity = 0;
    mt_status st = MT_OK;
    struct dirent *ent;
    while (st == MT_OK && (ent = readdir(d)) != NULL) {
        if (!is_archive_name(ent->d_name) || (wanted && !wanted(ctx, ent->d_name))) continue;
        if (l.count == capacity) {
            size_t grown = capacity ? 2 * capacity : 16;
            mt_archive_entry *bigger = realloc(l.entries, grown * sizeof *bigger);
            if (!bigger) {
                st = mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory listing %s", archive->dir);
                break;
            }
            l.entries = bigger;
            capacity = grown;
        }
        mt_archive_entry *e = &l.entries[l.count];
        memset(e, 0, sizeof *e);
        if (!(e->file_name = mt__archive_strdup(ent->d_name))) {
            st = mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory listing %s", archive->dir);
            break;
        }
        l.count++;
        mt_diag_clear(&e->diag);
        /* Every entry is checked before it is opened (mt__archive_open_fd):
         * a symbolic link, FIFO or directory with an archive name is
         * listed with its status and fault, never followed or read. */
        e->status = mt__archive_read_entry(archive, e->file_name, e, &e->diag);
    }
    closedir(d);
    if (st != MT_OK) {
        mt_archive_listing_free(&l);
        return st;
    }
    if (l.count > 1) qsort(l.entries, l.count, sizeof *l.entries, entry_compare);
    *out = l;
    return MT_OK;
}

mt_status mt_archive_list_file(const mt_archive *archive, const char *file_name,
                               mt_archive_entry *out, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!out) return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_list_file: NULL");
    memset(out, 0, sizeof *out);
    if (!archive || !file_name)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_list_file: NULL");
    if (strchr(file_name, '/') || !is_archive_name(file_name) ||
        strlen(file_name) > MT_ARCHIVE_FILE_NAME_MAX)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "'%s' is not an archive file name",
                                file_name);
    if (!(out->file_name = mt__archive_strdup(file_name)))
        return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory listing %s", file_name);
    mt_diag_clear(&out->diag);
    out->status = mt__archive_read_entry(archive, file_name, out, &out->diag);
    if (diag && out->status != MT_OK) *diag = out->diag;
    return out->status;
}

void mt_archive_entry_free(mt_archive_entry *entry)
{
    if (!entry) return;
    free(entry->file_name);
    free(entry->mesh_id);
    free(entry->source);
    memset(entry, 0, sizeof *entry);
}

void mt_archive_listing_free(mt_archive_listing *listing)
{
    if (!listing) return;
    for (size_t i = 0; i < listing->count; i++) mt_archive_entry_free(&listing->entries[i]);
    free(listing->entries);
    memset(listing, 0, sizeof *listing);
}

mt_status mt_archive_highest_version(const mt_archive *archive, const char *mesh_id,
                                     uint32_t *out_version, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!archive || !out_version)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_highest_version: NULL");
    *out_version = 0;
    mt_status st = mt_mesh_id_check(mesh_id, diag);
    if (st != MT_OK) return st;
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(mesh_id, 1, name, sizeof name);
    size_t stem_len = 0;
    uint32_t v = 0, best = 0;
    if (!mt__archive_name_parse(name, &stem_len, &v))
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mesh '%s': no archive name", mesh_id);
    DIR *d = opendir(archive->dir);
    if (!d)
        return mt__archive_fail_os(diag, MT_ERR_IO, errno, NULL, "%s: cannot read the directory",
                                   archive->dir);
    struct dirent *ent;
    while ((ent = readdir(d)) != NULL) {
        size_t len = 0;
        if (is_archive_name(ent->d_name) && mt__archive_name_parse(ent->d_name, &len, &v) &&
            len == stem_len && memcmp(ent->d_name, name, len) == 0 && v > best)
            best = v;
    }
    closedir(d);
    *out_version = best;
    return MT_OK;
}

/* Highest version of mesh_id present, by file name (0 when none or the
 * directory cannot be read: the look-up that follows says which). */
static uint32_t latest_version(const mt_archive *archive, const char *mesh_id)
{
    uint32_t best = 0;
    mt_diag ignored;
    return mt_archive_highest_version(archive, mesh_id, &best, &ignored) == MT_OK ? best : 0;
}

mt_status mt__archive_resolve(const mt_archive *archive, const char *mesh_id, uint32_t version,
                              char *name, mt_diag *diag)
{
    mt_status st = mt_mesh_id_check(mesh_id, diag);
    if (st != MT_OK) return st;
    if (version == 0) version = latest_version(archive, mesh_id);
    if (version == 0)
        return mt__archive_fail(diag, MT_ERR_NOT_FOUND, "%s: mesh '%s' is not archived",
                                archive->dir, mesh_id);
    return mt_archive_file_find(archive, mesh_id, version, name, MT_ARCHIVE_FILE_NAME_MAX + 1,
                                diag);
}

mt_status mt_archive_load(const mt_archive *archive, const char *mesh_id, uint32_t version,
                          mt_archive_record *out, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out) memset(out, 0, sizeof *out);
    if (!archive || !out)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_load: NULL argument");
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_status st = mt__archive_resolve(archive, mesh_id, version, name, diag);
    if (st != MT_OK) return st;
    return mt_archive_load_file(archive, name, out, diag);
}

mt_status mt_archive_load_mesh(const mt_archive *archive, const char *mesh_id, uint32_t version,
                               bool with_faces, mt_archive_record *out_record, mt_mesh **out_mesh,
                               mt_archive_load_info *out_info, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out_record) memset(out_record, 0, sizeof *out_record);
    if (out_mesh) *out_mesh = NULL;
    if (out_info) memset(out_info, 0, sizeof *out_info);
    if (!archive || !out_mesh)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_load_mesh: NULL argument");
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_status st = mt__archive_resolve(archive, mesh_id, version, name, diag);
    if (st != MT_OK) return st;
    return mt_archive_load_mesh_file(archive, name, with_faces, out_record, out_mesh, out_info,
                                     diag);
}

mt_status mt_archive_remove(mt_archive *archive, const char *mesh_id, uint32_t version,
                            mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!archive) return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_remove: NULL");
    if (archive->read_only)
        return mt__archive_fail(diag, MT_ERR_UNSUPPORTED, "%s: archive opened read-only",
                                archive->dir);
    mt_status st = mt_mesh_id_check(mesh_id, diag);
    if (st != MT_OK) return st;
    if (version == 0)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mesh '%s': version 0 is not a version",
                                mesh_id);
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    st = mt_archive_file_find(archive, mesh_id, version, name, sizeof name, diag);
    if (st != MT_OK) return st;
    char *path = mt__archive_path(archive, name);
    if (!path) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    if (unlink(path) != 0) {
        int err = errno;
        st = mt__archive_fail_os(diag, err == ENOENT ? MT_ERR_NOT_FOUND : MT_ERR_IO, err, NULL,
                                 "%s: cannot remove version %u of mesh '%s'", path, version,
                                 mesh_id);
        free(path);
        return st;
    }
    free(path);
    return mt__archive_fsync_dir(archive, diag);
}

mt_status mt_archive_set_aside(mt_archive *archive, const char *file_name, char *out_name,
                               size_t size, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out_name && size > 0) out_name[0] = '\0';
    if (!archive || !file_name)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_set_aside: NULL argument");
    if (archive->read_only)
        return mt__archive_fail(diag, MT_ERR_UNSUPPORTED, "%s: archive opened read-only",
                                archive->dir);
    if (strchr(file_name, '/') || !is_archive_name(file_name) ||
        strlen(file_name) > MT_ARCHIVE_FILE_NAME_MAX)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "'%s' is not an archive file name",
                                file_name);
    char hex[17], aside[sizeof MT__ARCHIVE_ASIDE_PREFIX + MT_ARCHIVE_FILE_NAME_MAX + 18];
    mt__archive_random_hex(hex);
    snprintf(aside, sizeof aside, MT__ARCHIVE_ASIDE_PREFIX "%s.%s", file_name, hex);
    char *from = mt__archive_path(archive, file_name), *to = mt__archive_path(archive, aside);
    mt_status st = from && to ? MT_OK : mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    /* rename acts on the entry itself (a symbolic link is renamed, not
     * followed); the random suffix keeps it from replacing anything. */
    if (st == MT_OK && rename(from, to) != 0) {
        int err = errno;
        st = mt__archive_fail_os(diag, err == ENOENT ? MT_ERR_NOT_FOUND : MT_ERR_IO, err, NULL,
                                 "%s: cannot set it aside as %s", from, aside);
    }
    free(from);
    free(to);
    if (st == MT_OK) st = mt__archive_fsync_dir(archive, diag);
    if (st == MT_OK && out_name && size > 0) snprintf(out_name, size, "%s", aside);
    return st;
}
