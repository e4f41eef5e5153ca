/* Test helper for the block map's adjacency queries (map.h): a sample of
 * vertices, faces and edges asked of the map and of a full mt_mesh_build of
 * its union (mt_map_face_list), the build's answers translated to map ids;
 * statuses, fans, neighbours and faces must be equal, in order. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "map_split.h"
#include "meshtopo/query.h"

static void *xcalloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size);
    if (!p) {
        fprintf(stderr, "map_queries: out of memory\n");
        abort();
    }
    return p;
}

static uint64_t next_random(uint64_t *state)
{
    *state = *state * 6364136223846793005ull + 1442695040888963407ull;
    return *state >> 33;
}

/* "fan: n0 n1 .. / f0 f1 ..; ..." in map ids (the build's translated). */
static void ring_text(const mt_ring *r, const uint32_t *vids, const uint32_t *fids, char *out,
                      size_t size)
{
    size_t at = 0;
    out[0] = '\0';
    for (size_t i = 0; i < r->num_fans && at + 24 < size; i++) {
        const mt_fan *f = &r->fans[i];
        at += (size_t)snprintf(out + at, size - at, "%s%s:", i ? "; " : "",
                               f->boundary ? "open" : "closed");
        for (uint32_t k = 0; k < f->neighbor_count && at + 12 < size; k++) {
            const uint32_t n = r->neighbors[f->neighbor_begin + k];
            at += (size_t)snprintf(out + at, size - at, " %u", vids ? vids[n] : n);
        }
        at += (size_t)snprintf(out + at, size - at, " /");
        for (uint32_t k = 0; k < f->face_count && at + 12 < size; k++) {
            const uint32_t x = r->faces[f->face_begin + k];
            at += (size_t)snprintf(out + at, size - at, " %u", fids ? fids[x] : x);
        }
    }
}

/* The build's ring of list vertex k against the map's ring of vids[k]. */
static int check_ring(const mt_map *map, const mt_mesh *mesh, const uint32_t *vids,
                      const uint32_t *fids, uint32_t k, const char *what)
{
    mt_ring full;
    memset(&full, 0, sizeof full);
    if (mt_vert_ring_growing(mesh, k, &full) != MT_OK) abort();
    mt_ring mine = {xcalloc(full.num_neighbors + 1, sizeof(uint32_t)),
                    full.num_neighbors + 1,
                    xcalloc(full.num_faces + 1, sizeof(uint32_t)),
                    full.num_faces + 1,
                    xcalloc(full.num_fans + 1, sizeof(mt_fan)),
                    full.num_fans + 1,
                    0,
                    0,
                    0};
    mt_diag d;
    int bad = 0;
    mt_status s = mt_map_vert_ring(map, vids[k], &mine, &d);
    if (s != MT_OK || mine.num_fans != full.num_fans || mine.num_faces != full.num_faces ||
        mine.num_neighbors != full.num_neighbors) {
        mt_test_fail(__FILE__, __LINE__,
                     "%s: ring of vertex %u: %s (%s), fans %zu/%zu, faces %zu/%zu", what, vids[k],
                     mt_strerror(s), d.message, mine.num_fans, full.num_fans, mine.num_faces,
                     full.num_faces);
        bad = 1;
    }
    for (size_t i = 0; !bad && i < full.num_fans; i++) {
        const mt_fan *x = &mine.fans[i], *y = &full.fans[i];
        bad = x->neighbor_begin != y->neighbor_begin || x->neighbor_count != y->neighbor_count ||
              x->face_begin != y->face_begin || x->face_count != y->face_count ||
              x->boundary != y->boundary;
    }
    for (size_t i = 0; !bad && i < full.num_neighbors; i++)
        bad = mine.neighbors[i] != vids[full.neighbors[i]];
    for (size_t i = 0; !bad && i < full.num_faces; i++) bad = mine.faces[i] != fids[full.faces[i]];
    if (bad && s == MT_OK) {
        char a[400], b[400];
        ring_text(&mine, NULL, NULL, a, sizeof a);
        ring_text(&full, vids, fids, b, sizeof b);
        mt_test_fail(__FILE__, __LINE__, "%s: ring of vertex %u: map {%s}, build {%s}", what,
                     vids[k], a, b);
    }
    free(mine.neighbors);
    free(mine.faces);
    free(mine.fans);
    mt_ring_free(&full);
    return bad;
}

/* The build's neighbours of list face j against the map's of fids[j]. */
static int check_face(const mt_map *map, const mt_mesh *mesh, const uint32_t *fids, uint32_t j,
                      const char *what)
{
    mt_face_adjacency full;
    memset(&full, 0, sizeof full);
    const mt_status want = mt_face_neighbors_growing(mesh, j, &full);
    const size_t nf = full.num_faces + 1, no = full.num_edges + 2;
    uint32_t *faces = xcalloc(nf, sizeof *faces), *offsets = xcalloc(no, sizeof *offsets);
    size_t num_faces = 0, num_edges = 0;
    mt_diag d;
    const mt_status s =
        mt_map_face_neighbors(map, fids[j], faces, nf, offsets, no, &num_faces, &num_edges, &d);
    int bad = s != want;
    if (!bad && s == MT_OK) {
        bad = num_faces != full.num_faces || num_edges != full.num_edges;
        for (size_t i = 0; !bad && i <= num_edges; i++) bad = offsets[i] != full.offsets[i];
        for (size_t i = 0; !bad && i < num_faces; i++) bad = faces[i] != fids[full.faces[i]];
    }
    if (bad)
        mt_test_fail(__FILE__, __LINE__, "%s: neighbours of face %u: %s, the build's %s", what,
                     fids[j], mt_strerror(s), mt_strerror(want));
    free(faces);
    free(offsets);
    mt_face_adjacency_free(&full);
    return bad;
}

/* The build's faces of list edge {a, b} against the map's. */
static int check_edge(const mt_map *map, const mt_mesh *mesh, const uint32_t *vids,
                      const uint32_t *fids, uint32_t a, uint32_t b, const char *what)
{
    size_t n_full = 0, n_map = 0;
    uint32_t full[64], mine[64];
    const mt_status want = mt_edge_faces(mesh, a, b, full, 64, &n_full);
    mt_diag d;
    const mt_status s = mt_map_edge_faces(map, vids[a], vids[b], mine, 64, &n_map, &d);
    int bad = s != want;
    if (!bad && s == MT_OK) {
        bad = n_full != n_map;
        for (size_t i = 0; !bad && i < n_full; i++) bad = mine[i] != fids[full[i]];
    }
    if (bad)
        mt_test_fail(__FILE__, __LINE__, "%s: faces of edge %u-%u: %s, the build's %s", what,
                     vids[a], vids[b], mt_strerror(s), mt_strerror(want));
    return bad;
}

int map_check_queries(const mt_map *map, const char *what, uint64_t seed, uint32_t samples)
{
    mt_map_counts c;
    mt_map_get_counts(map, &c);
    uint32_t *vids = xcalloc(c.num_verts, sizeof *vids), *fids = xcalloc(c.num_faces, sizeof *fids);
    mt_face_list list;
    mt_diag d;
    mt_mesh *mesh = NULL;
    if (mt_map_face_list(map, &list, vids, c.num_verts, fids, c.num_faces, &d) != MT_OK ||
        mt_mesh_build(&list, NULL, &mesh, &d) != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: the union: %s", what, d.message);
        free(vids);
        free(fids);
        return 1;
    }
    int bad = 0;
    uint64_t state = seed;
    const uint32_t nv = list.num_verts, nf = list.num_faces;
    for (uint32_t i = 0; !bad && nv > 0 && i < samples; i++) {
        const uint32_t k = nv <= samples ? i % nv : (uint32_t)(next_random(&state) % nv);
        bad += check_ring(map, mesh, vids, fids, k, what);
        /* Each edge at k, and one pair that is most likely no edge. */
        mt_ring ring;
        memset(&ring, 0, sizeof ring);
        if (mt_vert_ring_growing(mesh, k, &ring) != MT_OK) abort();
        for (size_t n = 0; !bad && n < ring.num_neighbors; n++)
            bad += check_edge(map, mesh, vids, fids, k, ring.neighbors[n], what);
        mt_ring_free(&ring);
        if (!bad)
            bad += check_edge(map, mesh, vids, fids, k, (uint32_t)(next_random(&state) % nv), what);
    }
    for (uint32_t i = 0; !bad && nf > 0 && i < samples; i++) {
        const uint32_t j = nf <= samples ? i % nf : (uint32_t)(next_random(&state) % nf);
        bad += check_face(map, mesh, fids, j, what);
    }
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    free(vids);
    free(fids);
    return bad;
}
