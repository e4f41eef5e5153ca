/* meshtopod's topology_t as an mt_cli_report for every printer of the CLI
 * (see cli_report.h): the client library converts the report
 * (mt_client_report_from_topology checks what came from the network), this
 * adds the provenance. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_report.h"

mt_status mt_cli_report_from_topology(const meshtopo_topology_t *t, mt_cli_report *out,
                                      mt_diag *diag)
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

int mt_cli_report_take(const char *command, const meshtopo_topology_t *t, mt_cli_report *out)
{
    mt_diag diag;
    mt_status st = mt_cli_report_from_topology(t, out, &diag);
    if (st == MT_OK) return MT_CLI_EXIT_OK;
    mt_cli_error(command, "mesh '%s': unusable report from meshtopod: %s", t->mesh_id,
                 diag.message[0] ? diag.message : mt_strerror(st));
    return MT_CLI_EXIT_REFUSED;
}

mt_cli_report mt_cli_report_local(const mt_report *r)
{
    mt_cli_report out;
    memset(&out, 0, sizeof out);
    out.report = *r;
    out.num_loop_lengths = r->boundary_loops;
    out.num_components = r->connected_components;
    out.num_defects_found = r->num_defects;
    return out;
}

void mt_cli_report_free(mt_cli_report *report)
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
