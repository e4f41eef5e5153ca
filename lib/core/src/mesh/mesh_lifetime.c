/* The end of a mesh's life and the memory it holds until then:
 * mt_mesh_destroy frees every array a mesh owns, whoever filled it (build,
 * restore, compaction, edits), and the memory_bytes functions count them.
 * Below the builders, so that all that makes or recycles a mesh can free one
 * without calling back up into them. */
#include "mesh/mesh_internal.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"

static void report_free(mt_report *r)
{
    mt__free(r->boundary_loop_lengths);
    mt__free(r->components);
    mt__free(r->face_size_histogram);
    mt__free(r->edge_use_histogram);
    mt__free(r->defects);
}

void mt__edit_state_free(mt__edit_state *s)
{
    if (!s) return;
    mt__vec_free(&s->undo);
    mt__vec_free(&s->freed);
    mt__vec_free(&s->touched);
    mt__vec_free(&s->prim);
    mt__vec_free(&s->work);
    mt__free(s->vert_deleted);
    mt__free(s);
}

void mt_mesh_destroy(mt_mesh *m)
{
    if (!m) return;
    mt__free(m->he_head); /* the block holding he_next and he_face too */
    mt__free(m->face_he);
    mt__free(m->vert_he);
    mt__free(m->positions);
    mt__free(m->copy_original);
    mt__free(m->copies_sorted);
    mt__free(m->bundle_offsets);
    mt__free(m->bundle_edges);
    mt__free(m->bundled_sorted);
    mt__free(m->bundled_bundle);
    mt__free(m->vert_component);
    report_free(&m->report);
    mt__edit_state_free(m->edit);
    mt__attribute_set_free(m->attributes);
    mt__free(m);
}

size_t mt_mesh_memory_bytes(const mt_mesh *m)
{
    if (!m) return 0;
    size_t bytes = sizeof *m;
    bytes += (size_t)m->num_half_edges * 3 * sizeof(uint32_t);
    bytes += (size_t)m->num_faces * sizeof(uint32_t);
    bytes += (size_t)m->num_verts_internal * sizeof(uint32_t);
    if (m->positions) bytes += (size_t)m->num_verts * 3 * sizeof(double);
    bytes += (size_t)m->num_copies * 2 * sizeof(uint32_t);
    if (m->bundle_offsets) {
        size_t bundled = m->bundle_offsets[m->num_bundles];
        bytes += ((size_t)m->num_bundles + 1 + 3 * bundled) * sizeof(uint32_t);
    }
    if (m->vert_component) bytes += (size_t)m->num_verts_internal * sizeof(uint32_t);
    return bytes;
}

size_t mt_mesh_report_memory_bytes(const mt_mesh *m)
{
    if (!m) return 0;
    const mt_report *r = &m->report;
    return r->boundary_loops * sizeof(uint32_t) +
           r->connected_components * sizeof(mt_component_info) +
           (r->num_face_size_bins + r->num_edge_use_bins) * sizeof(mt_histogram_bin) +
           r->num_defects * sizeof(mt_defect);
}
