/* The report phase of a build (report.c and its parts, report_*.c): reads
 * the build's state (build/build_state.h) once the fans are made and fills
 * the mesh's mt_report. build.c runs it last. */
#ifndef MESHTOPO_REPORT_INTERNAL_H
#define MESHTOPO_REPORT_INTERNAL_H

#include "build/build_state.h"

mt_status mt__build_report(mt__build *b);

/* Parts of the report, called by mt__build_report in order. */
mt_status mt__report_components(mt__build *b);  /* components, per-component counts */
mt_status mt__report_boundary(mt__build *b);    /* boundary-edge graph: loops, lengths */
mt_status mt__report_links(mt__build *b);       /* vertex links: non-manifold, bowtie */
mt_status mt__report_orientation(mt__build *b); /* orientability per component */
mt_status mt__report_duplicates(mt__build *b);  /* duplicate faces */

#endif
