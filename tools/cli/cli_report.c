/* meshtopod's topology_t as an cli_report for every printer of the CLI
 * (see cli_report.h): the client library converts the report
 * (mt_client_report_from_topology checks what came from the network), this
 * adds the provenance. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_report.h"

mt_status cli_report_from_topology(const meshtopo_topology_t *t, cli_report *out, mt_diag *diag)
{
    memset(out, 0, sizeof *out);
    mt_client_report converted;
    mt_status st = mt_client_report_from_topology(t, &converted, diag);
    if (st != MT_OK) return st;
    out->report = converted.report;
    out->num_loop_lengths = converted.num_loop_lengths;
    out->num_components = converted.num_components;
    out->num_defects_found = converted.num_defects_found;
    out->owned = true;
    out->mesh_id = t->mesh_id;
    out->version = t->version;
    out->source = t->source;
    out->content_hash = t->content_hash;
    out->build_duration_us = t->build_duration_us;
    return MT_OK;
}

int cli_report_take(const char *command, const meshtopo_topology_t *t, cli_report *out)
{
    mt_diag diag;
    mt_status st = cli_report_from_topology(t, out, &diag);
    if (st == MT_OK) return CLI_EXIT_OK;
    cli_error(command, "mesh '%s': unusable report from meshtopod: %s", t->mesh_id,
              diag.message[0] ? diag.message : mt_strerror(st));
    return CLI_EXIT_REFUSED;
}

cli_report cli_report_local(const mt_report *r)
{
    cli_report out;
    memset(&out, 0, sizeof out);
    out.report = *r;
    out.num_loop_lengths = r->boundary_loops;
    out.num_components = r->connected_components;
    out.num_defects_found = r->num_defects;
    return out;
}

void cli_report_free(cli_report *report)
{
    if (!report) return;
    if (report->owned) {
        free(report->report.boundary_loop_lengths);
        free(report->report.components);
        free(report->report.face_size_histogram);
        free(report->report.edge_use_histogram);
        free(report->report.defects);
    }
    memset(report, 0, sizeof *report);
}
