/* Sample messages of every meshtopo LCM type, filled with non-trivial values
 * (several per type so that together they set every field), and generic
 * field-by-field comparison through lcm-gen's typeinfo. Shared by the C
 * round-trip tests and the sample writer of the Java round-trip test. */
#ifndef MESHTOPO_TEST_MSGS_SAMPLES_H
#define MESHTOPO_TEST_MSGS_SAMPLES_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/msgs.h"

typedef struct mt_msgs_sample {
    const char *name; /* "reply_ring"; unique */
    const mt_msgs_type *type;
    /* Fills a zeroed message of `type`. Its arrays and strings point at
     * static data: there is nothing to free. */
    void (*fill)(void *msg);
} mt_msgs_sample;

extern const mt_msgs_sample mt_msgs_samples[];
extern const size_t mt_msgs_num_samples;

/* Encodes a filled message into a malloc'd buffer of exactly its encoded
 * size; NULL when encoding fails. */
uint8_t *mt_msgs_encode_alloc(const mt_msgs_type *type, const void *msg, size_t *out_size);

/* Compares two messages of `type` field by field, nested types and every
 * array element included (doubles by their bits). Returns 1 when equal;
 * otherwise 0 with the first difference ("mesh_t.positions[4]") in where. */
int mt_msgs_equal(const mt_msgs_type *type, const void *a, const void *b, char *where,
                  size_t where_size);

/* Whether field `field` (0 .. type->num_fields() - 1) of a message is set: a
 * scalar other than 0, a non-empty string or array. *out_name gets the
 * field's name. */
int mt_msgs_field_is_set(const mt_msgs_type *type, const void *msg, int field,
                         const char **out_name);

#endif
