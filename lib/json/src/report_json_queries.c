/* "vertex_queries" and "face_queries" of the inspect document
 * (report_json.h): each queried vertex's neighbours and valid faces, each
 * queried face's adjacent faces, as the sorted sets DEFINITIONS.md
 * "Queries" defines, by the queries that grow their buffers
 * (meshtopo/query.h), reused from one element to the next. */
#include <string.h>

#include "meshtopo/query.h"
#include "meshtopo/report_json.h"
#include "report_json_internal.h"

static mt_status write_vertex_queries(mt_json *j, const mt_mesh *mesh, const uint32_t *verts,
                                      size_t num_verts, mt_diag *diag)
{
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    mt_status st = MT_OK;
    mt_json_array_begin(j);
    for (size_t i = 0; i < num_verts; i++) {
        uint32_t v = verts[i];
        st = mt_vert_ring_growing(mesh, v, &ring);
        if (st != MT_OK) {
            mt_diag_set(diag, st, "query of vertex %u failed: %s", (unsigned)v, mt_strerror(st));
            break;
        }
        size_t nn = mt__json_sort_unique(ring.neighbors, ring.num_neighbors);
        size_t nf = mt__json_sort_unique(ring.faces, ring.num_faces);
        mt_json_object_begin(j);
        mt_json_key(j, "vertex");
        mt_json_uint(j, v);
        mt_json_key(j, "neighbors");
        mt__json_write_ids(j, ring.neighbors, nn);
        mt_json_key(j, "faces");
        mt__json_write_ids(j, ring.faces, nf);
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    mt_ring_free(&ring);
    return st;
}

static mt_status write_face_queries(mt_json *j, const mt_mesh *mesh, const uint32_t *faces,
                                    size_t num_faces, mt_diag *diag)
{
    mt_face_adjacency adj;
    memset(&adj, 0, sizeof adj);
    mt_status st = MT_OK;
    mt_json_array_begin(j);
    for (size_t i = 0; i < num_faces; i++) {
        uint32_t f = faces[i];
        st = mt_face_neighbors_growing(mesh, f, &adj);
        if (st != MT_OK && st != MT_ERR_NOT_FOUND) {
            mt_diag_set(diag, st, "query of face %u failed: %s", (unsigned)f, mt_strerror(st));
            break;
        }
        mt_json_object_begin(j);
        mt_json_key(j, "face");
        mt_json_uint(j, f);
        mt_json_key(j, "adjacent_faces");
        if (st == MT_ERR_NOT_FOUND) {
            mt_json_null(j); /* a rejected record has no adjacency */
            st = MT_OK;
        } else {
            size_t n = mt__json_sort_unique(adj.faces, adj.num_faces);
            size_t kept = 0;
            for (size_t k = 0; k < n; k++)
                if (adj.faces[k] != f) adj.faces[kept++] = adj.faces[k];
            mt__json_write_ids(j, adj.faces, kept);
        }
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    mt_face_adjacency_free(&adj);
    return st;
}

mt_status mt_report_json_write_queries(mt_json *j, const mt_mesh *mesh, const uint32_t *verts,
                                       size_t num_verts, const uint32_t *faces, size_t num_faces,
                                       mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!j || !mesh || (num_verts && !verts) || (num_faces && !faces))
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "report JSON: NULL mesh, writer or id list");
    mt_json_key(j, "vertex_queries");
    mt_status st = write_vertex_queries(j, mesh, verts, num_verts, diag);
    if (st != MT_OK) return st;
    mt_json_key(j, "face_queries");
    return write_face_queries(j, mesh, faces, num_faces, diag);
}
