/* `meshtopo inspect --self-intersections`: the geometric checks of a mesh
 * (faces passing through each other, non-simple and warped polygon faces,
 * boundary loops crossing themselves) gathered from the library's three
 * whole-mesh queries, and printed readable or as JSON. */
#include <stdlib.h>

#include "inspect.h"

void inspect_geometry_free(inspect_geometry *g)
{
    free(g->pairs);
    free(g->faces);
    free(g->loops);
    *g = (inspect_geometry){0};
}

/* One whole-mesh query answered into a new array of *out_count elements of
 * elem_size bytes: asks for the count, then for the elements. */
typedef mt_status (*whole_mesh_query)(const mt_mesh *mesh, void *out, size_t capacity,
                                      size_t *out_count, mt_diag *diag);

static mt_status pairs_query(const mt_mesh *m, void *out, size_t cap, size_t *n, mt_diag *d)
{
    return mt_mesh_self_intersections(m, out, cap, n, d);
}

static mt_status faces_query(const mt_mesh *m, void *out, size_t cap, size_t *n, mt_diag *d)
{
    return mt_mesh_nonsimple_faces(m, out, cap, n, d);
}

static mt_status loops_query(const mt_mesh *m, void *out, size_t cap, size_t *n, mt_diag *d)
{
    return mt_mesh_boundary_loop_crossings(m, out, cap, n, d);
}

static mt_status answer(const mt_mesh *mesh, whole_mesh_query query, size_t elem_size, void **out,
                        size_t *out_count, mt_diag *diag)
{
    mt_status s = query(mesh, NULL, 0, out_count, diag);
    if (s != MT_OK || *out_count == 0) return s;
    *out = malloc(*out_count * elem_size);
    if (!*out) return mt_diag_set(diag, MT_ERR_NOMEM, "no memory for %zu results", *out_count);
    return query(mesh, *out, *out_count, out_count, diag);
}

mt_status inspect_geometry_compute(const mt_mesh *mesh, inspect_geometry *g, mt_diag *diag)
{
    *g = (inspect_geometry){0};
    const double start = cli_now_ms();
    void *pairs = NULL, *faces = NULL, *loops = NULL;
    mt_status s = answer(mesh, pairs_query, sizeof *g->pairs, &pairs, &g->num_pairs, diag);
    g->pairs = pairs;
    if (s == MT_OK) s = answer(mesh, faces_query, sizeof *g->faces, &faces, &g->num_faces, diag);
    g->faces = faces;
    if (s == MT_OK) s = answer(mesh, loops_query, sizeof *g->loops, &loops, &g->num_loops, diag);
    g->loops = loops;
    g->ms = cli_now_ms() - start;
    if (s != MT_OK) inspect_geometry_free(g);
    return s;
}

size_t inspect_geometry_findings(const inspect_geometry *g)
{
    return g->num_pairs + g->num_faces + g->num_loops;
}

static const char *shape_name(mt_face_shape_kind kind)
{
    return kind == MT_FACE_SELF_CROSSING ? "self_crossing"
           : kind == MT_FACE_WARPED      ? "warped"
                                         : "simple";
}

static void json_pair(mt_json *j, uint32_t a, uint32_t b)
{
    mt_json_array_begin(j);
    mt_json_uint(j, a);
    mt_json_uint(j, b);
    mt_json_array_end(j);
}

void inspect_geometry_json(mt_json *j, const inspect_geometry *g)
{
    mt_json_key(j, "self_intersecting_pairs");
    mt_json_uint(j, g->num_pairs);
    mt_json_key(j, "non_simple_faces");
    mt_json_uint(j, g->num_faces);
    mt_json_key(j, "self_intersecting_boundary_loops");
    mt_json_uint(j, g->num_loops);
    mt_json_key(j, "self_intersections");
    mt_json_object_begin(j);
    mt_json_key(j, "face_pairs");
    mt_json_array_begin(j);
    for (size_t i = 0; i < g->num_pairs; i++) json_pair(j, g->pairs[i].a, g->pairs[i].b);
    mt_json_array_end(j);
    mt_json_key(j, "faces");
    mt_json_array_begin(j);
    for (size_t i = 0; i < g->num_faces; i++) {
        const mt_face_shape *f = &g->faces[i];
        mt_json_object_begin(j);
        mt_json_key(j, "face");
        mt_json_uint(j, f->face);
        mt_json_key(j, "kind");
        mt_json_string(j, shape_name(f->kind));
        mt_json_key(j, "sides");
        if (f->kind == MT_FACE_SELF_CROSSING)
            json_pair(j, f->side_a, f->side_b);
        else
            mt_json_null(j);
        mt_json_key(j, "warp");
        mt_json_double(j, f->warp);
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    mt_json_key(j, "boundary_loops");
    mt_json_array_begin(j);
    for (size_t i = 0; i < g->num_loops; i++) {
        const mt_loop_crossing *l = &g->loops[i];
        mt_json_object_begin(j);
        mt_json_key(j, "loop");
        mt_json_uint(j, l->loop);
        mt_json_key(j, "edges");
        mt_json_array_begin(j);
        json_pair(j, l->edge_a[0], l->edge_a[1]);
        json_pair(j, l->edge_b[0], l->edge_b[1]);
        mt_json_array_end(j);
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    mt_json_object_end(j);
}

/* How many of count items to list under limit (0 = all). */
static size_t shown(size_t count, size_t limit)
{
    return limit == 0 || count < limit ? count : limit;
}

static void more(FILE *out, size_t count, size_t limit)
{
    if (shown(count, limit) < count)
        fprintf(out, "    ... and %zu more (--limit 0 or --json lists all)\n",
                count - shown(count, limit));
}

void inspect_geometry_text(FILE *out, const inspect_geometry *g, size_t limit)
{
    fprintf(out, "self-intersections: %zu face %s", g->num_pairs,
            g->num_pairs == 1 ? "pair" : "pairs");
    if (g->ms >= 0) fprintf(out, " (checked in %.1f ms)", g->ms);
    fputc('\n', out);
    for (size_t i = 0; i < shown(g->num_pairs, limit); i++)
        fprintf(out, "    faces %u and %u pass through or touch each other\n", g->pairs[i].a,
                g->pairs[i].b);
    more(out, g->num_pairs, limit);
    fprintf(out, "non-simple faces: %zu\n", g->num_faces);
    for (size_t i = 0; i < shown(g->num_faces, limit); i++) {
        const mt_face_shape *f = &g->faces[i];
        if (f->kind == MT_FACE_SELF_CROSSING)
            fprintf(out, "    face %u crosses itself: its sides %u and %u meet\n", f->face,
                    f->side_a, f->side_b);
        else
            fprintf(out, "    face %u is warped: a corner is %.3g of its size off its plane\n",
                    f->face, f->warp);
    }
    more(out, g->num_faces, limit);
    fprintf(out, "self-crossing boundary loops: %zu\n", g->num_loops);
    for (size_t i = 0; i < shown(g->num_loops, limit); i++) {
        const mt_loop_crossing *l = &g->loops[i];
        fprintf(out, "    boundary loop %u: its edges %u-%u and %u-%u cross\n", l->loop,
                l->edge_a[0], l->edge_a[1], l->edge_b[0], l->edge_b[1]);
    }
    more(out, g->num_loops, limit);
}
