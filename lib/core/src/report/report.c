/* The topology report: mt__build_report fills mt_report from the build's
 * counts and the report parts (report_*.c), then derives the flags and the
 * genus of each component, the histograms and the sorted defect list. */
#include <stdlib.h>
#include <string.h>

#include "report/report_internal.h"

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

static int compare_defect(const void *pa, const void *pb)
{
    const mt_defect *a = pa, *b = pb;
    if (a->kind != b->kind) return (a->kind > b->kind) - (a->kind < b->kind);
    if (a->a != b->a) return (a->a > b->a) - (a->a < b->a);
    return (a->b > b->b) - (a->b < b->b);
}

/* Histogram bins from a flat count table plus a list of larger keys. */
static mt_status make_histogram(const uint64_t *small, uint32_t num_small, mt__vec *large,
                                mt_histogram_bin **out_bins, size_t *out_count)
{
    uint32_t *keys = large->data;
    if (large->len) qsort(keys, large->len, sizeof *keys, compare_u32);
    size_t bins = 0;
    for (uint32_t k = 0; k < num_small; k++) bins += small[k] != 0;
    for (size_t i = 0; i < large->len; i++) bins += i == 0 || keys[i] != keys[i - 1];
    mt_histogram_bin *out = mt__calloc(bins ? bins : 1, sizeof *out);
    if (!out) return MT_ERR_NOMEM;
    size_t n = 0;
    for (uint32_t k = 0; k < num_small; k++)
        if (small[k]) out[n++] = (mt_histogram_bin){k, small[k]};
    for (size_t i = 0; i < large->len; i++) {
        if (i == 0 || keys[i] != keys[i - 1])
            out[n++] = (mt_histogram_bin){keys[i], 1};
        else
            out[n - 1].count++;
    }
    *out_bins = out;
    *out_count = n;
    return MT_OK;
}

/* Moves the bundle lists of the build into the mesh's lookup arrays. */
static mt_status publish_bundles(mt__build *b)
{
    mt_mesh *m = b->m;
    m->num_bundles = (uint32_t)b->bundle_offsets.len;
    if (m->num_bundles == 0) return MT_OK;
    uint32_t total = (uint32_t)b->bundle_edges.len;
    if (mt__vec_push(&b->bundle_offsets, &total) != MT_OK) return MT_ERR_NOMEM;
    m->bundle_offsets = b->bundle_offsets.data;
    m->bundle_edges = b->bundle_edges.data;
    b->bundle_offsets = (mt__vec){NULL, 0, 0, sizeof(uint32_t)};
    b->bundle_edges = (mt__vec){NULL, 0, 0, sizeof(uint32_t)};
    m->bundled_sorted = mt__malloc((size_t)total * sizeof(uint32_t));
    m->bundled_bundle = mt__malloc((size_t)total * sizeof(uint32_t));
    if (!m->bundled_sorted || !m->bundled_bundle) return MT_ERR_NOMEM;
    /* Bundles are made in ascending edge order, so the list is sorted. */
    memcpy(m->bundled_sorted, m->bundle_edges, (size_t)total * sizeof(uint32_t));
    for (uint32_t k = 0; k < m->num_bundles; k++)
        for (uint32_t i = m->bundle_offsets[k]; i < m->bundle_offsets[k + 1]; i++)
            m->bundled_bundle[i] = k;
    return MT_OK;
}

/* Turns the list of half-edges without a face into the list of boundary
 * edges: edges used by one face, leaving out the seams of edge bundles. */
static void keep_boundary_edges(mt__build *b)
{
    const mt_mesh *m = b->m;
    uint32_t *list = b->boundary_halves.data;
    size_t kept = 0;
    for (size_t i = 0; i < b->boundary_halves.len; i++) {
        uint32_t e = list[i] >> 1;
        if (m->num_bundles == 0 || mt__edge_bundle(m, e) == MT_NONE) list[kept++] = e;
    }
    b->boundary_halves.len = kept;
}

static mt_status report_isolated(mt__build *b)
{
    mt_mesh *m = b->m;
    mt_report *r = &m->report;
    uint32_t *refs = b->invalid_refs.data;
    size_t num_refs = b->invalid_refs.len;
    if (num_refs) qsort(refs, num_refs, sizeof *refs, compare_u32);
    for (uint32_t v = 0; v < m->num_verts; v++) {
        if (m->vert_he[v] != MT_NONE) continue;
        r->isolated_vertices++;
        if (!num_refs || !bsearch(&v, refs, num_refs, sizeof *refs, compare_u32))
            r->unreferenced_vertices++;
        if (mt__add_defect(b, MT_DEFECT_ISOLATED_VERTEX, v, 0, 0) != MT_OK) return MT_ERR_NOMEM;
    }
    return MT_OK;
}

static void finish_components(mt__build *b)
{
    mt_report *r = &b->m->report;
    r->closed = r->boundary_edges == 0 && r->num_faces_valid > 0;
    r->manifold = r->nonmanifold_edges == 0 && r->nonmanifold_vertices == 0;
    r->orientable = true;
    r->consistently_oriented =
        r->inconsistent_orientation_edges == 0 && r->duplicate_directed_edges == 0;
    for (uint32_t c = 0; c < r->connected_components; c++) {
        mt_component_info *ci = &r->components[c];
        if (!ci->orientable) r->orientable = false;
        ci->genus = ci->genus_with_boundary = -1;
        if (!ci->manifold || !ci->orientable) continue;
        ci->genus_with_boundary =
            (int32_t)((2 - ci->euler_characteristic - (int64_t)ci->boundary_loops) / 2);
        if (ci->closed) ci->genus = (int32_t)((2 - ci->euler_characteristic) / 2);
    }
    r->genus = r->connected_components == 1 ? r->components[0].genus : -1;
}

mt_status mt__build_report(mt__build *b)
{
    mt_mesh *m = b->m;
    mt_report *r = &m->report;
    const mt_face_list *in = b->in;
    r->num_verts = in->num_verts;
    r->num_faces = in->num_faces;
    r->num_faces_valid = 0;
    for (uint32_t f = 0; f < in->num_faces; f++) r->num_faces_valid += m->face_he[f] != MT_NONE;
    r->num_edges = b->num_edges;
    r->num_half_edges = in->num_indices;
    r->boundary_edges = b->boundary_edges;
    r->nonmanifold_edges = b->nonmanifold_edges;
    r->inconsistent_orientation_edges = b->inconsistent_edges;
    r->duplicate_directed_edges = b->duplicate_directed_edges;
    r->degenerate_faces = b->degenerate_faces;
    r->out_of_range_indices = b->out_of_range_entries;
    r->faces_with_out_of_range_indices = b->out_of_range_faces;
    r->nonfinite_vertices = b->nonfinite_vertices;
    r->euler_characteristic = (int64_t)in->num_verts - (int64_t)b->num_edges + r->num_faces_valid;

    mt_status s = publish_bundles(b);
    if (s == MT_OK) keep_boundary_edges(b);
    if (s == MT_OK) s = mt__report_components(b);
    if (s == MT_OK) s = mt__report_boundary(b);
    if (s == MT_OK) s = mt__report_links(b);
    if (s == MT_OK) s = mt__report_orientation(b);
    if (s == MT_OK) s = mt__report_duplicates(b);
    if (s == MT_OK) s = report_isolated(b);
    if (s == MT_OK)
        s = make_histogram(b->size_hist, MT__SMALL_SIZES, &b->large_sizes, &r->face_size_histogram,
                           &r->num_face_size_bins);
    if (s == MT_OK)
        s = make_histogram(b->use_hist, MT__SMALL_USES, &b->large_uses, &r->edge_use_histogram,
                           &r->num_edge_use_bins);
    if (s != MT_OK) {
        mt__free(b->vert_comp);
        b->vert_comp = NULL;
        return s;
    }
    finish_components(b);

    mt_defect *defects = b->defects.data;
    if (b->defects.len) qsort(defects, b->defects.len, sizeof *defects, compare_defect);
    r->num_defects = b->defects.len;
    r->defects = defects ? defects : mt__calloc(1, sizeof(mt_defect));
    b->defects = (mt__vec){NULL, 0, 0, sizeof(mt_defect)};
    if (!r->defects) {
        mt__free(b->vert_comp);
        b->vert_comp = NULL;
        return MT_ERR_NOMEM;
    }

    if (b->num_components > 1) {
        m->vert_component = b->vert_comp;
    } else {
        mt__free(b->vert_comp);
    }
    b->vert_comp = NULL;
    return MT_OK;
}
