/* What every file-reader fuzz target checks: any input gives MT_OK with a
 * consistent face list, or an error with a message and a zeroed list; never
 * a crash, a leak or a read out of bounds. */
#ifndef MESHTOPO_FUZZ_READER_H
#define MESHTOPO_FUZZ_READER_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "meshtopo/io.h"

static inline int mt_fuzz_reader(const uint8_t *data, size_t size, mt_format format,
                                 const char *name)
{
    mt_face_list list;
    mt_diag diag;
    mt_status status = mt_read_memory(data, size, format, name, &list, &diag);
    if (status == MT_OK) {
        if (mt_face_list_check(&list, NULL) != MT_OK) __builtin_trap();
        if (list.num_verts && !list.positions) __builtin_trap();
    } else {
        if (list.num_verts || list.num_faces || list.num_indices || list.positions ||
            list.face_sizes || list.face_indices || diag.message[0] == '\0' ||
            memchr(diag.message, '\0', sizeof diag.message) == NULL)
            __builtin_trap();
    }
    mt_face_list_free(&list);
    return 0;
}

#endif
