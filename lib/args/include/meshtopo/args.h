/* Command-line arguments read against a table of options, for meshtopo's
 * programs (the CLI's subcommands, meshtopod, meshtopo-bench): `--name` (a
 * flag), `--name VALUE` or `--name=VALUE`, `-h`/`--help`, `--` ending the
 * options, positionals anywhere ("-" alone is a positional). Nothing here
 * prints or exits: a refused command line comes back as an error kind and
 * the argument at fault, and each program words the message its users know.
 * Private to meshtopo (not installed). */
#ifndef MESHTOPO_ARGS_H
#define MESHTOPO_ARGS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* One option: `--name` (value_name NULL) or `--name VALUE`. */
typedef struct mt__option {
    const char *name;       /* without the dashes: "vertices" */
    const char *value_name; /* NULL for a flag, else shown in help: "LIST" */
    const char *help;       /* one line */
} mt__option;

typedef enum mt__args_error {
    MT__ARGS_OK = 0,
    MT__ARGS_UNKNOWN_OPTION,     /* at: the argument ("-x"; "--name" without "=VALUE") */
    MT__ARGS_MISSING_VALUE,      /* option: the option whose value is missing */
    MT__ARGS_UNEXPECTED_VALUE,   /* option: a flag given --name=VALUE */
    MT__ARGS_TOO_FEW_ARGUMENTS,  /* fewer positionals than the command needs */
    MT__ARGS_TOO_MANY_ARGUMENTS, /* at: the first positional past the last one allowed */
    MT__ARGS_NO_MEMORY
} mt__args_error;

/* A command line read against options[]: values[i] is the value of
 * options[i] ("" for a flag given without a value), NULL when absent; the
 * last one given wins. */
typedef struct mt__args {
    const mt__option *options;
    size_t num_options;
    const char **values; /* [num_options] */
    char **positionals;  /* the non-option arguments, in order */
    size_t num_positionals;
    bool help;                /* -h or --help was given: reading stopped there */
    mt__args_error error;     /* why the command line was refused */
    const mt__option *option; /* the option at fault (missing or unexpected value) */
    char at[128];             /* the argument at fault, as given (cut to fit) */
} mt__args;

/* Reads argv[0..argc) (the arguments only, no program name) into *out. With
 * -h/--help the rest is not read and the positional counts are not checked.
 * Returns out->error; out's arrays are malloc'ed, free with mt__args_free
 * (also after an error). */
mt__args_error mt__args_parse(const mt__option *options, size_t num_options, size_t min_positionals,
                              size_t max_positionals, int argc, char **argv, mt__args *out);
void mt__args_free(mt__args *args);

/* The value of the option named `name`: NULL when absent, "" for a given flag. */
const char *mt__args_value(const mt__args *args, const char *name);
bool mt__args_flag(const mt__args *args, const char *name);

/* One line an option, "  --name VALUE           help", then the -h line. */
void mt__args_print_options(const mt__option *options, size_t num_options, FILE *out);

#endif
