/* Build workspaces: the scratch arrays a build would otherwise allocate and
 * free (its sides, their half-edges, the vertex counts and fan starts, the
 * matching buffers), kept between builds so that a program building mesh
 * after mesh does not pay for fresh pages each time. A workspace only
 * grows: an array is replaced when a build needs a larger one. It also
 * keeps the large arrays of meshes recycled into it, which the next build
 * takes for its own mesh. */
#include <stdlib.h>
#include <string.h>

#include "build/build_state.h"

mt_build_workspace *mt_build_workspace_create(void)
{
    return mt__calloc(1, sizeof(mt_build_workspace));
}

void mt_build_workspace_destroy(mt_build_workspace *workspace)
{
    if (!workspace) return;
    for (int k = 0; k < MT__SCRATCH_KINDS; k++) mt__free(workspace->array[k]);
    for (int k = 0; k < MT__KEPT_ARRAYS; k++) mt__free(workspace->kept[k]);
    mt__free(workspace);
}

size_t mt_build_workspace_bytes(const mt_build_workspace *workspace)
{
    if (!workspace) return 0;
    size_t total = sizeof *workspace;
    for (int k = 0; k < MT__SCRATCH_KINDS; k++) total += workspace->bytes[k];
    for (int k = 0; k < MT__KEPT_ARRAYS; k++) total += workspace->kept_bytes[k];
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

void *mt__kept_array_take(mt_build_workspace *w, size_t bytes)
{
    if (!w) return NULL;
    int best = -1;
    for (int k = 0; k < MT__KEPT_ARRAYS; k++) {
        size_t size = w->kept_bytes[k];
        if (!w->kept[k] || size < bytes || size / 2 > bytes) continue;
        if (best < 0 || size < w->kept_bytes[best]) best = k;
    }
    if (best < 0) return NULL;
    void *array = w->kept[best];
    w->kept[best] = NULL;
    w->kept_bytes[best] = 0;
    return array;
}

/* Keeps an array of `bytes` in a free slot, or in place of the smallest
 * kept array if that is smaller; otherwise frees it. NULL-safe. */
static void keep_array(mt_build_workspace *w, void *array, size_t bytes)
{
    if (!array) return;
    int slot = 0;
    for (int k = 1; k < MT__KEPT_ARRAYS && w->kept[slot]; k++) {
        if (!w->kept[k] || w->kept_bytes[k] < w->kept_bytes[slot]) slot = k;
    }
    if (w->kept[slot] && w->kept_bytes[slot] >= bytes) {
        mt__free(array);
        return;
    }
    mt__free(w->kept[slot]);
    w->kept[slot] = array;
    w->kept_bytes[slot] = bytes;
}

/* Array sizes come from the mesh's capacities (mt__cap_or), which never
 * overstate what was allocated. */
void mt_build_workspace_recycle(mt_build_workspace *workspace, mt_mesh *mesh)
{
    if (mesh && workspace) {
        size_t he_words = mesh->cap_half_edges ? 3 * (size_t)mesh->cap_half_edges
                                               : 3 * (size_t)mesh->num_half_edges +
                                                     2 * MT__HE_STAGGER / sizeof(uint32_t);
        size_t verts = mt__cap_or(mesh->cap_verts, mesh->num_verts_internal);
        size_t position_verts = mt__cap_or(mesh->cap_verts, mesh->num_verts);
        keep_array(workspace, mesh->he_head, he_words * sizeof(uint32_t));
        keep_array(workspace, mesh->face_he,
                   mt__cap_or(mesh->cap_faces, mesh->num_faces) * sizeof(uint32_t));
        keep_array(workspace, mesh->vert_he, verts * sizeof(uint32_t));
        keep_array(workspace, mesh->positions, position_verts * 3 * sizeof(double));
        mesh->he_head = mesh->he_next = mesh->he_face = NULL;
        mesh->face_he = mesh->vert_he = NULL;
        mesh->positions = NULL;
    }
    mt_mesh_destroy(mesh);
}
