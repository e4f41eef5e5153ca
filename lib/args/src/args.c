/* Reading a command line against a table of options (see meshtopo/args.h).
 * By hand rather than getopt_long: getopt keeps global state between calls
 * (tests parse many command lines in one process), permutes argv, and
 * prints its own messages, while each meshtopo program words its own. */
#include "meshtopo/args.h"

#include <stdlib.h>
#include <string.h>

static const mt__option *option_find(const mt__option *options, size_t num_options,
                                     const char *name, size_t name_len, size_t *out_index)
{
    for (size_t i = 0; i < num_options; i++) {
        if (strlen(options[i].name) == name_len && strncmp(options[i].name, name, name_len) == 0) {
            *out_index = i;
            return &options[i];
        }
    }
    return NULL;
}

static mt__args_error refuse(mt__args *out, mt__args_error error, const mt__option *option,
                             const char *at, size_t at_len)
{
    out->error = error;
    out->option = option;
    if (at_len >= sizeof out->at) at_len = sizeof out->at - 1;
    memcpy(out->at, at, at_len);
    out->at[at_len] = '\0';
    return error;
}

mt__args_error mt__args_parse(const mt__option *options, size_t num_options, size_t min_positionals,
                              size_t max_positionals, int argc, char **argv, mt__args *out)
{
    memset(out, 0, sizeof *out);
    out->options = options;
    out->num_options = num_options;
    /* calloc(0) may return NULL; ask for at least one element. */
    out->values = calloc(num_options + 1, sizeof *out->values);
    out->positionals = calloc((size_t)(argc > 0 ? argc : 0) + 1, sizeof *out->positionals);
    if (!out->values || !out->positionals) return refuse(out, MT__ARGS_NO_MEMORY, NULL, "", 0);
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
            out->help = true;
            return MT__ARGS_OK;
        }
        if (arg[1] != '-') return refuse(out, MT__ARGS_UNKNOWN_OPTION, NULL, arg, strlen(arg));
        const char *name = arg + 2;
        const char *eq = strchr(name, '=');
        size_t name_len = eq ? (size_t)(eq - name) : strlen(name);
        size_t index = 0;
        const mt__option *opt = option_find(options, num_options, name, name_len, &index);
        if (!opt) return refuse(out, MT__ARGS_UNKNOWN_OPTION, NULL, arg, name_len + 2);
        if (!opt->value_name) {
            if (eq) return refuse(out, MT__ARGS_UNEXPECTED_VALUE, opt, arg, name_len + 2);
            out->values[index] = "";
        } else if (eq) {
            out->values[index] = eq + 1;
        } else if (i + 1 < argc) {
            out->values[index] = argv[++i];
        } else {
            return refuse(out, MT__ARGS_MISSING_VALUE, opt, arg, strlen(arg));
        }
    }
    if (out->num_positionals < min_positionals)
        return refuse(out, MT__ARGS_TOO_FEW_ARGUMENTS, NULL, "", 0);
    if (out->num_positionals > max_positionals) {
        const char *extra = out->positionals[max_positionals];
        return refuse(out, MT__ARGS_TOO_MANY_ARGUMENTS, NULL, extra, strlen(extra));
    }
    return MT__ARGS_OK;
}

void mt__args_free(mt__args *args)
{
    free(args->values);
    free(args->positionals);
    args->values = NULL;
    args->positionals = NULL;
    args->num_positionals = 0;
}

const char *mt__args_value(const mt__args *args, const char *name)
{
    for (size_t i = 0; i < args->num_options; i++)
        if (strcmp(args->options[i].name, name) == 0) return args->values[i];
    return NULL;
}

bool mt__args_flag(const mt__args *args, const char *name)
{
    return mt__args_value(args, name) != NULL;
}

void mt__args_print_options(const mt__option *options, size_t num_options, FILE *out)
{
    for (size_t i = 0; i < num_options; i++) {
        const mt__option *o = &options[i];
        char left[64];
        snprintf(left, sizeof left, "--%s%s%s", o->name, o->value_name ? " " : "",
                 o->value_name ? o->value_name : "");
        fprintf(out, "  %-22s %s\n", left, o->help);
    }
    fprintf(out, "  %-22s %s\n", "-h, --help", "show this help");
}
