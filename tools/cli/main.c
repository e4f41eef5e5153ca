/* `meshtopo <command> [args]`: the command table and the dispatch. A new
 * subcommand is one row in `commands` plus its cmd_*.c file (or, for one
 * that reads or writes archives, a name in cli_module.c and a file of the
 * module); help, --help, option parsing and exit codes are handled here for
 * all of them. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

#ifndef MESHTOPO_VERSION
#define MESHTOPO_VERSION "unknown"
#endif

static const cli_command *const commands[] = {
    &cli_cmd_inspect, &cli_cmd_send, &cli_cmd_query, &cli_cmd_list,
    &cli_cmd_watch,   &cli_cmd_spy,  &cli_cmd_bench,
};
static const size_t num_commands = sizeof commands / sizeof commands[0];

/* The command called `name`; NULL after printing why when it is none, or
 * when its module cannot be loaded (*out_unknown tells which). */
static const cli_command *command_find(const char *name, bool *out_unknown)
{
    *out_unknown = false;
    for (size_t i = 0; i < num_commands; i++)
        if (strcmp(commands[i]->name, name) == 0) return commands[i];
    for (size_t i = 0; i < cli_module_count(); i++) {
        if (strcmp(cli_module_name(i), name) != 0) continue;
        char err[512];
        const cli_command *cmd = cli_module_command(name, err, sizeof err);
        if (!cmd) cli_error(name, "%s", err);
        return cmd;
    }
    *out_unknown = true;
    return NULL;
}

static void print_usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo <command> [args]\n"
            "       meshtopo help <command> | meshtopo <command> --help\n"
            "       meshtopo --help | --version\n"
            "\n"
            "commands:\n");
    for (size_t i = 0; i < num_commands; i++)
        fprintf(out, "  %-10s %s\n", commands[i]->name, commands[i]->summary);
    for (size_t i = 0; i < cli_module_count(); i++) {
        char err[512];
        const cli_command *cmd = cli_module_command(cli_module_name(i), err, sizeof err);
        fprintf(out, "  %-10s %s\n", cli_module_name(i), cmd ? cmd->summary : err);
    }
}

static void print_help(FILE *out)
{
    fprintf(out,
            "meshtopo: mesh topology tool (half-edge build, defects, queries)\n"
            "\n");
    print_usage(out);
    fprintf(out,
            "\n"
            "exit codes (all commands):\n"
            "  0  success (a report is printed whatever defects it lists)\n"
            "  1  --fail-on-defect was given and the report lists a defect\n"
            "  2  usage error (unknown command or option, bad argument)\n"
            "  3  a file could not be read or parsed\n"
            "  4  the mesh could not be built (e.g. --strict refused a defect)\n"
            "  5  meshtopod answered with an error (unknown mesh, refused defect, ...)\n"
            "  6  no answer from meshtopod (timeout), or LCM could not be used\n"
            "  7  a part of meshtopo could not be loaded (a broken installation)\n"
            "\n"
            "send, query, list, watch and replay talk to meshtopod over LCM; --lcm-url and\n"
            "--prefix default to $MESHTOPO_LCM_URL and $MESHTOPO_PREFIX.\n");
}

static int run_command(const cli_command *cmd, int argc, char **argv)
{
    if (cmd->run_raw) return cmd->run_raw(argc, argv);
    cli_args args;
    bool help = false;
    int code = cli_args_parse(cmd, argc, argv, &args, &help);
    if (code != CLI_EXIT_OK) {
        fprintf(stderr, "usage: meshtopo %s %s (see meshtopo help %s)\n", cmd->name, cmd->synopsis,
                cmd->name);
        return code;
    }
    if (help) {
        cli_print_command_help(cmd, stdout);
        cli_args_free(&args);
        return CLI_EXIT_OK;
    }
    code = cmd->run(&args);
    cli_args_free(&args);
    return code;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        print_usage(stderr);
        return CLI_EXIT_USAGE;
    }
    const char *name = argv[1];
    if (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0) {
        print_help(stdout);
        return CLI_EXIT_OK;
    }
    if (strcmp(name, "--version") == 0) {
        printf("meshtopo %s\n", MESHTOPO_VERSION);
        return CLI_EXIT_OK;
    }
    if (strcmp(name, "help") == 0) {
        if (argc == 2) {
            print_help(stdout);
            return CLI_EXIT_OK;
        }
        bool unknown;
        const cli_command *cmd = command_find(argv[2], &unknown);
        if (!cmd && !unknown) return CLI_EXIT_MISSING;
        if (!cmd || argc > 3) {
            if (!cmd)
                fprintf(stderr, "meshtopo: unknown command '%s'\n", argv[2]);
            else
                fprintf(stderr, "meshtopo: help takes one command name\n");
            print_usage(stderr);
            return CLI_EXIT_USAGE;
        }
        cli_print_command_help(cmd, stdout);
        return CLI_EXIT_OK;
    }
    bool unknown;
    const cli_command *cmd = command_find(name, &unknown);
    if (!cmd && !unknown) return CLI_EXIT_MISSING;
    if (!cmd) {
        fprintf(stderr, "meshtopo: unknown command '%s'\n", name);
        print_usage(stderr);
        return CLI_EXIT_USAGE;
    }
    return run_command(cmd, argc - 2, argv + 2);
}
