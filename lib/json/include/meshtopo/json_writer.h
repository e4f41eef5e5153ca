/* A small streaming JSON writer for meshtopo's machine-readable output (the
 * CLI's, and the reports the Python binding reads). We take no dependency
 * for writing JSON: strings are escaped per RFC 8259
 * (invalid UTF-8 becomes U+FFFD) and the layout is Python's
 * json.dumps(indent=1), so outputs diff cleanly against the corpus answers.
 * Misuse (a value where a key is due, too deep nesting) sets `error`. */
#ifndef MESHTOPO_JSON_WRITER_H
#define MESHTOPO_JSON_WRITER_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MT_JSON_MAX_DEPTH 32

typedef struct mt_json {
    FILE *out;
    int depth;                         /* open containers */
    bool is_object[MT_JSON_MAX_DEPTH]; /* per open container */
    bool has_items[MT_JSON_MAX_DEPTH]; /* something written in it yet */
    bool key_pending;                  /* a key was written, its value is due */
    bool error;                        /* misuse detected; output is incomplete */
    bool compact; /* set after init: no newlines or indentation (one line per document) */
} mt_json;

void mt_json_init(mt_json *j, FILE *out);

void mt_json_object_begin(mt_json *j);
void mt_json_object_end(mt_json *j);
void mt_json_array_begin(mt_json *j);
void mt_json_array_end(mt_json *j);

/* The key of the next member (inside an object only). */
void mt_json_key(mt_json *j, const char *key);

void mt_json_int(mt_json *j, int64_t value);
void mt_json_uint(mt_json *j, uint64_t value);
/* A number with the digits to read back the same double; NaN and infinities
 * are written as null. */
void mt_json_double(mt_json *j, double value);
void mt_json_bool(mt_json *j, bool value);
void mt_json_null(mt_json *j);
void mt_json_string(mt_json *j, const char *value);

/* Writes `text` as an escaped JSON string literal (quotes included). */
void mt_json_write_escaped(FILE *out, const char *text);

/* Ends the document with a newline; false if anything was misused. */
bool mt_json_finish(mt_json *j);

#ifdef __cplusplus
}
#endif

#endif
