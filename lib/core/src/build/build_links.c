/* Phase "links" of a build (build_state.h): one pass over the valid faces
 * sets the next of every face half-edge, each face's first half-edge and,
 * for the fans phase, one face half-edge leaving each vertex. Split by face
 * range: each part writes only the half-edges of its own corners; two parts
 * may both offer a vertex's fan start, and either will do. */
#include <stdatomic.h>

#include "build/build_phases.h"

/* The faces of part t. */
static void link_part(mt__build *b, uint32_t t)
{
    const mt__part *p = &b->part[t];
    mt_mesh *m = b->m;
    const uint32_t *sizes = b->in->face_sizes, *indices = b->in->face_indices, *c2h = b->c2h;
    uint32_t *he_next = m->he_next;
    _Atomic uint32_t *fan_start = b->fan_start;
    uint32_t offset = p->index_begin;
    for (uint32_t f = p->face_begin; f < p->face_end; f++) {
        const uint32_t n = sizes[f];
        if (m->face_he[f] == MT_NONE) {
            offset += n;
            continue;
        }
        const uint32_t *idx = indices + offset;
        const uint32_t *hs = c2h + offset;
        const uint32_t first = mt__edge_gap(b, hs[0]);
        uint32_t h = first;
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t next_i = i + 1 < n ? i + 1 : 0;
            const uint32_t hn = next_i ? mt__edge_gap(b, hs[next_i]) : first;
            he_next[h] = hn;
            atomic_store_explicit(&fan_start[idx[i]], h, memory_order_relaxed);
            h = hn;
        }
        m->face_he[f] = first;
        offset += n;
    }
}

void mt__build_links(mt__build *b)
{
    mt__parallel_run(b, link_part);
}
