/* `meshtopo archive ls|show|verify|export|rm`: the archive command and the
 * pieces its subcommand files share (opening the archive read-only or for
 * writing, parsing --version, the exit code of a library status). */
#ifndef MESHTOPO_CLI_CMD_ARCHIVE_H
#define MESHTOPO_CLI_CMD_ARCHIVE_H

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

/* The subcommands; args->positionals[0] is the subcommand's name. */
int cli_archive_ls(const cli_args *args);
int cli_archive_show(const cli_args *args);
int cli_archive_verify(const cli_args *args);
int cli_archive_export(const cli_args *args);
int cli_archive_rm(const cli_args *args);

#endif
