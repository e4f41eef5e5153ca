/* replay_fixture DIR ID VERSION UTIME SOURCE MESHFILE [HASH]: reads a mesh
 * file, builds and validates it and archives it as ID / VERSION in DIR with
 * the given utime (microseconds since the epoch), source and its real
 * content hash (or HASH, 16 hex digits, to make a file whose hash is wrong),
 * the way meshtopod archives a submission. The replay tests make their
 * archives with it. Exit 0 on success, 1 with a message on stderr otherwise. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "meshtopo/archive.h"
#include "meshtopo/client.h"
#include "meshtopo/io.h"
#include "meshtopo/validate.h"

static int fail(const char *what, const char *message)
{
    fprintf(stderr, "replay_fixture: %s: %s\n", what, message);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 7 && argc != 8) {
        fprintf(stderr, "usage: replay_fixture DIR ID VERSION UTIME SOURCE MESHFILE [HASH]\n");
        return 1;
    }
    char *end = NULL;
    errno = 0;
    unsigned long version = strtoul(argv[3], &end, 10);
    if (errno || *end || version == 0 || version > UINT32_MAX) return fail(argv[3], "bad version");
    long long utime = strtoll(argv[4], &end, 10);
    if (errno || *end) return fail(argv[4], "bad utime");
    uint64_t forced_hash = 0;
    if (argc == 8) {
        forced_hash = (uint64_t)strtoull(argv[7], &end, 16);
        if (errno || *end || !argv[7][0]) return fail(argv[7], "bad hash");
    }

    mt_diag diag;
    mt_face_list list;
    if (mt_read_file(argv[6], MT_FORMAT_AUTO, &list, &diag) != MT_OK)
        return fail(argv[6], diag.message);
    mt_mesh *mesh = NULL;
    mt_archive *archive = NULL;
    mt_archive_options options = {.create = true};
    uint64_t hash = 0;
    int code = 1;
    if (mt_mesh_build(&list, NULL, &mesh, &diag) != MT_OK ||
        mt_mesh_validate(mesh, &diag) != MT_OK ||
        mt_client_content_hash(&list, &hash, &diag) != MT_OK ||
        mt_archive_open(argv[1], &options, &archive, &diag) != MT_OK) {
        fail(argv[6], diag.message);
    } else {
        if (argc == 8) hash = forced_hash;
        mt_archive_meta meta = {argv[2], (uint32_t)version, (int64_t)utime, argv[5], hash};
        if (mt_archive_write(archive, &meta, &list, mesh, NULL, &diag) == MT_OK)
            code = 0;
        else
            fail(argv[1], diag.message);
    }
    mt_archive_close(archive);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    return code;
}
