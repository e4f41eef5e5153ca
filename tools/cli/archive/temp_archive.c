/* A built mesh archived alone in a private temporary directory
 * (temp_archive.h): mkdtemp makes a directory only this user can enter,
 * meshtopo::archive writes the one file there as it writes any archive
 * (crash-safe, exclusive creation), and removal takes both away. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <unistd.h>

#include "temp_archive.h"

bool cli_is_archive_path(const char *path)
{
    static const char *const suffixes[] = {MT_ARCHIVE_SUFFIX, MT_ARCHIVE_SUFFIX_LEGACY};
    size_t len = strlen(path);
    for (size_t i = 0; i < sizeof suffixes / sizeof suffixes[0]; i++) {
        size_t n = strlen(suffixes[i]);
        if (len > n && strcmp(path + len - n, suffixes[i]) == 0) return true;
    }
    return false;
}

static int64_t now_us(void)
{
    struct timeval tv;
    gettimeofday(&tv, NULL);
    return (int64_t)tv.tv_sec * 1000000 + tv.tv_usec;
}

int cli_temp_archive_write(const char *command, const mt_face_list *list, const mt_mesh *mesh,
                           const mt_archive_meta *meta, bool self_intersections,
                           cli_temp_archive *out)
{
    memset(out, 0, sizeof *out);
    const char *tmp = getenv("TMPDIR");
    if (!tmp || !tmp[0]) tmp = "/tmp";
    int n = snprintf(out->dir, sizeof out->dir, "%s/meshtopo-vtk-XXXXXX", tmp);
    if (n < 0 || (size_t)n >= sizeof out->dir || !mkdtemp(out->dir)) {
        cli_error(command, "cannot make a temporary directory in %s: %s", tmp,
                  n > 0 && (size_t)n < sizeof out->dir ? strerror(errno) : "name too long");
        out->dir[0] = '\0';
        return CLI_EXIT_READ;
    }
    mt_archive_meta own = {
        .mesh_id = "mesh", .version = 1, .utime = now_us(), .source = "meshtopo"};
    if (!meta) {
        if (mt_archive_content_hash(NULL, list, &own.content_hash, NULL) != MT_OK)
            own.content_hash = 0;
        meta = &own;
    }
    mt_archive *archive = NULL;
    mt_diag diag;
    mt_archive_write_options options = {
        .self_intersections = self_intersections ? MT_ARCHIVE_SELF_INTERSECTIONS_COMPUTE
                                                 : MT_ARCHIVE_SELF_INTERSECTIONS_SKIP};
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_status st = mt_archive_open(out->dir, NULL, &archive, &diag);
    if (st == MT_OK) st = mt_archive_write_with(archive, meta, list, mesh, &options, NULL, &diag);
    mt_archive_close(archive);
    if (st != MT_OK) {
        cli_error(command, "%s", diag.message);
        cli_temp_archive_remove(out);
        return CLI_EXIT_READ;
    }
    mt_archive_file_name(meta->mesh_id, meta->version, name, sizeof name);
    snprintf(out->path, sizeof out->path, "%s/%s", out->dir, name);
    return CLI_EXIT_OK;
}

void cli_temp_archive_remove(cli_temp_archive *temp)
{
    if (temp->path[0]) unlink(temp->path);
    if (temp->dir[0]) rmdir(temp->dir);
    temp->path[0] = temp->dir[0] = '\0';
}

int cli_temp_archive_copy(const char *command, const cli_temp_archive *temp, const char *out)
{
    char part[4200];
    int n = snprintf(part, sizeof part, "%s.part-%ld", out, (long)getpid());
    if (n < 0 || (size_t)n >= sizeof part) {
        cli_error(command, "%s: name too long", out);
        return CLI_EXIT_USAGE;
    }
    int from = open(temp->path, O_RDONLY | O_CLOEXEC);
    int to = open(part, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    const char *failed = from < 0 ? temp->path : to < 0 ? part : NULL;
    int err = errno;
    char buf[1 << 16];
    while (!failed) {
        ssize_t got = read(from, buf, sizeof buf);
        if (got == 0) break;
        if (got < 0) {
            if (errno == EINTR) continue;
            err = errno;
            failed = temp->path;
            break;
        }
        for (ssize_t done = 0; !failed && done < got;) {
            ssize_t put = write(to, buf + done, (size_t)(got - done));
            if (put < 0 && errno == EINTR) continue;
            if (put < 0) {
                err = errno;
                failed = part;
            } else {
                done += put;
            }
        }
    }
    if (from >= 0) close(from);
    if (to >= 0 && close(to) != 0 && !failed) {
        err = errno;
        failed = part;
    }
    if (!failed && rename(part, out) != 0) {
        err = errno;
        failed = out;
    }
    if (failed) {
        if (to >= 0) unlink(part);
        cli_error(command, "%s: %s", failed, strerror(err));
        return CLI_EXIT_READ;
    }
    return CLI_EXIT_OK;
}
