/* A report as JSON, for `inspect --json` and for the reports of meshtopod
 * (send, query report, watch): one summary writer with the corpus answers'
 * keys in their order (shared/corpus/DEFINITIONS.md), where each form adds
 * its own few keys (cli_report.h); undefined genera are null. The daemon's
 * form wraps it with provenance and the listed defects. */
#include <stdlib.h>

#include "cli_report.h"
#include "inspect.h"
#include "remote.h"

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

static void write_ids(mt_json *j, const uint32_t *ids, size_t count)
{
    mt_json_array_begin(j);
    for (size_t i = 0; i < count; i++) mt_json_uint(j, ids[i]);
    mt_json_array_end(j);
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
    n = mt_inspect_sort_unique(head, n);
    write_ids(j, head, n);
}

static int compare_genus(const void *a, const void *b)
{
    /* ascending, undefined (-1) last */
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    if (x < 0 || y < 0) return (x < 0) - (y < 0);
    return (x > y) - (x < y);
}

static bool write_component_genera(mt_json *j, const mt_cli_report *cr)
{
    int32_t *g = calloc(cr->num_components + 1, sizeof *g);
    if (!g) return false;
    for (size_t i = 0; i < cr->num_components; i++) g[i] = cr->report.components[i].genus;
    qsort(g, cr->num_components, sizeof *g, compare_genus);
    mt_json_array_begin(j);
    for (size_t i = 0; i < cr->num_components; i++) write_genus(j, g[i]);
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

bool mt_cli_report_write_summary(mt_json *j, const mt_cli_report *cr, mt_cli_report_keys keys)
{
    const mt_report *r = &cr->report;
    bool corpus = keys == MT_CLI_REPORT_KEYS_CORPUS, daemon = keys == MT_CLI_REPORT_KEYS_DAEMON;
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
    write_ids(j, r->boundary_loop_lengths, cr->num_loop_lengths);
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
        if (!write_component_genera(j, cr)) return false;
    }
    mt_json_key(j, "components");
    mt_json_array_begin(j);
    for (size_t i = 0; i < cr->num_components; i++) write_component(j, &r->components[i]);
    mt_json_array_end(j);
    return true;
}

bool mt_cli_report_write_json(mt_json *j, const mt_cli_report *cr)
{
    const mt_report *r = &cr->report;
    char hash[24];
    mt_json_object_begin(j);
    mt_json_key(j, "mesh_id");
    mt_json_string(j, cr->mesh_id);
    mt_json_key(j, "version");
    mt_json_int(j, cr->version);
    mt_json_key(j, "source");
    mt_json_string(j, cr->source);
    mt_json_key(j, "content_hash");
    mt_json_string(j, mt_cli_hash_text(cr->content_hash, hash, sizeof hash));
    mt_json_key(j, "build_duration_us");
    mt_json_int(j, cr->build_duration_us);
    bool ok = mt_cli_report_write_summary(j, cr, MT_CLI_REPORT_KEYS_DAEMON);
    write_uint(j, "num_defects", cr->num_defects_found);
    mt_json_key(j, "defects");
    mt_json_array_begin(j);
    for (size_t i = 0; i < r->num_defects; i++) {
        const mt_defect *d = &r->defects[i];
        mt_json_object_begin(j);
        mt_json_key(j, "kind");
        mt_json_string(
            j, d->kind < MT_DEFECT_KIND_COUNT ? mt_defect_key((mt_defect_kind)d->kind) : "unknown");
        /* as the wire's int32: "no element" reads -1 */
        mt_json_key(j, "a");
        mt_json_int(j, (int32_t)d->a);
        mt_json_key(j, "b");
        mt_json_int(j, (int32_t)d->b);
        mt_json_key(j, "c");
        mt_json_int(j, (int32_t)d->c);
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    mt_json_object_end(j);
    return ok;
}
