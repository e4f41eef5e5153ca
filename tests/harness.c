/* Test harness implementation: test selection by name and failure records. */
#include "harness.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

static int failures;
static int skipped; /* the running test called mt_test_skip */

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

void mt_test_skip(const char *fmt, ...)
{
    va_list args;
    printf("skipped: ");
    va_start(args, fmt);
    vprintf(fmt, args);
    va_end(args);
    putchar('\n');
    skipped = 1;
}

int mt_test_failures(void)
{
    return failures;
}

const char *mt_test_corpus_dir(void)
{
    return MESHTOPO_CORPUS_DIR;
}

/* Runs one test: 1 when it failed, 0 when it passed, -1 when it skipped
 * without a failure. */
static int run_one(const mt_test_case *c)
{
    int before = failures;
    skipped = 0;
    c->run();
    int failed = failures - before;
    printf("%s %s\n", failed ? "FAIL" : skipped ? "skip" : "ok  ", c->name);
    return failed ? 1 : skipped ? -1 : 0;
}

int mt_test_main(int argc, char **argv, const mt_test_table *const *tables, size_t num_tables)
{
    int list = argc > 1 && strcmp(argv[1], "--list") == 0;
    size_t passed = 0, failed = 0, skips = 0;
    for (size_t t = 0; t < num_tables; t++) {
        for (size_t i = 0; i < tables[t]->count; i++) {
            const mt_test_case *c = &tables[t]->cases[i];
            if (list) {
                printf("%s\n", c->name);
                continue;
            }
            if (argc > 1 && strcmp(argv[1], c->name) != 0) continue;
            int result = run_one(c);
            if (result > 0)
                failed++;
            else if (result < 0)
                skips++;
            else
                passed++;
        }
    }
    if (list) return 0;
    if (passed + failed + skips == 0) {
        fprintf(stderr, "no test named '%s'\n", argc > 1 ? argv[1] : "");
        return 2;
    }
    printf("%zu passed, %zu failed, %zu skipped\n", passed, failed, skips);
    if (failed) return 1;
    /* 77: ctest's SKIP_RETURN_CODE, when every test that ran skipped. */
    return passed == 0 ? 77 : 0;
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
