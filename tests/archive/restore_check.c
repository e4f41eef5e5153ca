/* rc_same_answers: every public query asked of two meshes, answers
 * compared element by element (see restore_check.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/archive.h"
#include "meshtopo/core.h"
#include "restore_check.h"

static bool differ(const char *what, const char *query, uint32_t id)
{
    printf("%s: %s of %u differs between the two meshes\n", what, query, id);
    return false;
}

/* One vertex's ring on one mesh, in freshly sized buffers. */
static mt_status ring_of(const mt_mesh *m, uint32_t v, mt_ring *r)
{
    memset(r, 0, sizeof *r);
    mt_status st = mt_vert_ring(m, v, r);
    if (st != MT_OK && st != MT_ERR_BUFFER_TOO_SMALL) return st;
    r->neighbors = calloc(r->num_neighbors + 1, sizeof *r->neighbors);
    r->faces = calloc(r->num_faces + 1, sizeof *r->faces);
    r->fans = calloc(r->num_fans + 1, sizeof *r->fans);
    r->neighbors_capacity = r->num_neighbors;
    r->faces_capacity = r->num_faces;
    r->fans_capacity = r->num_fans;
    return mt_vert_ring(m, v, r);
}

static void ring_free(mt_ring *r)
{
    free(r->neighbors);
    free(r->faces);
    free(r->fans);
}

static bool same_ring(const mt_mesh *a, const mt_mesh *b, uint32_t v)
{
    mt_ring ra, rb;
    mt_status sa = ring_of(a, v, &ra), sb = ring_of(b, v, &rb);
    bool same = sa == sb && ra.num_neighbors == rb.num_neighbors && ra.num_faces == rb.num_faces &&
                ra.num_fans == rb.num_fans;
    if (same && sa == MT_OK)
        same = memcmp(ra.neighbors, rb.neighbors, ra.num_neighbors * sizeof(uint32_t)) == 0 &&
               memcmp(ra.faces, rb.faces, ra.num_faces * sizeof(uint32_t)) == 0;
    for (size_t i = 0; same && sa == MT_OK && i < ra.num_fans; i++)
        same = ra.fans[i].neighbor_begin == rb.fans[i].neighbor_begin &&
               ra.fans[i].neighbor_count == rb.fans[i].neighbor_count &&
               ra.fans[i].face_begin == rb.fans[i].face_begin &&
               ra.fans[i].face_count == rb.fans[i].face_count &&
               ra.fans[i].boundary == rb.fans[i].boundary;
    uint32_t va = 0, vb = 0;
    if (same) same = mt_vert_valence(a, v, &va) == mt_vert_valence(b, v, &vb) && va == vb;
    ring_free(&ra);
    ring_free(&rb);
    return same;
}

/* Face vertices, neighbours, component and the faces of each side. */
static bool same_face(const mt_mesh *a, const mt_mesh *b, uint32_t f)
{
    size_t na = 0, nb = 0;
    mt_status sa = mt_face_verts(a, f, NULL, 0, &na), sb = mt_face_verts(b, f, NULL, 0, &nb);
    if (sa != sb || na != nb) return false;
    if (sa != MT_OK && sa != MT_ERR_BUFFER_TOO_SMALL) return true; /* a rejected record in both */
    uint32_t *va = calloc(na + 1, sizeof *va), *vb = calloc(nb + 1, sizeof *vb);
    bool same = mt_face_verts(a, f, va, na, &na) == MT_OK &&
                mt_face_verts(b, f, vb, nb, &nb) == MT_OK && memcmp(va, vb, na * sizeof *va) == 0;
    size_t fa = 0, fb = 0, ea = 0, eb = 0;
    uint32_t *offa = calloc(na + 2, sizeof *offa), *offb = calloc(nb + 2, sizeof *offb);
    if (same) {
        mt_face_neighbors(a, f, NULL, 0, offa, na + 1, &fa, &ea);
        mt_face_neighbors(b, f, NULL, 0, offb, nb + 1, &fb, &eb);
        same = fa == fb && ea == eb;
    }
    uint32_t *nfa = calloc(fa + 1, sizeof *nfa), *nfb = calloc(fb + 1, sizeof *nfb);
    if (same)
        same = mt_face_neighbors(a, f, nfa, fa, offa, na + 1, &fa, &ea) == MT_OK &&
               mt_face_neighbors(b, f, nfb, fb, offb, nb + 1, &fb, &eb) == MT_OK &&
               memcmp(nfa, nfb, fa * sizeof *nfa) == 0 &&
               memcmp(offa, offb, (na + 1) * sizeof *offa) == 0;
    uint32_t ca = 0, cb = 0;
    if (same) same = mt_face_component(a, f, &ca) == mt_face_component(b, f, &cb) && ca == cb;
    for (size_t i = 0; same && i < na; i++) {
        size_t ka = 0, kb = 0;
        uint32_t x = va[i], y = va[(i + 1) % na];
        mt_status ta = mt_edge_faces(a, x, y, NULL, 0, &ka);
        mt_status tb = mt_edge_faces(b, x, y, NULL, 0, &kb);
        same = ta == tb && ka == kb;
        if (!same) break;
        uint32_t *ea_faces = calloc(ka + 1, sizeof(uint32_t));
        uint32_t *eb_faces = calloc(kb + 1, sizeof(uint32_t));
        same = mt_edge_faces(a, x, y, ea_faces, ka, &ka) ==
                   mt_edge_faces(b, x, y, eb_faces, kb, &kb) &&
               memcmp(ea_faces, eb_faces, ka * sizeof(uint32_t)) == 0;
        free(ea_faces);
        free(eb_faces);
    }
    free(va);
    free(vb);
    free(offa);
    free(offb);
    free(nfa);
    free(nfb);
    return same;
}

static bool same_loops(const mt_mesh *a, const mt_mesh *b)
{
    size_t va = 0, la = 0, vb = 0, lb = 0;
    mt_boundary_loops(a, NULL, 0, NULL, 0, &va, &la);
    mt_boundary_loops(b, NULL, 0, NULL, 0, &vb, &lb);
    if (va != vb || la != lb) return false;
    uint32_t *xa = calloc(va + 1, 4), *xb = calloc(vb + 1, 4);
    uint32_t *oa = calloc(la + 2, 4), *ob = calloc(lb + 2, 4);
    bool same = mt_boundary_loops(a, xa, va, oa, la + 1, &va, &la) == MT_OK &&
                mt_boundary_loops(b, xb, vb, ob, lb + 1, &vb, &lb) == MT_OK &&
                memcmp(xa, xb, va * 4) == 0 && memcmp(oa, ob, (la + 1) * 4) == 0;
    free(xa);
    free(xb);
    free(oa);
    free(ob);
    return same;
}

bool rc_same_answers(const mt_mesh *a, const mt_mesh *b, const char *what)
{
    if (mt_mesh_num_verts(a) != mt_mesh_num_verts(b) ||
        mt_mesh_num_faces(a) != mt_mesh_num_faces(b))
        return differ(what, "counts", 0);
    char why[256];
    if (!mt_archive_report_equal(mt_mesh_report(a), mt_mesh_report(b), why, sizeof why)) {
        printf("%s: reports differ: %s\n", what, why);
        return false;
    }
    const uint32_t nv = mt_mesh_num_verts(a), nf = mt_mesh_num_faces(a);
    for (uint32_t v = 0; v <= nv; v++) { /* nv itself: out of range in both */
        if (!same_ring(a, b, v)) return differ(what, "vertex ring", v);
        const double *pa = mt_mesh_position(a, v), *pb = mt_mesh_position(b, v);
        if ((pa == NULL) != (pb == NULL) || (pa && memcmp(pa, pb, 3 * sizeof *pa) != 0))
            return differ(what, "position", v);
    }
    for (uint32_t f = 0; f <= nf; f++)
        if (!same_face(a, b, f)) return differ(what, "face", f);
    if (!same_loops(a, b)) return differ(what, "boundary loops", 0);
    return true;
}
