/* libFuzzer target for the edits (edit.h): the input bytes pick a small
 * generated mesh and then a sequence of edits on it. After every edit the
 * mesh must validate, a refused or failed edit must leave the face count and
 * the Euler characteristic unchanged, and the edits that keep the topology
 * (split, flip, collapse, face split, triangulate) must keep chi. At the end
 * the mesh is compacted and must validate with a report that agrees. Any
 * disagreement calls abort() so the fuzzer keeps the input.
 *
 * Input layout (missing bytes read as 0):
 *   byte 0    mesh: % 6 = icosahedron, octahedron, cube, 3x3 triangle grid,
 *             3x3 quad grid, 4x3 torus
 *   then      triples (op, x, y): op % 12 picks the edit, x and y pick a
 *             vertex, an edge (by half-edge) or a face modulo the live counts.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/core.h"

#define MAX_EDITS 256

static void fail(const char *what, const mt_diag *d)
{
    fprintf(stderr, "fuzz_edit: %s: %s\n", what, d ? d->message : "");
    abort();
}

static mt_status make_mesh(uint8_t kind, mt_face_list *l)
{
    switch (kind % 6) {
        case 0:
            return mt_gen_platonic(MT_ICOSAHEDRON, l);
        case 1:
            return mt_gen_platonic(MT_OCTAHEDRON, l);
        case 2:
            return mt_gen_platonic(MT_CUBE, l);
        case 3:
            return mt_gen_grid(3, 3, true, l);
        case 4:
            return mt_gen_grid(3, 3, false, l);
        default:
            return mt_gen_torus(4, 3, l);
    }
}

/* Edge number x (of the live half-edges) as two vertices. */
static bool pick_edge(const mt_mesh *m, uint8_t x, uint32_t *a, uint32_t *b)
{
    mt_mesh_view v;
    mt_mesh_get_view(m, &v);
    if (v.num_half_edges == 0) return false;
    for (uint32_t k = 0; k < v.num_half_edges; k++) {
        uint32_t h = (x + k) % v.num_half_edges;
        if (v.he_head[h] == MT_NONE) continue;
        *a = v.he_head[h ^ 1u];
        *b = v.he_head[h];
        return true;
    }
    return false;
}

static uint32_t pick_face(const mt_mesh *m, uint8_t x)
{
    mt_mesh_view v;
    mt_mesh_get_view(m, &v);
    for (uint32_t k = 0; k < v.num_faces; k++) {
        uint32_t f = (x + k) % v.num_faces;
        if (v.face_he[f] != MT_NONE) return f;
    }
    return MT_NONE;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    mt_face_list l;
    if (make_mesh(size ? data[0] : 0, &l) != MT_OK) return 0;
    mt_mesh *m = NULL;
    mt_diag d;
    if (mt_mesh_build(&l, NULL, &m, &d) != MT_OK) fail("build", &d);
    mt_face_list_free(&l);
    for (size_t i = 1, edits = 0; i < size && edits < MAX_EDITS; i += 3, edits++) {
        const uint8_t op = data[i], x = i + 1 < size ? data[i + 1] : 0;
        const uint8_t y = i + 2 < size ? data[i + 2] : 0;
        const mt_report *r = mt_mesh_report(m);
        const int64_t chi = r->euler_characteristic;
        const uint32_t faces = r->num_faces_valid;
        const uint32_t nv = mt_mesh_num_verts(m);
        uint32_t a = 0, b = 0, f = pick_face(m, x), vs[64];
        size_t n = 0;
        const bool edge = pick_edge(m, x, &a, &b);
        bool keeps_chi = true;
        mt_status s = MT_ERR_NOT_FOUND;
        switch (op % 12) {
            case 0:
                if (edge) s = mt_edge_split(m, a, b, NULL, NULL, &d);
                break;
            case 1:
                if (edge) s = mt_edge_flip(m, a, b, &d);
                break;
            case 2:
                if (edge) s = mt_edge_collapse(m, a, b, NULL, &d);
                break;
            case 3:
                if (f != MT_NONE && mt_face_verts(m, f, vs, 64, &n) == MT_OK && n > 0)
                    s = mt_face_split(m, f, vs[y % n], vs[(y / 16) % n], NULL, &d);
                break;
            case 4:
                if (f != MT_NONE) s = mt_face_triangulate(m, f, NULL, &d);
                break;
            case 5:
                s = mt_mesh_triangulate(m, &d);
                break;
            case 6:
                keeps_chi = false;
                if (f != MT_NONE) s = mt_face_delete(m, f, &d);
                break;
            case 7:
                keeps_chi = false;
                if (edge) s = mt_edge_delete(m, a, b, &d);
                break;
            case 8:
                keeps_chi = false;
                s = mt_vert_delete(m, x % (nv ? nv : 1), &d);
                break;
            case 10:
                if (edge) s = mt_face_join(m, a, b, NULL, &d);
                if (s == MT_OK && r->num_faces_valid != faces - 1)
                    fail("a join did not remove one face", &d);
                break;
            case 9: {
                keeps_chi = false;
                uint32_t tri[3] = {x % nv, y % nv, (uint32_t)(x + y + 1) % nv};
                s = mt_mesh_add_face(m, tri, 3, NULL, &d);
                break;
            }
            default: {
                keeps_chi = false;
                uint32_t v;
                s = mt_mesh_add_vert(m, NULL, &v, &d);
                break;
            }
        }
        if (s != MT_OK && (r->euler_characteristic != chi || r->num_faces_valid != faces))
            fail("a refused edit changed the mesh", &d);
        if (s == MT_OK && keeps_chi && r->euler_characteristic != chi)
            fail("an edit changed chi", &d);
        if (s != MT_OK && s != MT_ERR_REFUSED && s != MT_ERR_NOT_FOUND &&
            s != MT_ERR_OUT_OF_RANGE && s != MT_ERR_INVALID_ARG)
            fail(mt_strerror(s), &d);
        if (mt_mesh_validate(m, &d) != MT_OK) fail("validate after edit", &d);
        if ((int64_t)r->num_verts - (int64_t)r->num_edges + r->num_faces_valid !=
            r->euler_characteristic)
            fail("V - E + F differs from the Euler characteristic", &d);
    }
    const int64_t chi = mt_mesh_report(m)->euler_characteristic;
    if (mt_mesh_compact(m, NULL, 0, NULL, 0, &d) != MT_OK) fail("compact", &d);
    if (mt_mesh_validate(m, &d) != MT_OK) fail("validate after compact", &d);
    if (mt_mesh_report(m)->euler_characteristic != chi) fail("compact changed chi", &d);
    mt_mesh_destroy(m);
    return 0;
}
