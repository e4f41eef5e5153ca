/* Hand-written half-edge meshes for the query and validation tests (see
 * hand_mesh.h). Convention of every table: internal edge e has half-edges 2e
 * (from the smaller caller vertex to the larger) and 2e+1; N is MT_NONE. */
#include "hand_mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define N MT_NONE

static uint32_t *copy_array(const uint32_t *src, size_t n)
{
    if (!src) return NULL;
    uint32_t *dst = malloc(n ? n * sizeof *dst : 1);
    if (!dst) {
        fprintf(stderr, "hand_mesh: out of memory\n");
        exit(2);
    }
    if (n) memcpy(dst, src, n * sizeof *dst);
    return dst;
}

mt_mesh *hand_mesh_new(const hand_spec *s)
{
    mt_mesh *m = calloc(1, sizeof *m);
    if (!m) {
        fprintf(stderr, "hand_mesh: out of memory\n");
        exit(2);
    }
    const uint32_t nvi = s->num_verts + s->num_copies;
    m->num_verts = s->num_verts;
    m->num_verts_internal = nvi;
    m->num_faces = s->num_faces;
    m->num_half_edges = s->num_half_edges;
    m->he_head = copy_array(s->he_head, s->num_half_edges);
    m->he_next = copy_array(s->he_next, s->num_half_edges);
    m->he_face = copy_array(s->he_face, s->num_half_edges);
    m->face_he = copy_array(s->face_he, s->num_faces);
    m->vert_he = copy_array(s->vert_he, nvi);
    m->num_copies = s->num_copies;
    m->copy_original = copy_array(s->copy_original, s->num_copies);
    m->copies_sorted = copy_array(s->copies_sorted, s->num_copies);
    m->num_bundles = s->num_bundles;
    if (s->num_bundles) {
        uint32_t total = s->bundle_offsets[s->num_bundles];
        m->bundle_offsets = copy_array(s->bundle_offsets, s->num_bundles + 1);
        m->bundle_edges = copy_array(s->bundle_edges, total);
        m->bundled_sorted = copy_array(s->bundled_sorted, total);
        m->bundled_bundle = copy_array(s->bundled_bundle, total);
    }
    m->vert_component = copy_array(s->vert_component, nvi);
    m->report.num_verts = s->num_verts;
    m->report.num_faces = s->num_faces;
    for (uint32_t f = 0; f < s->num_faces; f++)
        if (s->face_he[f] != MT_NONE) m->report.num_faces_valid++;
    m->report.connected_components = s->components;
    return m;
}

void hand_mesh_free(mt_mesh *m)
{
    if (!m) return;
    free(m->he_head);
    free(m->he_next);
    free(m->he_face);
    free(m->face_he);
    free(m->vert_he);
    free(m->positions);
    free(m->copy_original);
    free(m->copies_sorted);
    free(m->bundle_offsets);
    free(m->bundle_edges);
    free(m->bundled_sorted);
    free(m->bundled_bundle);
    free(m->vert_component);
    free(m);
}

static void set_faces(hand_faces *out, uint32_t nv, uint32_t nf, const uint32_t *sizes,
                      const uint32_t *indices)
{
    if (!out) return;
    out->num_verts = nv;
    out->num_faces = nf;
    out->sizes = sizes;
    out->indices = indices;
}

static const uint32_t tri3[] = {3, 3, 3, 3};

/* Triangle (0, 1, 2):
 *   e0 = 0-1: h0 0->1 face 0, h1 1->0 boundary
 *   e1 = 1-2: h2 1->2 face 0, h3 2->1 boundary
 *   e2 = 0-2: h4 0->2 boundary, h5 2->0 face 0
 * face ring h0 h2 h5; boundary ring h1 h4 h3. */
mt_mesh *hand_triangle(hand_faces *out_faces)
{
    static const uint32_t idx[] = {0, 1, 2};
    static const uint32_t head[] = {1, 0, 2, 1, 2, 0};
    static const uint32_t next[] = {2, 4, 5, 1, 3, 0};
    static const uint32_t face[] = {0, N, 0, N, N, 0};
    static const uint32_t face_he[] = {0};
    static const uint32_t vert_he[] = {4, 1, 3};
    hand_spec s = {0};
    s.num_verts = 3;
    s.num_faces = 1;
    s.num_half_edges = 6;
    s.he_head = head;
    s.he_next = next;
    s.he_face = face;
    s.face_he = face_he;
    s.vert_he = vert_he;
    s.components = 1;
    set_faces(out_faces, 3, 1, tri3, idx);
    return hand_mesh_new(&s);
}

/* Rectangle (0, 1, 2), (0, 2, 3):
 *   e0 = 0-1: h0 face 0, h1 boundary    e1 = 1-2: h2 face 0, h3 boundary
 *   e2 = 0-2: h4 face 1, h5 face 0      e3 = 2-3: h6 face 1, h7 boundary
 *   e4 = 0-3: h8 boundary, h9 face 1
 * face rings h0 h2 h5 and h4 h6 h9; boundary ring h1 h8 h7 h3. */
mt_mesh *hand_rectangle(hand_faces *out_faces)
{
    static const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    static const uint32_t head[] = {1, 0, 2, 1, 2, 0, 3, 2, 3, 0};
    static const uint32_t next[] = {2, 8, 5, 1, 6, 0, 9, 3, 7, 4};
    static const uint32_t face[] = {0, N, 0, N, 1, 0, 1, N, N, 1};
    static const uint32_t face_he[] = {0, 4};
    static const uint32_t vert_he[] = {8, 1, 3, 7};
    hand_spec s = {0};
    s.num_verts = 4;
    s.num_faces = 2;
    s.num_half_edges = 10;
    s.he_head = head;
    s.he_next = next;
    s.he_face = face;
    s.face_he = face_he;
    s.vert_he = vert_he;
    s.components = 1;
    set_faces(out_faces, 4, 2, tri3, idx);
    return hand_mesh_new(&s);
}

/* Tetrahedron (0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2):
 *   e0 = 0-1: h0 face 1, h1 face 0    e1 = 0-2: h2 face 0, h3 face 3
 *   e2 = 0-3: h4 face 3, h5 face 1    e3 = 1-2: h6 face 2, h7 face 0
 *   e4 = 1-3: h8 face 1, h9 face 2    e5 = 2-3: h10 face 2, h11 face 3
 * face rings h2 h7 h1, h0 h8 h5, h6 h10 h9, h4 h11 h3. */
mt_mesh *hand_tetrahedron(hand_faces *out_faces)
{
    static const uint32_t idx[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    static const uint32_t head[] = {1, 0, 2, 0, 3, 0, 2, 1, 3, 1, 3, 2};
    static const uint32_t next[] = {8, 2, 7, 4, 11, 0, 10, 1, 5, 6, 9, 3};
    static const uint32_t face[] = {1, 0, 0, 3, 3, 1, 2, 0, 1, 2, 2, 3};
    static const uint32_t face_he[] = {2, 0, 6, 4};
    static const uint32_t vert_he[] = {0, 1, 3, 5};
    hand_spec s = {0};
    s.num_verts = 4;
    s.num_faces = 4;
    s.num_half_edges = 12;
    s.he_head = head;
    s.he_next = next;
    s.he_face = face;
    s.face_he = face_he;
    s.vert_he = vert_he;
    s.components = 1;
    set_faces(out_faces, 4, 4, tri3, idx);
    return hand_mesh_new(&s);
}

/* Bowtie (0, 1, 2), (0, 3, 4); internal vertex 5 is the copy of 0 in face 1:
 *   e0 = 0-1: h0 face 0, h1 boundary    e1 = 0-2: h2 boundary, h3 face 0
 *   e2 = 1-2: h4 face 0, h5 boundary    e3 = 5-3: h6 face 1, h7 boundary
 *   e4 = 5-4: h8 boundary, h9 face 1    e5 = 3-4: h10 face 1, h11 boundary
 * face rings h0 h4 h3 and h6 h10 h9; boundary rings h1 h2 h5 and h7 h8 h11. */
mt_mesh *hand_bowtie(hand_faces *out_faces)
{
    static const uint32_t idx[] = {0, 1, 2, 0, 3, 4};
    static const uint32_t head[] = {1, 0, 2, 0, 2, 1, 3, 5, 4, 5, 4, 3};
    static const uint32_t next[] = {4, 2, 5, 0, 3, 1, 10, 8, 11, 6, 9, 7};
    static const uint32_t face[] = {0, N, N, 0, 0, N, 1, N, N, 1, 1, N};
    static const uint32_t face_he[] = {0, 6};
    static const uint32_t vert_he[] = {2, 1, 5, 7, 11, 8};
    static const uint32_t copy_original[] = {0};
    static const uint32_t copies_sorted[] = {5};
    static const uint32_t component[] = {0, 0, 0, 1, 1, 1};
    hand_spec s = {0};
    s.num_verts = 5;
    s.num_faces = 2;
    s.num_half_edges = 12;
    s.num_copies = 1;
    s.he_head = head;
    s.he_next = next;
    s.he_face = face;
    s.face_he = face_he;
    s.vert_he = vert_he;
    s.copy_original = copy_original;
    s.copies_sorted = copies_sorted;
    s.vert_component = component;
    s.components = 2;
    set_faces(out_faces, 5, 2, tri3, idx);
    return hand_mesh_new(&s);
}

/* Fin (0, 1, 2), (1, 0, 3), (0, 1, 4); faces 0 and 1 pair on edge 0, face 2
 * has edge 5 on copies 5 (of 0) and 6 (of 1); edges 0 and 5 are bundle 0:
 *   e0 = 0-1: h0 face 0, h1 face 1       e1 = 1-2: h2 face 0, h3 boundary
 *   e2 = 0-2: h4 boundary, h5 face 0     e3 = 0-3: h6 face 1, h7 boundary
 *   e4 = 1-3: h8 boundary, h9 face 1     e5 = 5-6: h10 face 2, h11 boundary
 *   e6 = 6-4: h12 face 2, h13 boundary   e7 = 5-4: h14 boundary, h15 face 2
 * face rings h0 h2 h5, h1 h6 h9, h10 h12 h15; boundary rings h3 h8 h7 h4
 * and h11 h14 h13. */
mt_mesh *hand_fin(hand_faces *out_faces)
{
    static const uint32_t idx[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    static const uint32_t head[] = {1, 0, 2, 1, 2, 0, 3, 0, 3, 1, 6, 5, 4, 6, 4, 5};
    static const uint32_t next[] = {2, 6, 5, 8, 3, 0, 9, 4, 7, 1, 12, 14, 15, 11, 13, 10};
    static const uint32_t face[] = {0, 1, 0, N, N, 0, 1, N, N, 1, 2, N, 2, N, N, 2};
    static const uint32_t face_he[] = {0, 1, 10};
    static const uint32_t vert_he[] = {4, 8, 3, 7, 13, 14, 11};
    static const uint32_t copy_original[] = {0, 1};
    static const uint32_t copies_sorted[] = {5, 6};
    static const uint32_t bundle_offsets[] = {0, 2};
    static const uint32_t bundle_edges[] = {0, 5};
    static const uint32_t bundled_sorted[] = {0, 5};
    static const uint32_t bundled_bundle[] = {0, 0};
    hand_spec s = {0};
    s.num_verts = 5;
    s.num_faces = 3;
    s.num_half_edges = 16;
    s.num_copies = 2;
    s.num_bundles = 1;
    s.he_head = head;
    s.he_next = next;
    s.he_face = face;
    s.face_he = face_he;
    s.vert_he = vert_he;
    s.copy_original = copy_original;
    s.copies_sorted = copies_sorted;
    s.bundle_offsets = bundle_offsets;
    s.bundle_edges = bundle_edges;
    s.bundled_sorted = bundled_sorted;
    s.bundled_bundle = bundled_bundle;
    s.components = 1;
    set_faces(out_faces, 5, 3, tri3, idx);
    return hand_mesh_new(&s);
}

mt_mesh *hand_triangle_isolated(void)
{
    static const uint32_t head[] = {1, 0, 2, 1, 2, 0};
    static const uint32_t next[] = {2, 4, 5, 1, 3, 0};
    static const uint32_t face[] = {0, N, 0, N, N, 0};
    static const uint32_t face_he[] = {0, N};
    static const uint32_t vert_he[] = {4, 1, 3, N};
    hand_spec s = {0};
    s.num_verts = 4;
    s.num_faces = 2;
    s.num_half_edges = 6;
    s.he_head = head;
    s.he_next = next;
    s.he_face = face;
    s.face_he = face_he;
    s.vert_he = vert_he;
    s.components = 1;
    return hand_mesh_new(&s);
}
