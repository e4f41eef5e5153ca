/* Links against an installed meshtopo::io (and so zlib when static): reads a
 * small OFF file from memory, builds it and prints its Euler characteristic.
 * Built by the install test through find_package and pkg-config. */
#include <stdio.h>
#include <string.h>

#include <meshtopo/core.h>
#include <meshtopo/io.h>

static const char cube_off[] =
    "OFF\n8 6 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";

int main(void)
{
    mt_face_list faces;
    mt_diag diag;
    if (mt_read_memory(cube_off, strlen(cube_off), MT_FORMAT_OFF, "cube.off", &faces, &diag) !=
        MT_OK) {
        fprintf(stderr, "read failed: %s\n", diag.message);
        return 1;
    }
    mt_mesh *mesh = NULL;
    mt_status status = mt_mesh_build(&faces, NULL, &mesh, &diag);
    mt_face_list_free(&faces);
    if (status != MT_OK) {
        fprintf(stderr, "build failed: %s\n", diag.message);
        return 1;
    }
    printf("cube (%s): Euler characteristic: %lld\n", mt_format_name(MT_FORMAT_OFF),
           (long long)mt_mesh_report(mesh)->euler_characteristic);
    mt_mesh_destroy(mesh);
    return 0;
}
