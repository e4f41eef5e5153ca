/* Command-line parsing shared by every subcommand: `--name`, `--name VALUE`,
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

static const cli_option *option_find(const cli_command *cmd, const char *name, size_t name_len,
                                     size_t *out_index)
{
    for (size_t i = 0; i < cmd->num_options; i++) {
        const char *o = cmd->options[i].name;
        if (strlen(o) == name_len && strncmp(o, name, name_len) == 0) {
            *out_index = i;
            return &cmd->options[i];
        }
    }
    return NULL;
}

int cli_args_parse(const cli_command *cmd, int argc, char **argv, cli_args *out, bool *out_help)
{
    memset(out, 0, sizeof *out);
    *out_help = false;
    out->command = cmd->name;
    out->options = cmd->options;
    out->num_options = cmd->num_options;
    /* calloc(0) may return NULL; ask for at least one element. */
    out->values = calloc(cmd->num_options + 1, sizeof *out->values);
    out->positionals = calloc((size_t)argc + 1, sizeof *out->positionals);
    if (!out->values || !out->positionals) {
        cli_error(cmd->name, "out of memory");
        cli_args_free(out);
        return CLI_EXIT_USAGE;
    }
    bool options_done = false;
    for (int i = 0; i < argc; i++) {
        char *arg = argv[i];
        if (options_done || arg[0] != '-' || arg[1] == '\0') {
            out->positionals[out->num_positionals++] = arg;
            continue;
        }
        if (strcmp(arg, "--") == 0) {
            options_done = true;
            continue;
        }
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            *out_help = true;
            continue;
        }
        if (arg[1] != '-') {
            cli_error(cmd->name, "unknown option '%s'", arg);
            cli_args_free(out);
            return CLI_EXIT_USAGE;
        }
        const char *name = arg + 2;
        const char *eq = strchr(name, '=');
        size_t name_len = eq ? (size_t)(eq - name) : strlen(name);
        size_t index = 0;
        const cli_option *opt = option_find(cmd, name, name_len, &index);
        if (!opt) {
            cli_error(cmd->name, "unknown option '--%.*s'", (int)name_len, name);
            cli_args_free(out);
            return CLI_EXIT_USAGE;
        }
        if (!opt->value_name) {
            if (eq) {
                cli_error(cmd->name, "option '--%s' takes no value", opt->name);
                cli_args_free(out);
                return CLI_EXIT_USAGE;
            }
            out->values[index] = "";
        } else if (eq) {
            out->values[index] = eq + 1;
        } else if (i + 1 < argc) {
            out->values[index] = argv[++i];
        } else {
            cli_error(cmd->name, "option '--%s' needs a value (%s)", opt->name, opt->value_name);
            cli_args_free(out);
            return CLI_EXIT_USAGE;
        }
    }
    if (*out_help) return CLI_EXIT_OK;
    if (out->num_positionals < cmd->min_positionals) {
        cli_error(cmd->name, "missing argument");
        cli_args_free(out);
        return CLI_EXIT_USAGE;
    }
    if (out->num_positionals > cmd->max_positionals) {
        cli_error(cmd->name, "unexpected argument '%s'", out->positionals[cmd->max_positionals]);
        cli_args_free(out);
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
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
    for (size_t i = 0; i < cmd->num_options; i++) {
        const cli_option *o = &cmd->options[i];
        char left[64];
        snprintf(left, sizeof left, "--%s%s%s", o->name, o->value_name ? " " : "",
                 o->value_name ? o->value_name : "");
        fprintf(out, "  %-22s %s\n", left, o->help);
    }
    fprintf(out, "  %-22s %s\n", "-h, --help", "show this help");
}
