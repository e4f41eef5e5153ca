/* A topology report as the CLI prints it: the core's mt_report, how much of
 * its lists is present and, for a report from meshtopod, where it came from.
 * cli_report_from_topology takes a topology_t's report fields from the
 * client library (mt_client_report_from_topology); every printer of a
 * report reads an cli_report. */
#ifndef MESHTOPO_CLI_REPORT_H
#define MESHTOPO_CLI_REPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "meshtopo/client_report.h"
#include "meshtopo/json_writer.h"
#include "meshtopo/msgs.h"
#include "meshtopo/report.h"
#include "meshtopo/report_json.h"
#include "meshtopo/status.h"

typedef struct cli_report {
    /* The counts as the build computed them. A report published by meshtopod
     * may list fewer entries than its counts say (topology_t *_listed): the
     * lists hold the entries below, and report.num_defects counts the listed
     * defects. */
    mt_report report;
    size_t num_loop_lengths;    /* entries of report.boundary_loop_lengths, <= boundary_loops */
    size_t num_components;      /* entries of report.components, <= connected_components */
    uint64_t num_defects_found; /* every defect of the mesh, >= report.num_defects */

    /* Provenance of a report from meshtopod (NULL / 0 for a local one). */
    const char *mesh_id;
    int32_t version;
    const char *source;
    int64_t content_hash;
    int64_t build_duration_us;
    bool owned; /* the lists are this struct's (cli_report_free releases them) */
} cli_report;

/* Converts meshtopod's report into *out: counts and lists into the core's
 * types, ids as the 32 bits they carry (topology_t.lcm), the strings
 * borrowed from t (which must outlive *out). Data from the network is
 * checked: a negative count or a list longer than its count gives
 * MT_ERR_CORRUPT naming the field in diag; MT_ERR_NOMEM. *out is zeroed on
 * failure. Release it with cli_report_free. */
mt_status cli_report_from_topology(const meshtopo_topology_t *t, cli_report *out, mt_diag *diag);

/* cli_report_from_topology for a command: on failure prints "meshtopo
 * COMMAND: mesh 'ID': unusable report from meshtopod: REASON" and returns
 * CLI_EXIT_REFUSED, else CLI_EXIT_OK. */
int cli_report_take(const char *command, const meshtopo_topology_t *t, cli_report *out);

/* A locally built report seen as a complete cli_report (nothing copied:
 * r must outlive the result; nothing to free). */
cli_report cli_report_local(const mt_report *r);

/* Releases what cli_report_from_topology allocated and zeroes *report.
 * NULL-safe; fine on a zeroed or local report. */
void cli_report_free(cli_report *report);

/* ---- Printers (cli_report_text.c, cli_report_json.c) ------------------- */

/* Readable report from meshtopod (send, query report): provenance, counts,
 * boundary, components, flags, defect counts per kind. */
void cli_report_print_text(const cli_report *r, FILE *out);

/* The same on one line, after the channel it came on (watch). */
void cli_report_print_line(const cli_report *r, const char *channel, FILE *out);

/* The report from meshtopod as one JSON object: provenance, the summary
 * (mt_report_json_write_summary) with MT_REPORT_JSON_KEYS_DAEMON, num_defects and the listed
 * defects {kind, a, b, c}. false when out of memory. */
bool cli_report_write_json(mt_json *j, const cli_report *r);

#endif
