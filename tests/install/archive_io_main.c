/* Links against an installed meshtopo::core, meshtopo::io and
 * meshtopo::archive only, none of which needs LCM: reads a cube from an OFF
 * file in memory, builds it, archives it with its content hash, reloads it
 * (the content hash checked, as meshtopod loads) and compares the reloaded
 * face list with the one read. The install test builds it with pkg-config
 * and runs it where liblcm cannot be loaded (tests/install/archive_no_lcm.sh). */
#define _POSIX_C_SOURCE 200809L
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <meshtopo/archive.h>
#include <meshtopo/core.h>
#include <meshtopo/io.h>

static const char cube_off[] =
    "OFF\n8 6 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";

static int same_faces(const mt_face_list *a, const mt_face_list *b)
{
    return a->num_verts == b->num_verts && a->num_faces == b->num_faces &&
           a->num_indices == b->num_indices &&
           memcmp(a->positions, b->positions, 3 * sizeof(double) * a->num_verts) == 0 &&
           memcmp(a->face_sizes, b->face_sizes, sizeof(uint32_t) * a->num_faces) == 0 &&
           memcmp(a->face_indices, b->face_indices, sizeof(uint32_t) * a->num_indices) == 0;
}

int main(void)
{
    char dir[] = "/tmp/meshtopo-archive-io-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    mt_face_list cube;
    mt_diag diag;
    mt_mesh *mesh = NULL, *loaded = NULL;
    mt_archive *archive = NULL;
    mt_archive_record record = {0};
    mt_archive_load_info info;
    mt_archive_meta meta = {"cube off", 1, 1700000000000000, "install-test", 0};
    int code = 1;
    if (mt_read_memory(cube_off, strlen(cube_off), MT_FORMAT_OFF, "cube.off", &cube, &diag) !=
        MT_OK) {
        fprintf(stderr, "read failed: %s\n", diag.message);
        return 1;
    }
    if (mt_mesh_build(&cube, NULL, &mesh, &diag) != MT_OK ||
        mt_archive_open(dir, NULL, &archive, &diag) != MT_OK ||
        mt_archive_content_hash(NULL, &cube, &meta.content_hash, &diag) != MT_OK ||
        mt_archive_write(archive, &meta, &cube, mesh, NULL, &diag) != MT_OK) {
        fprintf(stderr, "archive: %s\n", diag.message);
    } else {
        mt_archive_set_content_hash(archive, mt_archive_content_hash, NULL);
        if (mt_archive_load_mesh(archive, "cube off", 1, true, &record, &loaded, &info, &diag) !=
            MT_OK) {
            fprintf(stderr, "load: %s\n", diag.message);
        } else if (!info.hash_checked || record.content_hash != meta.content_hash ||
                   !same_faces(&record.faces, &cube)) {
            fprintf(stderr, "load: the reloaded cube differs from the one archived\n");
        } else {
            printf("archive io ok: cube read, archived and reloaded (content hash %016" PRIx64
                   " checked), Euler characteristic %lld\n",
                   record.content_hash, (long long)mt_mesh_report(loaded)->euler_characteristic);
            code = 0;
        }
    }
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1], path[512];
    mt_archive_file_name("cube off", 1, name, sizeof name);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    remove(path);
    remove(dir);
    mt_archive_record_free(&record);
    mt_mesh_destroy(loaded);
    mt_archive_close(archive);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&cube);
    return code;
}
