/* Allocation for the core library: every allocation of the builder and the
 * edits goes through here. In the test build of the core (MT_TEST_HOOKS,
 * the meshtopo_core_testing objects tests/ link), tests can make the Nth
 * allocation fail and check that each failure path cleans up (the SQLite
 * fail-after-N technique); the library itself has no such hook.
 * Large arrays are not advised for transparent huge pages: where freed
 * memory goes back to a virtual machine's host, first touches of huge pages
 * cost far more than of 4 KiB ones (docs/performance/ has the measurements),
 * and a program that builds often keeps its memory in a build workspace,
 * where the page size made no difference. */
#include <stdlib.h>
#include <string.h>

#include "base/base.h"

#ifdef MT_TEST_HOOKS
/* Allocations left before one fails; negative means never. Test-only knob,
 * not thread safe by design (tests set it on a single thread). */
static long fail_countdown = -1;

void mt__test_fail_alloc_after(long count)
{
    fail_countdown = count;
}

static int should_fail(void)
{
    if (fail_countdown < 0) return 0;
    if (fail_countdown == 0) return 1;
    fail_countdown--;
    return 0;
}
#else
static inline int should_fail(void)
{
    return 0;
}
#endif

void *mt__malloc(size_t bytes)
{
    if (should_fail()) return NULL;
    return malloc(bytes ? bytes : 1);
}

void *mt__calloc(size_t count, size_t size)
{
    if (should_fail()) return NULL;
    if (count == 0 || size == 0) return calloc(1, 1);
    return calloc(count, size);
}

void *mt__realloc(void *ptr, size_t bytes)
{
    if (should_fail()) return NULL;
    return realloc(ptr, bytes ? bytes : 1);
}

void mt__free(void *ptr)
{
    free(ptr);
}

mt_status mt__vec_push(mt__vec *vec, const void *elem)
{
    if (vec->len == vec->cap) {
        size_t cap = vec->cap ? vec->cap * 2 : 16;
        size_t bytes;
        if (cap < vec->cap || !mt__mul_size(cap, vec->elem_size, &bytes)) return MT_ERR_NOMEM;
        void *data = mt__realloc(vec->data, bytes);
        if (!data) return MT_ERR_NOMEM;
        vec->data = data;
        vec->cap = cap;
    }
    memcpy((char *)vec->data + vec->len * vec->elem_size, elem, vec->elem_size);
    vec->len++;
    return MT_OK;
}

void mt__vec_free(mt__vec *vec)
{
    mt__free(vec->data);
    vec->data = NULL;
    vec->len = vec->cap = 0;
}

mt_status mt__vec_append(mt__vec *dst, mt__vec *src)
{
    if (dst->len == 0 && dst->elem_size == src->elem_size) {
        mt__vec_free(dst);
        *dst = *src;
        src->data = NULL;
        src->len = src->cap = 0;
        return MT_OK;
    }
    for (size_t i = 0; i < src->len; i++)
        if (mt__vec_push(dst, (char *)src->data + i * src->elem_size) != MT_OK) return MT_ERR_NOMEM;
    mt__vec_free(src);
    return MT_OK;
}
