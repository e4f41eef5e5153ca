/* The low level every family of the core stands on: allocation (with the
 * tests' fail-after-N hook in test builds only), growable arrays,
 * overflow-checked sizes, diagnostics and running work on several threads.
 * Knows nothing of meshes. */
#ifndef MESHTOPO_BASE_H
#define MESHTOPO_BASE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

/* Fills diag (if any) with status, element and a printf-style message, and
 * returns status, so that failures read `return mt__fail(diag, ...)`. */
mt_status mt__fail(mt_diag *diag, mt_status status, uint32_t element, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* The most threads any part of the library runs at once. */
enum { MT__MAX_THREADS = 8 };

/* Part `part` of `parts` of a piece of work (parallel.c). */
typedef void (*mt__part_fn)(void *ctx, uint32_t part, uint32_t parts);

/* Runs fn for every part in [0, parts) (at most MT__MAX_THREADS), part 0 on
 * the calling thread and each other on a thread of its own, and returns
 * once all are done. A thread that cannot be started leaves its part to
 * the calling thread. */
void mt__in_parallel(uint32_t parts, mt__part_fn fn, void *ctx);

/* [*first, *end): part `part` of `parts` equal shares of n items. */
void mt__part_range(uint32_t n, uint32_t part, uint32_t parts, uint32_t *first, uint32_t *end);

/* Allocation (alloc.c): the plain malloc family. Sizes of 0 allocate 1 byte
 * so NULL always means failure. */
void *mt__malloc(size_t bytes);
void *mt__calloc(size_t count, size_t size);
void *mt__realloc(void *ptr, size_t bytes);
void mt__free(void *ptr);
#ifdef MT_TEST_HOOKS
/* Makes the allocation after `count` more fail (-1 = never). Only in the
 * test build of the core (meshtopo_core_testing), never in the library. */
void mt__test_fail_alloc_after(long count);
#endif

/* A growable array of fixed-size elements (geometric growth, so pushing n
 * elements costs O(log n) allocations). Zero-initialise with elem_size set. */
typedef struct mt__vec {
    void *data;
    size_t len, cap, elem_size;
} mt__vec;

mt_status mt__vec_push(mt__vec *vec, const void *elem);
void mt__vec_free(mt__vec *vec);

/* Appends src's elements to dst (same element size) and frees src. */
mt_status mt__vec_append(mt__vec *dst, mt__vec *src);

/* Overflow-checked size arithmetic: returns 0 and leaves *out alone on overflow. */
static inline int mt__mul_size(size_t a, size_t b, size_t *out)
{
    if (a != 0 && b > SIZE_MAX / a) return 0;
    *out = a * b;
    return 1;
}

#endif
