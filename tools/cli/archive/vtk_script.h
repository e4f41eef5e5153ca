/* The VTK scripts the tool runs (the .py files of tools/vtk, installed in
 * share/meshtopo): found and run with Debian's python3 (python3-vtk9).
 * `meshtopo render` and `meshtopo archive export` use them. */
#ifndef MESHTOPO_CLI_VTK_SCRIPT_H
#define MESHTOPO_CLI_VTK_SCRIPT_H

#include "cli.h"

/* Environment variables: the python to run the scripts with (default
 * Debian's /usr/bin/python3, which has python3-vtk9; the first python3 on
 * PATH may be another one) and the directory holding them. */
#define CLI_ENV_PYTHON "MESHTOPO_PYTHON"
#define CLI_ENV_VTK_SCRIPTS "MESHTOPO_VTK_SCRIPTS"

/* Runs `python SCRIPT args...` (args NULL-terminated) and waits for it.
 * The script is looked for in $MESHTOPO_VTK_SCRIPTS when set, else in
 * ../share/meshtopo next to the executable (an installed tree, wherever it
 * was moved), the source tree the tool was built from, and the install
 * prefix's share/meshtopo. Returns the script's exit code when it is 0, 2
 * or 3 (the scripts' own: written, usage, failed with a message), else
 * CLI_EXIT_READ after saying what went wrong (script or python
 * missing, killed by a signal). */
int cli_vtk_script_run(const char *command, const char *script, const char *const *args);

#endif
