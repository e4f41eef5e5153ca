/* Links against an installed meshtopo::archive (and so HDF5): archives a
 * cube into a fresh directory, loads it back as a mesh and prints its Euler
 * characteristic. Built by the install tests through find_package and
 * pkg-config. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>

#include <meshtopo/archive.h>
#include <meshtopo/core.h>

/* Removes the archive's one file and its directory. */
static void remove_archive(const char *dir)
{
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    char path[512];
    mt_archive_file_name("cube", 1, name, sizeof name);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    remove(path);
    remove(dir);
}

int main(void)
{
    char dir[] = "/tmp/meshtopo-archive-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    mt_face_list cube;
    mt_diag diag;
    mt_mesh *mesh = NULL, *loaded = NULL;
    mt_archive *archive = NULL;
    mt_archive_meta meta = {"cube", 1, 0, "install-test", 0};
    int code = 1;
    if (mt_gen_platonic(MT_CUBE, &cube) != MT_OK) return 1;
    if (mt_mesh_build(&cube, NULL, &mesh, &diag) != MT_OK ||
        mt_archive_open(dir, NULL, &archive, &diag) != MT_OK ||
        mt_archive_content_hash(NULL, &cube, &meta.content_hash, &diag) != MT_OK ||
        mt_archive_write(archive, &meta, &cube, mesh, NULL, &diag) != MT_OK ||
        mt_archive_load_mesh(archive, "cube", 1, false, NULL, &loaded, NULL, &diag) != MT_OK) {
        fprintf(stderr, "archive: %s\n", diag.message);
    } else {
        printf("archive ok: cube v1 reloaded, Euler characteristic %lld (format %d)\n",
               (long long)mt_mesh_report(loaded)->euler_characteristic, MT_ARCHIVE_FORMAT_VERSION);
        code = 0;
    }
    mt_mesh_destroy(loaded);
    mt_archive_close(archive);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&cube);
    remove_archive(dir);
    return code;
}
