/* `meshtopo archive ls|show|verify|export|rm`: the subcommands the
 * dispatcher (cmd_archive.c) runs, one cmd_archive_*.c file each; what they
 * share is archive_common.h. */
#ifndef MESHTOPO_CLI_CMD_ARCHIVE_H
#define MESHTOPO_CLI_CMD_ARCHIVE_H

#include "cli.h"

/* The subcommands; args->positionals[0] is the subcommand's name. */
int cli_archive_ls(const cli_args *args);
int cli_archive_show(const cli_args *args);
int cli_archive_verify(const cli_args *args);
int cli_archive_export(const cli_args *args);
int cli_archive_rm(const cli_args *args);

#endif
