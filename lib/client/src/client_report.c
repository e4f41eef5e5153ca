/* meshtopod's topology_t turned into the core's mt_report, once, for every
 * reader of a report from the daemon (client_report.h): the reverse of the
 * daemon's copy (daemon/topology.c), field by field. The message comes from
 * the network: counts must be non-negative and lists no longer than their
 * counts, else MT_ERR_CORRUPT names the field; ids are kept as the 32 bits
 * they carry. */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/client_report.h"

/* The conversion's state: the first problem found wins. */
typedef struct convert {
    mt_status status;
    mt_diag *diag;
} convert;

/* value as a count; records the first negative one. */
static uint64_t count_of(convert *c, const char *field, int64_t index, int64_t value)
{
    if (value >= 0) return (uint64_t)value;
    if (c->status == MT_OK) {
        char where[32] = "";
        if (index >= 0) snprintf(where, sizeof where, "[%" PRId64 "]", index);
        c->status = mt_diag_set(c->diag, MT_ERR_CORRUPT,
                                "topology_t.%s%s = %" PRId64 " is negative", field, where, value);
    }
    return 0;
}

/* A list of `listed` entries for a count of `count`. */
static size_t listed_of(convert *c, const char *field, int32_t listed, uint64_t count)
{
    if ((uint64_t)listed > count && c->status == MT_OK)
        c->status = mt_diag_set(c->diag, MT_ERR_CORRUPT,
                                "topology_t.%s = %" PRId32 " lists more than its count %" PRIu64,
                                field, listed, count);
    return (size_t)listed;
}

/* calloc of n elements (never NULL for n = 0 unless out of memory). */
static void *alloc_list(convert *c, size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    if (!p && c->status == MT_OK) c->status = mt_diag_set(c->diag, MT_ERR_NOMEM, "out of memory");
    return p;
}

#define COUNT(field) count_of(&c, #field, -1, t->field)
#define ELEMENT(field, i) count_of(&c, #field, (int64_t)(i), t->field[i])

mt_status mt_client_report_from_topology(const meshtopo_topology_t *t, mt_client_report *out,
                                         mt_diag *diag)
{
    memset(out, 0, sizeof *out);
    mt_diag_clear(diag);
    if (!t) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "no topology_t given");
    convert c = {MT_OK, diag};
    mt_report *r = &out->report;

    r->num_verts = (uint32_t)COUNT(num_verts);
    r->num_faces = (uint32_t)COUNT(num_faces);
    r->num_faces_valid = (uint32_t)COUNT(num_faces_valid);
    r->num_edges = COUNT(num_edges);
    r->num_half_edges = COUNT(num_half_edges);
    r->boundary_edges = COUNT(boundary_edges);
    r->boundary_loops = (uint32_t)COUNT(boundary_loops);
    r->boundary_loops_ambiguous = t->boundary_loops_ambiguous != 0;
    out->num_loop_lengths =
        listed_of(&c, "num_boundary_loop_lengths", t->num_boundary_loop_lengths, r->boundary_loops);
    r->boundary_loop_lengths = alloc_list(&c, out->num_loop_lengths, sizeof(uint32_t));
    for (size_t i = 0; r->boundary_loop_lengths && i < out->num_loop_lengths; i++)
        r->boundary_loop_lengths[i] = (uint32_t)ELEMENT(boundary_loop_lengths, i);

    r->nonmanifold_edges = COUNT(nonmanifold_edges);
    r->inconsistent_orientation_edges = COUNT(inconsistent_orientation_edges);
    r->duplicate_directed_edges = COUNT(duplicate_directed_edges);
    r->nonmanifold_vertices = (uint32_t)COUNT(nonmanifold_vertices);
    r->bowtie_vertices = (uint32_t)COUNT(bowtie_vertices);
    r->isolated_vertices = (uint32_t)COUNT(isolated_vertices);
    r->unreferenced_vertices = (uint32_t)COUNT(unreferenced_vertices);
    r->degenerate_faces = (uint32_t)COUNT(degenerate_faces);
    r->duplicate_faces = (uint32_t)COUNT(duplicate_faces);
    r->out_of_range_indices = COUNT(out_of_range_indices);
    r->faces_with_out_of_range_indices = (uint32_t)COUNT(faces_with_out_of_range_indices);
    r->nonfinite_vertices = (uint32_t)COUNT(nonfinite_vertices);

    r->connected_components = (uint32_t)COUNT(connected_components);
    r->vertex_connected_components = (uint32_t)COUNT(vertex_connected_components);
    r->euler_characteristic = t->euler_characteristic;
    r->closed = t->closed != 0;
    r->manifold = t->manifold != 0;
    r->orientable = t->orientable != 0;
    r->consistently_oriented = t->consistently_oriented != 0;
    r->genus = t->genus;

    out->num_components =
        listed_of(&c, "num_components_listed", t->num_components_listed, r->connected_components);
    r->components = alloc_list(&c, out->num_components, sizeof *r->components);
    for (size_t i = 0; r->components && i < out->num_components; i++) {
        mt_component_info *ci = &r->components[i];
        ci->min_face = (uint32_t)ELEMENT(component_min_face, i);
        ci->faces = (uint32_t)ELEMENT(component_faces, i);
        ci->vertices = (uint32_t)ELEMENT(component_vertices, i);
        ci->edges = ELEMENT(component_edges, i);
        ci->euler_characteristic = t->component_euler_characteristic[i];
        ci->boundary_edges = ELEMENT(component_boundary_edges, i);
        ci->boundary_loops = (uint32_t)ELEMENT(component_boundary_loops, i);
        ci->closed = t->component_closed[i] != 0;
        ci->manifold = t->component_manifold[i] != 0;
        ci->orientable = t->component_orientable[i] != 0;
        ci->genus = t->component_genus[i];
        ci->genus_with_boundary = t->component_genus_with_boundary[i];
    }

    r->num_face_size_bins = (size_t)t->num_face_size_bins;
    r->face_size_histogram = alloc_list(&c, r->num_face_size_bins, sizeof(mt_histogram_bin));
    for (size_t i = 0; r->face_size_histogram && i < r->num_face_size_bins; i++) {
        r->face_size_histogram[i].key = (uint32_t)ELEMENT(face_size_keys, i);
        r->face_size_histogram[i].count = ELEMENT(face_size_counts, i);
    }
    r->num_edge_use_bins = (size_t)t->num_edge_use_bins;
    r->edge_use_histogram = alloc_list(&c, r->num_edge_use_bins, sizeof(mt_histogram_bin));
    for (size_t i = 0; r->edge_use_histogram && i < r->num_edge_use_bins; i++) {
        r->edge_use_histogram[i].key = (uint32_t)ELEMENT(edge_use_keys, i);
        r->edge_use_histogram[i].count = ELEMENT(edge_use_counts, i);
    }

    out->num_defects_found = COUNT(num_defects);
    r->num_defects =
        listed_of(&c, "num_defects_listed", t->num_defects_listed, out->num_defects_found);
    r->defects = alloc_list(&c, r->num_defects, sizeof *r->defects);
    for (size_t i = 0; r->defects && i < r->num_defects; i++) {
        /* The 32 bits of the core's ids; a kind out of the table stays out of it. */
        r->defects[i].kind = (uint32_t)(int32_t)t->defect_kind[i];
        r->defects[i].a = (uint32_t)t->defect_a[i];
        r->defects[i].b = (uint32_t)t->defect_b[i];
        r->defects[i].c = (uint32_t)t->defect_c[i];
    }
    if (c.status != MT_OK) mt_client_report_free(out);
    return c.status;
}

#undef COUNT
#undef ELEMENT

void mt_client_report_free(mt_client_report *report)
{
    if (!report) return;
    free(report->report.boundary_loop_lengths);
    free(report->report.components);
    free(report->report.face_size_histogram);
    free(report->report.edge_use_histogram);
    free(report->report.defects);
    memset(report, 0, sizeof *report);
}
