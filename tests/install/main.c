/* A program using an installed meshtopo: builds a tetrahedron from a face
 * list written by hand, prints its topology and the one-ring of vertex 0.
 * It is the README's example, built by the install test through both
 * find_package(meshtopo) and pkg-config. */
#include <stdio.h>
#include <stdlib.h>

#include <meshtopo/core.h>

int main(void)
{
    /* Four triangles, consistently oriented: each edge is crossed once each way. */
    uint32_t sizes[] = {3, 3, 3, 3};
    uint32_t indices[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    mt_face_list faces = {.num_verts = 4,
                          .num_faces = 4,
                          .num_indices = 12,
                          .positions = NULL,
                          .face_sizes = sizes,
                          .face_indices = indices};

    mt_mesh *mesh = NULL;
    mt_diag diag;
    if (mt_mesh_build(&faces, NULL, &mesh, &diag) != MT_OK) {
        fprintf(stderr, "build failed: %s\n", diag.message);
        return 1;
    }
    const mt_report *report = mt_mesh_report(mesh);
    printf("V=%u E=%llu F=%u\n", report->num_verts, (unsigned long long)report->num_edges,
           report->num_faces_valid);
    printf("Euler characteristic: %lld, genus: %d, closed: %s, manifold: %s\n",
           (long long)report->euler_characteristic, report->genus, report->closed ? "yes" : "no",
           report->manifold ? "yes" : "no");

    /* Caller-owned outputs: ask for the sizes first, then fill. */
    mt_ring ring = {0};
    mt_status status = mt_vert_ring(mesh, 0, &ring);
    if (status != MT_OK && status != MT_ERR_BUFFER_TOO_SMALL) return 1;
    ring.neighbors = calloc(ring.num_neighbors, sizeof *ring.neighbors);
    ring.neighbors_capacity = ring.num_neighbors;
    ring.faces = calloc(ring.num_faces, sizeof *ring.faces);
    ring.faces_capacity = ring.num_faces;
    ring.fans = calloc(ring.num_fans, sizeof *ring.fans);
    ring.fans_capacity = ring.num_fans;
    if (mt_vert_ring(mesh, 0, &ring) != MT_OK) return 1;
    printf("one-ring of vertex 0:");
    for (size_t i = 0; i < ring.num_neighbors; i++) printf(" %u", ring.neighbors[i]);
    printf("\n");

    free(ring.neighbors);
    free(ring.faces);
    free(ring.fans);
    mt_mesh_destroy(mesh);
    return 0;
}
