/* The readable forms of a report from meshtopod (an ack, a REPORT reply, a
 * TOPOLOGY message): the summary `send` and `query report` print, and the
 * one line per build of `watch`. Both read the converted cli_report
 * (cli_report.c); numbers print as the daemon sent them. */
#include <inttypes.h>

#include "cli_report.h"
#include "remote.h"

static const char *yes_no(bool b)
{
    return b ? "yes" : "no";
}

static const char *defect_name(uint32_t kind)
{
    return kind < MT_DEFECT_KIND_COUNT ? mt_defect_key((mt_defect_kind)kind) : "unknown";
}

void cli_report_print_text(const cli_report *cr, FILE *out)
{
    const mt_report *r = &cr->report;
    char hash[24];
    fprintf(out, "mesh %s version %" PRId32 " (source %s, content hash %s, built in %.3f ms)\n",
            cr->mesh_id, cr->version, cr->source,
            cli_hash_text(cr->content_hash, hash, sizeof hash),
            (double)cr->build_duration_us / 1000.0);
    fprintf(out,
            "counts: V %" PRIu32 ", F %" PRIu32 " (%" PRIu32 " valid), E %" PRIu64
            ", half-edges %" PRIu64 "\n",
            r->num_verts, r->num_faces, r->num_faces_valid, r->num_edges, r->num_half_edges);
    fprintf(out, "boundary: %" PRIu64 " edges in %" PRIu32 " loops%s", r->boundary_edges,
            r->boundary_loops, r->boundary_loops_ambiguous ? " (ambiguous)" : "");
    if (cr->num_loop_lengths > 0) {
        fprintf(out, "; lengths");
        for (size_t i = 0; i < cr->num_loop_lengths; i++)
            fprintf(out, "%s %" PRIu32, i ? "," : "", r->boundary_loop_lengths[i]);
    }
    fputc('\n', out);
    fprintf(out,
            "components: %" PRIu32 " (by edges), %" PRIu32
            " (by vertices); Euler "
            "characteristic %" PRId64 "; genus ",
            r->connected_components, r->vertex_connected_components, r->euler_characteristic);
    if (r->genus < 0)
        fprintf(out, "undefined\n");
    else
        fprintf(out, "%" PRId32 "\n", r->genus);
    fprintf(out, "closed %s, manifold %s, orientable %s, consistently oriented %s\n",
            yes_no(r->closed), yes_no(r->manifold), yes_no(r->orientable),
            yes_no(r->consistently_oriented));
    if (cr->num_defects_found == 0) {
        fprintf(out, "defects: none\n");
        return;
    }
    fprintf(out, "defects: %" PRIu64, cr->num_defects_found);
    /* count per kind over the listed ones (grouped by kind) */
    size_t i = 0;
    while (i < r->num_defects) {
        size_t k = i;
        while (k < r->num_defects && r->defects[k].kind == r->defects[i].kind) k++;
        fprintf(out, "%s %zu %s", i ? "," : ":", k - i, defect_name(r->defects[i].kind));
        i = k;
    }
    if (r->num_defects < cr->num_defects_found) fprintf(out, " (%zu listed)", r->num_defects);
    fputc('\n', out);
}

void cli_report_print_line(const cli_report *cr, const char *channel, FILE *out)
{
    const mt_report *r = &cr->report;
    fprintf(out,
            "%s %s version %" PRId32 ": V %" PRIu32 ", F %" PRIu32 " (%" PRIu32
            " valid), E %" PRIu64 "; %" PRIu64 " boundary edges in %" PRIu32 " loops; %" PRIu32
            " components; Euler characteristic %" PRId64 "; %s, %s, %s; %" PRIu64
            " defects; built in %.3f ms\n",
            channel, cr->mesh_id, cr->version, r->num_verts, r->num_faces, r->num_faces_valid,
            r->num_edges, r->boundary_edges, r->boundary_loops, r->connected_components,
            r->euler_characteristic, r->closed ? "closed" : "open",
            r->manifold ? "manifold" : "non-manifold",
            r->orientable ? "orientable" : "non-orientable", cr->num_defects_found,
            (double)cr->build_duration_us / 1000.0);
}
