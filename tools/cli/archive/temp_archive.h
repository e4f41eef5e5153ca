/* A built mesh archived alone in a private temporary directory: the file
 * the VTK scripts read (meshtopo render, meshtopo archive export to .vtu,
 * .hdf or .vtkhdf), with the topology arrays of format 6 and, when asked,
 * the self-intersections. */
#ifndef MESHTOPO_CLI_TEMP_ARCHIVE_H
#define MESHTOPO_CLI_TEMP_ARCHIVE_H

#include <stdbool.h>

#include "cli.h"
#include "meshtopo/archive.h"

/* A one-file archive in a fresh private directory ($TMPDIR or /tmp). */
typedef struct cli_temp_archive {
    char dir[4096];
    char path[4096 + MT_ARCHIVE_FILE_NAME_MAX + 2]; /* the file */
} cli_temp_archive;

/* Archives mesh (list's build) as meta says (NULL: id "mesh", version 1,
 * now, source "meshtopo", its content hash) into a new temporary
 * directory, with CellData/self_intersecting computed when asked. Returns
 * CLI_EXIT_OK, or CLI_EXIT_READ after printing why (nothing is then
 * left behind). */
int cli_temp_archive_write(const char *command, const mt_face_list *list, const mt_mesh *mesh,
                           const mt_archive_meta *meta, bool self_intersections,
                           cli_temp_archive *out);

/* Removes the file and the directory. */
void cli_temp_archive_remove(cli_temp_archive *temp);

/* Copies the archive file to `out` (written to a temporary name beside it
 * and renamed into place). CLI_EXIT_OK or CLI_EXIT_READ after
 * printing why. */
int cli_temp_archive_copy(const char *command, const cli_temp_archive *temp, const char *out);

/* Whether path names an archive file by its suffix (".hdf", ".vtkhdf"). */
bool cli_is_archive_path(const char *path);

#endif
