/* Files of earlier archive formats made from files this meshtopo wrote: the
 * format_version attribute lowered, below format 8 the per-kind arrays
 * (/VTKHDF/.../defect_<key>) removed and, below format 7, the defects
 * dataset rewritten in the {kind, a, b, c} rows those formats stored. The other
 * differences between formats (no half-edge arrays, no digest) are for each
 * test to make. */
#ifndef MESHTOPO_TESTS_ARCHIVE_LEGACY_H
#define MESHTOPO_TESTS_ARCHIVE_LEGACY_H

#include <stdbool.h>
#include <stdint.h>

/* Sets /meshtopo's format_version to `version` and gives /VTKHDF's arrays
 * and /meshtopo/report/defects that version's layout. false on failure. */
bool al_set_format(const char *path, int64_t version);

/* The HDF5 compound of a defect record as format 7 writes it (close with
 * H5Tclose; an hid_t, as int64_t). */
int64_t al_record_type(void);

/* Replaces /meshtopo/report/defects by `count` defect records (format 7's
 * layout, no description attribute). */
bool al_write_records(const char *path, const void *records, uint64_t count);

/* Replaces /meshtopo/report/defects by `count` rows {kind, a, b, c} in the
 * layout of formats 1 to 6 (kind the enum of the defect keys). */
bool al_write_compact_defects(const char *path, const uint32_t (*rows)[4], uint64_t count);

#endif
