/* The keys a corpus reference file (NAME.expected.json) may hold, shared by
 * the tests that read those files: any other key fails them, so a new
 * reference quantity cannot go unchecked. */
#ifndef MESHTOPO_TEST_CORPUS_KEYS_H
#define MESHTOPO_TEST_CORPUS_KEYS_H

#include <stddef.h>

extern const char *const mt_test_corpus_keys[];
extern const size_t mt_test_num_corpus_keys;

#endif
