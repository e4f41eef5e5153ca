/* Entry points of the build's own phases (faces, edges, links, fans; see
 * build_state.h), which build.c runs in that order. Each phase reads and
 * writes only the state of build_state.h; none calls another. */
#ifndef MESHTOPO_BUILD_PHASES_H
#define MESHTOPO_BUILD_PHASES_H

#include "build/build_state.h"

mt_status mt__build_faces(mt__build *b);
mt_status mt__build_edges(mt__build *b);
/* Moves the heads and faces of the half-edges, left in the blocks by
 * mt__build_edges, into the mesh's arrays (allocated meanwhile). */
void mt__build_edges_publish(mt__build *b);
/* Sets next of every face half-edge, each face's first half-edge and a
 * fan start per vertex (m->vert_he and b->fan_start allocated by the caller). */
void mt__build_links(mt__build *b);
mt_status mt__build_fans(mt__build *b);

#endif
