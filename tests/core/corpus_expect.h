/* Comparing a topology report with a corpus reference file
 * (NAME.expected.json, tests/corpus/DEFINITIONS.md), shared by the tests
 * that check the corpus: test_core's corpus tests (the library itself) and
 * daemon.corpus.* (meshtopod's answers over LCM, turned back into an
 * mt_report). Every mismatch is recorded with mt_test_fail, naming the mesh
 * and the key path, and the checks go on. */
#ifndef MESHTOPO_TEST_CORPUS_EXPECT_H
#define MESHTOPO_TEST_CORPUS_EXPECT_H

#include <cJSON.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/report.h"

/* Records a failure "NAME: KEY: message". */
void mt_test_corpus_fail(const char *name, const char *key, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Reads NAME.expected.json from mt_test_corpus_dir(), checks that it holds
 * exactly the keys of corpus_keys.h and that "file" names NAME.<extension>,
 * and writes the mesh file's path into mesh_path. Returns the parsed file
 * (free with cJSON_Delete), or NULL after recording why. */
cJSON *mt_test_corpus_load(const char *name, char *mesh_path, size_t mesh_path_size);

/* Compares every report-level key of the file (counts, histograms, boundary
 * loops, defect counts and the non-manifold vertex head from the defect
 * list, flags, genus, component genera, the per-component figures) with r. */
void mt_test_corpus_check_report(const char *name, const mt_report *r, const cJSON *expected);

/* An integral JSON number. */
bool mt_test_json_int(const cJSON *item, long long *out);

/* An array of ids in the file against ids computed by the test, in order. */
void mt_test_expect_ids(const char *name, const char *key, const cJSON *item, const uint32_t *ids,
                        size_t count);

/* Sorts ids and removes repeats and `skip` (MT_NONE for none); returns the count. */
size_t mt_test_sort_unique(uint32_t *ids, size_t count, uint32_t skip);

/* qsort comparison of uint32_t. */
int mt_test_compare_u32(const void *a, const void *b);

#endif
