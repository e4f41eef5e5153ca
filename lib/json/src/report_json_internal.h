/* Helpers shared by meshtopo::json's writers: id lists as JSON arrays and
 * sorting ids into the sets DEFINITIONS.md compares. Internal (mt__). */
#ifndef MESHTOPO_REPORT_JSON_INTERNAL_H
#define MESHTOPO_REPORT_JSON_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/json_writer.h"

/* Writes ids[0 .. count) as one JSON array. */
void mt__json_write_ids(mt_json *j, const uint32_t *ids, size_t count);

/* Sorts ids ascending and drops repeats in place; returns the new count. */
size_t mt__json_sort_unique(uint32_t *ids, size_t count);

#endif
