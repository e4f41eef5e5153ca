/* The commands that read or write archives (archive, replay, render) live
 * in a module, meshtopo-archive-commands.so, loaded when one of them is
 * named: HDF5 and the libraries it brings (curl, TLS, Kerberos, ...) take
 * about 7 ms to load and start, which every other command would pay too.
 * The module is looked for only where it is installed with this program
 * (MESHTOPO_CLI_MODULE_FROM_BINDIR, relative to the directory of
 * /proc/self/exe; the build tree has the same layout), never on a search
 * path, so no other library can stand in for it. */
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"

#ifndef MESHTOPO_CLI_MODULE_FROM_BINDIR
/* the module's path from the program's directory, set by tools/CMakeLists.txt */
#error "MESHTOPO_CLI_MODULE_FROM_BINDIR is not set"
#endif

enum { MODULE_PATH_MAX = 4096 };

static const char *const module_commands[] = {"archive", "replay", "render"};

size_t cli_module_count(void)
{
    return sizeof module_commands / sizeof module_commands[0];
}

const char *cli_module_name(size_t i)
{
    return i < cli_module_count() ? module_commands[i] : NULL;
}

const cli_command *cli_module_command(const char *name, char *err, size_t err_size)
{
    size_t i = 0;
    while (i < cli_module_count() && strcmp(module_commands[i], name) != 0) i++;
    if (i == cli_module_count()) {
        snprintf(err, err_size, "'%s' is not a command of the archive module", name);
        return NULL;
    }
    static void *module;
    char path[MODULE_PATH_MAX];
    if (!module) {
        if (!cli_beside_program(MESHTOPO_CLI_MODULE_FROM_BINDIR, path, sizeof path)) {
            snprintf(err, err_size, "cannot find this program's directory (/proc/self/exe)");
            return NULL;
        }
        module = dlopen(path, RTLD_NOW | RTLD_LOCAL);
        if (!module) {
            const char *why = dlerror();
            snprintf(err, err_size, "cannot load the archive commands: %s", why ? why : path);
            return NULL;
        }
    }
    char symbol[64];
    snprintf(symbol, sizeof symbol, "cli_cmd_%s", name);
    const cli_command *cmd = dlsym(module, symbol);
    if (!cmd) snprintf(err, err_size, "the archive module has no command '%s'", name);
    return cmd;
}
