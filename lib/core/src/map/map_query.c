/* Adjacency queries on the block map: a vertex's ring, a face's neighbours
 * and an edge's faces, answered as a full build of the map's union would
 * answer them. Each query builds the map's faces at the vertices it asks
 * about with mt_mesh_build, vertices and faces renumbered in the order of
 * their map ids, and translates the answer back to map ids. Those faces
 * decide the answer: the build pairs the sides of two vertices into edges
 * among themselves in face order (build_edges.c sorts a vertex's sides by
 * (other vertex, face)), numbers edges in vertex id order, and makes a
 * vertex's fans from its own sides (build_fans.c), so a build of the faces
 * at a vertex gives it the fans, edges and neighbours the full build gives.
 * Cost: one build of those faces, O(their size) expected time, independent
 * of the map. */
#include <stdlib.h>
#include <string.h>

#include "map/map_internal.h"
#include "meshtopo/query.h"

/* The map's faces around some vertices, built: local ids are ranks of map
 * ids (local vertex i is map vertex verts[i], local face j map face faces[j]). */
typedef struct local_build {
    mt_mesh *mesh;
    uint32_t *verts, *faces;
    uint32_t num_verts, num_faces;
} local_build;

static void local_free(local_build *l)
{
    mt_mesh_destroy(l->mesh);
    mt__free(l->verts);
    mt__free(l->faces);
    memset(l, 0, sizeof *l);
}

static int compare_u32(const void *pa, const void *pb)
{
    const uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

/* Sorts ids and drops repeats; returns the new length. */
static uint32_t sort_unique(uint32_t *ids, uint32_t n)
{
    if (n == 0) return 0;
    qsort(ids, n, sizeof *ids, compare_u32);
    uint32_t k = 1;
    for (uint32_t i = 1; i < n; i++)
        if (ids[i] != ids[k - 1]) ids[k++] = ids[i];
    return k;
}

/* The local id of a map vertex or face (MT_NONE when it is not there). */
static uint32_t local_id(const uint32_t *sorted, uint32_t n, uint32_t id)
{
    if (n == 0) return MT_NONE; /* bsearch takes no NULL array */
    const uint32_t *at = bsearch(&id, sorted, n, sizeof id, compare_u32);
    return at ? (uint32_t)(at - sorted) : MT_NONE;
}

/* The corners of live face f. */
static const uint32_t *face_corners(const mt_map *map, uint32_t f, uint32_t *out_size)
{
    const mt__map_block *b = map->blocks[map->face_block[f]];
    const uint32_t local = map->face_local[f] & MT__MAP_LOCAL_MASK;
    *out_size = mt__blk_size(b, local);
    return b->corners + mt__blk_begin(b, local);
}

/* Appends v's faces to faces (growing it); false when out of memory. */
static bool push_vertex_faces(const mt_map *map, uint32_t v, mt__vec *faces)
{
    for (uint32_t f = map->vert_head[v]; f != MT_NONE;) {
        if (mt__vec_push(faces, &f) != MT_OK) return false;
        const mt__map_block *b;
        uint32_t local;
        const uint32_t c = mt__map_corner_of(map, f, v, &b, &local);
        f = b->corner_next[c];
    }
    return true;
}

static bool vertex_live(const mt_map *map, uint32_t v)
{
    return v < map->vert_end && (map->vert_flags[v] & MT__V_ALIVE);
}

/* Collects the faces at the seeds (and face `also`, unless MT_NONE: a face
 * the build rejects may be in no vertex's list), and builds them as a face
 * list in map id order. */
static mt_status local_make(const mt_map *map, const uint32_t *seeds, uint32_t num_seeds,
                            uint32_t also, local_build *out, mt_diag *diag)
{
    memset(out, 0, sizeof *out);
    mt__vec faces = {NULL, 0, 0, sizeof(uint32_t)}, verts = {NULL, 0, 0, sizeof(uint32_t)};
    mt_face_list list;
    memset(&list, 0, sizeof list);
    mt_status st = MT_ERR_NOMEM;
    bool ok = also == MT_NONE || mt__vec_push(&faces, &also) == MT_OK;
    for (uint32_t i = 0; ok && i < num_seeds; i++) ok = push_vertex_faces(map, seeds[i], &faces);
    if (ok) faces.len = sort_unique(faces.data, (uint32_t)faces.len);
    /* Every vertex of the faces, and the face list over local ids. */
    uint64_t num_indices = 0;
    verts.len = 0;
    for (size_t i = 0; ok && i < faces.len; i++) {
        uint32_t n;
        const uint32_t *c = face_corners(map, ((const uint32_t *)faces.data)[i], &n);
        num_indices += n;
        for (uint32_t k = 0; ok && k < n; k++)
            if (c[k] < MT__MAP_OOR) ok = mt__vec_push(&verts, &c[k]) == MT_OK;
    }
    if (ok) verts.len = sort_unique(verts.data, (uint32_t)verts.len);
    if (ok)
        ok = mt_face_list_alloc(&list, (uint32_t)verts.len, (uint32_t)faces.len, num_indices,
                                NULL) == MT_OK;
    if (ok) {
        mt__free(list.positions); /* the adjacency queries need no geometry */
        list.positions = NULL;
        uint64_t at = 0;
        for (size_t i = 0; i < faces.len; i++) {
            uint32_t n;
            const uint32_t *c = face_corners(map, ((const uint32_t *)faces.data)[i], &n);
            list.face_sizes[i] = n;
            for (uint32_t k = 0; k < n; k++)
                list.face_indices[at++] =
                    c[k] >= MT__MAP_OOR ? c[k] : local_id(verts.data, (uint32_t)verts.len, c[k]);
        }
        const mt_build_options options = {false, 1, NULL};
        st = mt_mesh_build(&list, &options, &out->mesh, diag);
        ok = st == MT_OK;
    }
    mt_face_list_free(&list);
    if (!ok) {
        mt__vec_free(&faces);
        mt__vec_free(&verts);
        if (st == MT_ERR_NOMEM) return mt__fail(diag, st, MT_NONE, "map query: out of memory");
        return st;
    }
    out->verts = verts.data;
    out->num_verts = (uint32_t)verts.len;
    out->faces = faces.data;
    out->num_faces = (uint32_t)faces.len;
    return MT_OK;
}

mt_status mt_map_vert_ring(const mt_map *map, uint32_t vert, mt_ring *ring, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!map || !ring) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "map ring: NULL");
    if (!vertex_live(map, vert))
        return mt__fail(diag, MT_ERR_OUT_OF_RANGE, vert, "map ring: no live vertex %u", vert);
    local_build l;
    mt_status st = local_make(map, &vert, 1, MT_NONE, &l, diag);
    if (st != MT_OK) return st;
    const uint32_t local = local_id(l.verts, l.num_verts, vert);
    if (local == MT_NONE) {
        /* In no face: the ring of an isolated vertex. */
        ring->num_neighbors = ring->num_faces = ring->num_fans = 0;
        local_free(&l);
        return MT_OK;
    }
    st = mt_vert_ring(l.mesh, local, ring);
    if (st == MT_OK) {
        for (size_t i = 0; i < ring->num_neighbors; i++)
            ring->neighbors[i] = l.verts[ring->neighbors[i]];
        for (size_t i = 0; i < ring->num_faces; i++) ring->faces[i] = l.faces[ring->faces[i]];
    } else {
        mt__fail(diag, st, vert, "map ring of vertex %u: %s", vert, mt_strerror(st));
    }
    local_free(&l);
    return st;
}

/* The live face f's vertices, as seeds (out-of-range corners left out). */
static uint32_t face_seeds(const mt_map *map, uint32_t f, uint32_t *seeds)
{
    uint32_t n, k = 0;
    const uint32_t *c = face_corners(map, f, &n);
    for (uint32_t i = 0; i < n; i++)
        if (c[i] < MT__MAP_OOR) seeds[k++] = c[i];
    return k;
}

mt_status mt_map_face_neighbors(const mt_map *map, uint32_t face, uint32_t *out_faces,
                                size_t faces_capacity, uint32_t *out_offsets,
                                size_t offsets_capacity, size_t *out_num_faces,
                                size_t *out_num_edges, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!map || !out_num_faces || !out_num_edges)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "map face neighbours: NULL");
    if (face >= map->face_end || map->face_block[face] == MT_NONE)
        return mt__fail(diag, MT_ERR_OUT_OF_RANGE, face, "map face neighbours: no live face %u",
                        face);
    uint32_t seeds[MT_MAP_BLOCK_MAX_FACE_SIZE];
    const uint32_t num_seeds = face_seeds(map, face, seeds);
    local_build l;
    mt_status st = local_make(map, seeds, num_seeds, face, &l, diag);
    if (st != MT_OK) return st;
    st = mt_face_neighbors(l.mesh, local_id(l.faces, l.num_faces, face), out_faces, faces_capacity,
                           out_offsets, offsets_capacity, out_num_faces, out_num_edges);
    if (st == MT_OK && out_faces && faces_capacity >= *out_num_faces)
        for (size_t i = 0; i < *out_num_faces; i++) out_faces[i] = l.faces[out_faces[i]];
    if (st != MT_OK)
        mt__fail(diag, st, face, "map face neighbours of face %u: %s", face, mt_strerror(st));
    local_free(&l);
    return st;
}

mt_status mt_map_edge_faces(const mt_map *map, uint32_t a, uint32_t b, uint32_t *out_faces,
                            size_t capacity, size_t *out_count, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!map || !out_count)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "map edge faces: NULL");
    if (!vertex_live(map, a) || !vertex_live(map, b))
        return mt__fail(diag, MT_ERR_OUT_OF_RANGE, vertex_live(map, a) ? b : a,
                        "map edge faces: no live vertex %u", vertex_live(map, a) ? b : a);
    const uint32_t seeds[2] = {a, b};
    local_build l;
    mt_status st = local_make(map, seeds, 2, MT_NONE, &l, diag);
    if (st != MT_OK) return st;
    const uint32_t la = local_id(l.verts, l.num_verts, a), lb = local_id(l.verts, l.num_verts, b);
    if (la == MT_NONE || lb == MT_NONE) {
        local_free(&l);
        return MT_ERR_NOT_FOUND; /* a vertex in no face has no edge */
    }
    st = mt_edge_faces(l.mesh, la, lb, out_faces, capacity, out_count);
    if (st == MT_OK && out_faces && capacity >= *out_count)
        for (size_t i = 0; i < *out_count; i++) out_faces[i] = l.faces[out_faces[i]];
    if (st != MT_OK && st != MT_ERR_NOT_FOUND)
        mt__fail(diag, st, a, "map edge faces of %u-%u: %s", a, b, mt_strerror(st));
    local_free(&l);
    return st;
}
