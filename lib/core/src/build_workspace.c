/* Build workspaces: the scratch arrays a build would otherwise allocate and
 * free (its sides, their half-edges, the vertex counts and fan starts, the
 * matching buffers), kept between builds so that a program building mesh
 * after mesh does not pay for fresh pages each time. A workspace only
 * grows: an array is replaced when a build needs a larger one. */
#include <stdlib.h>
#include <string.h>

#include "build_internal.h"

mt_build_workspace *mt_build_workspace_create(void)
{
    return mt__calloc(1, sizeof(mt_build_workspace));
}

void mt_build_workspace_destroy(mt_build_workspace *workspace)
{
    if (!workspace) return;
    for (int k = 0; k < MT__SCRATCH_KINDS; k++) mt__free(workspace->array[k]);
    mt__free(workspace);
}

size_t mt_build_workspace_bytes(const mt_build_workspace *workspace)
{
    if (!workspace) return 0;
    size_t total = sizeof *workspace;
    for (int k = 0; k < MT__SCRATCH_KINDS; k++) total += workspace->bytes[k];
    return total;
}

void *mt__scratch_get(mt__build *b, mt__scratch which, size_t count, size_t size, int zero)
{
    size_t bytes;
    if (!mt__mul_size(count, size, &bytes)) return NULL;
    mt_build_workspace *w = b->workspace;
    void *array;
    if (!w) {
        array = mt__malloc(bytes);
    } else if (w->array[which] && w->bytes[which] >= bytes) {
        array = w->array[which];
    } else {
        mt__free(w->array[which]);
        w->bytes[which] = 0;
        w->array[which] = array = mt__malloc(bytes);
        if (array) w->bytes[which] = bytes;
    }
    if (array && zero) memset(array, 0, bytes);
    return array;
}

void mt__scratch_put(mt__build *b, void *array)
{
    if (!b->workspace) mt__free(array);
}
