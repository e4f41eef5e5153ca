/* Printing a topology_t report received from meshtopod (an ack, a REPORT
 * reply, a TOPOLOGY message): the readable summary and the JSON object. The
 * JSON keys are those of the corpus answers (shared/corpus/DEFINITIONS.md)
 * where the report carries the same quantity; undefined genera are null. */
#include <inttypes.h>

#include "meshtopo/report.h"
#include "remote.h"

static const char *yes_no(int8_t b)
{
    return b ? "yes" : "no";
}

static const char *defect_name(int8_t kind)
{
    return kind >= 0 && kind < MT_DEFECT_KIND_COUNT ? mt_defect_key((mt_defect_kind)kind)
                                                    : "unknown";
}

void mt_cli_topology_print_text(const meshtopo_topology_t *t, FILE *out)
{
    char hash[24];
    fprintf(out, "mesh %s version %" PRId32 " (source %s, content hash %s, built in %.3f ms)\n",
            t->mesh_id, t->version, t->source, mt_cli_hash_text(t->content_hash, hash, sizeof hash),
            (double)t->build_duration_us / 1000.0);
    fprintf(out,
            "counts: V %" PRId32 ", F %" PRId32 " (%" PRId32 " valid), E %" PRId64
            ", half-edges %" PRId64 "\n",
            t->num_verts, t->num_faces, t->num_faces_valid, t->num_edges, t->num_half_edges);
    fprintf(out, "boundary: %" PRId64 " edges in %" PRId32 " loops%s", t->boundary_edges,
            t->boundary_loops, t->boundary_loops_ambiguous ? " (ambiguous)" : "");
    if (t->num_boundary_loop_lengths > 0) {
        fprintf(out, "; lengths");
        for (int32_t i = 0; i < t->num_boundary_loop_lengths; i++)
            fprintf(out, "%s %" PRId32, i ? "," : "", t->boundary_loop_lengths[i]);
    }
    fputc('\n', out);
    fprintf(out,
            "components: %" PRId32 " (by edges), %" PRId32
            " (by vertices); Euler "
            "characteristic %" PRId64 "; genus ",
            t->connected_components, t->vertex_connected_components, t->euler_characteristic);
    if (t->genus < 0)
        fprintf(out, "undefined\n");
    else
        fprintf(out, "%" PRId32 "\n", t->genus);
    fprintf(out, "closed %s, manifold %s, orientable %s, consistently oriented %s\n",
            yes_no(t->closed), yes_no(t->manifold), yes_no(t->orientable),
            yes_no(t->consistently_oriented));
    if (t->num_defects == 0) {
        fprintf(out, "defects: none\n");
        return;
    }
    fprintf(out, "defects: %" PRId64, t->num_defects);
    /* count per kind over the listed ones (grouped by kind) */
    int32_t i = 0;
    while (i < t->num_defects_listed) {
        int32_t k = i;
        while (k < t->num_defects_listed && t->defect_kind[k] == t->defect_kind[i]) k++;
        fprintf(out, "%s %" PRId32 " %s", i ? "," : ":", k - i, defect_name(t->defect_kind[i]));
        i = k;
    }
    if (t->num_defects_listed < t->num_defects)
        fprintf(out, " (%" PRId32 " listed)", t->num_defects_listed);
    fputc('\n', out);
}

static void write_genus(mt_json *j, int32_t genus)
{
    if (genus < 0)
        mt_json_null(j);
    else
        mt_json_int(j, genus);
}

static void write_histogram(mt_json *j, const int32_t *keys, const int64_t *counts, int32_t n)
{
    mt_json_object_begin(j);
    for (int32_t i = 0; i < n; i++) {
        char key[16];
        snprintf(key, sizeof key, "%" PRId32, keys[i]);
        mt_json_key(j, key);
        mt_json_int(j, counts[i]);
    }
    mt_json_object_end(j);
}

static void write_count(mt_json *j, const char *key, int64_t value)
{
    mt_json_key(j, key);
    mt_json_int(j, value);
}

static void write_flag(mt_json *j, const char *key, int8_t value)
{
    mt_json_key(j, key);
    mt_json_bool(j, value != 0);
}

void mt_cli_topology_write_json(mt_json *j, const meshtopo_topology_t *t)
{
    char hash[24];
    mt_json_object_begin(j);
    mt_json_key(j, "mesh_id");
    mt_json_string(j, t->mesh_id);
    write_count(j, "version", t->version);
    mt_json_key(j, "source");
    mt_json_string(j, t->source);
    mt_json_key(j, "content_hash");
    mt_json_string(j, mt_cli_hash_text(t->content_hash, hash, sizeof hash));
    write_count(j, "build_duration_us", t->build_duration_us);
    write_count(j, "V", t->num_verts);
    write_count(j, "F", t->num_faces);
    write_count(j, "F_valid", t->num_faces_valid);
    write_count(j, "E", t->num_edges);
    write_count(j, "half_edges", t->num_half_edges);
    mt_json_key(j, "face_size_histogram");
    write_histogram(j, t->face_size_keys, t->face_size_counts, t->num_face_size_bins);
    mt_json_key(j, "edge_use_histogram");
    write_histogram(j, t->edge_use_keys, t->edge_use_counts, t->num_edge_use_bins);
    write_count(j, "boundary_edges", t->boundary_edges);
    /* as in the corpus answers: {"count", "lengths" (ascending), "ambiguous"} */
    mt_json_key(j, "boundary_loops");
    mt_json_object_begin(j);
    write_count(j, "count", t->boundary_loops);
    mt_json_key(j, "lengths");
    mt_json_array_begin(j);
    for (int32_t i = 0; i < t->num_boundary_loop_lengths; i++)
        mt_json_int(j, t->boundary_loop_lengths[i]);
    mt_json_array_end(j);
    write_flag(j, "ambiguous", t->boundary_loops_ambiguous);
    mt_json_object_end(j);
    write_count(j, "nonmanifold_edges", t->nonmanifold_edges);
    write_count(j, "inconsistent_orientation_edges", t->inconsistent_orientation_edges);
    write_count(j, "duplicate_directed_edges", t->duplicate_directed_edges);
    write_count(j, "nonmanifold_vertices", t->nonmanifold_vertices);
    write_count(j, "bowtie_vertices", t->bowtie_vertices);
    write_count(j, "isolated_vertices", t->isolated_vertices);
    write_count(j, "unreferenced_vertices", t->unreferenced_vertices);
    write_count(j, "degenerate_faces", t->degenerate_faces);
    write_count(j, "duplicate_faces", t->duplicate_faces);
    write_count(j, "out_of_range_indices", t->out_of_range_indices);
    write_count(j, "faces_with_out_of_range_indices", t->faces_with_out_of_range_indices);
    write_count(j, "nonfinite_vertices", t->nonfinite_vertices);
    write_count(j, "connected_components", t->connected_components);
    write_count(j, "vertex_connected_components", t->vertex_connected_components);
    write_count(j, "euler_characteristic", t->euler_characteristic);
    write_flag(j, "closed", t->closed);
    write_flag(j, "manifold", t->manifold);
    write_flag(j, "orientable", t->orientable);
    write_flag(j, "consistently_oriented", t->consistently_oriented);
    mt_json_key(j, "genus");
    write_genus(j, t->genus);
    mt_json_key(j, "components");
    mt_json_array_begin(j);
    for (int32_t i = 0; i < t->num_components_listed; i++) {
        mt_json_object_begin(j);
        write_count(j, "faces", t->component_faces[i]);
        write_count(j, "vertices", t->component_vertices[i]);
        write_count(j, "edges", t->component_edges[i]);
        write_count(j, "euler_characteristic", t->component_euler_characteristic[i]);
        write_count(j, "boundary_edges", t->component_boundary_edges[i]);
        write_count(j, "boundary_loops", t->component_boundary_loops[i]);
        write_flag(j, "closed", t->component_closed[i]);
        write_flag(j, "manifold", t->component_manifold[i]);
        write_flag(j, "orientable", t->component_orientable[i]);
        mt_json_key(j, "genus");
        write_genus(j, t->component_genus[i]);
        mt_json_key(j, "genus_with_boundary");
        write_genus(j, t->component_genus_with_boundary[i]);
        write_count(j, "min_face_index", t->component_min_face[i]);
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    write_count(j, "num_defects", t->num_defects);
    mt_json_key(j, "defects");
    mt_json_array_begin(j);
    for (int32_t i = 0; i < t->num_defects_listed; i++) {
        mt_json_object_begin(j);
        mt_json_key(j, "kind");
        mt_json_string(j, defect_name(t->defect_kind[i]));
        write_count(j, "a", t->defect_a[i]);
        write_count(j, "b", t->defect_b[i]);
        write_count(j, "c", t->defect_c[i]);
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    mt_json_object_end(j);
}
