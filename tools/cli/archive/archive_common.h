/* What the `meshtopo archive` subcommands (cmd_archive_*.c) share: opening
 * the archive read-only or for writing, with the content hash checked as
 * meshtopod checks it, and parsing --version. They call this file, never
 * each other nor the dispatcher (cmd_archive.c), which calls them. */
#ifndef MESHTOPO_CLI_ARCHIVE_COMMON_H
#define MESHTOPO_CLI_ARCHIVE_COMMON_H

#include <stdbool.h>
#include <stdint.h>

#include "cli.h"
#include "meshtopo/archive.h"

/* Opens DIR (must exist). Returns CLI_EXIT_OK or CLI_EXIT_READ after
 * printing the reason. */
int cli_archive_open(const char *dir, bool read_only, mt_archive **out);

/* --version N (N >= 1) into *out; 0 when absent. CLI_EXIT_OK or
 * CLI_EXIT_USAGE after printing the problem. */
int cli_archive_version(const cli_args *args, uint32_t *out);

#endif
