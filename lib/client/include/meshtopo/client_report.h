/* meshtopo::client: a topology report from meshtopod (topology_t, in an ack
 * or a REPORT reply, or a TOPOLOGY broadcast) as the core's mt_report, so
 * every reader of a daemon's report reads the same type as a local build's
 * (and writes it with the same JSON summary, meshtopo/report_json.h). */
#ifndef MESHTOPO_CLIENT_REPORT_H
#define MESHTOPO_CLIENT_REPORT_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/msgs.h"
#include "meshtopo/report.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_client_report {
    /* The counts as the build computed them. The daemon may list fewer
     * entries than its counts say (topology_t *_listed): the lists hold the
     * entries below, and report.num_defects counts the listed defects. */
    mt_report report;
    size_t num_loop_lengths;    /* entries of report.boundary_loop_lengths, <= boundary_loops */
    size_t num_components;      /* entries of report.components, <= connected_components */
    uint64_t num_defects_found; /* every defect of the mesh, >= report.num_defects */
} mt_client_report;

/* Converts meshtopod's report into *out: counts and lists into the core's
 * types, ids as the 32 bits they carry (topology_t.lcm). Data from the
 * network is checked: a negative count or a list longer than its count
 * gives MT_ERR_CORRUPT naming the field in diag; MT_ERR_NOMEM. *out is
 * zeroed on failure. Release it with mt_client_report_free. */
mt_status mt_client_report_from_topology(const meshtopo_topology_t *t, mt_client_report *out,
                                         mt_diag *diag);

/* Releases the lists of a converted report and zeroes it. NULL-safe; fine
 * on a zeroed report. */
void mt_client_report_free(mt_client_report *report);

#ifdef __cplusplus
}
#endif

#endif
