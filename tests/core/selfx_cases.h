/* Hand-made and generated meshes for the self-intersection oracle
 * (selfx_oracle.c): each case is a face list and, where the answer is
 * known by construction, how many pairs, undecided pairs, non-simple faces
 * and self-crossing boundary loops it must give (-1: not stated). */
#ifndef MESHTOPO_TESTS_SELFX_CASES_H
#define MESHTOPO_TESTS_SELFX_CASES_H

#include <stddef.h>

#include "meshtopo/face_list.h"

typedef struct sx_case {
    char name[48];
    mt_face_list list; /* owned: mt_face_list_free */
    long pairs, undecided, nonsimple, loops;
} sx_case;

/* Fills out[0 .. n) with the cases and returns n (at most capacity);
 * 0 when out of memory. */
size_t sx_make_cases(sx_case *out, size_t capacity);

#endif
