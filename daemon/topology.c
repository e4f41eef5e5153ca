/* meshtopod's topology reports: a built mesh's mt_report copied field by
 * field into a meshtopo_topology_t (msgs/topology_t.lcm), ids as the 32 bits
 * of the core's uint32 ids. Lists can be cut to a length (the published
 * report of a build); the *_listed counts then say how many were kept. Any
 * thread. */
#include "topology.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"

static size_t min_size(size_t a, size_t b)
{
    return a < b ? a : b;
}

/* calloc of n elements, never NULL for n = 0 unless out of memory. */
static void *alloc_array(size_t n, size_t size, int *failed)
{
    void *p = calloc(n ? n : 1, size);
    if (!p) *failed = 1;
    return p;
}

static char *copy_text(const char *text, int *failed)
{
    if (!text) text = "";
    char *p = strdup(text);
    if (!p) *failed = 1;
    return p;
}

int mtd_topology_fill(const mt_mesh *mesh, const mtd_mesh_info *info, int64_t build_duration_us,
                      size_t list_max, meshtopo_topology_t *t)
{
    memset(t, 0, sizeof *t);
    const mt_report *r = mt_mesh_report(mesh);
    int failed = 0;
    t->utime = mtd_now_utime();
    t->mesh_id = copy_text(info->id, &failed);
    t->version = (int32_t)info->version;
    t->source = copy_text(info->source, &failed);
    t->mesh_utime = info->utime;
    t->build_duration_us = build_duration_us;
    t->content_hash = (int64_t)info->content_hash;

    t->num_verts = (int32_t)r->num_verts;
    t->num_faces = (int32_t)r->num_faces;
    t->num_faces_valid = (int32_t)r->num_faces_valid;
    t->num_edges = (int64_t)r->num_edges;
    t->num_half_edges = (int64_t)r->num_half_edges;
    t->boundary_edges = (int64_t)r->boundary_edges;
    t->boundary_loops = (int32_t)r->boundary_loops;
    t->boundary_loops_ambiguous = r->boundary_loops_ambiguous;
    size_t n = min_size(r->boundary_loops, list_max);
    t->num_boundary_loop_lengths = (int32_t)n;
    t->boundary_loop_lengths = alloc_array(n, sizeof(int32_t), &failed);
    for (size_t i = 0; t->boundary_loop_lengths && i < n; i++)
        t->boundary_loop_lengths[i] = (int32_t)r->boundary_loop_lengths[i];

    t->nonmanifold_edges = (int64_t)r->nonmanifold_edges;
    t->inconsistent_orientation_edges = (int64_t)r->inconsistent_orientation_edges;
    t->duplicate_directed_edges = (int64_t)r->duplicate_directed_edges;
    t->nonmanifold_vertices = (int32_t)r->nonmanifold_vertices;
    t->bowtie_vertices = (int32_t)r->bowtie_vertices;
    t->isolated_vertices = (int32_t)r->isolated_vertices;
    t->unreferenced_vertices = (int32_t)r->unreferenced_vertices;
    t->degenerate_faces = (int32_t)r->degenerate_faces;
    t->duplicate_faces = (int32_t)r->duplicate_faces;
    t->out_of_range_indices = (int64_t)r->out_of_range_indices;
    t->faces_with_out_of_range_indices = (int32_t)r->faces_with_out_of_range_indices;
    t->nonfinite_vertices = (int32_t)r->nonfinite_vertices;

    t->connected_components = (int32_t)r->connected_components;
    t->vertex_connected_components = (int32_t)r->vertex_connected_components;
    t->euler_characteristic = r->euler_characteristic;
    t->closed = r->closed;
    t->manifold = r->manifold;
    t->orientable = r->orientable;
    t->consistently_oriented = r->consistently_oriented;
    t->genus = r->genus;

    n = min_size(r->connected_components, list_max);
    t->num_components_listed = (int32_t)n;
    t->component_min_face = alloc_array(n, sizeof(int32_t), &failed);
    t->component_faces = alloc_array(n, sizeof(int32_t), &failed);
    t->component_vertices = alloc_array(n, sizeof(int32_t), &failed);
    t->component_edges = alloc_array(n, sizeof(int64_t), &failed);
    t->component_euler_characteristic = alloc_array(n, sizeof(int64_t), &failed);
    t->component_boundary_edges = alloc_array(n, sizeof(int64_t), &failed);
    t->component_boundary_loops = alloc_array(n, sizeof(int32_t), &failed);
    t->component_closed = alloc_array(n, sizeof(int8_t), &failed);
    t->component_manifold = alloc_array(n, sizeof(int8_t), &failed);
    t->component_orientable = alloc_array(n, sizeof(int8_t), &failed);
    t->component_genus = alloc_array(n, sizeof(int32_t), &failed);
    t->component_genus_with_boundary = alloc_array(n, sizeof(int32_t), &failed);
    for (size_t i = 0; !failed && i < n; i++) {
        const mt_component_info *c = &r->components[i];
        t->component_min_face[i] = (int32_t)c->min_face;
        t->component_faces[i] = (int32_t)c->faces;
        t->component_vertices[i] = (int32_t)c->vertices;
        t->component_edges[i] = (int64_t)c->edges;
        t->component_euler_characteristic[i] = c->euler_characteristic;
        t->component_boundary_edges[i] = (int64_t)c->boundary_edges;
        t->component_boundary_loops[i] = (int32_t)c->boundary_loops;
        t->component_closed[i] = c->closed;
        t->component_manifold[i] = c->manifold;
        t->component_orientable[i] = c->orientable;
        t->component_genus[i] = c->genus;
        t->component_genus_with_boundary[i] = c->genus_with_boundary;
    }

    n = r->num_face_size_bins;
    t->num_face_size_bins = (int32_t)n;
    t->face_size_keys = alloc_array(n, sizeof(int32_t), &failed);
    t->face_size_counts = alloc_array(n, sizeof(int64_t), &failed);
    for (size_t i = 0; !failed && i < n; i++) {
        t->face_size_keys[i] = (int32_t)r->face_size_histogram[i].key;
        t->face_size_counts[i] = (int64_t)r->face_size_histogram[i].count;
    }
    n = r->num_edge_use_bins;
    t->num_edge_use_bins = (int32_t)n;
    t->edge_use_keys = alloc_array(n, sizeof(int32_t), &failed);
    t->edge_use_counts = alloc_array(n, sizeof(int64_t), &failed);
    for (size_t i = 0; !failed && i < n; i++) {
        t->edge_use_keys[i] = (int32_t)r->edge_use_histogram[i].key;
        t->edge_use_counts[i] = (int64_t)r->edge_use_histogram[i].count;
    }

    t->num_defects = (int64_t)r->num_defects;
    n = min_size(r->num_defects, list_max);
    t->num_defects_listed = (int32_t)n;
    t->defect_kind = alloc_array(n, sizeof(int8_t), &failed);
    t->defect_a = alloc_array(n, sizeof(int32_t), &failed);
    t->defect_b = alloc_array(n, sizeof(int32_t), &failed);
    t->defect_c = alloc_array(n, sizeof(int32_t), &failed);
    for (size_t i = 0; !failed && i < n; i++) {
        t->defect_kind[i] = (int8_t)r->defects[i].kind;
        t->defect_a[i] = (int32_t)r->defects[i].a;
        t->defect_b[i] = (int32_t)r->defects[i].b;
        t->defect_c[i] = (int32_t)r->defects[i].c;
    }
    if (failed) {
        mtd_topology_free(t);
        return -1;
    }
    return 0;
}

void mtd_topology_free(meshtopo_topology_t *t)
{
    if (!t) return;
    void *arrays[] = {t->mesh_id,
                      t->source,
                      t->boundary_loop_lengths,
                      t->component_min_face,
                      t->component_faces,
                      t->component_vertices,
                      t->component_edges,
                      t->component_euler_characteristic,
                      t->component_boundary_edges,
                      t->component_boundary_loops,
                      t->component_closed,
                      t->component_manifold,
                      t->component_orientable,
                      t->component_genus,
                      t->component_genus_with_boundary,
                      t->face_size_keys,
                      t->face_size_counts,
                      t->edge_use_keys,
                      t->edge_use_counts,
                      t->defect_kind,
                      t->defect_a,
                      t->defect_b,
                      t->defect_c};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
    memset(t, 0, sizeof *t);
}
