/* Defect colours per vertex and per face record (defect_colors.h): each
 * element gets the colour of its most telling mark, found with the
 * library's queries (mt_face_component for rejected faces, mt_edge_faces
 * for the faces on each side), local to each face: linear in the face
 * list. The colours are the ones tools/vtk/render.py draws. */
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "defect_colors.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"

/* Marks by rank: a higher one wins. */
enum { VERT_PLAIN, VERT_BOUNDARY, VERT_REJECTED_CORNER, VERT_NON_MANIFOLD, VERT_RANKS };
enum {
    FACE_PLAIN,
    FACE_FLIPPED,
    FACE_NON_MANIFOLD,
    FACE_SELF_INTERSECTING,
    FACE_REJECTED,
    FACE_RANKS
};

static const uint8_t vert_rgb[VERT_RANKS][3] = {
    {184, 184, 184}, {255, 0, 0}, {255, 140, 0}, {255, 0, 255}};
static const uint8_t face_rgb[FACE_RANKS][3] = {
    {184, 184, 184}, {70, 130, 255}, {255, 0, 255}, {255, 220, 0}, {255, 140, 0}};

static void raise_rank(uint8_t *ranks, uint32_t i, uint8_t rank)
{
    if (ranks[i] < rank) ranks[i] = rank;
}

/* Whether face g (its corners at idx, size n) runs the side u -> w. */
static bool face_runs(const uint32_t *idx, uint32_t n, uint32_t u, uint32_t w)
{
    for (uint32_t k = 0; k < n; k++)
        if (idx[k] == u && idx[(k + 1) % n] == w) return true;
    return false;
}

bool cli_defect_colors(const mt_face_list *list, const mt_mesh *mesh, const mt_face_pair *pairs,
                       size_t num_pairs, uint8_t *out_vertex, uint8_t *out_face)
{
    const uint32_t nv = list->num_verts, nf = list->num_faces;
    uint8_t *vrank = calloc((size_t)nv + 1, 1), *frank = calloc((size_t)nf + 1, 1);
    uint64_t *first = malloc(((size_t)nf + 1) * sizeof *first);
    bool ok = vrank && frank && first;
    if (ok) {
        first[0] = 0;
        for (uint32_t f = 0; f < nf; f++) first[f + 1] = first[f] + list->face_sizes[f];
    }
    for (uint32_t f = 0; ok && f < nf; f++) {
        const uint32_t *idx = list->face_indices + first[f], n = list->face_sizes[f];
        uint32_t component;
        if (mt_face_component(mesh, f, &component) != MT_OK) {
            frank[f] = FACE_REJECTED;
            for (uint32_t k = 0; k < n; k++)
                if (idx[k] < nv) raise_rank(vrank, idx[k], VERT_REJECTED_CORNER);
            continue;
        }
        for (uint32_t k = 0; k < n; k++) {
            uint32_t u = idx[k], w = idx[(k + 1) % n], on[8];
            size_t count = 0;
            mt_status st = mt_edge_faces(mesh, u, w, on, 8, &count);
            if (st != MT_OK && st != MT_ERR_BUFFER_TOO_SMALL) continue;
            if (count == 1) {
                raise_rank(vrank, u, VERT_BOUNDARY);
                raise_rank(vrank, w, VERT_BOUNDARY);
            } else if (count >= 3) {
                raise_rank(frank, f, FACE_NON_MANIFOLD);
            } else if (count == 2) {
                uint32_t g = on[0] == f ? on[1] : on[0];
                if (face_runs(list->face_indices + first[g], list->face_sizes[g], u, w))
                    raise_rank(frank, f, FACE_FLIPPED);
            }
        }
    }
    const mt_report *report = mt_mesh_report(mesh);
    for (size_t i = 0; ok && i < report->num_defects; i++)
        if (report->defects[i].kind == MT_DEFECT_NONMANIFOLD_VERTEX && report->defects[i].a < nv)
            raise_rank(vrank, report->defects[i].a, VERT_NON_MANIFOLD);
    for (size_t i = 0; ok && i < num_pairs; i++) {
        if (pairs[i].a < nf) raise_rank(frank, pairs[i].a, FACE_SELF_INTERSECTING);
        if (pairs[i].b < nf) raise_rank(frank, pairs[i].b, FACE_SELF_INTERSECTING);
    }
    for (uint32_t v = 0; ok && v < nv; v++)
        memcpy(out_vertex + 3 * (size_t)v, vert_rgb[vrank[v]], 3);
    for (uint32_t f = 0; ok && f < nf; f++) memcpy(out_face + 3 * (size_t)f, face_rgb[frank[f]], 3);
    free(vrank);
    free(frank);
    free(first);
    return ok;
}
