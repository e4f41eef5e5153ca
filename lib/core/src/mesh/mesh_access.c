/* Read access to a built mesh: its report, the caller's counts, positions,
 * the raw view, and the two look-ups the queries need where the structure is
 * not manifold (the copies of a caller vertex, the bundle of an internal
 * edge). Constant time, or a binary search over the few copied vertices and
 * bundled edges. */
#include "mesh/mesh_internal.h"
#include "meshtopo/mesh.h"

const mt_report *mt_mesh_report(const mt_mesh *mesh)
{
    return mesh ? &mesh->report : NULL;
}

uint32_t mt_mesh_num_verts(const mt_mesh *mesh)
{
    return mesh ? mesh->num_verts : 0;
}

uint32_t mt_mesh_num_faces(const mt_mesh *mesh)
{
    return mesh ? mesh->num_faces : 0;
}

const double *mt_mesh_position(const mt_mesh *mesh, uint32_t vert)
{
    if (!mesh || !mesh->positions || vert >= mesh->num_verts) return NULL;
    return mesh->positions + 3 * (size_t)vert;
}

void mt_mesh_get_view(const mt_mesh *mesh, mt_mesh_view *out_view)
{
    if (!out_view) return;
    mt_mesh_view v = {0};
    if (mesh) {
        v.num_verts = mesh->num_verts;
        v.num_verts_internal = mesh->num_verts_internal;
        v.num_faces = mesh->num_faces;
        v.num_half_edges = mesh->num_half_edges;
        v.he_head = mesh->he_head;
        v.he_next = mesh->he_next;
        v.he_face = mesh->he_face;
        v.face_he = mesh->face_he;
        v.vert_he = mesh->vert_he;
        v.positions = mesh->positions;
    }
    *out_view = v;
}

uint32_t mt_vert_original(const mt_mesh *mesh, uint32_t internal_vert)
{
    if (!mesh || internal_vert >= mesh->num_verts_internal) return MT_NONE;
    if (internal_vert < mesh->num_verts) return internal_vert;
    uint32_t copy = internal_vert - mesh->num_verts;
    return copy < mesh->num_copies ? mesh->copy_original[copy] : MT_NONE;
}

/* Original of the k-th entry of copies_sorted; UINT32_MAX for an entry that
 * is not a copy id, so that a corrupted table sorts it last and it is never
 * returned for a real vertex. */
static uint32_t sorted_copy_original(const mt_mesh *m, uint32_t k)
{
    uint32_t c = m->copies_sorted[k];
    if (c < m->num_verts || c - m->num_verts >= m->num_copies) return UINT32_MAX;
    return m->copy_original[c - m->num_verts];
}

uint32_t mt__vert_copies(const mt_mesh *m, uint32_t v, const uint32_t **out_first)
{
    *out_first = m->copies_sorted;
    if (m->num_copies == 0 || v >= m->num_verts) return 0;
    /* Lower bound of v among the originals, then count the run. */
    uint32_t lo = 0, hi = m->num_copies;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (sorted_copy_original(m, mid) < v)
            lo = mid + 1;
        else
            hi = mid;
    }
    uint32_t end = lo;
    while (end < m->num_copies && sorted_copy_original(m, end) == v) end++;
    *out_first = m->copies_sorted + lo;
    return end - lo;
}

uint32_t mt__edge_bundle(const mt_mesh *m, uint32_t edge)
{
    if (m->num_bundles == 0 || !m->bundle_offsets) return MT_NONE;
    uint32_t lo = 0, hi = m->bundle_offsets[m->num_bundles];
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        uint32_t e = m->bundled_sorted[mid];
        if (e == edge) return m->bundled_bundle[mid];
        if (e < edge)
            lo = mid + 1;
        else
            hi = mid;
    }
    return MT_NONE;
}
