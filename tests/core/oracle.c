/* The tests' reference report: each quantity of DEFINITIONS.md computed the
 * plain way (sort the sides into edges, sort link edges per vertex,
 * union-find for every "connected" notion, parity union-find for
 * orientability). Nothing here is shared with the library's builder, so the
 * two can be checked against each other. */
#include "oracle.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- small helpers ---------------------------------------------------- */

static void *oracle_alloc(size_t count, size_t size)
{
    if (size != 0 && count > SIZE_MAX / size) {
        fprintf(stderr, "oracle: allocation of %zu x %zu bytes overflows\n", count, size);
        exit(1);
    }
    void *p = calloc(count ? count : 1, size ? size : 1);
    if (!p) {
        fprintf(stderr, "oracle: out of memory (%zu x %zu bytes)\n", count, size);
        exit(1);
    }
    return p;
}

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return (a > b) - (a < b);
}

/* Sorts values[0..n) and removes repeats; returns the new count. */
static size_t sort_unique(uint32_t *values, size_t n)
{
    if (n == 0) return 0;
    qsort(values, n, sizeof *values, cmp_u32);
    size_t m = 1;
    for (size_t i = 1; i < n; i++)
        if (values[i] != values[m - 1]) values[m++] = values[i];
    return m;
}

/* Union-find with path halving; the smaller id becomes the root. */
static uint32_t *uf_new(size_t n)
{
    uint32_t *parent = oracle_alloc(n, sizeof *parent);
    for (size_t i = 0; i < n; i++) parent[i] = (uint32_t)i;
    return parent;
}

static uint32_t uf_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

static void uf_union(uint32_t *parent, uint32_t x, uint32_t y)
{
    x = uf_find(parent, x);
    y = uf_find(parent, y);
    if (x < y) parent[y] = x;
    if (y < x) parent[x] = y;
}

/* Union-find whose links carry a parity bit: parity of x relative to its root
 * is the xor of the bits on the way up. Union by size keeps paths short. */
static uint32_t parity_find(const uint32_t *parent, const uint8_t *bit, uint32_t x,
                            uint8_t *out_parity)
{
    uint8_t p = 0;
    while (parent[x] != x) {
        p ^= bit[x];
        x = parent[x];
    }
    *out_parity = p;
    return x;
}

/* Asks parity(x) xor parity(y) == want; returns false on a contradiction. */
static bool parity_union(uint32_t *parent, uint8_t *bit, uint32_t *size, uint32_t x, uint32_t y,
                         uint8_t want)
{
    uint8_t px, py;
    uint32_t rx = parity_find(parent, bit, x, &px);
    uint32_t ry = parity_find(parent, bit, y, &py);
    if (rx == ry) return (uint8_t)(px ^ py) == want;
    if (size[rx] < size[ry]) {
        uint32_t t = rx;
        rx = ry;
        ry = t;
    }
    parent[ry] = rx;
    bit[ry] = (uint8_t)(px ^ py ^ want);
    size[rx] += size[ry];
    return true;
}

/* ---- sides and link edges -------------------------------------------- */

typedef struct side {
    uint32_t a, b; /* a < b */
    uint32_t face;
    uint8_t forward; /* the face runs a -> b */
} side;

static int cmp_side(const void *x, const void *y)
{
    const side *s = x, *t = y;
    if (s->a != t->a) return s->a < t->a ? -1 : 1;
    if (s->b != t->b) return s->b < t->b ? -1 : 1;
    if (s->face != t->face) return s->face < t->face ? -1 : 1;
    return 0;
}

typedef struct link_edge {
    uint32_t v, comp; /* the vertex, and the component of the face */
    uint32_t p, q;    /* the face's vertices before and after v */
} link_edge;

static int cmp_link_edge(const void *x, const void *y)
{
    const link_edge *s = x, *t = y;
    if (s->v != t->v) return s->v < t->v ? -1 : 1;
    if (s->comp != t->comp) return s->comp < t->comp ? -1 : 1;
    return 0;
}

static int cmp_dup_side(const void *x, const void *y)
{
    const mt_oracle_side *s = x, *t = y;
    if (s->a != t->a) return s->a < t->a ? -1 : 1;
    return (s->b > t->b) - (s->b < t->b);
}

/* One end of a boundary edge, for joining the edges that meet at a vertex. */
typedef struct boundary_end {
    uint32_t v, comp;
    uint32_t edge; /* index among the boundary edges */
} boundary_end;

static int cmp_boundary_end(const void *x, const void *y)
{
    const boundary_end *s = x, *t = y;
    if (s->v != t->v) return s->v < t->v ? -1 : 1;
    return (s->comp > t->comp) - (s->comp < t->comp);
}

static size_t index_of(const uint32_t *sorted, size_t n, uint32_t value)
{
    const uint32_t *hit = bsearch(&value, sorted, n, sizeof *sorted, cmp_u32);
    return (size_t)(hit - sorted);
}

/* The link multigraph made of edges[0..n): its connected parts and whether
 * a node has degree > 2. */
static void link_analyse(const link_edge *edges, size_t n, uint32_t *out_parts, bool *out_branch)
{
    uint32_t *nodes = oracle_alloc(2 * n, sizeof *nodes);
    for (size_t i = 0; i < n; i++) {
        nodes[2 * i] = edges[i].p;
        nodes[2 * i + 1] = edges[i].q;
    }
    size_t m = sort_unique(nodes, 2 * n);
    uint32_t *degree = oracle_alloc(m, sizeof *degree);
    uint32_t *parent = uf_new(m);
    for (size_t i = 0; i < n; i++) {
        size_t p = index_of(nodes, m, edges[i].p);
        size_t q = index_of(nodes, m, edges[i].q);
        degree[p]++;
        degree[q]++;
        uf_union(parent, (uint32_t)p, (uint32_t)q);
    }
    uint32_t parts = 0;
    bool branch = false;
    for (size_t i = 0; i < m; i++) {
        if (uf_find(parent, (uint32_t)i) == i) parts++;
        if (degree[i] > 2) branch = true;
    }
    free(nodes);
    free(degree);
    free(parent);
    *out_parts = parts;
    *out_branch = branch;
}

/* ---- duplicate faces --------------------------------------------------- */

/* qsort has no context argument: the canonical cycles being compared. */
static const uint32_t *dup_canon;
static const uint64_t *dup_offset;
static const uint32_t *dup_sizes;

/* Orders faces by (size, canonical cycle, id). */
static int cmp_canon_face(const void *x, const void *y)
{
    uint32_t f = *(const uint32_t *)x, g = *(const uint32_t *)y;
    if (dup_sizes[f] != dup_sizes[g]) return dup_sizes[f] < dup_sizes[g] ? -1 : 1;
    const uint32_t *cf = dup_canon + dup_offset[f], *cg = dup_canon + dup_offset[g];
    for (uint32_t i = 0; i < dup_sizes[f]; i++)
        if (cf[i] != cg[i]) return cf[i] < cg[i] ? -1 : 1;
    return (f > g) - (f < g);
}

/* Writes the cycle rec[0..n) starting at its smallest vertex, in the
 * direction whose second vertex is smaller (the vertices are distinct). */
static void canonical_cycle(const uint32_t *rec, uint32_t n, uint32_t *out)
{
    uint32_t m = 0;
    for (uint32_t i = 1; i < n; i++)
        if (rec[i] < rec[m]) m = i;
    bool backward = rec[(m + n - 1) % n] < rec[(m + 1) % n];
    for (uint32_t i = 0; i < n; i++) out[i] = backward ? rec[(m + n - i) % n] : rec[(m + i) % n];
}

static bool same_cycle(const uint32_t *canon, const uint64_t *offset, const uint32_t *sizes,
                       uint32_t f, uint32_t g)
{
    return sizes[f] == sizes[g] &&
           memcmp(canon + offset[f], canon + offset[g], (size_t)sizes[f] * sizeof *canon) == 0;
}

/* ---- the report --------------------------------------------------------- */

static bool sizes_consistent(const mt_face_list *list)
{
    if (list->num_faces > 0 && !list->face_sizes) return false;
    if (list->num_indices > 0 && !list->face_indices) return false;
    uint64_t sum = 0;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        sum += list->face_sizes[f];
        if (sum > list->num_indices) return false;
    }
    return sum == list->num_indices;
}

static mt_histogram_bin *histogram_of(uint32_t *keys, size_t n, size_t *out_bins)
{
    qsort(keys, n, sizeof *keys, cmp_u32);
    mt_histogram_bin *bins = oracle_alloc(n, sizeof *bins);
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (m == 0 || bins[m - 1].key != keys[i]) bins[m++].key = keys[i];
        bins[m - 1].count++;
    }
    *out_bins = m;
    return bins;
}

bool mt_oracle_compute(const mt_face_list *list, mt_oracle *out)
{
    memset(out, 0, sizeof *out);
    if (!list || !sizes_consistent(list)) return false;
    const uint32_t V = list->num_verts, F = list->num_faces;
    const uint32_t *sizes = list->face_sizes;
    const uint32_t *idx = list->face_indices;
    mt_report *r = &out->report;
    r->num_verts = V;
    r->num_faces = F;
    r->genus = -1;

    /* Records: offsets, out-of-range entries, repeats, validity. */
    out->face_offset = oracle_alloc(F, sizeof *out->face_offset);
    out->face_valid = oracle_alloc(F, sizeof *out->face_valid);
    out->face_degenerate = oracle_alloc(F, sizeof *out->face_degenerate);
    out->face_distinct = oracle_alloc(F, sizeof *out->face_distinct);
    out->face_first_bad = oracle_alloc(F, sizeof *out->face_first_bad);
    out->face_duplicate_of = oracle_alloc(F, sizeof *out->face_duplicate_of);
    out->face_component = oracle_alloc(F, sizeof *out->face_component);
    bool *referenced = oracle_alloc(V, sizeof *referenced);
    bool *in_valid = oracle_alloc(V, sizeof *in_valid);
    uint32_t max_size = 0;
    for (uint32_t f = 0; f < F; f++)
        if (sizes[f] > max_size) max_size = sizes[f];
    uint32_t *scratch = oracle_alloc(max_size, sizeof *scratch);
    uint64_t offset = 0;
    size_t num_sides = 0;
    for (uint32_t f = 0; f < F; f++) {
        const uint32_t n = sizes[f];
        const uint32_t *rec = n > 0 ? idx + offset : NULL;
        out->face_offset[f] = offset;
        out->face_first_bad[f] = MT_NONE;
        out->face_duplicate_of[f] = MT_NONE;
        out->face_component[f] = MT_NONE;
        for (uint32_t i = 0; i < n; i++) {
            if (rec[i] >= V) {
                r->out_of_range_indices++;
                if (out->face_first_bad[f] == MT_NONE) out->face_first_bad[f] = i;
            } else {
                referenced[rec[i]] = true;
            }
        }
        if (out->face_first_bad[f] != MT_NONE) r->faces_with_out_of_range_indices++;
        if (n > 0) memcpy(scratch, rec, (size_t)n * sizeof *scratch);
        out->face_distinct[f] = (uint32_t)sort_unique(scratch, n);
        out->face_degenerate[f] = n < 3 || out->face_distinct[f] < n;
        if (out->face_degenerate[f]) r->degenerate_faces++;
        out->face_valid[f] = !out->face_degenerate[f] && out->face_first_bad[f] == MT_NONE;
        if (out->face_valid[f]) {
            r->num_faces_valid++;
            num_sides += n;
            for (uint32_t i = 0; i < n; i++) in_valid[rec[i]] = true;
        }
        r->num_half_edges += n;
        offset += n;
    }
    free(scratch);
    out->isolated_verts = oracle_alloc(V, sizeof *out->isolated_verts);
    for (uint32_t v = 0; v < V; v++) {
        if (!referenced[v]) r->unreferenced_vertices++;
        if (!in_valid[v]) out->isolated_verts[r->isolated_vertices++] = v;
    }
    free(referenced);
    free(in_valid);

    /* Face size histogram over every record. */
    uint32_t *keys = oracle_alloc(F, sizeof *keys);
    if (F > 0) memcpy(keys, sizes, (size_t)F * sizeof *keys);
    r->face_size_histogram = histogram_of(keys, F, &r->num_face_size_bins);
    free(keys);

    /* Sides of valid faces, sorted into edges. */
    side *sides = oracle_alloc(num_sides, sizeof *sides);
    size_t s = 0;
    for (uint32_t f = 0; f < F; f++) {
        if (!out->face_valid[f]) continue;
        const uint32_t n = sizes[f];
        const uint32_t *rec = idx + out->face_offset[f];
        for (uint32_t i = 0; i < n; i++) {
            uint32_t u = rec[i], w = rec[(i + 1) % n];
            sides[s].a = u < w ? u : w;
            sides[s].b = u < w ? w : u;
            sides[s].face = f;
            sides[s].forward = u < w;
            s++;
        }
    }
    qsort(sides, num_sides, sizeof *sides, cmp_side);
    out->edges = oracle_alloc(num_sides, sizeof *out->edges);
    out->edge_faces = oracle_alloc(num_sides, sizeof *out->edge_faces);
    out->dup_sides = oracle_alloc(num_sides, sizeof *out->dup_sides);
    for (size_t i = 0; i < num_sides; i++) out->edge_faces[i] = sides[i].face;
    for (size_t i = 0; i < num_sides;) {
        size_t j = i;
        while (j < num_sides && sides[j].a == sides[i].a && sides[j].b == sides[i].b) j++;
        mt_oracle_edge *e = &out->edges[out->num_edges++];
        e->a = sides[i].a;
        e->b = sides[i].b;
        e->uses = (uint32_t)(j - i);
        e->face_begin = i;
        for (size_t k = i; k < j; k++) e->forward += sides[k].forward;
        const uint32_t backward = e->uses - e->forward;
        if (e->uses == 1) r->boundary_edges++;
        if (e->uses > 2) r->nonmanifold_edges++;
        if (e->uses == 2 && (e->forward == 2 || backward == 2)) r->inconsistent_orientation_edges++;
        if (e->forward >= 2 || backward >= 2) r->duplicate_directed_edges++;
        if (e->forward >= 2)
            out->dup_sides[out->num_dup_sides++] = (mt_oracle_side){e->a, e->b, e->forward};
        if (backward >= 2)
            out->dup_sides[out->num_dup_sides++] = (mt_oracle_side){e->b, e->a, backward};
        i = j;
    }
    free(sides);
    r->num_edges = out->num_edges;
    keys = oracle_alloc(out->num_edges, sizeof *keys);
    for (size_t e = 0; e < out->num_edges; e++) keys[e] = out->edges[e].uses;
    r->edge_use_histogram = histogram_of(keys, out->num_edges, &r->num_edge_use_bins);
    free(keys);
    qsort(out->dup_sides, out->num_dup_sides, sizeof *out->dup_sides, cmp_dup_side);

    /* Vertex neighbours (from the edges) and faces (ascending by construction). */
    out->vert_nb_offsets = oracle_alloc((size_t)V + 1, sizeof(size_t));
    out->vert_face_offsets = oracle_alloc((size_t)V + 1, sizeof(size_t));
    for (size_t e = 0; e < out->num_edges; e++) {
        out->vert_nb_offsets[out->edges[e].a + 1]++;
        out->vert_nb_offsets[out->edges[e].b + 1]++;
    }
    for (uint32_t f = 0; f < F; f++) {
        if (!out->face_valid[f]) continue;
        for (uint32_t i = 0; i < sizes[f]; i++)
            out->vert_face_offsets[idx[out->face_offset[f] + i] + 1]++;
    }
    for (uint32_t v = 0; v < V; v++) {
        out->vert_nb_offsets[v + 1] += out->vert_nb_offsets[v];
        out->vert_face_offsets[v + 1] += out->vert_face_offsets[v];
    }
    out->vert_nb = oracle_alloc(out->vert_nb_offsets[V], sizeof *out->vert_nb);
    out->vert_faces = oracle_alloc(out->vert_face_offsets[V], sizeof *out->vert_faces);
    size_t *fill = oracle_alloc((size_t)V + 1, sizeof *fill);
    memcpy(fill, out->vert_nb_offsets, ((size_t)V + 1) * sizeof *fill);
    for (size_t e = 0; e < out->num_edges; e++) {
        out->vert_nb[fill[out->edges[e].a]++] = out->edges[e].b;
        out->vert_nb[fill[out->edges[e].b]++] = out->edges[e].a;
    }
    for (uint32_t v = 0; v < V; v++) {
        size_t begin = out->vert_nb_offsets[v];
        qsort(out->vert_nb + begin, out->vert_nb_offsets[v + 1] - begin, sizeof(uint32_t), cmp_u32);
    }
    memcpy(fill, out->vert_face_offsets, ((size_t)V + 1) * sizeof *fill);
    for (uint32_t f = 0; f < F; f++) {
        if (!out->face_valid[f]) continue;
        for (uint32_t i = 0; i < sizes[f]; i++)
            out->vert_faces[fill[idx[out->face_offset[f] + i]]++] = f;
    }
    free(fill);

    /* Face adjacency: every other face on each of its edges, then deduplicated. */
    size_t *adj_count = oracle_alloc((size_t)F + 1, sizeof *adj_count);
    for (size_t e = 0; e < out->num_edges; e++) {
        const mt_oracle_edge *ed = &out->edges[e];
        for (uint32_t k = 0; k < ed->uses; k++)
            adj_count[out->edge_faces[ed->face_begin + k] + 1] += ed->uses - 1;
    }
    for (uint32_t f = 0; f < F; f++) adj_count[f + 1] += adj_count[f];
    uint32_t *adj_raw = oracle_alloc(adj_count[F], sizeof *adj_raw);
    size_t *adj_fill = oracle_alloc((size_t)F + 1, sizeof *adj_fill);
    memcpy(adj_fill, adj_count, ((size_t)F + 1) * sizeof *adj_fill);
    for (size_t e = 0; e < out->num_edges; e++) {
        const mt_oracle_edge *ed = &out->edges[e];
        const uint32_t *ef = out->edge_faces + ed->face_begin;
        for (uint32_t k = 0; k < ed->uses; k++)
            for (uint32_t l = 0; l < ed->uses; l++)
                if (k != l) adj_raw[adj_fill[ef[k]]++] = ef[l];
    }
    free(adj_fill);
    out->face_adj_offsets = oracle_alloc((size_t)F + 1, sizeof(size_t));
    out->face_adj = oracle_alloc(adj_count[F], sizeof *out->face_adj);
    for (uint32_t f = 0; f < F; f++) {
        size_t n = sort_unique(adj_raw + adj_count[f], adj_count[f + 1] - adj_count[f]);
        memcpy(out->face_adj + out->face_adj_offsets[f], adj_raw + adj_count[f],
               n * sizeof(uint32_t));
        out->face_adj_offsets[f + 1] = out->face_adj_offsets[f] + n;
    }
    free(adj_raw);
    free(adj_count);

    /* Edge-connected components, numbered by their smallest face. */
    uint32_t *face_uf = uf_new(F);
    for (size_t e = 0; e < out->num_edges; e++) {
        const mt_oracle_edge *ed = &out->edges[e];
        for (uint32_t k = 1; k < ed->uses; k++)
            uf_union(face_uf, out->edge_faces[ed->face_begin], out->edge_faces[ed->face_begin + k]);
    }
    uint32_t *root_label = oracle_alloc(F, sizeof *root_label);
    for (uint32_t f = 0; f < F; f++) root_label[f] = MT_NONE;
    uint32_t C = 0;
    for (uint32_t f = 0; f < F; f++) {
        if (!out->face_valid[f]) continue;
        uint32_t root = uf_find(face_uf, f);
        if (root_label[root] == MT_NONE) root_label[root] = C++;
        out->face_component[f] = root_label[root];
    }
    free(face_uf);
    free(root_label);
    r->connected_components = C;
    mt_component_info *comps = oracle_alloc(C, sizeof *comps);
    r->components = comps;
    for (uint32_t c = 0; c < C; c++) {
        comps[c].min_face = MT_NONE;
        comps[c].manifold = true;
        comps[c].orientable = true;
    }
    for (uint32_t f = 0; f < F; f++) {
        uint32_t c = out->face_component[f];
        if (c == MT_NONE) continue;
        if (comps[c].min_face == MT_NONE) comps[c].min_face = f;
        comps[c].faces++;
    }

    /* Vertex-connected components: faces sharing a vertex are joined. */
    face_uf = uf_new(F);
    for (uint32_t v = 0; v < V; v++)
        for (size_t k = out->vert_face_offsets[v] + 1; k < out->vert_face_offsets[v + 1]; k++)
            uf_union(face_uf, out->vert_faces[out->vert_face_offsets[v]], out->vert_faces[k]);
    for (uint32_t f = 0; f < F; f++)
        if (out->face_valid[f] && uf_find(face_uf, f) == f) r->vertex_connected_components++;
    free(face_uf);

    /* Per component: distinct vertices, edges, boundary and non-manifold edges. */
    for (uint32_t v = 0; v < V; v++) {
        size_t begin = out->vert_face_offsets[v], n = out->vert_face_offsets[v + 1] - begin;
        uint32_t *cs = oracle_alloc(n, sizeof *cs);
        for (size_t k = 0; k < n; k++) cs[k] = out->face_component[out->vert_faces[begin + k]];
        size_t m = sort_unique(cs, n);
        for (size_t k = 0; k < m; k++) comps[cs[k]].vertices++;
        free(cs);
    }
    for (size_t e = 0; e < out->num_edges; e++) {
        mt_oracle_edge *ed = &out->edges[e];
        ed->component = out->face_component[out->edge_faces[ed->face_begin]];
        comps[ed->component].edges++;
        if (ed->uses == 1) comps[ed->component].boundary_edges++;
        if (ed->uses > 2) comps[ed->component].manifold = false;
    }

    /* Vertex links: whole, and restricted to each component. */
    link_edge *links = oracle_alloc(num_sides, sizeof *links);
    size_t num_links = 0;
    for (uint32_t f = 0; f < F; f++) {
        if (!out->face_valid[f]) continue;
        const uint32_t n = sizes[f];
        const uint32_t *rec = idx + out->face_offset[f];
        for (uint32_t i = 0; i < n; i++) {
            link_edge *l = &links[num_links++];
            l->v = rec[i];
            l->comp = out->face_component[f];
            l->p = rec[(i + n - 1) % n];
            l->q = rec[(i + 1) % n];
        }
    }
    qsort(links, num_links, sizeof *links, cmp_link_edge);
    out->link_parts = oracle_alloc(V, sizeof *out->link_parts);
    out->link_branch = oracle_alloc(V, sizeof *out->link_branch);
    out->nonmanifold_verts = oracle_alloc(V, sizeof *out->nonmanifold_verts);
    for (size_t i = 0; i < num_links;) {
        size_t j = i;
        while (j < num_links && links[j].v == links[i].v) j++;
        const uint32_t v = links[i].v;
        link_analyse(links + i, j - i, &out->link_parts[v], &out->link_branch[v]);
        if (out->link_parts[v] != 1 || out->link_branch[v])
            out->nonmanifold_verts[r->nonmanifold_vertices++] = v;
        if (out->link_parts[v] > 1) r->bowtie_vertices++;
        for (size_t k = i; k < j;) {
            size_t l = k;
            while (l < j && links[l].comp == links[k].comp) l++;
            uint32_t parts;
            bool branch;
            link_analyse(links + k, l - k, &parts, &branch);
            if (parts != 1 || branch) comps[links[k].comp].manifold = false;
            k = l;
        }
        i = j;
    }
    free(links);

    /* Orientability: flip bits over edges used exactly twice. */
    uint32_t *par_parent = uf_new(F);
    uint8_t *par_bit = oracle_alloc(F, sizeof *par_bit);
    uint32_t *par_size = oracle_alloc(F, sizeof *par_size);
    for (uint32_t f = 0; f < F; f++) par_size[f] = 1;
    for (size_t e = 0; e < out->num_edges; e++) {
        const mt_oracle_edge *ed = &out->edges[e];
        if (ed->uses != 2) continue;
        uint32_t f = out->edge_faces[ed->face_begin], g = out->edge_faces[ed->face_begin + 1];
        uint8_t same_direction = ed->forward != 1;
        if (!parity_union(par_parent, par_bit, par_size, f, g, same_direction))
            comps[ed->component].orientable = false;
    }
    free(par_parent);
    free(par_bit);
    free(par_size);

    /* Boundary: graph of the edges used once, whole and per component. */
    size_t num_boundary = (size_t)r->boundary_edges;
    uint32_t *bedge = oracle_alloc(num_boundary, sizeof *bedge); /* index in edges */
    size_t nb = 0;
    for (size_t e = 0; e < out->num_edges; e++)
        if (out->edges[e].uses == 1) bedge[nb++] = (uint32_t)e;
    /* Each boundary edge joins the others at both of its ends: sort the ends. */
    boundary_end *ends = oracle_alloc(2 * num_boundary, sizeof *ends);
    for (size_t i = 0; i < num_boundary; i++) {
        const mt_oracle_edge *ed = &out->edges[bedge[i]];
        ends[2 * i] = (boundary_end){ed->a, ed->component, (uint32_t)i};
        ends[2 * i + 1] = (boundary_end){ed->b, ed->component, (uint32_t)i};
    }
    qsort(ends, 2 * num_boundary, sizeof *ends, cmp_boundary_end);
    uint32_t *whole_uf = uf_new(num_boundary);
    uint32_t *comp_uf = uf_new(num_boundary);
    const size_t num_ends = 2 * num_boundary;
    for (size_t i = 0; i < num_ends;) {
        size_t j = i + 1;
        while (j < num_ends && ends[j].v == ends[i].v) j++;
        if (j - i != 2) r->boundary_loops_ambiguous = true;
        for (size_t k = i + 1; k < j; k++) {
            uf_union(whole_uf, ends[i].edge, ends[k].edge);
            if (ends[k].comp == ends[k - 1].comp) uf_union(comp_uf, ends[k - 1].edge, ends[k].edge);
        }
        i = j;
    }
    free(ends);
    uint32_t *class_size = oracle_alloc(num_boundary, sizeof *class_size);
    for (size_t i = 0; i < num_boundary; i++) class_size[uf_find(whole_uf, (uint32_t)i)]++;
    r->boundary_loop_lengths = oracle_alloc(num_boundary, sizeof *r->boundary_loop_lengths);
    for (size_t i = 0; i < num_boundary; i++) {
        if (uf_find(whole_uf, (uint32_t)i) == i)
            r->boundary_loop_lengths[r->boundary_loops++] = class_size[i];
        if (uf_find(comp_uf, (uint32_t)i) == i)
            comps[out->edges[bedge[i]].component].boundary_loops++;
    }
    qsort(r->boundary_loop_lengths, r->boundary_loops, sizeof(uint32_t), cmp_u32);
    free(class_size);
    free(whole_uf);
    free(comp_uf);
    free(bedge);

    /* Component figures that follow from the counts. */
    r->orientable = true;
    for (uint32_t c = 0; c < C; c++) {
        mt_component_info *ci = &comps[c];
        ci->euler_characteristic = (int64_t)ci->vertices - (int64_t)ci->edges + (int64_t)ci->faces;
        ci->closed = ci->boundary_edges == 0;
        ci->genus = -1;
        ci->genus_with_boundary = -1;
        if (ci->manifold && ci->orientable) {
            ci->genus_with_boundary =
                (int32_t)((2 - ci->euler_characteristic - (int64_t)ci->boundary_loops) / 2);
            if (ci->closed) ci->genus = (int32_t)((2 - ci->euler_characteristic) / 2);
        }
        if (!ci->orientable) r->orientable = false;
    }

    /* Duplicate faces: valid faces with the same canonical cycle. */
    uint32_t *canon = oracle_alloc(list->num_indices, sizeof *canon);
    uint32_t *order = oracle_alloc(F, sizeof *order);
    uint32_t num_order = 0;
    for (uint32_t f = 0; f < F; f++) {
        if (!out->face_valid[f]) continue;
        canonical_cycle(idx + out->face_offset[f], sizes[f], canon + out->face_offset[f]);
        order[num_order++] = f;
    }
    dup_canon = canon;
    dup_offset = out->face_offset;
    dup_sizes = sizes;
    qsort(order, num_order, sizeof *order, cmp_canon_face);
    uint32_t group_first = MT_NONE; /* smallest face of the current run of equal cycles */
    for (uint32_t i = 0; i < num_order; i++) {
        uint32_t f = order[i];
        if (i > 0 && same_cycle(canon, out->face_offset, sizes, order[i - 1], f)) {
            out->face_duplicate_of[f] = group_first;
            r->duplicate_faces++;
        } else {
            group_first = f;
        }
    }
    dup_canon = NULL;
    dup_offset = NULL;
    dup_sizes = NULL;
    free(canon);
    free(order);

    /* Non-finite coordinates. */
    out->nonfinite_axis = oracle_alloc(V, sizeof *out->nonfinite_axis);
    for (uint32_t v = 0; v < V; v++) {
        out->nonfinite_axis[v] = MT_NONE;
        if (!list->positions) continue;
        for (uint32_t axis = 0; axis < 3; axis++) {
            if (!isfinite(list->positions[3 * (size_t)v + axis])) {
                out->nonfinite_axis[v] = axis;
                r->nonfinite_vertices++;
                break;
            }
        }
    }

    /* Global figures. */
    r->euler_characteristic = (int64_t)V - (int64_t)r->num_edges + (int64_t)r->num_faces_valid;
    r->closed = r->boundary_edges == 0 && r->num_faces_valid > 0;
    r->manifold = r->nonmanifold_edges == 0 && r->nonmanifold_vertices == 0;
    r->consistently_oriented =
        r->inconsistent_orientation_edges == 0 && r->duplicate_directed_edges == 0;
    r->genus = C == 1 ? comps[0].genus : -1;
    return true;
}

void mt_oracle_free(mt_oracle *o)
{
    if (!o) return;
    free(o->report.boundary_loop_lengths);
    free(o->report.components);
    free(o->report.face_size_histogram);
    free(o->report.edge_use_histogram);
    free(o->face_offset);
    free(o->face_valid);
    free(o->face_degenerate);
    free(o->face_distinct);
    free(o->face_first_bad);
    free(o->face_duplicate_of);
    free(o->face_component);
    free(o->edges);
    free(o->edge_faces);
    free(o->dup_sides);
    free(o->vert_nb_offsets);
    free(o->vert_nb);
    free(o->vert_face_offsets);
    free(o->vert_faces);
    free(o->face_adj_offsets);
    free(o->face_adj);
    free(o->link_parts);
    free(o->link_branch);
    free(o->nonmanifold_verts);
    free(o->isolated_verts);
    free(o->nonfinite_axis);
    memset(o, 0, sizeof *o);
}

const mt_oracle_edge *mt_oracle_find_edge(const mt_oracle *o, uint32_t a, uint32_t b)
{
    if (a > b) {
        uint32_t t = a;
        a = b;
        b = t;
    }
    size_t lo = 0, hi = o->num_edges;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        const mt_oracle_edge *e = &o->edges[mid];
        if (e->a < a || (e->a == a && e->b < b))
            lo = mid + 1;
        else
            hi = mid;
    }
    if (lo < o->num_edges && o->edges[lo].a == a && o->edges[lo].b == b) return &o->edges[lo];
    return NULL;
}

bool mt_oracle_has_defect(const mt_oracle *o)
{
    const mt_report *r = &o->report;
    return r->out_of_range_indices > 0 || r->degenerate_faces > 0 || r->duplicate_faces > 0 ||
           r->nonmanifold_edges > 0 || r->nonmanifold_vertices > 0 ||
           r->duplicate_directed_edges > 0 || r->isolated_vertices > 0 || r->nonfinite_vertices > 0;
}
