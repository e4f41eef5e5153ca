/* meshtopo::args: command lines read against a table of options, as the
 * CLI, meshtopod and meshtopo-bench read theirs; each refused kind of
 * command line names its error and the argument at fault. */
#include <string.h>

#include "harness.h"
#include "meshtopo/args.h"

static const mt__option options[] = {
    {"json", NULL, "print JSON"},
    {"faces", "N", "triangles"},
};
#define NUM_OPTIONS (sizeof options / sizeof options[0])

/* Parses the words of `line` (space-separated, at most 16). */
static mt__args_error parse(const char *line, size_t min_pos, size_t max_pos, mt__args *out)
{
    static char buf[256];
    static char *argv[16];
    int argc = 0;
    snprintf(buf, sizeof buf, "%s", line);
    for (char *w = strtok(buf, " "); w && argc < 16; w = strtok(NULL, " ")) argv[argc++] = w;
    return mt__args_parse(options, NUM_OPTIONS, min_pos, max_pos, argc, argv, out);
}

static void test_values_flags_and_positionals(void)
{
    mt__args a;
    CHECK_EQ(parse("in.off --faces 12 out --json", 1, 2, &a), MT__ARGS_OK);
    CHECK(strcmp(mt__args_value(&a, "faces"), "12") == 0);
    CHECK(mt__args_flag(&a, "json"));
    CHECK_EQ(a.num_positionals, 2);
    CHECK(strcmp(a.positionals[0], "in.off") == 0 && strcmp(a.positionals[1], "out") == 0);
    CHECK(!a.help);
    mt__args_free(&a);

    /* --name=VALUE, the last one wins, "-" is a positional, "--" ends options. */
    CHECK_EQ(parse("--faces=3 --faces=4 - -- --json", 0, 2, &a), MT__ARGS_OK);
    CHECK(strcmp(mt__args_value(&a, "faces"), "4") == 0);
    CHECK(!mt__args_flag(&a, "json"));
    CHECK_EQ(a.num_positionals, 2);
    CHECK(strcmp(a.positionals[0], "-") == 0 && strcmp(a.positionals[1], "--json") == 0);
    mt__args_free(&a);

    /* A flag given alone is "". */
    CHECK_EQ(parse("--json", 0, 0, &a), MT__ARGS_OK);
    CHECK(strcmp(mt__args_value(&a, "json"), "") == 0);
    mt__args_free(&a);
}

static void test_help_stops_reading(void)
{
    mt__args a;
    CHECK_EQ(parse("--json -h --bogus", 1, 1, &a), MT__ARGS_OK);
    CHECK(a.help);
    mt__args_free(&a);
    CHECK_EQ(parse("--help", 1, 1, &a), MT__ARGS_OK);
    CHECK(a.help);
    mt__args_free(&a);
}

static void test_refusals_name_the_argument(void)
{
    mt__args a;
    CHECK_EQ(parse("--bogus=1", 0, 1, &a), MT__ARGS_UNKNOWN_OPTION);
    CHECK(strcmp(a.at, "--bogus") == 0);
    mt__args_free(&a);
    CHECK_EQ(parse("-x", 0, 1, &a), MT__ARGS_UNKNOWN_OPTION);
    CHECK(strcmp(a.at, "-x") == 0);
    mt__args_free(&a);
    CHECK_EQ(parse("--faces", 0, 1, &a), MT__ARGS_MISSING_VALUE);
    CHECK(a.option == &options[1]);
    mt__args_free(&a);
    CHECK_EQ(parse("--json=yes", 0, 1, &a), MT__ARGS_UNEXPECTED_VALUE);
    CHECK(a.option == &options[0]);
    CHECK(strcmp(a.at, "--json") == 0);
    mt__args_free(&a);
    CHECK_EQ(parse("--json", 1, 1, &a), MT__ARGS_TOO_FEW_ARGUMENTS);
    mt__args_free(&a);
    CHECK_EQ(parse("a b c", 0, 1, &a), MT__ARGS_TOO_MANY_ARGUMENTS);
    CHECK(strcmp(a.at, "b") == 0);
    mt__args_free(&a);

    /* An argument longer than the record is cut, never overrun. */
    char longer[200];
    memset(longer, 'y', sizeof longer - 1);
    longer[0] = '-';
    longer[1] = '-';
    longer[sizeof longer - 1] = '\0';
    char *argv[] = {longer};
    CHECK_EQ(mt__args_parse(options, NUM_OPTIONS, 0, 0, 1, argv, &a), MT__ARGS_UNKNOWN_OPTION);
    CHECK_EQ(strlen(a.at), sizeof a.at - 1);
    mt__args_free(&a);
}

static void test_no_arguments_and_no_options(void)
{
    mt__args a;
    CHECK_EQ(mt__args_parse(NULL, 0, 0, 0, 0, NULL, &a), MT__ARGS_OK);
    CHECK_EQ(a.num_positionals, 0);
    CHECK(mt__args_value(&a, "json") == NULL);
    mt__args_free(&a);
    char *argv[] = {"--json"};
    CHECK_EQ(mt__args_parse(NULL, 0, 0, 0, 1, argv, &a), MT__ARGS_UNKNOWN_OPTION);
    mt__args_free(&a);
}

static const mt_test_case cases[] = {
    {"values_flags_and_positionals", test_values_flags_and_positionals},
    {"help_stops_reading", test_help_stops_reading},
    {"refusals_name_the_argument", test_refusals_name_the_argument},
    {"no_arguments_and_no_options", test_no_arguments_and_no_options},
};
const mt_test_table mt_tests_args = {cases, sizeof cases / sizeof cases[0]};
