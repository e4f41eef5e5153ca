/* Command-line parsing shared by every subcommand, with meshtopo::args (as
 * meshtopod and meshtopo-bench parse theirs): `--name`, `--name VALUE`,
 * `--name=VALUE`, `-h`/`--help`, `--` ending the options, positionals
 * anywhere. Unknown options, missing values and wrong positional counts are
 * reported on stderr as usage errors; nothing here exits the process. */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

void cli_error(const char *command, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "meshtopo %s: ", command);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

int cli_finish_output(const char *command, int code, int failure_code)
{
    if (fflush(stdout) == 0 || code != CLI_EXIT_OK) return code;
    cli_error(command, "cannot write the output");
    return failure_code;
}

/* Refuses a command line as meshtopo's subcommands always have. */
static int refuse(const cli_command *cmd, const mt__args *parsed, cli_args *out)
{
    switch (parsed->error) {
        case MT__ARGS_UNKNOWN_OPTION:
            cli_error(cmd->name, "unknown option '%s'", parsed->at);
            break;
        case MT__ARGS_UNEXPECTED_VALUE:
            cli_error(cmd->name, "option '--%s' takes no value", parsed->option->name);
            break;
        case MT__ARGS_MISSING_VALUE:
            cli_error(cmd->name, "option '--%s' needs a value (%s)", parsed->option->name,
                      parsed->option->value_name);
            break;
        case MT__ARGS_TOO_FEW_ARGUMENTS:
            cli_error(cmd->name, "missing argument");
            break;
        case MT__ARGS_TOO_MANY_ARGUMENTS:
            cli_error(cmd->name, "unexpected argument '%s'", parsed->at);
            break;
        default:
            cli_error(cmd->name, "out of memory");
            break;
    }
    cli_args_free(out);
    return CLI_EXIT_USAGE;
}

int cli_args_parse(const cli_command *cmd, int argc, char **argv, cli_args *out, bool *out_help)
{
    memset(out, 0, sizeof *out);
    out->command = cmd->name;
    out->options = cmd->options;
    out->num_options = cmd->num_options;
    mt__args parsed;
    mt__args_error error = mt__args_parse(cmd->options, cmd->num_options, cmd->min_positionals,
                                          cmd->max_positionals, argc, argv, &parsed);
    out->values = parsed.values;
    out->positionals = parsed.positionals;
    out->num_positionals = parsed.num_positionals;
    *out_help = parsed.help;
    return error == MT__ARGS_OK ? CLI_EXIT_OK : refuse(cmd, &parsed, out);
}

void cli_args_free(cli_args *args)
{
    free(args->values);
    free(args->positionals);
    args->values = NULL;
    args->positionals = NULL;
    args->num_positionals = 0;
}

const char *cli_arg(const cli_args *args, const char *name)
{
    for (size_t i = 0; i < args->num_options; i++)
        if (strcmp(args->options[i].name, name) == 0) return args->values[i];
    return NULL;
}

bool cli_flag(const cli_args *args, const char *name)
{
    return cli_arg(args, name) != NULL;
}

void cli_print_command_help(const cli_command *cmd, FILE *out)
{
    fprintf(out, "usage: meshtopo %s %s\n\n%s\n", cmd->name, cmd->synopsis, cmd->summary);
    if (cmd->description && cmd->description[0]) fprintf(out, "\n%s", cmd->description);
    if (cmd->num_options == 0) return;
    fprintf(out, "\noptions:\n");
    mt__args_print_options(cmd->options, cmd->num_options, out);
}
