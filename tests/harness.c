/* Test harness implementation: test selection by name and failure records. */
#include "harness.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

static int failures;

void mt_test_fail(const char *file, int line, const char *fmt, ...)
{
    va_list args;
    fprintf(stderr, "%s:%d: ", file, line);
    va_start(args, fmt);
    vfprintf(stderr, fmt, args);
    va_end(args);
    fputc('\n', stderr);
    failures++;
}

int mt_test_failures(void)
{
    return failures;
}

const char *mt_test_corpus_dir(void)
{
    const char *env = getenv("MESHTOPO_CORPUS");
    if (env && *env) return env;
    return MESHTOPO_DEFAULT_CORPUS;
}

static int run_one(const mt_test_case *c)
{
    int before = failures;
    c->run();
    int failed = failures - before;
    printf("%s %s\n", failed ? "FAIL" : "ok  ", c->name);
    return failed;
}

int mt_test_main(int argc, char **argv, const mt_test_table *const *tables, size_t num_tables)
{
    int list = argc > 1 && strcmp(argv[1], "--list") == 0;
    size_t passed = 0, failed = 0;
    for (size_t t = 0; t < num_tables; t++) {
        for (size_t i = 0; i < tables[t]->count; i++) {
            const mt_test_case *c = &tables[t]->cases[i];
            if (list) {
                printf("%s\n", c->name);
                continue;
            }
            if (argc > 1 && strcmp(argv[1], c->name) != 0) continue;
            if (run_one(c))
                failed++;
            else
                passed++;
        }
    }
    if (list) return 0;
    if (passed + failed == 0) {
        fprintf(stderr, "no test named '%s'\n", argc > 1 ? argv[1] : "");
        return 2;
    }
    printf("%zu passed, %zu failed\n", passed, failed);
    return failed ? 1 : 0;
}

long mt_test_rss_kb(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "VmRSS: %ld kB", &kb) == 1) break;
    if (f) fclose(f);
    return kb;
}
