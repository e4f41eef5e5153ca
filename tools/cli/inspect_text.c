/* `meshtopo inspect` without --json: a readable report for someone who has
 * to decide whether a mesh from a sensor or a CAD export is usable: counts,
 * boundary, components, global flags, each defect kind with how many and
 * where (mt_defect_describe), then the one-rings and face neighbours asked
 * for with --vertices / --faces. Long lists are cut after --limit items. */
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "inspect.h"

/* How many items a list shows before "and N more". */
static size_t shown(const inspect_request *req, size_t count)
{
    return req->limit == 0 || count < req->limit ? count : req->limit;
}

static void print_more(FILE *out, size_t count, size_t printed)
{
    if (count > printed) fprintf(out, " and %zu more", count - printed);
}

static const char *plural(uint64_t n, const char *one, const char *many)
{
    return n == 1 ? one : many;
}

static void print_bytes(FILE *out, size_t bytes)
{
    if (bytes < 10 * 1024)
        fprintf(out, "%zu B", bytes);
    else if (bytes < 10 * 1024 * 1024)
        fprintf(out, "%.1f kB", (double)bytes / 1024.0);
    else
        fprintf(out, "%.1f MB", (double)bytes / (1024.0 * 1024.0));
}

static const char *yes_no(bool b)
{
    return b ? "yes" : "no";
}

static void print_face_sizes(FILE *out, const mt_report *r)
{
    fprintf(out, "face sizes:");
    if (r->num_face_size_bins == 0) fprintf(out, " no faces");
    for (size_t i = 0; i < r->num_face_size_bins; i++) {
        const mt_histogram_bin *b = &r->face_size_histogram[i];
        fprintf(out, "%s %" PRIu64 " ", i ? "," : "", b->count);
        if (b->key == 3)
            fprintf(out, "%s", plural(b->count, "triangle", "triangles"));
        else if (b->key == 4)
            fprintf(out, "%s", plural(b->count, "quad", "quads"));
        else if (b->key > 4)
            fprintf(out, "%u-%s", (unsigned)b->key, plural(b->count, "gon", "gons"));
        else
            fprintf(out, "%s with %u %s", plural(b->count, "record", "records"), (unsigned)b->key,
                    plural(b->key, "entry", "entries"));
    }
    fputc('\n', out);
}

static void print_edge_use(FILE *out, const mt_report *r)
{
    fprintf(out, "edge use:");
    if (r->num_edge_use_bins == 0) fprintf(out, " no edges");
    for (size_t i = 0; i < r->num_edge_use_bins; i++) {
        const mt_histogram_bin *b = &r->edge_use_histogram[i];
        fprintf(out, "%s %" PRIu64 " %s used by %u %s", i ? "," : "", b->count,
                plural(b->count, "edge", "edges"), (unsigned)b->key,
                plural(b->key, "face", "faces"));
        if (b->key == 1) fprintf(out, " (boundary)");
        if (b->key > 2) fprintf(out, " (non-manifold)");
    }
    fputc('\n', out);
}

static void print_boundary(FILE *out, const inspect_request *req, const mt_report *r)
{
    if (r->boundary_edges == 0) {
        fprintf(out, "boundary: none\n");
        return;
    }
    fprintf(out, "boundary: %" PRIu64 " %s in %u %s; %s ", r->boundary_edges,
            plural(r->boundary_edges, "edge", "edges"), (unsigned)r->boundary_loops,
            plural(r->boundary_loops, "loop", "loops"),
            plural(r->boundary_loops, "length", "lengths (ascending)"));
    size_t n = shown(req, r->boundary_loops);
    for (size_t i = 0; i < n; i++)
        fprintf(out, "%s%u", i ? ", " : "", (unsigned)r->boundary_loop_lengths[i]);
    print_more(out, r->boundary_loops, n);
    fputc('\n', out);
    if (r->boundary_loops_ambiguous)
        fprintf(out,
                "  (loops touch: some vertex has more than two boundary edges, so a loop "
                "may be a figure eight)\n");
}

static void print_genus(FILE *out, int32_t genus, int32_t with_boundary, bool closed)
{
    if (genus >= 0)
        fprintf(out, "genus %d", (int)genus);
    else if (with_boundary >= 0 && !closed)
        fprintf(out, "genus %d with boundary", (int)with_boundary);
    else
        fprintf(out, "genus undefined");
}

static void print_components(FILE *out, const inspect_request *req, const mt_report *r)
{
    fprintf(out,
            "components: %u joined by edges, %u when faces sharing only a vertex count as joined\n",
            (unsigned)r->connected_components, (unsigned)r->vertex_connected_components);
    size_t n = shown(req, r->connected_components);
    for (size_t i = 0; i < n; i++) {
        const mt_component_info *c = &r->components[i];
        fprintf(out,
                "  #%zu (from face %u): %u %s, %u %s, %" PRIu64 " %s, Euler characteristic %" PRId64
                ", ",
                i, (unsigned)c->min_face, (unsigned)c->faces, plural(c->faces, "face", "faces"),
                (unsigned)c->vertices, plural(c->vertices, "vertex", "vertices"), c->edges,
                plural(c->edges, "edge", "edges"), c->euler_characteristic);
        if (c->closed)
            fprintf(out, "closed");
        else
            fprintf(out, "open (%" PRIu64 " boundary %s, %u %s)", c->boundary_edges,
                    plural(c->boundary_edges, "edge", "edges"), (unsigned)c->boundary_loops,
                    plural(c->boundary_loops, "loop", "loops"));
        fprintf(out, ", %s, %s, ", c->manifold ? "manifold" : "non-manifold",
                c->orientable ? "orientable" : "non-orientable");
        print_genus(out, c->genus, c->genus_with_boundary, c->closed);
        fputc('\n', out);
    }
    if (r->connected_components > n)
        fprintf(out, "  ... and %zu more\n", (size_t)r->connected_components - n);
}

/* Headline of one defect kind: "3 faces use out-of-range vertex indices". */
static void print_defect_headline(FILE *out, const mt_report *r, uint32_t kind, size_t count)
{
    switch (kind) {
        case MT_DEFECT_OUT_OF_RANGE_INDEX:
            fprintf(out,
                    "%zu %s out-of-range vertex indices (%" PRIu64 " bad %s in all); %s left out",
                    count, plural(count, "face uses", "faces use"), r->out_of_range_indices,
                    plural(r->out_of_range_indices, "entry", "entries"),
                    plural(count, "it is", "they are"));
            break;
        case MT_DEFECT_DEGENERATE_FACE:
            fprintf(out, "%zu %s fewer than 3 entries or a repeated vertex; %s left out", count,
                    plural(count, "face has", "faces have"), plural(count, "it is", "they are"));
            break;
        case MT_DEFECT_DUPLICATE_FACE:
            fprintf(out, "%zu %s an earlier face (same vertex cycle)", count,
                    plural(count, "face repeats", "faces repeat"));
            break;
        case MT_DEFECT_NONMANIFOLD_EDGE:
            fprintf(out, "%zu %s more than two faces (non-manifold)", count,
                    plural(count, "edge is shared by", "edges are shared by"));
            break;
        case MT_DEFECT_SAME_DIRECTION_EDGE:
            /* Counted in edges (the report's figure), whatever the entries per edge. */
            fprintf(out, "%" PRIu64 " %s by two or more faces in the same direction",
                    r->duplicate_directed_edges,
                    plural(r->duplicate_directed_edges, "edge is crossed", "edges are crossed"));
            if (r->inconsistent_orientation_edges > 0)
                fprintf(out, " (%" PRIu64 " of them between exactly two faces: a flipped face)",
                        r->inconsistent_orientation_edges);
            break;
        case MT_DEFECT_NONMANIFOLD_VERTEX:
            fprintf(out, "%zu %s not form a single fan (%u %s where separate fans meet)", count,
                    plural(count, "vertex's faces do", "vertices' faces do"),
                    (unsigned)r->bowtie_vertices, plural(r->bowtie_vertices, "bowtie", "bowties"));
            break;
        case MT_DEFECT_ISOLATED_VERTEX:
            fprintf(out, "%zu %s by no valid face (%u in no face record at all)", count,
                    plural(count, "vertex is used", "vertices are used"),
                    (unsigned)r->unreferenced_vertices);
            break;
        case MT_DEFECT_NONFINITE_COORD:
            fprintf(out, "%zu %s a NaN or infinite coordinate", count,
                    plural(count, "vertex has", "vertices have"));
            break;
        default:
            fprintf(out, "%zu x %s", count,
                    kind < MT_DEFECT_KIND_COUNT ? mt_defect_description((mt_defect_kind)kind)
                                                : "unknown defect");
            break;
    }
}

static void print_defects(FILE *out, const inspect_request *req, const mt_report *r)
{
    if (r->num_defects == 0) {
        fprintf(out, "defects: none\n");
        return;
    }
    fprintf(out, "defects (%zu %s):\n", r->num_defects, plural(r->num_defects, "entry", "entries"));
    /* The list is grouped by kind; walk it one group at a time. */
    size_t i = 0;
    while (i < r->num_defects) {
        uint32_t kind = r->defects[i].kind;
        size_t end = i;
        while (end < r->num_defects && r->defects[end].kind == kind) end++;
        size_t count = end - i;
        fprintf(out, "  ");
        print_defect_headline(out, r, kind, count);
        fprintf(out, ":\n");
        size_t n = shown(req, count);
        for (size_t k = 0; k < n; k++) {
            char text[512];
            mt_defect_describe(&r->defects[i + k], text, sizeof text);
            fprintf(out, "    %s\n", text);
        }
        if (count > n)
            fprintf(out, "    ... and %zu more (--limit 0 or --json --json-defects lists all)\n",
                    count - n);
        i = end;
    }
}

static void print_id_run(FILE *out, const uint32_t *ids, size_t count)
{
    for (size_t i = 0; i < count; i++) fprintf(out, "%s%u", i ? ", " : "", (unsigned)ids[i]);
}

/* Number of edges at v used by exactly one face (DEFINITIONS.md boundary
 * edges), over the distinct neighbours of its ring. */
static mt_status count_boundary_edges(const mt_mesh *mesh, uint32_t v, const mt_ring *ring,
                                      size_t *out)
{
    *out = 0;
    uint32_t *nbrs = calloc(ring->num_neighbors + 1, sizeof *nbrs);
    if (!nbrs) return MT_ERR_NOMEM;
    if (ring->num_neighbors) memcpy(nbrs, ring->neighbors, ring->num_neighbors * sizeof *nbrs);
    size_t n = inspect_sort_unique(nbrs, ring->num_neighbors);
    mt_status st = MT_OK;
    for (size_t i = 0; i < n && st == MT_OK; i++) {
        size_t uses = 0;
        st = mt_edge_faces(mesh, v, nbrs[i], NULL, 0, &uses);
        if (st == MT_ERR_BUFFER_TOO_SMALL) st = MT_OK; /* only the count is wanted */
        if (st == MT_OK && uses == 1) (*out)++;
    }
    free(nbrs);
    return st;
}

/* The report's non-manifold entry for v, or NULL. */
static const mt_defect *nonmanifold_entry(const mt_report *r, uint32_t v)
{
    for (size_t i = 0; i < r->num_defects; i++)
        if (r->defects[i].kind == MT_DEFECT_NONMANIFOLD_VERTEX && r->defects[i].a == v)
            return &r->defects[i];
    return NULL;
}

static mt_status print_vertex(FILE *out, const mt_mesh *mesh, uint32_t v, mt_ring *ring)
{
    mt_status st = mt_vert_ring_growing(mesh, v, ring);
    if (st != MT_OK) return st;
    if (ring->num_fans == 0) {
        fprintf(out, "vertex %u: isolated (in no valid face)\n", (unsigned)v);
        return MT_OK;
    }
    uint32_t valence = 0;
    size_t boundary = 0;
    st = mt_vert_valence(mesh, v, &valence);
    if (st == MT_OK) st = count_boundary_edges(mesh, v, ring, &boundary);
    if (st != MT_OK) return st;
    fprintf(out, "vertex %u: %u %s, %zu %s, ", (unsigned)v, (unsigned)valence,
            plural(valence, "neighbour", "neighbours"), ring->num_faces,
            plural(ring->num_faces, "face", "faces"));
    if (boundary)
        fprintf(out, "on the boundary (%zu boundary %s)", boundary,
                plural(boundary, "edge", "edges"));
    else
        fprintf(out, "interior");
    const mt_defect *nm = nonmanifold_entry(mt_mesh_report(mesh), v);
    if (nm && nm->b > 1)
        fprintf(out, ", non-manifold: %u separate fans meet here", (unsigned)nm->b);
    else if (nm)
        fprintf(out, ", non-manifold: on an edge shared by more than two faces");
    else
        fprintf(out, ", manifold");
    fputc('\n', out);
    if (ring->num_fans > 1 && !nm)
        fprintf(out, "  (the ring is split where two faces run the same way along an edge)\n");
    for (size_t k = 0; k < ring->num_fans; k++) {
        const mt_fan *fan = &ring->fans[k];
        fprintf(out, "  fan %zu of %zu, %s: neighbours ", k + 1, ring->num_fans,
                fan->boundary ? "open" : "closed");
        print_id_run(out, ring->neighbors + fan->neighbor_begin, fan->neighbor_count);
        fprintf(out, "; faces ");
        print_id_run(out, ring->faces + fan->face_begin, fan->face_count);
        fputc('\n', out);
    }
    return MT_OK;
}

/* Why a face record was left out, from the report's defect list. */
static void print_rejected_face(FILE *out, const mt_report *r, uint32_t f)
{
    fprintf(out, "face %u: left out of the mesh", (unsigned)f);
    for (size_t i = 0; i < r->num_defects; i++) {
        const mt_defect *d = &r->defects[i];
        if ((d->kind == MT_DEFECT_OUT_OF_RANGE_INDEX || d->kind == MT_DEFECT_DEGENERATE_FACE) &&
            d->a == f) {
            char text[512];
            mt_defect_describe(d, text, sizeof text);
            fprintf(out, ": %s", text);
            break;
        }
    }
    fputc('\n', out);
}

typedef struct face_scratch {
    mt_face_corners corners, other;
    mt_face_adjacency adj;
} face_scratch;

static mt_status print_face(FILE *out, const mt_mesh *mesh, uint32_t f, face_scratch *s)
{
    mt_status st = mt_face_verts_growing(mesh, f, &s->corners);
    if (st == MT_ERR_NOT_FOUND) {
        print_rejected_face(out, mt_mesh_report(mesh), f);
        return MT_OK;
    }
    if (st == MT_OK) st = mt_face_neighbors_growing(mesh, f, &s->adj);
    if (st != MT_OK) return st;
    fprintf(out, "face %u: %zu vertices (", (unsigned)f, s->corners.count);
    print_id_run(out, s->corners.verts, s->corners.count);
    fprintf(out, ")\n");
    for (size_t i = 0; i < s->adj.num_edges && i < s->corners.count; i++) {
        uint32_t a = s->corners.verts[i], b = s->corners.verts[(i + 1) % s->corners.count];
        size_t n = s->adj.offsets[i + 1] - s->adj.offsets[i];
        fprintf(out, "  edge %u-%u: ", (unsigned)a, (unsigned)b);
        if (n == 0) {
            fprintf(out, "boundary\n");
            continue;
        }
        const uint32_t *across = s->adj.faces + s->adj.offsets[i];
        mt_side_use use;
        st = inspect_side_use(mesh, &s->corners, &s->adj, i, &s->other, &use);
        if (st != MT_OK) return st;
        fprintf(out, "shared with %s ", plural(n, "face", "faces"));
        print_id_run(out, across, n);
        if (n > 1) fprintf(out, " (non-manifold: %zu faces on this edge)", n + 1);
        if (use.same_direction) fprintf(out, " (runs the same direction: one face is flipped)");
        fputc('\n', out);
    }
    return MT_OK;
}

static int print_queries(FILE *out, const inspect_request *req)
{
    const mt_mesh *mesh = req->mesh->mesh;
    mt_status st = MT_OK;
    uint32_t failed = MT_NONE;
    const char *what = "vertex";
    if (req->vertices.count) {
        mt_ring ring;
        memset(&ring, 0, sizeof ring);
        fputc('\n', out);
        for (size_t i = 0; i < req->vertices.count && st == MT_OK; i++) {
            failed = req->vertices.ids[i];
            st = print_vertex(out, mesh, failed, &ring);
        }
        mt_ring_free(&ring);
    }
    if (st == MT_OK && req->faces.count) {
        face_scratch s;
        memset(&s, 0, sizeof s);
        what = "face";
        fputc('\n', out);
        for (size_t i = 0; i < req->faces.count && st == MT_OK; i++) {
            failed = req->faces.ids[i];
            st = print_face(out, mesh, failed, &s);
        }
        mt_face_corners_free(&s.corners);
        mt_face_corners_free(&s.other);
        mt_face_adjacency_free(&s.adj);
    }
    if (st != MT_OK) {
        cli_error("inspect", "query of %s %u failed: %s", what, (unsigned)failed, mt_strerror(st));
        return CLI_EXIT_BUILD;
    }
    return CLI_EXIT_OK;
}

/* --weld: what was merged and which vertices the weld made non-manifold. */
static void print_weld(FILE *out, const inspect_request *req)
{
    const cli_weld *w = &req->mesh->weld;
    if (!w->enabled) return;
    if (w->blocks)
        fprintf(out,
                "weld: exact (identical coordinates), map of %zu %s of size %.17g: ", w->blocks,
                plural(w->blocks, "block", "blocks"), w->block_size);
    else if (w->eps == 0)
        fprintf(out, "weld: exact (identical coordinates): ");
    else
        fprintf(out, "weld: within %.17g: ", w->eps);
    fprintf(out, "%u of %u %s merged, %u left; ", (unsigned)w->merged, (unsigned)w->vertices_before,
            plural(w->vertices_before, "vertex", "vertices"), (unsigned)w->vertices_after);
    if (w->num_nonmanifold == 0) {
        fprintf(out, "no vertex made non-manifold by the weld\n");
        return;
    }
    fprintf(out, "%zu made non-manifold by the weld:", w->num_nonmanifold);
    size_t n = shown(req, w->num_nonmanifold);
    for (size_t i = 0; i < n; i++) fprintf(out, "%s %u", i ? "," : "", (unsigned)w->nonmanifold[i]);
    print_more(out, w->num_nonmanifold, n);
    fputc('\n', out);
}

int inspect_print_text(const inspect_request *req, FILE *out)
{
    const mt_mesh *mesh = req->mesh->mesh;
    const mt_report *r = mt_mesh_report(mesh);
    fprintf(out, "file: %s (read in %.1f ms, built in %.1f ms; mesh ", req->path,
            req->mesh->read_ms, req->mesh->build_ms);
    print_bytes(out, mt_mesh_memory_bytes(mesh));
    fprintf(out, ", report ");
    print_bytes(out, mt_mesh_report_memory_bytes(mesh));
    fprintf(out, ")\n");
    print_weld(out, req);
    fprintf(out, "counts: %u %s, %u face %s (%u valid), %" PRIu64 " %s, %" PRIu64 " half-edges\n",
            (unsigned)r->num_verts, plural(r->num_verts, "vertex", "vertices"),
            (unsigned)r->num_faces, plural(r->num_faces, "record", "records"),
            (unsigned)r->num_faces_valid, r->num_edges, plural(r->num_edges, "edge", "edges"),
            r->num_half_edges);
    print_face_sizes(out, r);
    print_edge_use(out, r);
    print_boundary(out, req, r);
    print_components(out, req, r);
    fprintf(out, "Euler characteristic: %" PRId64 " (V - E + F over valid faces, all vertices)\n",
            r->euler_characteristic);
    fprintf(out, "closed: %s, manifold: %s, orientable: %s, consistently oriented: %s, ",
            yes_no(r->closed), yes_no(r->manifold), yes_no(r->orientable),
            yes_no(r->consistently_oriented));
    if (r->genus >= 0)
        fprintf(out, "genus: %d\n", (int)r->genus);
    else
        fprintf(out, "genus: undefined%s\n",
                r->connected_components != 1 ? " (not exactly one component)" : "");
    print_defects(out, req, r);
    if (req->geometry) inspect_geometry_text(out, req->geometry, req->limit);
    return print_queries(out, req);
}
