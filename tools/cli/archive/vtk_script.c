/* Finding and running the VTK scripts (vtk_script.h): the script by
 * $MESHTOPO_VTK_SCRIPTS, then relative to the executable, the source tree
 * and the install prefix; the interpreter by $MESHTOPO_PYTHON, else
 * Debian's python3 (the one python3-vtk9 installs into). The script runs
 * as a child process with the tool's standard streams; its exit code is
 * the command's. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "vtk_script.h"

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

/* Set by tools/CMakeLists.txt. */
#ifndef MESHTOPO_PYTHON
#define MESHTOPO_PYTHON "/usr/bin/python3"
#endif
#ifndef MESHTOPO_VTK_SCRIPTS_BUILD
#define MESHTOPO_VTK_SCRIPTS_BUILD ""
#endif
#ifndef MESHTOPO_VTK_SCRIPTS_INSTALLED
#define MESHTOPO_VTK_SCRIPTS_INSTALLED "/usr/local/share/meshtopo"
#endif

/* The exit code a child uses when it cannot start the interpreter. */
enum { EXEC_FAILED = 127 };

static bool readable_in(const char *dir, const char *script, char *out, size_t size)
{
    if (!dir || !dir[0]) return false;
    int n = snprintf(out, size, "%s/%s", dir, script);
    return n > 0 && (size_t)n < size && access(out, R_OK) == 0;
}

/* The script's path into out; false after printing where it was looked for. */
static bool script_find(const char *command, const char *script, char *out, size_t size)
{
    const char *env = getenv(CLI_ENV_VTK_SCRIPTS);
    if (env && env[0]) {
        if (readable_in(env, script, out, size)) return true;
        cli_error(command, "$%s is %s, which has no readable %s", CLI_ENV_VTK_SCRIPTS, env, script);
        return false;
    }
    char exe[PATH_MAX], dir[PATH_MAX + 32];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            snprintf(dir, sizeof dir, "%s/../share/meshtopo", exe);
            if (readable_in(dir, script, out, size)) return true;
        }
    }
    if (readable_in(MESHTOPO_VTK_SCRIPTS_BUILD, script, out, size)) return true;
    if (readable_in(MESHTOPO_VTK_SCRIPTS_INSTALLED, script, out, size)) return true;
    cli_error(command,
              "%s not found: looked in ../share/meshtopo beside the executable%s%s and %s "
              "(set $%s to its directory)",
              script, MESHTOPO_VTK_SCRIPTS_BUILD[0] ? ", " : "", MESHTOPO_VTK_SCRIPTS_BUILD,
              MESHTOPO_VTK_SCRIPTS_INSTALLED, CLI_ENV_VTK_SCRIPTS);
    return false;
}

int cli_vtk_script_run(const char *command, const char *script, const char *const *args)
{
    char path[PATH_MAX];
    if (!script_find(command, script, path, sizeof path)) return CLI_EXIT_READ;
    const char *python = getenv(CLI_ENV_PYTHON);
    if (!python || !python[0]) python = MESHTOPO_PYTHON;
    size_t count = 0;
    while (args[count]) count++;
    const char **argv = calloc(count + 3, sizeof *argv);
    if (!argv) {
        cli_error(command, "out of memory");
        return CLI_EXIT_READ;
    }
    argv[0] = python;
    argv[1] = path;
    for (size_t i = 0; i < count; i++) argv[i + 2] = args[i];
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        execv(python, (char *const *)argv);
        fprintf(stderr,
                "meshtopo %s: cannot run %s: %s (Debian: python3 and python3-vtk9; $%s "
                "names another python)\n",
                command, python, strerror(errno), CLI_ENV_PYTHON);
        _exit(EXEC_FAILED);
    }
    free(argv);
    if (pid < 0) {
        cli_error(command, "cannot start %s: %s", python, strerror(errno));
        return CLI_EXIT_READ;
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            cli_error(command, "waiting for %s: %s", script, strerror(errno));
            return CLI_EXIT_READ;
        }
    }
    if (WIFSIGNALED(status)) {
        cli_error(command, "%s was killed by signal %d", script, WTERMSIG(status));
        return CLI_EXIT_READ;
    }
    int code = WEXITSTATUS(status);
    if (code == CLI_EXIT_OK || code == CLI_EXIT_USAGE || code == CLI_EXIT_READ) return code;
    if (code != EXEC_FAILED) cli_error(command, "%s failed (exit code %d)", script, code);
    return CLI_EXIT_READ;
}
