/* The benchmark subcommands' command lines: read against each one's table
 * of options (meshtopo::args), refusals printed as meshtopo-bench words
 * them, and counts checked against their bounds. */
#include <errno.h>
#include <inttypes.h>
#include <stdlib.h>

#include "bench.h"

bool mt__bench_parse_u64(const char *text, uint64_t min, uint64_t max, uint64_t *out)
{
    if (!text) return false;
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 10);
    if (errno || end == text || *end || text[0] == '-' || v < min || v > max) return false;
    *out = v;
    return true;
}

bool mt__bench_parse_u32(const char *text, uint32_t min, uint32_t max, uint32_t *out)
{
    uint64_t v;
    if (!mt__bench_parse_u64(text, min, max, &v)) return false;
    *out = (uint32_t)v;
    return true;
}

int mt__bench_args_read(const char *program, const mt__option *options, size_t num_options,
                        int argc, char **argv, mt__args *out)
{
    mt__args_error error = mt__args_parse(options, num_options, 0, 0, argc, argv, out);
    switch (error) {
        case MT__ARGS_OK:
            return out->help ? 1 : 0;
        case MT__ARGS_UNKNOWN_OPTION:
            fprintf(stderr, "%s: unknown option %s\n", program, out->at);
            break;
        case MT__ARGS_MISSING_VALUE:
            fprintf(stderr, "%s: --%s needs a value (%s)\n", program, out->option->name,
                    out->option->value_name);
            break;
        case MT__ARGS_UNEXPECTED_VALUE:
            fprintf(stderr, "%s: --%s takes no value\n", program, out->option->name);
            break;
        case MT__ARGS_TOO_MANY_ARGUMENTS:
            fprintf(stderr, "%s: unexpected argument: %s\n", program, out->at);
            break;
        default:
            fprintf(stderr, "%s: cannot read the command line\n", program);
            break;
    }
    mt__args_free(out);
    return 2;
}

bool mt__bench_arg_u64(const mt__args *args, const char *program, const char *name, uint64_t min,
                       uint64_t max, uint64_t *out, bool *given)
{
    const char *text = mt__args_value(args, name);
    if (given) *given = text != NULL;
    if (!text || mt__bench_parse_u64(text, min, max, out)) return true;
    fprintf(stderr, "%s: --%s: bad value '%s' (a whole number from %" PRIu64 " to %" PRIu64 ")\n",
            program, name, text, min, max);
    return false;
}

bool mt__bench_arg_u32(const mt__args *args, const char *program, const char *name, uint32_t min,
                       uint32_t max, uint32_t *out, bool *given)
{
    uint64_t v = *out;
    if (!mt__bench_arg_u64(args, program, name, min, max, &v, given)) return false;
    *out = (uint32_t)v;
    return true;
}

int mt__bench_usage_exit(int parsed, void (*usage)(FILE *out))
{
    usage(parsed == 1 ? stdout : stderr);
    return parsed == 1 ? 0 : 2;
}
