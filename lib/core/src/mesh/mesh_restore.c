/* mt_mesh_get_parts and mt_mesh_restore (mesh_parts.h): a mesh's arrays read
 * out, and a mesh made from such arrays without a rebuild. Restoring copies
 * the arrays into the build's layout, deep-copies the report, checks the
 * counts against each other and then runs mt_mesh_validate, which bounds-
 * checks every stored index before following it: arrays from a file are
 * never trusted. */
#include <string.h>

#include "mesh/mesh_internal.h"
#include "meshtopo/mesh_parts.h"
#include "meshtopo/validate.h"

void mt_mesh_get_parts(const mt_mesh *mesh, mt_mesh_parts *out_parts)
{
    if (!out_parts) return;
    mt_mesh_parts p;
    memset(&p, 0, sizeof p);
    if (mesh) {
        p.num_verts = mesh->num_verts;
        p.num_verts_internal = mesh->num_verts_internal;
        p.num_faces = mesh->num_faces;
        p.num_half_edges = mesh->num_half_edges;
        p.he_head = mesh->he_head;
        p.he_next = mesh->he_next;
        p.he_face = mesh->he_face;
        p.face_he = mesh->face_he;
        p.vert_he = mesh->vert_he;
        p.positions = mesh->positions;
        p.num_copies = mesh->num_copies;
        p.copy_original = mesh->copy_original;
        p.copies_sorted = mesh->copies_sorted;
        p.num_bundles = mesh->num_bundles;
        p.num_bundled = mesh->num_bundles ? mesh->bundle_offsets[mesh->num_bundles] : 0;
        p.bundle_offsets = mesh->num_bundles ? mesh->bundle_offsets : NULL;
        p.bundle_edges = mesh->bundle_edges;
        p.bundled_sorted = mesh->bundled_sorted;
        p.bundled_bundle = mesh->bundled_bundle;
        p.vert_component = mesh->vert_component;
    }
    *out_parts = p;
}

/* A pending mesh (mt_mesh_restore_begin): the mesh first, so that the
 * mt_mesh pointer handed out is the allocation mt_mesh_destroy frees, plus
 * what finishing needs to know about the sizes it allocated. */
typedef struct pending_mesh {
    mt_mesh mesh;
    uint32_t num_bundled;
} pending_mesh;

/* count elements of elem bytes (at least one byte, so that NULL always
 * means failure); *ok turns false on overflow or out of memory. */
static void *alloc_array(size_t count, size_t elem, bool *ok)
{
    size_t bytes;
    if (!*ok) return NULL;
    if (!mt__mul_size(count, elem, &bytes)) {
        *ok = false;
        return NULL;
    }
    void *p = mt__malloc(bytes);
    if (!p) *ok = false;
    return p;
}

static void *copy_array(const void *src, size_t count, size_t elem, bool *ok)
{
    void *dst = alloc_array(count, elem, ok);
    if (dst && count) memcpy(dst, src, count * elem);
    return dst;
}

/* Every array a non-zero count needs is there, so that the copies read
 * only what the caller holds. The counts themselves are checked by
 * mt_mesh_restore_begin and mt_mesh_restore_finish. */
static mt_status check_pointers(const mt_mesh_parts *p, mt_diag *diag)
{
    if (p->num_half_edges > 0 && (!p->he_head || !p->he_next || !p->he_face))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "restore: %u half-edges but a half-edge array is missing",
                        p->num_half_edges);
    if (p->num_faces > 0 && !p->face_he)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "restore: %u faces but no face_he array",
                        p->num_faces);
    if (p->num_verts_internal > 0 && !p->vert_he)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "restore: %u internal vertices but no vert_he array",
                        p->num_verts_internal);
    if (p->num_copies > 0 && (!p->copy_original || !p->copies_sorted))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "restore: %u vertex copies but a copy array is missing", p->num_copies);
    if (p->num_bundles > 0 && !p->bundle_offsets)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "restore: %u edge bundles but no bundle_offsets", p->num_bundles);
    if (p->num_bundled > 0 && (!p->bundle_edges || !p->bundled_sorted || !p->bundled_bundle))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "restore: %u bundled edges but a bundle array is missing", p->num_bundled);
    return MT_OK;
}

/* The report's lists are there for its counts and its defect kinds known. */
static mt_status check_report(const mt_mesh *m, const mt_report *r, mt_diag *diag)
{
    if (r->num_verts != m->num_verts || r->num_faces != m->num_faces)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "restore: the report counts %u vertices and %u faces, the arrays %u and %u",
                        r->num_verts, r->num_faces, m->num_verts, m->num_faces);
    if ((r->boundary_loops && !r->boundary_loop_lengths) ||
        (r->connected_components && !r->components) ||
        (r->num_face_size_bins && !r->face_size_histogram) ||
        (r->num_edge_use_bins && !r->edge_use_histogram) || (r->num_defects && !r->defects))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "restore: the report has a non-zero count without its list");
    for (size_t i = 0; i < r->num_defects; i++)
        if (r->defects[i].kind >= MT_DEFECT_KIND_COUNT)
            return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                            "restore: report defect %zu has unknown kind %u", i,
                            r->defects[i].kind);
    return MT_OK;
}

/* The report with its own copies of the lists (at least one element each,
 * as the build allocates them). */
static bool copy_report(const mt_report *src, mt_report *dst)
{
    bool ok = true;
    *dst = *src;
    dst->boundary_loop_lengths = NULL;
    dst->components = NULL;
    dst->face_size_histogram = NULL;
    dst->edge_use_histogram = NULL;
    dst->defects = NULL;
    dst->boundary_loop_lengths =
        copy_array(src->boundary_loop_lengths, src->boundary_loops, sizeof(uint32_t), &ok);
    dst->components =
        copy_array(src->components, src->connected_components, sizeof(mt_component_info), &ok);
    dst->face_size_histogram = copy_array(src->face_size_histogram, src->num_face_size_bins,
                                          sizeof(mt_histogram_bin), &ok);
    dst->edge_use_histogram =
        copy_array(src->edge_use_histogram, src->num_edge_use_bins, sizeof(mt_histogram_bin), &ok);
    dst->defects = copy_array(src->defects, src->num_defects, sizeof(mt_defect), &ok);
    return ok;
}

mt_status mt_mesh_restore_begin(const mt_mesh_shape *shape, mt_mesh **out_pending,
                                mt_mesh_parts_buffers *out, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out_pending) *out_pending = NULL;
    if (out) memset(out, 0, sizeof *out);
    if (!shape || !out_pending || !out)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "restore: NULL argument");
    const mt_mesh_shape *s = shape;
    if (s->num_half_edges > 0x7fffffffu)
        return mt__fail(diag, MT_ERR_TOO_LARGE, MT_NONE,
                        "restore: %u half-edges, more than 2^31 - 1", s->num_half_edges);
    if (s->num_verts > s->num_verts_internal ||
        s->num_verts_internal - s->num_verts != s->num_copies)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "restore: %u internal vertices is not %u caller vertices plus %u copies",
                        s->num_verts_internal, s->num_verts, s->num_copies);
    if (s->num_bundles == 0 && s->num_bundled != 0)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "restore: %u bundled edges but no edge bundles", s->num_bundled);
    pending_mesh *pm = mt__calloc(1, sizeof *pm);
    if (!pm) return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "restore: out of memory");
    mt_mesh *m = &pm->mesh;
    pm->num_bundled = s->num_bundled;
    m->num_verts = s->num_verts;
    m->num_verts_internal = s->num_verts_internal;
    m->num_faces = s->num_faces;
    m->num_half_edges = s->num_half_edges;
    m->num_copies = s->num_copies;
    m->num_bundles = s->num_bundles;
    /* The three half-edge arrays in one staggered block, as build.c lays
     * them out (mt_mesh_destroy and the edits rely on it). */
    bool ok = true;
    const size_t n = s->num_half_edges, stagger = MT__HE_STAGGER / sizeof(uint32_t);
    uint32_t *block = alloc_array(3 * n + 2 * stagger, sizeof(uint32_t), &ok);
    if (block) {
        m->he_head = block;
        m->he_next = block + n + stagger;
        m->he_face = m->he_next + n + stagger;
    }
    m->face_he = alloc_array(s->num_faces, sizeof(uint32_t), &ok);
    m->vert_he = alloc_array(s->num_verts_internal, sizeof(uint32_t), &ok);
    if (s->has_positions) m->positions = alloc_array((size_t)s->num_verts * 3, sizeof(double), &ok);
    if (s->num_copies > 0) {
        m->copy_original = alloc_array(s->num_copies, sizeof(uint32_t), &ok);
        m->copies_sorted = alloc_array(s->num_copies, sizeof(uint32_t), &ok);
    }
    if (s->num_bundles > 0) {
        m->bundle_offsets = alloc_array((size_t)s->num_bundles + 1, sizeof(uint32_t), &ok);
        m->bundle_edges = alloc_array(s->num_bundled, sizeof(uint32_t), &ok);
        m->bundled_sorted = alloc_array(s->num_bundled, sizeof(uint32_t), &ok);
        m->bundled_bundle = alloc_array(s->num_bundled, sizeof(uint32_t), &ok);
    }
    if (s->has_vert_component)
        m->vert_component = alloc_array(s->num_verts_internal, sizeof(uint32_t), &ok);
    if (!ok) {
        mt_mesh_destroy(m);
        return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "restore: out of memory for the arrays");
    }
    out->he_head = m->he_head;
    out->he_next = m->he_next;
    out->he_face = m->he_face;
    out->face_he = m->face_he;
    out->vert_he = m->vert_he;
    out->positions = m->positions;
    out->copy_original = m->copy_original;
    out->copies_sorted = m->copies_sorted;
    out->bundle_offsets = m->bundle_offsets;
    out->bundle_edges = m->bundle_edges;
    out->bundled_sorted = m->bundled_sorted;
    out->bundled_bundle = m->bundled_bundle;
    out->vert_component = m->vert_component;
    *out_pending = m;
    return MT_OK;
}

mt_status mt_mesh_restore_finish(mt_mesh *pending, const mt_report *report, mt_mesh **out_mesh,
                                 mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out_mesh) *out_mesh = NULL;
    if (!pending || !report || !out_mesh) {
        mt_mesh_destroy(pending);
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "restore: NULL argument");
    }
    pending_mesh *pm = (pending_mesh *)pending;
    mt_mesh *m = pending;
    /* validate takes bundle_offsets[num_bundles] as the bundled arrays'
     * length: it must be the length allocated. */
    const uint32_t total = m->num_bundles ? m->bundle_offsets[m->num_bundles] : 0;
    mt_status st = MT_OK;
    if (total != pm->num_bundled)
        st = mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                      "restore: bundle_offsets ends at %u but %u bundled edges are given", total,
                      pm->num_bundled);
    if (st == MT_OK) st = check_report(m, report, diag);
    if (st == MT_OK && !copy_report(report, &m->report))
        st = mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "restore: out of memory copying the report");
    if (st == MT_OK) st = mt_mesh_validate(m, diag);
    if (st != MT_OK) {
        mt_mesh_destroy(m);
        return st;
    }
    *out_mesh = m;
    return MT_OK;
}

mt_status mt_mesh_restore(const mt_mesh_parts *parts, const mt_report *report, mt_mesh **out_mesh,
                          mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out_mesh) *out_mesh = NULL;
    if (!parts || !report || !out_mesh)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "restore: NULL argument");
    const mt_mesh_parts *p = parts;
    mt_status st = check_pointers(p, diag);
    if (st != MT_OK) return st;
    mt_mesh_shape shape = {p->num_verts,      p->num_verts_internal, p->num_faces,
                           p->num_half_edges, p->num_copies,         p->num_bundles,
                           p->num_bundled,    p->positions != NULL,  p->vert_component != NULL};
    mt_mesh *pending = NULL;
    mt_mesh_parts_buffers b;
    st = mt_mesh_restore_begin(&shape, &pending, &b, diag);
    if (st != MT_OK) return st;
    const size_t he = (size_t)p->num_half_edges * sizeof(uint32_t);
    if (he) {
        memcpy(b.he_head, p->he_head, he);
        memcpy(b.he_next, p->he_next, he);
        memcpy(b.he_face, p->he_face, he);
    }
    if (p->num_faces) memcpy(b.face_he, p->face_he, (size_t)p->num_faces * sizeof(uint32_t));
    if (p->num_verts_internal)
        memcpy(b.vert_he, p->vert_he, (size_t)p->num_verts_internal * sizeof(uint32_t));
    if (p->positions && p->num_verts)
        memcpy(b.positions, p->positions, (size_t)p->num_verts * 3 * sizeof(double));
    if (p->num_copies) {
        memcpy(b.copy_original, p->copy_original, (size_t)p->num_copies * sizeof(uint32_t));
        memcpy(b.copies_sorted, p->copies_sorted, (size_t)p->num_copies * sizeof(uint32_t));
    }
    if (p->num_bundles) {
        memcpy(b.bundle_offsets, p->bundle_offsets,
               ((size_t)p->num_bundles + 1) * sizeof(uint32_t));
        const size_t bb = (size_t)p->num_bundled * sizeof(uint32_t);
        if (bb) {
            memcpy(b.bundle_edges, p->bundle_edges, bb);
            memcpy(b.bundled_sorted, p->bundled_sorted, bb);
            memcpy(b.bundled_bundle, p->bundled_bundle, bb);
        }
    }
    if (p->vert_component && p->num_verts_internal)
        memcpy(b.vert_component, p->vert_component,
               (size_t)p->num_verts_internal * sizeof(uint32_t));
    return mt_mesh_restore_finish(pending, report, out_mesh, diag);
}
