/* The test harness: each test executable holds a table of named tests and
 * runs the one named on its command line (ctest registers one entry per
 * name), or all of them. Checks print file:line and both values, and let the
 * test go on so one run shows every failure. */
#ifndef MESHTOPO_TEST_HARNESS_H
#define MESHTOPO_TEST_HARNESS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef struct mt_test_case {
    const char *name;
    void (*run)(void);
} mt_test_case;

/* Each test file exports one table:
 *     static const mt_test_case cases[] = {{"name", function}, ...};
 *     const mt_test_table mt_tests_FILE = {cases, sizeof cases / sizeof cases[0]};
 * CMake finds the tables and the rows, generates the suite's main() and
 * registers one ctest entry per row. */
typedef struct mt_test_table {
    const mt_test_case *cases;
    size_t count;
} mt_test_table;

/* Runs the test named by argv[1] (all tests without an argument; `--list`
 * prints the names). Returns the process exit status. */
int mt_test_main(int argc, char **argv, const mt_test_table *const *tables, size_t num_tables);

/* Records a failure; used by the CHECK macros. */
void mt_test_fail(const char *file, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Marks the running test skipped, printing why (for example a corpus mesh
 * that is not there). A test that skips returns at once; failures it
 * recorded before still count. A run whose tests all skipped exits 77,
 * which ctest counts as skipped. */
void mt_test_skip(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Number of failures recorded so far in this test. */
int mt_test_failures(void);

/* Directory of the build's corpus: tests/corpus and the meshes
 * MESHTOPO_EXTRA_CORPUS added when the build tree was configured
 * (cmake/MeshtopoCorpus.cmake). */
const char *mt_test_corpus_dir(void);

/* Resident memory of this process in kB, from /proc/self/status; -1 when
 * it cannot be read. */
long mt_test_rss_kb(void);

#define CHECK(cond)                                                               \
    do {                                                                          \
        if (!(cond)) mt_test_fail(__FILE__, __LINE__, "CHECK(%s) failed", #cond); \
    } while (0)

#define CHECK_EQ(a, b)                                                                       \
    do {                                                                                     \
        long long mt__a = (long long)(a), mt__b = (long long)(b);                            \
        if (mt__a != mt__b)                                                                  \
            mt_test_fail(__FILE__, __LINE__, "%s == %s failed: %lld != %lld", #a, #b, mt__a, \
                         mt__b);                                                             \
    } while (0)

/* Checks that a call returned `expected` (an mt_status). */
#define CHECK_STATUS(expr, expected)                                                           \
    do {                                                                                       \
        int mt__s = (int)(expr);                                                               \
        if (mt__s != (int)(expected))                                                          \
            mt_test_fail(__FILE__, __LINE__, "%s returned %d (%s), expected %s", #expr, mt__s, \
                         mt_strerror((mt_status)mt__s), #expected);                            \
    } while (0)

#define CHECK_OK(expr) CHECK_STATUS(expr, MT_OK)

#endif
