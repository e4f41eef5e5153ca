/* The summary of a topology report as JSON members (report_json.h): the
 * corpus answers' keys in their order (tests/corpus/DEFINITIONS.md), for
 * `inspect --json`, the Python binding and the CLI's reports from
 * meshtopod, where each form adds its own few keys; undefined genera are
 * null. */
#include <stdio.h>
#include <stdlib.h>

#include "meshtopo/report_json.h"
#include "report_json_internal.h"

enum { LIST_HEAD = 20 }; /* length of nonmanifold_vertices_list_head */

static void write_histogram(mt_json *j, const mt_histogram_bin *bins, size_t count)
{
    mt_json_object_begin(j);
    for (size_t i = 0; i < count; i++) {
        char key[16];
        snprintf(key, sizeof key, "%u", (unsigned)bins[i].key);
        mt_json_key(j, key);
        mt_json_uint(j, bins[i].count);
    }
    mt_json_object_end(j);
}

static void write_genus(mt_json *j, int32_t genus)
{
    if (genus < 0)
        mt_json_null(j);
    else
        mt_json_int(j, genus);
}

static void write_uint(mt_json *j, const char *key, uint64_t value)
{
    mt_json_key(j, key);
    mt_json_uint(j, value);
}

static void write_bool(mt_json *j, const char *key, bool value)
{
    mt_json_key(j, key);
    mt_json_bool(j, value);
}

static void write_nonmanifold_head(mt_json *j, const mt_report *r)
{
    uint32_t head[LIST_HEAD];
    size_t n = 0;
    /* The defect list is sorted by kind, then id; keep the smallest anyway. */
    for (size_t i = 0; i < r->num_defects; i++) {
        if (r->defects[i].kind != MT_DEFECT_NONMANIFOLD_VERTEX) continue;
        uint32_t v = r->defects[i].a;
        if (n < LIST_HEAD) {
            head[n++] = v;
        } else {
            size_t max = 0;
            for (size_t k = 1; k < n; k++)
                if (head[k] > head[max]) max = k;
            if (v < head[max]) head[max] = v;
        }
    }
    n = mt__json_sort_unique(head, n);
    mt__json_write_ids(j, head, n);
}

static int compare_genus(const void *a, const void *b)
{
    /* ascending, undefined (-1) last */
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    if (x < 0 || y < 0) return (x < 0) - (y < 0);
    return (x > y) - (x < y);
}

static bool write_component_genera(mt_json *j, const mt_report *r, size_t num_components)
{
    int32_t *g = calloc(num_components + 1, sizeof *g);
    if (!g) return false;
    for (size_t i = 0; i < num_components; i++) g[i] = r->components[i].genus;
    qsort(g, num_components, sizeof *g, compare_genus);
    mt_json_array_begin(j);
    for (size_t i = 0; i < num_components; i++) write_genus(j, g[i]);
    mt_json_array_end(j);
    free(g);
    return true;
}

static void write_component(mt_json *j, const mt_component_info *c)
{
    mt_json_object_begin(j);
    write_uint(j, "faces", c->faces);
    write_uint(j, "vertices", c->vertices);
    write_uint(j, "edges", c->edges);
    mt_json_key(j, "euler_characteristic");
    mt_json_int(j, c->euler_characteristic);
    write_uint(j, "boundary_edges", c->boundary_edges);
    write_uint(j, "boundary_loops", c->boundary_loops);
    write_bool(j, "closed", c->closed);
    write_bool(j, "manifold", c->manifold);
    write_bool(j, "orientable", c->orientable);
    mt_json_key(j, "genus");
    write_genus(j, c->genus);
    mt_json_key(j, "genus_with_boundary");
    write_genus(j, c->genus_with_boundary);
    write_uint(j, "min_face_index", c->min_face);
    mt_json_object_end(j);
}

bool mt_report_json_write_summary(mt_json *j, const mt_report *r, size_t num_loop_lengths,
                                  size_t num_components, mt_report_json_keys keys)
{
    bool corpus = keys == MT_REPORT_JSON_KEYS_CORPUS, daemon = keys == MT_REPORT_JSON_KEYS_DAEMON;
    write_uint(j, "V", r->num_verts);
    write_uint(j, "F", r->num_faces);
    write_uint(j, "F_valid", r->num_faces_valid);
    write_uint(j, "E", r->num_edges);
    write_uint(j, "half_edges", r->num_half_edges);
    mt_json_key(j, "face_size_histogram");
    write_histogram(j, r->face_size_histogram, r->num_face_size_bins);
    mt_json_key(j, "edge_use_histogram");
    write_histogram(j, r->edge_use_histogram, r->num_edge_use_bins);
    write_uint(j, "boundary_edges", r->boundary_edges);
    mt_json_key(j, "boundary_loops");
    mt_json_object_begin(j);
    write_uint(j, "count", r->boundary_loops);
    mt_json_key(j, "lengths");
    mt__json_write_ids(j, r->boundary_loop_lengths, num_loop_lengths);
    write_bool(j, "ambiguous", r->boundary_loops_ambiguous);
    mt_json_object_end(j);
    write_uint(j, "nonmanifold_edges", r->nonmanifold_edges);
    write_uint(j, "inconsistent_orientation_edges", r->inconsistent_orientation_edges);
    write_uint(j, "duplicate_directed_edges", r->duplicate_directed_edges);
    write_uint(j, "nonmanifold_vertices", r->nonmanifold_vertices);
    if (corpus) {
        mt_json_key(j, "nonmanifold_vertices_list_head");
        write_nonmanifold_head(j, r);
    }
    write_uint(j, "bowtie_vertices", r->bowtie_vertices);
    write_uint(j, "isolated_vertices", r->isolated_vertices);
    write_uint(j, "unreferenced_vertices", r->unreferenced_vertices);
    write_uint(j, "degenerate_faces", r->degenerate_faces);
    if (daemon) write_uint(j, "duplicate_faces", r->duplicate_faces);
    write_uint(j, "out_of_range_indices", r->out_of_range_indices);
    write_uint(j, "faces_with_out_of_range_indices", r->faces_with_out_of_range_indices);
    if (daemon) write_uint(j, "nonfinite_vertices", r->nonfinite_vertices);
    write_uint(j, "connected_components", r->connected_components);
    write_uint(j, "vertex_connected_components", r->vertex_connected_components);
    mt_json_key(j, "euler_characteristic");
    mt_json_int(j, r->euler_characteristic);
    write_bool(j, "closed", r->closed);
    write_bool(j, "manifold", r->manifold);
    write_bool(j, "orientable", r->orientable);
    write_bool(j, "consistently_oriented", r->consistently_oriented);
    mt_json_key(j, "genus");
    write_genus(j, r->genus);
    if (corpus) {
        mt_json_key(j, "component_genera");
        if (!write_component_genera(j, r, num_components)) return false;
    }
    mt_json_key(j, "components");
    mt_json_array_begin(j);
    for (size_t i = 0; i < num_components; i++) write_component(j, &r->components[i]);
    mt_json_array_end(j);
    return true;
}
