/* Property tests of the core builder against the brute-force reference in
 * oracle.c: the reference is first checked against every corpus answer, then
 * random polygon soups, closed meshes with faces dropped, index noise,
 * flipped, duplicated and glued faces, their permutations, strict mode and
 * malformed arguments are built; each build must validate and match the
 * reference in every report field, every defect entry and a sample of
 * queries. A failing input is shrunk to a small face list and printed. */
#include <dirent.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cJSON.h>

#include "corpus_keys.h"
#include "harness.h"
#include "meshtopo/face_list.h"
#include "meshtopo/generate.h"
#include "meshtopo/io.h"
#include "meshtopo/mesh.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"
#include "meshtopo/status.h"
#include "meshtopo/validate.h"
#include "oracle.h"

/* ==== deterministic random numbers (splitmix64) ========================== */

typedef struct rng {
    uint64_t state;
} rng;

static uint64_t rng_next(rng *r)
{
    uint64_t z = (r->state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static uint32_t rng_below(rng *r, uint32_t n)
{
    return n ? (uint32_t)(rng_next(r) % n) : 0;
}

static double rng_unit(rng *r)
{
    return (double)(rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
}

static bool rng_chance(rng *r, double p)
{
    return rng_unit(r) < p;
}

static rng rng_seeded(uint64_t seed)
{
    rng r = {seed * 0x2545f4914f6cdd1dull + 0x1234567ull};
    rng_next(&r);
    return r;
}

/* An index that is out of range for num_verts vertices, often one a
 * careless builder would mistake for something else. */
static uint32_t bad_index(rng *r, uint32_t num_verts)
{
    switch (rng_below(r, 8)) {
        case 0:
            return num_verts;
        case 1:
            return num_verts + 1 + rng_below(r, 100);
        case 2:
            return 0x7fffffffu;
        case 3:
            return 0x80000000u;
        case 4:
            return 0xfffffffeu;
        case 5:
            return 0xffffffffu; /* MT_NONE, and OBJ's -1 */
        case 6:
            return 0x80000000u + rng_below(r, 0x7fffffffu);
        default: {
            uint64_t span = 0x100000000ull - num_verts; /* every out-of-range value */
            return (uint32_t)(num_verts + rng_next(r) % span);
        }
    }
}

/* ==== building face lists ============================================== */

typedef struct list_builder {
    uint32_t num_verts, verts_capacity;
    uint32_t num_faces, faces_capacity;
    uint64_t num_indices, indices_capacity;
    uint32_t *sizes, *indices;
    double *positions; /* NULL: no geometry */
} list_builder;

static void *xrealloc(void *p, size_t count, size_t size)
{
    void *q = realloc(p, (count ? count : 1) * size);
    if (!q) {
        fprintf(stderr, "test_property: out of memory\n");
        exit(1);
    }
    return q;
}

static void lb_init(list_builder *b, bool with_positions)
{
    memset(b, 0, sizeof *b);
    if (with_positions) b->positions = xrealloc(NULL, 3, sizeof(double));
}

/* Adds a vertex (position ignored without geometry) and returns its id. */
static uint32_t lb_vertex(list_builder *b, double x, double y, double z)
{
    if (b->num_verts == b->verts_capacity) {
        b->verts_capacity = b->verts_capacity ? 2 * b->verts_capacity : 16;
        if (b->positions)
            b->positions = xrealloc(b->positions, 3 * (size_t)b->verts_capacity, sizeof(double));
    }
    if (b->positions) {
        b->positions[3 * (size_t)b->num_verts] = x;
        b->positions[3 * (size_t)b->num_verts + 1] = y;
        b->positions[3 * (size_t)b->num_verts + 2] = z;
    }
    return b->num_verts++;
}

static void lb_face(list_builder *b, const uint32_t *verts, uint32_t n)
{
    if (b->num_faces == b->faces_capacity) {
        b->faces_capacity = b->faces_capacity ? 2 * b->faces_capacity : 16;
        b->sizes = xrealloc(b->sizes, b->faces_capacity, sizeof *b->sizes);
    }
    while (b->num_indices + n > b->indices_capacity) {
        b->indices_capacity = b->indices_capacity ? 2 * b->indices_capacity : 64;
        b->indices = xrealloc(b->indices, b->indices_capacity, sizeof *b->indices);
    }
    b->sizes[b->num_faces++] = n;
    if (n) memcpy(b->indices + b->num_indices, verts, n * sizeof *verts);
    b->num_indices += n;
}

/* Appends every vertex (with its position) and face of `list`, vertex ids
 * shifted by the builder's current vertex count; out-of-range indices are
 * kept as they are. Returns the shift. */
static uint32_t lb_append(list_builder *b, const mt_face_list *list)
{
    uint32_t base = b->num_verts;
    for (uint32_t v = 0; v < list->num_verts; v++) {
        const double *p = list->positions ? list->positions + 3 * (size_t)v : NULL;
        lb_vertex(b, p ? p[0] : 0, p ? p[1] : 0, p ? p[2] : 0);
    }
    uint64_t off = 0;
    uint32_t *tmp = NULL;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        uint32_t n = list->face_sizes[f];
        tmp = xrealloc(tmp, n, sizeof *tmp);
        for (uint32_t i = 0; i < n; i++) {
            uint32_t w = list->face_indices[off + i];
            tmp[i] = w < list->num_verts ? w + base : w;
        }
        lb_face(b, tmp, n);
        off += n;
    }
    free(tmp);
    return base;
}

/* Moves the builder's content into a face list freed by mt_face_list_free. */
static void lb_finish(list_builder *b, mt_face_list *out)
{
    if (mt_face_list_alloc(out, b->num_verts, b->num_faces, b->num_indices, NULL) != MT_OK) {
        fprintf(stderr, "test_property: cannot allocate a face list\n");
        exit(1);
    }
    if (b->num_faces) memcpy(out->face_sizes, b->sizes, b->num_faces * sizeof *b->sizes);
    if (b->num_indices) memcpy(out->face_indices, b->indices, b->num_indices * sizeof *b->indices);
    if (b->positions) {
        if (b->num_verts)
            memcpy(out->positions, b->positions, 3 * (size_t)b->num_verts * sizeof(double));
    } else {
        free(out->positions);
        out->positions = NULL;
    }
    free(b->sizes);
    free(b->indices);
    free(b->positions);
    memset(b, 0, sizeof *b);
}

static void list_copy(const mt_face_list *in, mt_face_list *out)
{
    list_builder b;
    lb_init(&b, in->positions != NULL);
    lb_append(&b, in);
    lb_finish(&b, out);
}

/* Prints a face list as C initialisers, to paste into a regression test. */
static void list_print(FILE *to, const mt_face_list *l)
{
    fprintf(to, "  num_verts = %u, num_faces = %u, num_indices = %llu, positions %s\n",
            l->num_verts, l->num_faces, (unsigned long long)l->num_indices,
            l->positions ? "given" : "NULL");
    fprintf(to, "  face_sizes   = {");
    for (uint32_t f = 0; f < l->num_faces; f++)
        fprintf(to, "%s%u", f ? ", " : "", l->face_sizes[f]);
    fprintf(to, "}\n  face_indices = {");
    uint64_t off = 0;
    for (uint32_t f = 0; f < l->num_faces; f++) {
        for (uint32_t i = 0; i < l->face_sizes[f]; i++)
            fprintf(to, "%s%u", off + i ? (i ? ", " : ",  ") : "", l->face_indices[off + i]);
        off += l->face_sizes[f];
    }
    fprintf(to, "}\n");
    if (l->positions) {
        for (uint32_t v = 0; v < l->num_verts; v++) {
            const double *p = l->positions + 3 * (size_t)v;
            if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
                fprintf(to, "  vertex %u position (%g, %g, %g)\n", v, p[0], p[1], p[2]);
        }
    }
}

/* ==== files ============================================================ */

static char *file_read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 4096, n = 0, got;
    char *text = xrealloc(NULL, cap, 1);
    while ((got = fread(text + n, 1, cap - n - 1, f)) > 0) {
        n += got;
        if (n + 1 == cap) text = xrealloc(text, cap *= 2, 1);
    }
    fclose(f);
    text[n] = 0;
    return text;
}

/* ==== probes: comparisons that count mismatches and may stay quiet ======= */

/* One input under test: a label to reproduce it, and whether mismatches are
 * recorded as test failures (false while shrinking a failing input). */
typedef struct probe {
    const char *label;
    bool quiet;
    int mismatches;
} probe;

#define PROBE_MAX_MESSAGES 40

static void probe_fail(probe *p, const char *file, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static void probe_fail(probe *p, const char *file, int line, const char *fmt, ...)
{
    p->mismatches++;
    if (p->quiet) return;
    if (p->mismatches > PROBE_MAX_MESSAGES) { /* the test has failed already */
        if (p->mismatches == PROBE_MAX_MESSAGES + 1)
            fprintf(stderr, "%s: (further mismatches not shown)\n", p->label);
        return;
    }
    char text[600];
    va_list args;
    va_start(args, fmt);
    vsnprintf(text, sizeof text, fmt, args);
    va_end(args);
    mt_test_fail(file, line, "%s: %s", p->label, text);
}

#define EXPECT(p, cond, ...)                                           \
    do {                                                               \
        if (!(cond)) probe_fail((p), __FILE__, __LINE__, __VA_ARGS__); \
    } while (0)

#define EXPECT_EQ(p, what, got, want)                                                         \
    do {                                                                                      \
        long long mt__g = (long long)(got), mt__w = (long long)(want);                        \
        if (mt__g != mt__w)                                                                   \
            probe_fail((p), __FILE__, __LINE__, "%s: got %lld, expected %lld", (what), mt__g, \
                       mt__w);                                                                \
    } while (0)

#define EXPECT_STATUS(p, what, got, want)                                               \
    do {                                                                                \
        mt_status mt__g = (got), mt__w = (want);                                        \
        if (mt__g != mt__w)                                                             \
            probe_fail((p), __FILE__, __LINE__, "%s: returned %s, expected %s", (what), \
                       mt_strerror(mt__g), mt_strerror(mt__w));                         \
    } while (0)

/* Whether sorted a[0..na) equals sorted b[0..nb). */
static bool same_sets(const uint32_t *a, size_t na, const uint32_t *b, size_t nb)
{
    return na == nb && (na == 0 || memcmp(a, b, na * sizeof *a) == 0);
}

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return (a > b) - (a < b);
}

static size_t sort_unique(uint32_t *v, size_t n)
{
    if (n == 0) return 0;
    qsort(v, n, sizeof *v, cmp_u32);
    size_t m = 1;
    for (size_t i = 1; i < n; i++)
        if (v[i] != v[m - 1]) v[m++] = v[i];
    return m;
}

static void format_set(char *buf, size_t size, const uint32_t *v, size_t n)
{
    size_t used = 0;
    buf[0] = 0;
    for (size_t i = 0; i < n && used + 16 < size; i++)
        used += (size_t)snprintf(buf + used, size - used, "%s%u", i ? " " : "", v[i]);
    if (used + 16 >= size) snprintf(buf + used, size - used, " ...");
}

static void expect_set(probe *p, const char *what, const uint32_t *got, size_t ngot,
                       const uint32_t *want, size_t nwant)
{
    if (same_sets(got, ngot, want, nwant)) return;
    char g[256], w[256];
    format_set(g, sizeof g, got, ngot);
    format_set(w, sizeof w, want, nwant);
    probe_fail(p, __FILE__, __LINE__, "%s: got {%s}, expected {%s}", what, g, w);
}

/* ==== report against the reference ===================================== */

/* Every count, flag, histogram and loop length (not the component list). */
static void compare_counts(probe *p, const mt_report *got, const mt_report *want)
{
    EXPECT_EQ(p, "num_verts", got->num_verts, want->num_verts);
    EXPECT_EQ(p, "num_faces", got->num_faces, want->num_faces);
    EXPECT_EQ(p, "num_faces_valid", got->num_faces_valid, want->num_faces_valid);
    EXPECT_EQ(p, "num_edges", got->num_edges, want->num_edges);
    EXPECT_EQ(p, "num_half_edges", got->num_half_edges, want->num_half_edges);
    EXPECT_EQ(p, "boundary_edges", got->boundary_edges, want->boundary_edges);
    EXPECT_EQ(p, "boundary_loops", got->boundary_loops, want->boundary_loops);
    EXPECT_EQ(p, "boundary_loops_ambiguous", got->boundary_loops_ambiguous,
              want->boundary_loops_ambiguous);
    if (got->boundary_loops == want->boundary_loops && want->boundary_loops > 0) {
        EXPECT(p, got->boundary_loop_lengths != NULL, "boundary_loop_lengths is NULL");
        if (got->boundary_loop_lengths)
            expect_set(p, "boundary_loop_lengths", got->boundary_loop_lengths, got->boundary_loops,
                       want->boundary_loop_lengths, want->boundary_loops);
    }
    EXPECT_EQ(p, "nonmanifold_edges", got->nonmanifold_edges, want->nonmanifold_edges);
    EXPECT_EQ(p, "inconsistent_orientation_edges", got->inconsistent_orientation_edges,
              want->inconsistent_orientation_edges);
    EXPECT_EQ(p, "duplicate_directed_edges", got->duplicate_directed_edges,
              want->duplicate_directed_edges);
    EXPECT_EQ(p, "nonmanifold_vertices", got->nonmanifold_vertices, want->nonmanifold_vertices);
    EXPECT_EQ(p, "bowtie_vertices", got->bowtie_vertices, want->bowtie_vertices);
    EXPECT_EQ(p, "isolated_vertices", got->isolated_vertices, want->isolated_vertices);
    EXPECT_EQ(p, "unreferenced_vertices", got->unreferenced_vertices, want->unreferenced_vertices);
    EXPECT_EQ(p, "degenerate_faces", got->degenerate_faces, want->degenerate_faces);
    EXPECT_EQ(p, "duplicate_faces", got->duplicate_faces, want->duplicate_faces);
    EXPECT_EQ(p, "out_of_range_indices", got->out_of_range_indices, want->out_of_range_indices);
    EXPECT_EQ(p, "faces_with_out_of_range_indices", got->faces_with_out_of_range_indices,
              want->faces_with_out_of_range_indices);
    EXPECT_EQ(p, "nonfinite_vertices", got->nonfinite_vertices, want->nonfinite_vertices);
    EXPECT_EQ(p, "connected_components", got->connected_components, want->connected_components);
    EXPECT_EQ(p, "vertex_connected_components", got->vertex_connected_components,
              want->vertex_connected_components);
    EXPECT_EQ(p, "euler_characteristic", got->euler_characteristic, want->euler_characteristic);
    EXPECT_EQ(p, "closed", got->closed, want->closed);
    EXPECT_EQ(p, "manifold", got->manifold, want->manifold);
    EXPECT_EQ(p, "orientable", got->orientable, want->orientable);
    EXPECT_EQ(p, "consistently_oriented", got->consistently_oriented, want->consistently_oriented);
    EXPECT_EQ(p, "genus", got->genus, want->genus);

    EXPECT_EQ(p, "num_face_size_bins", got->num_face_size_bins, want->num_face_size_bins);
    for (size_t i = 0; i < got->num_face_size_bins && i < want->num_face_size_bins; i++) {
        EXPECT_EQ(p, "face_size_histogram key", got->face_size_histogram[i].key,
                  want->face_size_histogram[i].key);
        EXPECT_EQ(p, "face_size_histogram count", got->face_size_histogram[i].count,
                  want->face_size_histogram[i].count);
    }
    EXPECT_EQ(p, "num_edge_use_bins", got->num_edge_use_bins, want->num_edge_use_bins);
    for (size_t i = 0; i < got->num_edge_use_bins && i < want->num_edge_use_bins; i++) {
        EXPECT_EQ(p, "edge_use_histogram key", got->edge_use_histogram[i].key,
                  want->edge_use_histogram[i].key);
        EXPECT_EQ(p, "edge_use_histogram count", got->edge_use_histogram[i].count,
                  want->edge_use_histogram[i].count);
    }
}

static void compare_component(probe *p, uint32_t i, const mt_component_info *g,
                              const mt_component_info *w, bool with_min_face)
{
    char what[96];
#define COMPONENT_FIELD(field)                                    \
    do {                                                          \
        snprintf(what, sizeof what, "components[%u]." #field, i); \
        EXPECT_EQ(p, what, g->field, w->field);                   \
    } while (0)
    if (with_min_face) COMPONENT_FIELD(min_face);
    COMPONENT_FIELD(faces);
    COMPONENT_FIELD(vertices);
    COMPONENT_FIELD(edges);
    COMPONENT_FIELD(euler_characteristic);
    COMPONENT_FIELD(boundary_edges);
    COMPONENT_FIELD(boundary_loops);
    COMPONENT_FIELD(closed);
    COMPONENT_FIELD(manifold);
    COMPONENT_FIELD(orientable);
    COMPONENT_FIELD(genus);
    COMPONENT_FIELD(genus_with_boundary);
#undef COMPONENT_FIELD
}

static void compare_components(probe *p, const mt_report *got, const mt_report *want)
{
    if (got->connected_components != want->connected_components) return; /* already reported */
    if (want->connected_components > 0) EXPECT(p, got->components != NULL, "components is NULL");
    if (!got->components) return;
    for (uint32_t i = 0; i < want->connected_components; i++)
        compare_component(p, i, &got->components[i], &want->components[i], true);
}

/* Components as a multiset (a permutation renumbers faces and reorders them). */
static int cmp_component_figures(const void *x, const void *y)
{
    const mt_component_info *a = x, *b = y;
    long long ka[11] = {a->faces,
                        a->vertices,
                        (long long)a->edges,
                        a->euler_characteristic,
                        (long long)a->boundary_edges,
                        a->boundary_loops,
                        a->closed,
                        a->manifold,
                        a->orientable,
                        a->genus,
                        a->genus_with_boundary};
    long long kb[11] = {b->faces,
                        b->vertices,
                        (long long)b->edges,
                        b->euler_characteristic,
                        (long long)b->boundary_edges,
                        b->boundary_loops,
                        b->closed,
                        b->manifold,
                        b->orientable,
                        b->genus,
                        b->genus_with_boundary};
    for (int i = 0; i < 11; i++)
        if (ka[i] != kb[i]) return ka[i] < kb[i] ? -1 : 1;
    return 0;
}

static void compare_component_multisets(probe *p, const mt_report *got, const mt_report *want)
{
    if (got->connected_components != want->connected_components || !got->components) return;
    size_t n = want->connected_components;
    mt_component_info *g = xrealloc(NULL, n, sizeof *g), *w = xrealloc(NULL, n, sizeof *w);
    memcpy(g, got->components, n * sizeof *g);
    memcpy(w, want->components, n * sizeof *w);
    qsort(g, n, sizeof *g, cmp_component_figures);
    qsort(w, n, sizeof *w, cmp_component_figures);
    for (uint32_t i = 0; i < n; i++) compare_component(p, i, &g[i], &w[i], false);
    free(g);
    free(w);
}

/* Root of a face's duplicate class in the reference. */
static uint32_t duplicate_root(const mt_oracle *o, uint32_t f)
{
    return o->face_duplicate_of[f] == MT_NONE ? f : o->face_duplicate_of[f];
}

static int cmp_side_key(const void *x, const void *y)
{
    const mt_oracle_side *s = x, *t = y;
    if (s->a != t->a) return s->a < t->a ? -1 : 1;
    return (s->b > t->b) - (s->b < t->b);
}

/* The defect list: order, per-kind counts, and each entry's a, b, c. */
static void compare_defects(probe *p, const mt_report *r, const mt_oracle *o,
                            const mt_face_list *in)
{
    const mt_report *w = &o->report;
    size_t count[MT_DEFECT_KIND_COUNT] = {0};
    bool *side_seen = xrealloc(NULL, o->num_dup_sides, sizeof *side_seen);
    memset(side_seen, 0, (o->num_dup_sides ? o->num_dup_sides : 1) * sizeof *side_seen);
    if (r->num_defects > 0) EXPECT(p, r->defects != NULL, "defects is NULL");
    for (size_t i = 0; r->defects && i < r->num_defects; i++) {
        const mt_defect *d = &r->defects[i];
        if (d->kind >= MT_DEFECT_KIND_COUNT) {
            probe_fail(p, __FILE__, __LINE__, "defect %zu has kind %u", i, d->kind);
            continue;
        }
        count[d->kind]++;
        const char *key = mt_defect_key((mt_defect_kind)d->kind);
        if (i > 0) {
            const mt_defect *e = &r->defects[i - 1];
            bool ordered =
                e->kind < d->kind ||
                (e->kind == d->kind &&
                 (e->a < d->a || (e->a == d->a && (d->kind == MT_DEFECT_SAME_DIRECTION_EDGE ||
                                                   d->kind == MT_DEFECT_NONMANIFOLD_EDGE))));
            EXPECT(p, ordered, "defects %zu (%s %u) and %zu (%s %u) are out of order", i - 1,
                   mt_defect_key((mt_defect_kind)e->kind), e->a, i, key, d->a);
        }
        switch ((mt_defect_kind)d->kind) {
            case MT_DEFECT_OUT_OF_RANGE_INDEX: {
                bool ok = d->a < in->num_faces && o->face_first_bad[d->a] != MT_NONE &&
                          d->c == o->face_first_bad[d->a] &&
                          d->b == in->face_indices[o->face_offset[d->a] + o->face_first_bad[d->a]];
                EXPECT(p, ok,
                       "defect %s (%u, %u, %u): face %u's first out-of-range entry is %u at %u",
                       key, d->a, d->b, d->c, d->a,
                       d->a < in->num_faces && o->face_first_bad[d->a] != MT_NONE
                           ? in->face_indices[o->face_offset[d->a] + o->face_first_bad[d->a]]
                           : MT_NONE,
                       d->a < in->num_faces ? o->face_first_bad[d->a] : MT_NONE);
                break;
            }
            case MT_DEFECT_DEGENERATE_FACE: {
                bool ok = d->a < in->num_faces && o->face_degenerate[d->a] &&
                          d->b == o->face_distinct[d->a] && d->c == in->face_sizes[d->a];
                EXPECT(p, ok,
                       "defect %s (%u, %u, %u): reference says degenerate %d, %u distinct, size %u",
                       key, d->a, d->b, d->c, d->a < in->num_faces && o->face_degenerate[d->a],
                       d->a < in->num_faces ? o->face_distinct[d->a] : 0,
                       d->a < in->num_faces ? in->face_sizes[d->a] : 0);
                break;
            }
            case MT_DEFECT_DUPLICATE_FACE: {
                bool ok = d->a < in->num_faces && d->b < d->a &&
                          o->face_duplicate_of[d->a] != MT_NONE && o->face_valid[d->b] &&
                          duplicate_root(o, d->b) == duplicate_root(o, d->a);
                EXPECT(p, ok,
                       "defect %s (%u, %u, %u): reference's first face with that cycle is %u", key,
                       d->a, d->b, d->c,
                       d->a < in->num_faces ? o->face_duplicate_of[d->a] : MT_NONE);
                break;
            }
            case MT_DEFECT_NONMANIFOLD_EDGE: {
                const mt_oracle_edge *e = mt_oracle_find_edge(o, d->a, d->b);
                bool ok = d->a < d->b && e && e->uses > 2 && d->c == e->uses;
                EXPECT(p, ok, "defect %s (%u, %u, %u): reference use count %u", key, d->a, d->b,
                       d->c, e ? e->uses : 0);
                break;
            }
            case MT_DEFECT_SAME_DIRECTION_EDGE: {
                mt_oracle_side s = {d->a, d->b, 0};
                const mt_oracle_side *hit =
                    bsearch(&s, o->dup_sides, o->num_dup_sides, sizeof s, cmp_side_key);
                bool ok = hit && hit->count == d->c && !side_seen[hit - o->dup_sides];
                if (hit) side_seen[hit - o->dup_sides] = true;
                EXPECT(p, ok, "defect %s (%u, %u, %u): reference has that side %u times%s", key,
                       d->a, d->b, d->c, hit ? hit->count : 0,
                       hit && !ok ? " (or listed twice)" : "");
                break;
            }
            case MT_DEFECT_NONMANIFOLD_VERTEX: {
                bool ok = d->a < in->num_verts &&
                          (o->link_parts[d->a] != 1 || o->link_branch[d->a]) &&
                          d->b == o->link_parts[d->a] && d->c == (uint32_t)o->link_branch[d->a];
                EXPECT(p, ok, "defect %s (%u, %u, %u): reference link has %u parts, branch %d", key,
                       d->a, d->b, d->c, d->a < in->num_verts ? o->link_parts[d->a] : 0,
                       d->a < in->num_verts && o->link_branch[d->a]);
                break;
            }
            case MT_DEFECT_ISOLATED_VERTEX: {
                bool ok = d->a < in->num_verts &&
                          o->vert_face_offsets[d->a] == o->vert_face_offsets[d->a + 1];
                EXPECT(p, ok, "defect %s (%u, %u, %u): vertex is not isolated", key, d->a, d->b,
                       d->c);
                break;
            }
            case MT_DEFECT_NONFINITE_COORD: {
                bool ok = d->a < in->num_verts && o->nonfinite_axis[d->a] == d->b;
                EXPECT(p, ok, "defect %s (%u, %u, %u): reference's first non-finite axis is %u",
                       key, d->a, d->b, d->c,
                       d->a < in->num_verts ? o->nonfinite_axis[d->a] : MT_NONE);
                break;
            }
            default:
                break;
        }
    }
    free(side_seen);
    /* With every entry correct, distinct (ordered by id) and counted, the
     * lists are equal. */
    const struct {
        mt_defect_kind kind;
        uint64_t want;
    } totals[] = {
        {MT_DEFECT_OUT_OF_RANGE_INDEX, w->faces_with_out_of_range_indices},
        {MT_DEFECT_DEGENERATE_FACE, w->degenerate_faces},
        {MT_DEFECT_DUPLICATE_FACE, w->duplicate_faces},
        {MT_DEFECT_NONMANIFOLD_EDGE, w->nonmanifold_edges},
        {MT_DEFECT_SAME_DIRECTION_EDGE, o->num_dup_sides},
        {MT_DEFECT_NONMANIFOLD_VERTEX, w->nonmanifold_vertices},
        {MT_DEFECT_ISOLATED_VERTEX, w->isolated_vertices},
        {MT_DEFECT_NONFINITE_COORD, w->nonfinite_vertices},
    };
    for (size_t k = 0; k < sizeof totals / sizeof totals[0]; k++) {
        char what[96];
        snprintf(what, sizeof what, "number of %s defects", mt_defect_key(totals[k].kind));
        EXPECT_EQ(p, what, count[totals[k].kind], totals[k].want);
        snprintf(what, sizeof what, "mt_report_count_defects(%s)", mt_defect_key(totals[k].kind));
        EXPECT_EQ(p, what, mt_report_count_defects(r, totals[k].kind), count[totals[k].kind]);
    }
    /* Entries of one kind keyed by `a` are strictly ascending (no repeats). */
    for (size_t i = 1; r->defects && i < r->num_defects; i++) {
        const mt_defect *d = &r->defects[i], *e = &r->defects[i - 1];
        if (d->kind == e->kind && d->kind != MT_DEFECT_SAME_DIRECTION_EDGE &&
            d->kind != MT_DEFECT_NONMANIFOLD_EDGE)
            EXPECT(p, d->a != e->a, "defect %s listed twice for %u",
                   mt_defect_key((mt_defect_kind)d->kind), d->a);
        if (d->kind == e->kind && d->kind == MT_DEFECT_NONMANIFOLD_EDGE)
            EXPECT(p, d->a != e->a || d->b != e->b, "non-manifold edge %u-%u listed twice", d->a,
                   d->b);
    }
    /* Each entry can be described. */
    for (size_t i = 0; r->defects && i < r->num_defects && i < 4; i++) {
        char text[160];
        size_t need = mt_defect_describe(&r->defects[i], NULL, 0);
        size_t wrote = mt_defect_describe(&r->defects[i], text, sizeof text);
        EXPECT(p,
               need > 0 && need == wrote &&
                   strlen(text) == (need < sizeof text ? need : sizeof text - 1),
               "mt_defect_describe of defect %zu: %zu, %zu, \"%s\"", i, need, wrote, text);
    }
}

/* ==== queries against the reference ==================================== */

/* Position of v in face f's record, MT_NONE when absent. */
static uint32_t face_position(const mt_face_list *in, const mt_oracle *o, uint32_t f, uint32_t v)
{
    const uint32_t *rec = in->face_indices + o->face_offset[f];
    for (uint32_t i = 0; i < in->face_sizes[f]; i++)
        if (rec[i] == v) return i;
    return MT_NONE;
}

/* Whether no edge at v is crossed twice in one direction. */
static bool vert_orientation_clean(const mt_oracle *o, uint32_t v)
{
    for (size_t k = o->vert_nb_offsets[v]; k < o->vert_nb_offsets[v + 1]; k++) {
        const mt_oracle_edge *e = mt_oracle_find_edge(o, v, o->vert_nb[k]);
        if (!e || e->forward >= 2 || e->uses - e->forward >= 2) return false;
    }
    return true;
}

static bool vert_on_boundary(const mt_oracle *o, uint32_t v)
{
    for (size_t k = o->vert_nb_offsets[v]; k < o->vert_nb_offsets[v + 1]; k++) {
        const mt_oracle_edge *e = mt_oracle_find_edge(o, v, o->vert_nb[k]);
        if (e && e->uses == 1) return true;
    }
    return false;
}

static void check_vert(probe *p, const mt_mesh *m, const mt_oracle *o, const mt_face_list *in,
                       uint32_t v)
{
    const uint32_t *want_nb = o->vert_nb + o->vert_nb_offsets[v];
    const size_t num_want_nb = o->vert_nb_offsets[v + 1] - o->vert_nb_offsets[v];
    const uint32_t *want_faces = o->vert_faces + o->vert_face_offsets[v];
    const size_t num_want_faces = o->vert_face_offsets[v + 1] - o->vert_face_offsets[v];

    mt_ring sizing;
    memset(&sizing, 0, sizeof sizing);
    mt_status st = mt_vert_ring(m, v, &sizing);
    EXPECT(p, st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL, "mt_vert_ring(%u) sizing call: %s", v,
           mt_strerror(st));
    if (st != MT_OK && st != MT_ERR_BUFFER_TOO_SMALL) return;
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    ring.neighbors = xrealloc(NULL, sizing.num_neighbors, sizeof(uint32_t));
    ring.neighbors_capacity = sizing.num_neighbors;
    ring.faces = xrealloc(NULL, sizing.num_faces, sizeof(uint32_t));
    ring.faces_capacity = sizing.num_faces;
    ring.fans = xrealloc(NULL, sizing.num_fans, sizeof(mt_fan));
    ring.fans_capacity = sizing.num_fans;
    st = mt_vert_ring(m, v, &ring);
    EXPECT_STATUS(p, "mt_vert_ring", st, MT_OK);
    if (st == MT_OK) {
        EXPECT(p,
               ring.num_neighbors == sizing.num_neighbors && ring.num_faces == sizing.num_faces &&
                   ring.num_fans == sizing.num_fans,
               "mt_vert_ring(%u): sizing call said %zu/%zu/%zu, filling call %zu/%zu/%zu", v,
               sizing.num_neighbors, sizing.num_faces, sizing.num_fans, ring.num_neighbors,
               ring.num_faces, ring.num_fans);
        /* Each incident valid face exactly once; neighbours as a set. */
        uint32_t *tmp = xrealloc(NULL, ring.num_faces + ring.num_neighbors + 1, sizeof *tmp);
        memcpy(tmp, ring.faces, ring.num_faces * sizeof *tmp);
        qsort(tmp, ring.num_faces, sizeof *tmp, cmp_u32);
        char what[64];
        snprintf(what, sizeof what, "mt_vert_ring(%u) faces", v);
        expect_set(p, what, tmp, ring.num_faces, want_faces, num_want_faces);
        memcpy(tmp, ring.neighbors, ring.num_neighbors * sizeof *tmp);
        size_t n = sort_unique(tmp, ring.num_neighbors);
        snprintf(what, sizeof what, "mt_vert_ring(%u) neighbours", v);
        expect_set(p, what, tmp, n, want_nb, num_want_nb);
        free(tmp);

        /* Fans: contiguous ranges, and neighbours i and i+1 bound face i. */
        const bool manifold = o->link_parts[v] == 1 && !o->link_branch[v];
        const bool oriented = manifold && vert_orientation_clean(o, v);
        size_t next_nb = 0, next_face = 0;
        for (size_t k = 0; k < ring.num_fans; k++) {
            const mt_fan *fan = &ring.fans[k];
            EXPECT(p,
                   fan->neighbor_begin == next_nb && fan->face_begin == next_face &&
                       fan->face_count >= 1 &&
                       fan->neighbor_count == fan->face_count + (fan->boundary ? 1u : 0u),
                   "vertex %u fan %zu: ranges %u+%u, %u+%u, boundary %d", v, k, fan->neighbor_begin,
                   fan->neighbor_count, fan->face_begin, fan->face_count, fan->boundary);
            if (fan->neighbor_begin + (size_t)fan->neighbor_count > ring.num_neighbors ||
                fan->face_begin + (size_t)fan->face_count > ring.num_faces ||
                fan->neighbor_count < fan->face_count || fan->face_count == 0)
                break;
            next_nb = fan->neighbor_begin + (size_t)fan->neighbor_count;
            next_face = fan->face_begin + (size_t)fan->face_count;
            for (uint32_t i = 0; i < fan->face_count; i++) {
                uint32_t f = ring.faces[fan->face_begin + i];
                uint32_t x = ring.neighbors[fan->neighbor_begin + i];
                uint32_t y = ring.neighbors[fan->neighbor_begin +
                                            (fan->boundary ? i + 1 : (i + 1) % fan->face_count)];
                if (f >= in->num_faces || !o->face_valid[f]) continue; /* reported above */
                uint32_t pos = face_position(in, o, f, v);
                if (pos == MT_NONE) continue;
                const uint32_t sz = in->face_sizes[f];
                const uint32_t *rec = in->face_indices + o->face_offset[f];
                uint32_t prev = rec[(pos + sz - 1) % sz], next = rec[(pos + 1) % sz];
                EXPECT(p, (x == prev && y == next) || (x == next && y == prev),
                       "vertex %u fan %zu: face %u is bounded by %u and %u, its sides at the "
                       "vertex go to %u and %u",
                       v, k, f, x, y, prev, next);
                if (oriented)
                    EXPECT(p, x == next && y == prev,
                           "vertex %u: ring not counter-clockwise at face %u (%u then %u, face "
                           "goes %u -> %u -> %u)",
                           v, f, x, y, prev, v, next);
            }
        }
        EXPECT(p, next_nb == ring.num_neighbors && next_face == ring.num_faces,
               "vertex %u: fans cover %zu neighbours, %zu faces of %zu, %zu", v, next_nb, next_face,
               ring.num_neighbors, ring.num_faces);
        EXPECT(p, ring.num_fans >= o->link_parts[v], "vertex %u: %zu fans, link has %u parts", v,
               ring.num_fans, o->link_parts[v]);
        if (!o->link_branch[v] && vert_orientation_clean(o, v))
            EXPECT_EQ(p, "number of fans (link parts, consistently oriented)", ring.num_fans,
                      o->link_parts[v]);
        if (oriented && ring.num_fans == 1)
            EXPECT(p, ring.fans[0].boundary == vert_on_boundary(o, v),
                   "vertex %u: fan boundary flag %d, reference %d", v, ring.fans[0].boundary,
                   vert_on_boundary(o, v));

        /* A buffer one short is refused and gets the sizes. */
        if (ring.num_neighbors > 0) {
            mt_ring small = ring;
            small.neighbors_capacity = ring.num_neighbors - 1;
            small.num_neighbors = small.num_faces = small.num_fans = 0;
            EXPECT_STATUS(p, "mt_vert_ring with a short buffer", mt_vert_ring(m, v, &small),
                          MT_ERR_BUFFER_TOO_SMALL);
            EXPECT_EQ(p, "needed neighbours", small.num_neighbors, ring.num_neighbors);
        }
    }
    free(ring.neighbors);
    free(ring.faces);
    free(ring.fans);

    uint32_t valence = MT_NONE;
    EXPECT_STATUS(p, "mt_vert_valence", mt_vert_valence(m, v, &valence), MT_OK);
    EXPECT_EQ(p, "valence", valence, num_want_nb);

    const double *pos = mt_mesh_position(m, v);
    if (in->positions)
        EXPECT(p, pos && memcmp(pos, in->positions + 3 * (size_t)v, 3 * sizeof(double)) == 0,
               "position of vertex %u differs from the input", v);
    else
        EXPECT(p, pos == NULL, "mesh without geometry gives a position for %u", v);
}

static void check_face(probe *p, const mt_mesh *m, const mt_oracle *o, const mt_face_list *in,
                       uint32_t f)
{
    const uint32_t n = in->face_sizes[f];
    const bool valid = o->face_valid[f];
    const uint32_t *rec = valid ? in->face_indices + o->face_offset[f] : NULL;
    char what[96];

    size_t count = 0;
    mt_status st = mt_face_verts(m, f, NULL, 0, &count);
    if (!valid) {
        snprintf(what, sizeof what, "mt_face_verts(rejected face %u)", f);
        EXPECT_STATUS(p, what, st, MT_ERR_NOT_FOUND);
    } else {
        EXPECT(p, (st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL) && count == n,
               "mt_face_verts(%u) sizing: %s, count %zu, face size %u", f, mt_strerror(st), count,
               n);
        uint32_t *verts = xrealloc(NULL, n, sizeof *verts);
        st = mt_face_verts(m, f, verts, n, &count);
        EXPECT(p, st == MT_OK && count == n && memcmp(verts, rec, n * sizeof *verts) == 0,
               "mt_face_verts(%u): %s, %zu vertices, not the record", f, mt_strerror(st), count);
        free(verts);
    }

    size_t num_faces = 0, num_edges = 0;
    st = mt_face_neighbors(m, f, NULL, 0, NULL, 0, &num_faces, &num_edges);
    if (!valid) {
        snprintf(what, sizeof what, "mt_face_neighbors(rejected face %u)", f);
        EXPECT_STATUS(p, what, st, MT_ERR_NOT_FOUND);
    } else {
        EXPECT(p, (st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL) && num_edges == n,
               "mt_face_neighbors(%u) sizing: %s, %zu edges, face size %u", f, mt_strerror(st),
               num_edges, n);
        if (num_edges == n) {
            uint32_t *faces = xrealloc(NULL, num_faces, sizeof *faces);
            uint32_t *offsets = xrealloc(NULL, (size_t)n + 1, sizeof *offsets);
            st = mt_face_neighbors(m, f, faces, num_faces, offsets, (size_t)n + 1, &num_faces,
                                   &num_edges);
            EXPECT_STATUS(p, "mt_face_neighbors", st, MT_OK);
            bool offsets_ok = st == MT_OK && offsets[0] == 0 && offsets[n] == num_faces;
            for (uint32_t i = 0; offsets_ok && i < n; i++)
                offsets_ok = offsets[i] <= offsets[i + 1];
            EXPECT(p, offsets_ok, "mt_face_neighbors(%u): bad offsets", f);
            if (offsets_ok) {
                uint32_t *want = xrealloc(NULL, num_faces + in->num_faces + 1, sizeof *want);
                for (uint32_t i = 0; i < n; i++) {
                    const mt_oracle_edge *e = mt_oracle_find_edge(o, rec[i], rec[(i + 1) % n]);
                    size_t nw = 0;
                    for (uint32_t k = 0; e && k < e->uses; k++)
                        if (o->edge_faces[e->face_begin + k] != f)
                            want[nw++] = o->edge_faces[e->face_begin + k];
                    size_t ng = offsets[i + 1] - offsets[i];
                    uint32_t *got = xrealloc(NULL, ng, sizeof *got);
                    memcpy(got, faces + offsets[i], ng * sizeof *got);
                    qsort(got, ng, sizeof *got, cmp_u32);
                    snprintf(what, sizeof what, "faces across edge %u (%u-%u) of face %u", i,
                             rec[i], rec[(i + 1) % n], f);
                    expect_set(p, what, got, ng, want, nw);
                    free(got);
                }
                memcpy(want, faces, num_faces * sizeof *want);
                size_t nu = sort_unique(want, num_faces);
                snprintf(what, sizeof what, "faces adjacent to face %u", f);
                expect_set(p, what, want, nu, o->face_adj + o->face_adj_offsets[f],
                           o->face_adj_offsets[f + 1] - o->face_adj_offsets[f]);
                free(want);
            }
            free(faces);
            free(offsets);
        }
    }

    uint32_t comp = MT_NONE;
    st = mt_face_component(m, f, &comp);
    if (!valid) {
        snprintf(what, sizeof what, "mt_face_component(rejected face %u)", f);
        EXPECT_STATUS(p, what, st, MT_ERR_NOT_FOUND);
    } else {
        EXPECT(p, st == MT_OK && comp == o->face_component[f],
               "mt_face_component(%u): %s, component %u, reference %u", f, mt_strerror(st), comp,
               o->face_component[f]);
    }
}

static void check_edge(probe *p, const mt_mesh *m, const mt_oracle *o, uint32_t V, uint32_t a,
                       uint32_t b)
{
    const mt_oracle_edge *e = mt_oracle_find_edge(o, a, b);
    for (int swap = 0; swap < 2; swap++) {
        uint32_t x = swap ? b : a, y = swap ? a : b;
        size_t count = 0;
        mt_status st = mt_edge_faces(m, x, y, NULL, 0, &count);
        if (!e) {
            if (x < V && y < V)
                EXPECT(p, st == MT_ERR_NOT_FOUND, "mt_edge_faces(%u, %u) on no edge: %s", x, y,
                       mt_strerror(st));
            else
                EXPECT(p, st == MT_ERR_NOT_FOUND || st == MT_ERR_OUT_OF_RANGE,
                       "mt_edge_faces(%u, %u) out of range: %s", x, y, mt_strerror(st));
            continue;
        }
        EXPECT(p, (st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL) && count == e->uses,
               "mt_edge_faces(%u, %u) sizing: %s, count %zu, uses %u", x, y, mt_strerror(st), count,
               e->uses);
        uint32_t *faces = xrealloc(NULL, e->uses, sizeof *faces);
        st = mt_edge_faces(m, x, y, faces, e->uses, &count);
        EXPECT_STATUS(p, "mt_edge_faces", st, MT_OK);
        char what[64];
        snprintf(what, sizeof what, "mt_edge_faces(%u, %u) (ascending)", x, y);
        if (st == MT_OK) expect_set(p, what, faces, count, o->edge_faces + e->face_begin, e->uses);
        free(faces);
    }
}

/* Boundary rings: every step runs along an edge of the mesh, every edge
 * used by one face is walked exactly once with its face on the left, and on
 * a manifold, consistently oriented mesh the rings are the boundary loops. */
static void check_boundary_loops(probe *p, const mt_mesh *m, const mt_oracle *o)
{
    const mt_report *w = &o->report;
    size_t nv = 0, nl = 0;
    mt_status st = mt_boundary_loops(m, NULL, 0, NULL, 0, &nv, &nl);
    EXPECT(p, st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL, "mt_boundary_loops sizing: %s",
           mt_strerror(st));
    if (st != MT_OK && st != MT_ERR_BUFFER_TOO_SMALL) return;
    const bool simple = w->manifold && w->consistently_oriented;
    if (simple) {
        EXPECT_EQ(p, "mt_boundary_loops loops", nl, w->boundary_loops);
        EXPECT_EQ(p, "mt_boundary_loops vertices", nv, w->boundary_edges);
    }
    EXPECT(p, nv >= w->boundary_edges, "mt_boundary_loops: %zu steps for %llu boundary edges", nv,
           (unsigned long long)w->boundary_edges);
    uint32_t *verts = xrealloc(NULL, nv, sizeof *verts);
    uint32_t *offsets = xrealloc(NULL, nl + 1, sizeof *offsets);
    uint32_t *lengths = xrealloc(NULL, nl, sizeof *lengths);
    uint32_t *walked = xrealloc(NULL, o->num_edges, sizeof *walked);
    memset(walked, 0, (o->num_edges ? o->num_edges : 1) * sizeof *walked);
    size_t filled_v = 0, filled_l = 0;
    st = mt_boundary_loops(m, verts, nv, offsets, nl + 1, &filled_v, &filled_l);
    EXPECT_STATUS(p, "mt_boundary_loops", st, MT_OK);
    bool offsets_ok =
        st == MT_OK && filled_v == nv && filled_l == nl && offsets[0] == 0 && offsets[nl] == nv;
    for (size_t l = 0; offsets_ok && l < nl; l++) offsets_ok = offsets[l] < offsets[l + 1];
    EXPECT(p, st != MT_OK || offsets_ok, "mt_boundary_loops: bad offsets or counts");
    if (offsets_ok) {
        for (size_t l = 0; l < nl; l++) {
            lengths[l] = offsets[l + 1] - offsets[l];
            for (uint32_t i = offsets[l]; i < offsets[l + 1]; i++) {
                uint32_t u = verts[i], x = verts[i + 1 < offsets[l + 1] ? i + 1 : offsets[l]];
                const mt_oracle_edge *e = mt_oracle_find_edge(o, u, x);
                EXPECT(p, e != NULL, "boundary ring %zu steps %u -> %u along no edge", l, u, x);
                if (!e || e->uses != 1) continue;
                walked[e - o->edges]++;
                EXPECT(p, (e->forward == 1) == (u < x),
                       "boundary ring %zu runs %u -> %u against its face (faces should be on the "
                       "left)",
                       l, u, x);
            }
        }
        for (size_t e = 0; e < o->num_edges; e++)
            if (o->edges[e].uses == 1)
                EXPECT(p, walked[e] == 1, "boundary edge %u-%u is walked %u times by the rings",
                       o->edges[e].a, o->edges[e].b, walked[e]);
        if (simple) {
            qsort(lengths, nl, sizeof *lengths, cmp_u32);
            expect_set(p, "mt_boundary_loops lengths", lengths, nl, w->boundary_loop_lengths,
                       w->boundary_loops);
        }
    }
    free(verts);
    free(offsets);
    free(lengths);
    free(walked);
}

/* The raw view agrees with the record classification. */
static void check_view(probe *p, const mt_mesh *m, const mt_oracle *o, const mt_face_list *in)
{
    mt_mesh_view view;
    mt_mesh_get_view(m, &view);
    EXPECT_EQ(p, "view.num_verts", view.num_verts, in->num_verts);
    EXPECT_EQ(p, "view.num_faces", view.num_faces, in->num_faces);
    EXPECT(p, view.num_verts_internal >= view.num_verts, "fewer internal vertices than vertices");
    if (view.num_verts != in->num_verts || view.num_faces != in->num_faces) return;
    for (uint32_t f = 0; f < in->num_faces; f++) {
        bool kept = view.face_he[f] != MT_NONE;
        EXPECT(p, kept == o->face_valid[f], "face %u: face_he %u but the record is %s", f,
               view.face_he[f], o->face_valid[f] ? "valid" : "rejected");
        if (kept && view.face_he[f] < view.num_half_edges)
            EXPECT(p, view.he_face[view.face_he[f]] == f, "face %u: its half-edge names face %u", f,
                   view.he_face[view.face_he[f]]);
    }
    for (uint32_t v = 0; v < in->num_verts; v++) {
        bool isolated = o->vert_face_offsets[v] == o->vert_face_offsets[v + 1];
        /* A used vertex keeps one of its fans; copies hold the others. */
        EXPECT(p, (view.vert_he[v] == MT_NONE) == isolated,
               "vertex %u: vert_he %u but the vertex is %sisolated", v, view.vert_he[v],
               isolated ? "" : "not ");
    }
    for (uint32_t c = view.num_verts; c < view.num_verts_internal; c++) {
        uint32_t orig = mt_vert_original(m, c);
        EXPECT(p, orig < in->num_verts, "vertex copy %u maps to %u", c, orig);
        if (orig < in->num_verts)
            EXPECT(p, o->vert_face_offsets[orig] != o->vert_face_offsets[orig + 1],
                   "vertex copy %u of isolated vertex %u", c, orig);
    }
    EXPECT(p, mt_mesh_num_verts(m) == in->num_verts && mt_mesh_num_faces(m) == in->num_faces,
           "mt_mesh_num_verts/faces: %u, %u", mt_mesh_num_verts(m), mt_mesh_num_faces(m));
}

static void check_queries(probe *p, const mt_mesh *m, const mt_oracle *o, const mt_face_list *in,
                          uint64_t seed)
{
    rng r = rng_seeded(seed ^ 0x5151);
    const uint32_t V = in->num_verts, F = in->num_faces;
    const bool all = V <= 64 && F <= 128;
    for (uint32_t i = 0; i < (all || V == 0 ? V : 24); i++)
        check_vert(p, m, o, in, all ? i : rng_below(&r, V));
    if (!all) {
        for (uint32_t i = 0; i < 8 && i < o->report.nonmanifold_vertices; i++)
            check_vert(p, m, o, in,
                       o->nonmanifold_verts[rng_below(&r, o->report.nonmanifold_vertices)]);
        for (uint32_t i = 0; i < 4 && i < o->report.isolated_vertices; i++)
            check_vert(p, m, o, in, o->isolated_verts[i]);
    }
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    EXPECT_STATUS(p, "mt_vert_ring(num_verts)", mt_vert_ring(m, V, &ring), MT_ERR_OUT_OF_RANGE);
    EXPECT_STATUS(p, "mt_vert_ring(MT_NONE)", mt_vert_ring(m, MT_NONE, &ring), MT_ERR_OUT_OF_RANGE);
    EXPECT(p, mt_mesh_position(m, V) == NULL, "position of vertex num_verts is not NULL");

    for (uint32_t i = 0; i < (all || F == 0 ? F : 24); i++)
        check_face(p, m, o, in, all ? i : rng_below(&r, F));
    size_t count;
    uint32_t comp;
    EXPECT_STATUS(p, "mt_face_verts(num_faces)", mt_face_verts(m, F, NULL, 0, &count),
                  MT_ERR_OUT_OF_RANGE);
    EXPECT_STATUS(p, "mt_face_component(num_faces)", mt_face_component(m, F, &comp),
                  MT_ERR_OUT_OF_RANGE);
    size_t nf, ne;
    EXPECT_STATUS(p, "mt_face_neighbors(num_faces)",
                  mt_face_neighbors(m, F, NULL, 0, NULL, 0, &nf, &ne), MT_ERR_OUT_OF_RANGE);

    const size_t E = o->num_edges;
    const bool all_edges = E <= 200;
    for (size_t i = 0; i < (all_edges ? E : 40); i++) {
        const mt_oracle_edge *e = &o->edges[all_edges ? i : rng_below(&r, (uint32_t)E)];
        check_edge(p, m, o, V, e->a, e->b);
    }
    for (size_t i = 0; !all_edges && i < 8 && i < o->num_dup_sides; i++)
        check_edge(p, m, o, V, o->dup_sides[i].a, o->dup_sides[i].b);
    for (uint32_t i = 0; V > 1 && i < 8; i++) {
        uint32_t a = rng_below(&r, V), b = rng_below(&r, V);
        if (a != b && !mt_oracle_find_edge(o, a, b)) check_edge(p, m, o, V, a, b);
    }
    if (V > 0) check_edge(p, m, o, V, 0, V);
    check_edge(p, m, o, V, MT_NONE, 0);

    check_boundary_loops(p, m, o);
}

/* ==== one input ========================================================= */

/* Builds `in`, validates it and compares the report and queries with the
 * reference. Returns the mesh (or NULL when the build failed). */
static mt_mesh *check_build(probe *p, const mt_face_list *in, const mt_oracle *o, uint32_t threads,
                            uint64_t seed)
{
    mt_build_options options;
    memset(&options, 0, sizeof options);
    options.threads = threads;
    mt_mesh *m = NULL;
    mt_diag diag;
    memset(&diag, 0, sizeof diag);
    mt_status st = mt_mesh_build(in, &options, &m, &diag);
    EXPECT(p, st == MT_OK, "mt_mesh_build (threads %u): %s: %s", threads, mt_strerror(st),
           diag.message);
    if (st != MT_OK) return NULL;
    EXPECT(p, m != NULL, "mt_mesh_build succeeded without a mesh");
    if (!m) return NULL;
    st = mt_mesh_validate(m, &diag);
    EXPECT(p, st == MT_OK, "mt_mesh_validate: %s: %s", mt_strerror(st), diag.message);
    const mt_report *r = mt_mesh_report(m);
    EXPECT(p, r != NULL, "mt_mesh_report is NULL");
    if (!r) return m;
    compare_counts(p, r, &o->report);
    compare_components(p, r, &o->report);
    compare_defects(p, r, o, in);
    if (st != MT_OK) return m; /* queries on a broken structure could loop */
    check_view(p, m, o, in);
    check_queries(p, m, o, in, seed);
    return m;
}

/* A non-NULL pointer that is not a mesh, to see that a failed build clears *out. */
static mt_mesh *not_a_mesh(void)
{
    static int marker;
    return (mt_mesh *)(void *)&marker;
}

/* Strict mode refuses exactly the inputs with a defect, naming the first. */
static void check_strict(probe *p, const mt_face_list *in, const mt_oracle *o, uint32_t threads)
{
    mt_build_options options;
    memset(&options, 0, sizeof options);
    options.strict = true;
    options.threads = threads;
    mt_mesh *m = not_a_mesh();
    mt_diag diag;
    memset(&diag, 0, sizeof diag);
    mt_status st = mt_mesh_build(in, &options, &m, &diag);
    if (!mt_oracle_has_defect(o)) {
        EXPECT(p, st == MT_OK, "strict build of a clean input: %s: %s", mt_strerror(st),
               diag.message);
        if (st == MT_OK && m) {
            st = mt_mesh_validate(m, &diag);
            EXPECT(p, st == MT_OK, "mt_mesh_validate (strict): %s: %s", mt_strerror(st),
                   diag.message);
            compare_counts(p, mt_mesh_report(m), &o->report);
            compare_components(p, mt_mesh_report(m), &o->report);
            EXPECT_EQ(p, "defects of a clean input", mt_mesh_report(m)->num_defects, 0);
        }
        if (st == MT_OK && m != not_a_mesh()) mt_mesh_destroy(m);
        return;
    }
    EXPECT_STATUS(p, "strict build of a defective input", st, MT_ERR_DEFECT);
    EXPECT(p, m == NULL, "failed strict build left *out_mesh set");
    if (st == MT_OK && m && m != not_a_mesh()) mt_mesh_destroy(m);
    if (st != MT_ERR_DEFECT) return;
    EXPECT_EQ(p, "diag.status", diag.status, MT_ERR_DEFECT);
    EXPECT(p, diag.message[0] != 0, "strict refusal without a message");
    EXPECT(p, diag.element != MT_NONE, "strict refusal names no element: \"%s\"", diag.message);
    char id[16];
    snprintf(id, sizeof id, "%u", diag.element);
    EXPECT(p, strstr(diag.message, id) != NULL, "message \"%s\" does not name element %u",
           diag.message, diag.element);
    /* The element is the one of the first defect of the full report. */
    options.strict = false;
    mt_mesh *full = NULL;
    if (mt_mesh_build(in, &options, &full, NULL) == MT_OK && full) {
        const mt_report *r = mt_mesh_report(full);
        if (r->num_defects > 0)
            EXPECT(p, diag.element == r->defects[0].a,
                   "strict refusal names element %u (\"%s\"); the first defect is %s with %u",
                   diag.element, diag.message, mt_defect_key((mt_defect_kind)r->defects[0].kind),
                   r->defects[0].a);
        mt_mesh_destroy(full);
    }
}

/* Worker threads for a seed's builds: the calling thread, the default, 2, 3. */
static uint32_t threads_for(uint64_t seed)
{
    static const uint32_t choices[] = {1, 0, 2, 3};
    return choices[seed % 4];
}

typedef enum check_mode { CHECK_PLAIN, CHECK_PERMUTED, CHECK_STRICT } check_mode;

static const char *mode_name(check_mode mode)
{
    return mode == CHECK_PLAIN ? "plain" : mode == CHECK_PERMUTED ? "permuted" : "strict";
}

/* Runs one check of `in`; returns the number of mismatches. */
static int check_case(const mt_face_list *in, const char *label, bool quiet, check_mode mode,
                      uint64_t seed)
{
    probe p = {label, quiet, 0};
    mt_oracle o;
    if (!mt_oracle_compute(in, &o)) {
        probe_fail(&p, __FILE__, __LINE__, "the reference refuses the input's sizes");
        return p.mismatches;
    }
    const uint32_t threads = threads_for(seed);
    if (mode == CHECK_PLAIN) {
        mt_mesh_destroy(check_build(&p, in, &o, threads, seed));
    } else if (mode == CHECK_STRICT) {
        check_strict(&p, in, &o, threads);
    } else {
        mt_face_list perm;
        list_copy(in, &perm);
        mt_diag diag;
        mt_status st = mt_face_list_permute(&perm, seed, &diag);
        EXPECT(&p, st == MT_OK, "mt_face_list_permute: %s: %s", mt_strerror(st), diag.message);
        mt_oracle po;
        if (st == MT_OK && mt_oracle_compute(&perm, &po)) {
            char sub[200];
            snprintf(sub, sizeof sub, "%.120s, reference of the permuted list", label);
            probe q = {sub, quiet, 0};
            compare_counts(&q, &po.report, &o.report);
            compare_component_multisets(&q, &po.report, &o.report);
            p.mismatches += q.mismatches;
            mt_mesh *m = check_build(&p, &perm, &po, threads, seed);
            if (m) {
                snprintf(sub, sizeof sub, "%.120s, permuted build against the unpermuted reference",
                         label);
                probe s = {sub, quiet, 0};
                compare_counts(&s, mt_mesh_report(m), &o.report);
                compare_component_multisets(&s, mt_mesh_report(m), &o.report);
                p.mismatches += s.mismatches;
            }
            mt_mesh_destroy(m);
            mt_oracle_free(&po);
        }
        mt_face_list_free(&perm);
    }
    mt_oracle_free(&o);
    return p.mismatches;
}

/* ==== shrinking a failing input ======================================== */

static void list_without_faces(const mt_face_list *in, uint32_t first, uint32_t count,
                               mt_face_list *out)
{
    list_builder b;
    lb_init(&b, in->positions != NULL);
    for (uint32_t v = 0; v < in->num_verts; v++) {
        const double *q = in->positions ? in->positions + 3 * (size_t)v : NULL;
        lb_vertex(&b, q ? q[0] : 0, q ? q[1] : 0, q ? q[2] : 0);
    }
    uint64_t off = 0;
    for (uint32_t f = 0; f < in->num_faces; f++) {
        if (f < first || f >= first + count) lb_face(&b, in->face_indices + off, in->face_sizes[f]);
        off += in->face_sizes[f];
    }
    lb_finish(&b, out);
}

/* Renumbers the vertices used by some record to 0..k-1 (out-of-range
 * values stay out of range), dropping the others. */
static void list_compact_vertices(const mt_face_list *in, mt_face_list *out)
{
    uint32_t *map = xrealloc(NULL, in->num_verts, sizeof *map);
    for (uint32_t v = 0; v < in->num_verts; v++) map[v] = MT_NONE;
    uint32_t k = 0;
    for (uint64_t i = 0; i < in->num_indices; i++) {
        uint32_t v = in->face_indices[i];
        if (v < in->num_verts && map[v] == MT_NONE) map[v] = k++;
    }
    list_builder b;
    lb_init(&b, in->positions != NULL);
    uint32_t *order = xrealloc(NULL, k, sizeof *order);
    for (uint32_t v = 0; v < in->num_verts; v++)
        if (map[v] != MT_NONE) order[map[v]] = v;
    for (uint32_t i = 0; i < k; i++) {
        const double *q = in->positions ? in->positions + 3 * (size_t)order[i] : NULL;
        lb_vertex(&b, q ? q[0] : 0, q ? q[1] : 0, q ? q[2] : 0);
    }
    uint64_t off = 0;
    uint32_t *tmp = NULL;
    for (uint32_t f = 0; f < in->num_faces; f++) {
        uint32_t n = in->face_sizes[f];
        tmp = xrealloc(tmp, n, sizeof *tmp);
        for (uint32_t i = 0; i < n; i++) {
            uint32_t v = in->face_indices[off + i];
            tmp[i] = v < in->num_verts ? map[v] : v; /* v >= num_verts >= k: still out */
        }
        lb_face(&b, tmp, n);
        off += n;
    }
    free(tmp);
    free(order);
    free(map);
    lb_finish(&b, out);
}

#define SHRINK_BUDGET 3000
#define SHRINK_SECONDS 30

/* Deletes faces (halves, quarters, ... single faces) and unused vertices
 * while the check still fails, then prints the smallest failing list. */
static void shrink_and_print(const mt_face_list *in, const char *label, check_mode mode,
                             uint64_t seed)
{
    mt_face_list cur;
    list_copy(in, &cur);
    int budget = SHRINK_BUDGET;
    const time_t deadline = time(NULL) + SHRINK_SECONDS;
    for (uint32_t chunk = cur.num_faces > 1 ? cur.num_faces / 2 : 1; chunk >= 1 && budget > 0;
         chunk /= 2) {
        for (uint32_t start = 0; start < cur.num_faces && budget > 0;) {
            mt_face_list cand;
            list_without_faces(&cur, start, chunk, &cand);
            if (--budget == 0 || time(NULL) > deadline) budget = 0;
            if (check_case(&cand, label, true, mode, seed) > 0) {
                mt_face_list_free(&cur);
                cur = cand;
            } else {
                mt_face_list_free(&cand);
                start += chunk;
            }
        }
        if (chunk == 1) break;
    }
    mt_face_list cand;
    list_compact_vertices(&cur, &cand);
    if (check_case(&cand, label, true, mode, seed) > 0) {
        mt_face_list_free(&cur);
        cur = cand;
    } else {
        mt_face_list_free(&cand);
    }
    if (cur.positions) {
        list_copy(&cur, &cand);
        free(cand.positions);
        cand.positions = NULL;
        if (check_case(&cand, label, true, mode, seed) > 0) {
            mt_face_list_free(&cur);
            cur = cand;
        } else {
            mt_face_list_free(&cand);
        }
    }
    fprintf(stderr, "---- %s: smallest failing input found (%s check, seed %llu):\n", label,
            mode_name(mode), (unsigned long long)seed);
    list_print(stderr, &cur);
    char sub[200];
    snprintf(sub, sizeof sub, "%s, shrunk", label);
    check_case(&cur, sub, false, mode, seed);
    fprintf(stderr, "----\n");
    mt_face_list_free(&cur);
}

/* ==== input families =================================================== */

typedef void (*family_fn)(rng *r, mt_face_list *out);

static void face_reverse(uint32_t *rec, uint32_t n)
{
    for (uint32_t i = 0, j = n ? n - 1 : 0; i < j; i++, j--) {
        uint32_t t = rec[i];
        rec[i] = rec[j];
        rec[j] = t;
    }
}

static void face_rotate(uint32_t *rec, uint32_t n, uint32_t by)
{
    for (uint32_t s = 0; n > 0 && s < by % n; s++) {
        uint32_t first = rec[0];
        memmove(rec, rec + 1, (n - 1) * sizeof *rec);
        rec[n - 1] = first;
    }
}

static void random_vertex(rng *r, list_builder *b)
{
    lb_vertex(b, rng_unit(r) * 2 - 1, rng_unit(r) * 2 - 1, rng_unit(r) * 2 - 1);
}

/* Random polygon soups: few vertices (so faces meet), sizes 0..7, some
 * repeated and out-of-range entries, sometimes no or non-finite positions. */
static void make_soup(rng *r, mt_face_list *out)
{
    list_builder b;
    lb_init(&b, !rng_chance(r, 0.2));
    uint32_t num_verts = rng_chance(r, 0.05) ? 0 : 1 + rng_below(r, rng_chance(r, 0.2) ? 150 : 20);
    for (uint32_t v = 0; v < num_verts; v++) random_vertex(r, &b);
    if (b.positions && num_verts > 0 && rng_chance(r, 0.15)) {
        static const double odd[] = {NAN, INFINITY, -INFINITY};
        for (uint32_t k = 1 + rng_below(r, 3); k > 0; k--)
            b.positions[3 * (size_t)rng_below(r, num_verts) + rng_below(r, 3)] =
                odd[rng_below(r, 3)];
    }
    const uint32_t hot = num_verts < 6 ? num_verts : 6; /* a small pool makes shared edges */
    const bool use_hot = rng_chance(r, 0.3);
    const double bad_rate = rng_chance(r, 0.5) ? 0.0 : 0.06;
    uint32_t num_faces = rng_below(r, num_verts > 40 ? 240 : 48);
    uint32_t verts[200];
    for (uint32_t f = 0; f < num_faces; f++) {
        uint32_t n;
        double u = rng_unit(r);
        if (num_verts >= 80 && rng_chance(r, 0.03)) {
            /* a big polygon over a run of consecutive ids, sometimes repeating one */
            n = 64 + rng_below(r, num_verts - 64 < 136 ? num_verts - 64 : 136);
            uint32_t first = rng_below(r, num_verts);
            for (uint32_t i = 0; i < n; i++) verts[i] = (first + i) % num_verts;
            if (rng_chance(r, 0.3)) verts[rng_below(r, n)] = verts[rng_below(r, n)];
            if (rng_chance(r, 0.5)) face_reverse(verts, n);
            lb_face(&b, verts, n);
            continue;
        }
        if (u < 0.45)
            n = 3;
        else if (u < 0.65)
            n = 4;
        else if (u < 0.68)
            n = 0;
        else
            n = 1 + rng_below(r, 7);
        for (uint32_t i = 0; i < n; i++) {
            if (num_verts == 0 || rng_chance(r, bad_rate))
                verts[i] = bad_index(r, num_verts);
            else if (i > 0 && rng_chance(r, 0.05))
                verts[i] = verts[rng_below(r, i)];
            else
                verts[i] = rng_below(r, use_hot ? hot : num_verts);
        }
        lb_face(&b, verts, n);
    }
    lb_finish(&b, out);
}

static void make_closed(rng *r, mt_face_list *out)
{
    mt_status st;
    switch (rng_below(r, 6)) {
        case 0:
            st = mt_gen_icosphere(rng_below(r, 3), out);
            break;
        case 1:
        case 4:
            st = mt_gen_torus(3 + rng_below(r, 6), 3 + rng_below(r, 6), out);
            break;
        case 2:
            st = mt_gen_double_torus(4 + rng_below(r, 3), out);
            break;
        case 3:
            st = mt_gen_platonic((mt_platonic)rng_below(r, 5), out);
            break;
        default:
            st = mt_gen_icosphere(1, out);
            break;
    }
    if (st != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "a generator failed: %s", mt_strerror(st));
        mt_face_list_alloc(out, 0, 0, 0, NULL);
    }
}

/* Drops 10-90% of the faces of `base` (consumed): holes, bowties, pieces. */
static void drop_faces(rng *r, mt_face_list *base, mt_face_list *out)
{
    const double drop = 0.1 + 0.8 * rng_unit(r);
    list_builder b;
    lb_init(&b, base->positions != NULL);
    for (uint32_t v = 0; v < base->num_verts; v++) {
        const double *q = base->positions ? base->positions + 3 * (size_t)v : NULL;
        lb_vertex(&b, q ? q[0] : 0, q ? q[1] : 0, q ? q[2] : 0);
    }
    uint64_t off = 0;
    for (uint32_t f = 0; f < base->num_faces; f++) {
        if (!rng_chance(r, drop)) lb_face(&b, base->face_indices + off, base->face_sizes[f]);
        off += base->face_sizes[f];
    }
    mt_face_list_free(base);
    lb_finish(&b, out);
}

static void make_subset(rng *r, mt_face_list *out)
{
    mt_face_list base;
    make_closed(r, &base);
    drop_faces(r, &base, out);
}

/* Replaces k random entries by other vertices or out-of-range values. */
static void add_index_noise(rng *r, mt_face_list *list)
{
    if (list->num_indices == 0) return;
    uint32_t k = 1 + rng_below(r, 1 + (uint32_t)(list->num_indices / 20));
    for (uint32_t i = 0; i < k; i++) {
        uint64_t at = rng_next(r) % list->num_indices;
        list->face_indices[at] =
            rng_chance(r, 0.7) ? rng_below(r, list->num_verts) : bad_index(r, list->num_verts);
    }
}

static void make_noise(rng *r, mt_face_list *out)
{
    make_closed(r, out);
    add_index_noise(r, out);
}

/* Reverses some faces (at least one) and rotates some (which changes nothing). */
static void flip_faces(rng *r, mt_face_list *list)
{
    if (list->num_faces == 0) return;
    const double rate = 0.5 * rng_unit(r);
    bool flipped = false;
    uint64_t off = 0;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        uint32_t *rec = list->face_indices + off;
        if (rng_chance(r, rate)) {
            face_reverse(rec, list->face_sizes[f]);
            flipped = true;
        }
        if (rng_chance(r, 0.2)) face_rotate(rec, list->face_sizes[f], rng_below(r, 7));
        off += list->face_sizes[f];
    }
    if (!flipped) {
        uint32_t f = rng_below(r, list->num_faces);
        off = 0;
        for (uint32_t g = 0; g < f; g++) off += list->face_sizes[g];
        face_reverse(list->face_indices + off, list->face_sizes[f]);
    }
}

/* Closed meshes, Moebius strips and grids with some faces reversed. */
static void make_flips(rng *r, mt_face_list *out)
{
    mt_status st = MT_OK;
    double u = rng_unit(r);
    if (u < 0.6)
        make_closed(r, out);
    else if (u < 0.75)
        st = mt_gen_moebius(3 + rng_below(r, 10), out);
    else
        st = mt_gen_grid(1 + rng_below(r, 5), 1 + rng_below(r, 5), rng_chance(r, 0.5), out);
    if (st != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "a generator failed: %s", mt_strerror(st));
        mt_face_list_alloc(out, 0, 0, 0, NULL);
        return;
    }
    flip_faces(r, out);
}

/* Offset of face f's record (linear; the lists here are small). */
static uint64_t record_offset(const list_builder *b, uint32_t f)
{
    uint64_t off = 0;
    for (uint32_t g = 0; g < f; g++) off += b->sizes[g];
    return off;
}

/* Merges vertex x into y (x's uses become y) and removes x by moving the
 * last vertex into its slot. Returns the old id of the moved vertex. */
static uint32_t lb_merge_vertex(list_builder *b, uint32_t x, uint32_t y)
{
    const uint32_t last = b->num_verts - 1;
    for (uint64_t i = 0; i < b->num_indices; i++) {
        if (b->indices[i] == x) b->indices[i] = y;
    }
    for (uint64_t i = 0; i < b->num_indices; i++) {
        if (b->indices[i] == last) b->indices[i] = x;
    }
    if (b->positions && x != last)
        memcpy(b->positions + 3 * (size_t)x, b->positions + 3 * (size_t)last, 3 * sizeof(double));
    b->num_verts--;
    return last;
}

/* Closed meshes with duplicated faces (same, rotated or reversed order),
 * fins glued on existing edges, and second meshes sharing a vertex or an
 * edge with the first. */
static void glue_onto(rng *r, mt_face_list *base, mt_face_list *out)
{
    list_builder b;
    lb_init(&b, base->positions != NULL);
    lb_append(&b, base);
    mt_face_list_free(base);
    uint32_t ops = 1 + rng_below(r, 4);
    uint32_t tmp[64];
    for (uint32_t op = 0; op < ops && b.num_faces > 0; op++) {
        uint32_t f = rng_below(r, b.num_faces);
        uint32_t n = b.sizes[f];
        if (n > 64) continue;
        memcpy(tmp, b.indices + record_offset(&b, f), n * sizeof *tmp);
        uint32_t i = rng_below(r, n);
        switch (rng_below(r, 4)) {
            case 0: /* duplicate */
                if (rng_chance(r, 0.5)) face_reverse(tmp, n);
                if (rng_chance(r, 0.5)) face_rotate(tmp, n, rng_below(r, n));
                lb_face(&b, tmp, n);
                break;
            case 1: { /* fins on side i */
                for (uint32_t k = 1 + rng_below(r, 2); k > 0; k--) {
                    uint32_t c = lb_vertex(&b, rng_unit(r), rng_unit(r), rng_unit(r) + 2);
                    uint32_t fin[3] = {tmp[i], tmp[(i + 1) % n], c};
                    if (rng_chance(r, 0.5)) face_reverse(fin, 3);
                    lb_face(&b, fin, 3);
                }
                break;
            }
            case 2:
            case 3: { /* a second mesh sharing a vertex (op 2) or an edge (op 3) */
                bool share_edge = rng_below(r, 2) == 1;
                mt_face_list second;
                mt_status st = rng_chance(r, 0.5)
                                   ? mt_gen_platonic((mt_platonic)rng_below(r, 5), &second)
                                   : mt_gen_torus(3, 3, &second);
                if (st != MT_OK) {
                    mt_test_fail(__FILE__, __LINE__, "a generator failed: %s", mt_strerror(st));
                    break;
                }
                if (rng_chance(r, 0.3)) { /* flipped as a whole */
                    uint64_t off = 0;
                    for (uint32_t g = 0; g < second.num_faces; g++) {
                        face_reverse(second.face_indices + off, second.face_sizes[g]);
                        off += second.face_sizes[g];
                    }
                }
                uint32_t s0 = second.face_indices[0], s1 = second.face_indices[1];
                uint32_t shift = lb_append(&b, &second);
                mt_face_list_free(&second);
                s0 += shift;
                s1 += shift;
                uint32_t t0 = tmp[i], t1 = tmp[(i + 1) % n];
                if (share_edge && rng_chance(r, 0.5)) {
                    uint32_t t = t0;
                    t0 = t1;
                    t1 = t;
                }
                uint32_t moved = lb_merge_vertex(&b, s0, t0);
                if (moved == s1) s1 = s0;
                if (share_edge) lb_merge_vertex(&b, s1, t1);
                break;
            }
        }
    }
    lb_finish(&b, out);
}

static void make_glued(rng *r, mt_face_list *out)
{
    mt_face_list base;
    make_closed(r, &base);
    glue_onto(r, &base, out);
}

/* Big closed meshes (20k-80k faces), as they are or dropped, noisy,
 * flipped or glued: enough work for the build's threads. */
static void make_large(rng *r, mt_face_list *out)
{
    mt_face_list base;
    mt_status st;
    switch (rng_below(r, 3)) {
        case 0:
            st = mt_gen_icosphere(5 + rng_below(r, 2), &base);
            break;
        case 1:
            st = mt_gen_torus(100 + rng_below(r, 100), 100 + rng_below(r, 100), &base);
            break;
        default:
            st = mt_gen_double_torus(16 + 16 * rng_below(r, 2), &base);
            break;
    }
    if (st != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "a generator failed: %s", mt_strerror(st));
        mt_face_list_alloc(out, 0, 0, 0, NULL);
        return;
    }
    switch (rng_below(r, 5)) {
        case 0:
            *out = base;
            break;
        case 1:
            drop_faces(r, &base, out);
            break;
        case 2:
            add_index_noise(r, &base);
            *out = base;
            break;
        case 3:
            flip_faces(r, &base);
            *out = base;
            break;
        default:
            glue_onto(r, &base, out);
            break;
    }
}

/* A big soup whose faces take nearby vertex ids, so that they share edges
 * in every possible way. */
static void make_large_soup(rng *r, mt_face_list *out)
{
    list_builder b;
    lb_init(&b, true);
    const uint32_t num_verts = 5000 + rng_below(r, 20000);
    for (uint32_t v = 0; v < num_verts; v++) random_vertex(r, &b);
    const uint32_t num_faces = 2 * num_verts + rng_below(r, num_verts);
    uint32_t verts[6];
    for (uint32_t f = 0; f < num_faces; f++) {
        uint32_t n = rng_chance(r, 0.8) ? 3 : 1 + rng_below(r, 6);
        uint32_t first = rng_below(r, num_verts - 12);
        for (uint32_t i = 0; i < n; i++)
            verts[i] = rng_chance(r, 0.002) ? bad_index(r, num_verts) : first + rng_below(r, 12);
        lb_face(&b, verts, n);
    }
    lb_finish(&b, out);
}

/* Every family, for the permuted and strict runs. */
static void make_any(rng *r, mt_face_list *out)
{
    static const family_fn families[] = {make_soup,  make_subset, make_noise,
                                         make_flips, make_glued,  make_closed};
    families[rng_below(r, sizeof families / sizeof families[0])](r, out);
}

/* Runs `cases` inputs of a family; the first failures are shrunk and printed. */
static void run_family(const char *name, family_fn make, uint32_t cases, check_mode mode)
{
    /* MT_PROP_TRACE=1 prints every input before it is built (to find one
     * that crashes); MT_PROP_MAX_FAILING=n goes on past the first 2
     * failures; MT_PROP_SCALE=k runs k times as many inputs (a soak run). */
    const bool trace = getenv("MT_PROP_TRACE") != NULL;
    const char *max_env = getenv("MT_PROP_MAX_FAILING");
    const int max_failing = max_env ? atoi(max_env) : 2;
    const char *scale_env = getenv("MT_PROP_SCALE");
    if (scale_env && atoi(scale_env) > 1) cases *= (uint32_t)atoi(scale_env);
    int failing = 0;
    for (uint32_t i = 0; i < cases && failing < max_failing; i++) {
        const uint64_t seed = i + 1;
        rng r = rng_seeded(seed);
        mt_face_list in;
        make(&r, &in);
        char label[160];
        snprintf(label, sizeof label, "%s case %u (%s, seed %llu, threads %u)", name, i,
                 mode_name(mode), (unsigned long long)seed, threads_for(seed));
        if (trace) {
            fprintf(stderr, "%s\n", label);
            list_print(stderr, &in);
        }
        if (check_case(&in, label, false, mode, seed) > 0) {
            failing++;
            shrink_and_print(&in, label, mode, seed);
        }
        mt_face_list_free(&in);
    }
}

/* ==== the reference against the corpus answers ========================= */

/* A JSON number, bool or null (as -1) member. */
static void expect_json_number(probe *p, const cJSON *obj, const char *key, long long got)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!cJSON_IsNumber(v) && !cJSON_IsBool(v) && !cJSON_IsNull(v)) {
        probe_fail(p, __FILE__, __LINE__, "expected file has no number \"%s\"", key);
        return;
    }
    long long want = cJSON_IsNull(v)   ? -1
                     : cJSON_IsBool(v) ? cJSON_IsTrue(v)
                                       : (long long)v->valuedouble;
    EXPECT_EQ(p, key, got, want);
}

/* A JSON array of numbers (null as -1). */
static void expect_json_list(probe *p, const cJSON *arr, const char *what, const long long *got,
                             size_t n)
{
    if (!cJSON_IsArray(arr)) {
        probe_fail(p, __FILE__, __LINE__, "expected file has no list %s", what);
        return;
    }
    const size_t count = (size_t)cJSON_GetArraySize(arr);
    EXPECT_EQ(p, what, n, count);
    size_t i = 0;
    const cJSON *v;
    cJSON_ArrayForEach(v, arr)
    {
        if (i >= n) break;
        EXPECT_EQ(p, what, got[i], cJSON_IsNull(v) ? -1 : (long long)v->valuedouble);
        i++;
    }
}

static void expect_json_set(probe *p, const cJSON *arr, const char *what, const uint32_t *got,
                            size_t n)
{
    long long *tmp = xrealloc(NULL, n, sizeof *tmp);
    for (size_t i = 0; i < n; i++) tmp[i] = got[i];
    expect_json_list(p, arr, what, tmp, n);
    free(tmp);
}

static void expect_json_histogram(probe *p, const cJSON *obj, const char *what,
                                  const mt_histogram_bin *bins, size_t n)
{
    if (!cJSON_IsObject(obj)) {
        probe_fail(p, __FILE__, __LINE__, "expected file has no histogram %s", what);
        return;
    }
    EXPECT_EQ(p, what, n, cJSON_GetArraySize(obj));
    for (size_t i = 0; i < n; i++) {
        char key[16];
        snprintf(key, sizeof key, "%u", bins[i].key);
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
        EXPECT(p, cJSON_IsNumber(v) && (uint64_t)v->valuedouble == bins[i].count,
               "%s[%u]: reference %llu, expected %g", what, bins[i].key,
               (unsigned long long)bins[i].count, cJSON_IsNumber(v) ? v->valuedouble : -1.0);
    }
}

static int cmp_genus(const void *x, const void *y)
{
    long long a = *(const long long *)x, b = *(const long long *)y;
    if (a < 0 || b < 0) return (a < 0) - (b < 0); /* nulls (-1) last */
    return (a > b) - (a < b);
}

static const cJSON *member(const cJSON *obj, const char *key)
{
    return cJSON_GetObjectItemCaseSensitive(obj, key);
}

static void compare_with_expected(probe *p, const mt_oracle *o, const cJSON *x)
{
    const mt_report *r = &o->report;
    const cJSON *item;
    cJSON_ArrayForEach(item, x)
    {
        bool known = false;
        for (size_t k = 0; k < mt_test_num_corpus_keys; k++)
            known = known || strcmp(item->string, mt_test_corpus_keys[k]) == 0;
        EXPECT(p, known, "expected file has a key the test does not check: %s", item->string);
    }
    expect_json_number(p, x, "V", r->num_verts);
    expect_json_number(p, x, "F", r->num_faces);
    expect_json_number(p, x, "F_valid", r->num_faces_valid);
    expect_json_number(p, x, "E", (long long)r->num_edges);
    expect_json_number(p, x, "half_edges", (long long)r->num_half_edges);
    expect_json_histogram(p, member(x, "face_size_histogram"), "face_size_histogram",
                          r->face_size_histogram, r->num_face_size_bins);
    expect_json_histogram(p, member(x, "edge_use_histogram"), "edge_use_histogram",
                          r->edge_use_histogram, r->num_edge_use_bins);
    expect_json_number(p, x, "boundary_edges", (long long)r->boundary_edges);
    const cJSON *loops = member(x, "boundary_loops");
    expect_json_number(p, loops, "count", r->boundary_loops);
    expect_json_number(p, loops, "ambiguous", r->boundary_loops_ambiguous);
    expect_json_set(p, member(loops, "lengths"), "boundary_loops.lengths", r->boundary_loop_lengths,
                    r->boundary_loops);
    expect_json_number(p, x, "nonmanifold_edges", (long long)r->nonmanifold_edges);
    expect_json_number(p, x, "inconsistent_orientation_edges",
                       (long long)r->inconsistent_orientation_edges);
    expect_json_number(p, x, "duplicate_directed_edges", (long long)r->duplicate_directed_edges);
    expect_json_number(p, x, "nonmanifold_vertices", r->nonmanifold_vertices);
    expect_json_set(p, member(x, "nonmanifold_vertices_list_head"),
                    "nonmanifold_vertices_list_head", o->nonmanifold_verts,
                    r->nonmanifold_vertices < 20 ? r->nonmanifold_vertices : 20);
    expect_json_number(p, x, "bowtie_vertices", r->bowtie_vertices);
    expect_json_number(p, x, "isolated_vertices", r->isolated_vertices);
    expect_json_number(p, x, "unreferenced_vertices", r->unreferenced_vertices);
    expect_json_number(p, x, "degenerate_faces", r->degenerate_faces);
    expect_json_number(p, x, "out_of_range_indices", (long long)r->out_of_range_indices);
    expect_json_number(p, x, "faces_with_out_of_range_indices", r->faces_with_out_of_range_indices);
    expect_json_number(p, x, "connected_components", r->connected_components);
    expect_json_number(p, x, "vertex_connected_components", r->vertex_connected_components);
    expect_json_number(p, x, "euler_characteristic", r->euler_characteristic);
    expect_json_number(p, x, "closed", r->closed);
    expect_json_number(p, x, "manifold", r->manifold);
    expect_json_number(p, x, "orientable", r->orientable);
    expect_json_number(p, x, "consistently_oriented", r->consistently_oriented);
    expect_json_number(p, x, "genus", r->genus);

    long long *genera = xrealloc(NULL, r->connected_components, sizeof *genera);
    for (uint32_t c = 0; c < r->connected_components; c++) genera[c] = r->components[c].genus;
    qsort(genera, r->connected_components, sizeof *genera, cmp_genus);
    expect_json_list(p, member(x, "component_genera"), "component_genera", genera,
                     r->connected_components);
    free(genera);

    const cJSON *comps = member(x, "components");
    EXPECT(p, cJSON_IsArray(comps) && cJSON_GetArraySize(comps) == (int)r->connected_components,
           "components: expected %d, reference %u", cJSON_GetArraySize(comps),
           r->connected_components);
    uint32_t c = 0;
    const cJSON *jc;
    cJSON_ArrayForEach(jc, comps)
    {
        if (c >= r->connected_components) break;
        const mt_component_info *ci = &r->components[c++];
        expect_json_number(p, jc, "min_face_index", ci->min_face);
        expect_json_number(p, jc, "faces", ci->faces);
        expect_json_number(p, jc, "vertices", ci->vertices);
        expect_json_number(p, jc, "edges", (long long)ci->edges);
        expect_json_number(p, jc, "euler_characteristic", ci->euler_characteristic);
        expect_json_number(p, jc, "boundary_edges", (long long)ci->boundary_edges);
        expect_json_number(p, jc, "boundary_loops", ci->boundary_loops);
        expect_json_number(p, jc, "closed", ci->closed);
        expect_json_number(p, jc, "manifold", ci->manifold);
        expect_json_number(p, jc, "orientable", ci->orientable);
        expect_json_number(p, jc, "genus", ci->genus);
        expect_json_number(p, jc, "genus_with_boundary", ci->genus_with_boundary);
    }

    const cJSON *vq = member(x, "vertex_queries"), *q;
    EXPECT(p, cJSON_IsArray(vq), "no vertex_queries");
    cJSON_ArrayForEach(q, vq)
    {
        const cJSON *id = member(q, "vertex");
        uint32_t v = cJSON_IsNumber(id) ? (uint32_t)id->valuedouble : MT_NONE;
        if (v >= r->num_verts) {
            probe_fail(p, __FILE__, __LINE__, "a vertex query has a bad vertex");
            continue;
        }
        char what[64];
        snprintf(what, sizeof what, "neighbors of vertex %u", v);
        expect_json_set(p, member(q, "neighbors"), what, o->vert_nb + o->vert_nb_offsets[v],
                        o->vert_nb_offsets[v + 1] - o->vert_nb_offsets[v]);
        snprintf(what, sizeof what, "faces of vertex %u", v);
        expect_json_set(p, member(q, "faces"), what, o->vert_faces + o->vert_face_offsets[v],
                        o->vert_face_offsets[v + 1] - o->vert_face_offsets[v]);
    }
    const cJSON *fq = member(x, "face_queries");
    EXPECT(p, cJSON_IsArray(fq), "no face_queries");
    cJSON_ArrayForEach(q, fq)
    {
        const cJSON *id = member(q, "face");
        uint32_t f = cJSON_IsNumber(id) ? (uint32_t)id->valuedouble : MT_NONE;
        if (f >= r->num_faces) {
            probe_fail(p, __FILE__, __LINE__, "a face query has a bad face");
            continue;
        }
        char what[64];
        snprintf(what, sizeof what, "adjacent faces of face %u", f);
        expect_json_set(p, member(q, "adjacent_faces"), what, o->face_adj + o->face_adj_offsets[f],
                        o->face_adj_offsets[f + 1] - o->face_adj_offsets[f]);
    }
}

static int cmp_str(const void *x, const void *y)
{
    return strcmp(*(char *const *)x, *(char *const *)y);
}

/* Names of the corpus answer files, sorted; returns how many. */
static size_t corpus_answers(char ***out_names)
{
    const char *dir = mt_test_corpus_dir();
    DIR *d = opendir(dir);
    char **names = NULL;
    size_t n = 0;
    if (!d) {
        mt_test_fail(__FILE__, __LINE__, "cannot open the corpus directory %s", dir);
        *out_names = NULL;
        return 0;
    }
    const char *suffix = ".expected.json";
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name);
        if (len <= strlen(suffix) || strcmp(e->d_name + len - strlen(suffix), suffix) != 0)
            continue;
        names = xrealloc(names, n + 1, sizeof *names);
        names[n] = xrealloc(NULL, len + 1, 1);
        memcpy(names[n], e->d_name, len + 1);
        n++;
    }
    closedir(d);
    qsort(names, n, sizeof *names, cmp_str);
    *out_names = names;
    return n;
}

/* Reads answer file `name` and its mesh; false (with a failure) if either fails. */
static bool corpus_load(const char *name, cJSON **out_answer, mt_face_list *out_list)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", mt_test_corpus_dir(), name);
    char *text = file_read_text(path);
    if (!text) {
        mt_test_fail(__FILE__, __LINE__, "cannot read %s", path);
        return false;
    }
    cJSON *answer = cJSON_Parse(text);
    free(text);
    const cJSON *file = member(answer, "file");
    if (!answer || !cJSON_IsString(file)) {
        mt_test_fail(__FILE__, __LINE__, "%s: not an answer file", path);
        cJSON_Delete(answer);
        return false;
    }
    snprintf(path, sizeof path, "%s/%s", mt_test_corpus_dir(), file->valuestring);
    mt_diag diag;
    mt_status st = mt_read_file(path, MT_FORMAT_AUTO, out_list, &diag);
    if (st != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "mt_read_file(%s): %s: %s", path, mt_strerror(st),
                     diag.message);
        cJSON_Delete(answer);
        return false;
    }
    *out_answer = answer;
    return true;
}

static void test_oracle_matches_corpus(void)
{
    char **names;
    size_t n = corpus_answers(&names);
    CHECK(n >= 20);
    for (size_t i = 0; i < n; i++) {
        cJSON *answer;
        mt_face_list list;
        if (corpus_load(names[i], &answer, &list)) {
            probe p = {names[i], false, 0};
            mt_oracle o;
            CHECK(mt_oracle_compute(&list, &o));
            compare_with_expected(&p, &o, answer);
            mt_oracle_free(&o);
            mt_face_list_free(&list);
            cJSON_Delete(answer);
        }
        free(names[i]);
    }
    free(names);
}

/* The builder on every corpus mesh, against the reference (which the test
 * above ties to the answers): every field, defect entry and a query sample. */
static void test_build_matches_oracle_on_corpus(void)
{
    char **names;
    size_t n = corpus_answers(&names);
    CHECK(n >= 20);
    for (size_t i = 0; i < n; i++) {
        cJSON *answer;
        mt_face_list list;
        if (corpus_load(names[i], &answer, &list)) {
            if (check_case(&list, names[i], false, CHECK_PLAIN, i) > 0 && list.num_faces <= 2000)
                shrink_and_print(&list, names[i], CHECK_PLAIN, i);
            mt_face_list_free(&list);
            cJSON_Delete(answer);
        }
        free(names[i]);
    }
    free(names);
}

/* ==== the reference on hand-checked shapes the corpus lacks ============ */

static void list_from(uint32_t num_verts, const uint32_t *sizes, uint32_t num_faces,
                      const uint32_t *indices, mt_face_list *out)
{
    list_builder b;
    lb_init(&b, true);
    for (uint32_t v = 0; v < num_verts; v++) lb_vertex(&b, v, v * v, 1.0 / (v + 1));
    uint64_t off = 0;
    for (uint32_t f = 0; f < num_faces; f++) {
        lb_face(&b, indices + off, sizes[f]);
        off += sizes[f];
    }
    lb_finish(&b, out);
}

static void test_oracle_hand_cases(void)
{
    mt_face_list l;
    mt_oracle o;
    static const uint32_t tri6[] = {3, 3, 3, 3, 3, 3};

    /* Tetrahedron plus face 0 again reversed and rotated: 3 edges used 4
     * times, 2 duplicate faces of face 0. */
    static const uint32_t tet_dup[] = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2, 0, 2, 1, 1, 2, 0};
    list_from(4, tri6, 4, tet_dup, &l);
    CHECK(mt_oracle_compute(&l, &o));
    CHECK_EQ(o.report.num_edges, 6);
    CHECK_EQ(o.report.closed, 1);
    CHECK_EQ(o.report.genus, 0);
    CHECK_EQ(o.report.duplicate_faces, 0);
    CHECK_EQ(o.report.consistently_oriented, 1);
    mt_oracle_free(&o);
    mt_face_list_free(&l);
    list_from(4, tri6, 6, tet_dup, &l);
    CHECK(mt_oracle_compute(&l, &o));
    CHECK_EQ(o.report.nonmanifold_edges, 3);
    CHECK_EQ(o.report.duplicate_faces, 2);
    CHECK_EQ(o.face_duplicate_of[4], 0);
    CHECK_EQ(o.face_duplicate_of[5], 0);
    CHECK_EQ(o.face_duplicate_of[3], MT_NONE);
    CHECK_EQ(o.report.duplicate_directed_edges, 3); /* (0,1) twice: faces 0 and 5 */
    CHECK_EQ(o.report.nonmanifold_vertices, 3);
    CHECK_EQ(o.report.manifold, 0);
    CHECK_EQ(o.report.genus, -1);
    CHECK(mt_oracle_has_defect(&o));
    mt_oracle_free(&o);
    mt_face_list_free(&l);

    /* Tetrahedron with its last face flipped: orientable, not consistent. */
    static const uint32_t tet_flip[] = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 2, 3};
    list_from(4, tri6, 4, tet_flip, &l);
    CHECK(mt_oracle_compute(&l, &o));
    CHECK_EQ(o.report.inconsistent_orientation_edges, 3);
    CHECK_EQ(o.report.duplicate_directed_edges, 3);
    CHECK_EQ(o.num_dup_sides, 3);
    CHECK_EQ(o.report.orientable, 1);
    CHECK_EQ(o.report.consistently_oriented, 0);
    CHECK_EQ(o.report.genus, 0);
    mt_oracle_free(&o);
    mt_face_list_free(&l);

    /* Bowtie: two triangles sharing vertex 0. */
    static const uint32_t bowtie[] = {0, 1, 2, 0, 3, 4};
    list_from(5, tri6, 2, bowtie, &l);
    CHECK(mt_oracle_compute(&l, &o));
    CHECK_EQ(o.report.bowtie_vertices, 1);
    CHECK_EQ(o.report.nonmanifold_vertices, 1);
    CHECK_EQ(o.nonmanifold_verts[0], 0);
    CHECK_EQ(o.link_parts[0], 2);
    CHECK_EQ(o.report.boundary_loops, 1);
    CHECK_EQ(o.report.boundary_loop_lengths[0], 6);
    CHECK_EQ(o.report.boundary_loops_ambiguous, 1);
    CHECK_EQ(o.report.connected_components, 2);
    CHECK_EQ(o.report.vertex_connected_components, 1);
    CHECK_EQ(o.report.components[1].min_face, 1);
    CHECK_EQ(o.report.components[0].manifold, 1);
    CHECK_EQ(o.report.components[0].boundary_loops, 1);
    CHECK_EQ(o.report.components[0].genus_with_boundary, 0);
    CHECK_EQ(o.report.components[0].genus, -1);
    CHECK_EQ(o.report.euler_characteristic, 1);
    mt_oracle_free(&o);
    mt_face_list_free(&l);

    /* Fin: edge 0-1 used three times, twice as 0 -> 1. */
    static const uint32_t fin[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    list_from(5, tri6, 3, fin, &l);
    CHECK(mt_oracle_compute(&l, &o));
    CHECK_EQ(o.report.nonmanifold_edges, 1);
    CHECK_EQ(o.report.inconsistent_orientation_edges, 0);
    CHECK_EQ(o.report.duplicate_directed_edges, 1);
    CHECK_EQ(o.num_dup_sides, 1);
    CHECK(o.num_dup_sides == 1 && o.dup_sides[0].a == 0 && o.dup_sides[0].b == 1 &&
          o.dup_sides[0].count == 2);
    CHECK_EQ(o.report.nonmanifold_vertices, 2);
    CHECK_EQ(o.report.bowtie_vertices, 0);
    CHECK_EQ(o.link_branch[0], 1);
    CHECK_EQ(o.report.connected_components, 1);
    CHECK_EQ(o.report.components[0].manifold, 0);
    CHECK_EQ(o.report.boundary_edges, 6);
    CHECK_EQ(o.face_adj_offsets[1] - o.face_adj_offsets[0], 2);
    mt_oracle_free(&o);
    mt_face_list_free(&l);

    /* Isolated versus unreferenced; out-of-range and repeated entries; NaN. */
    static const uint32_t mixed_sizes[] = {3, 3, 4, 0, 2};
    static const uint32_t mixed[] = {0, 1, 2, 3, 3, 4, 0, 9, 0xffffffffu, 9, 1, 2};
    list_from(6, mixed_sizes, 5, mixed, &l);
    l.positions[3 * 1 + 1] = NAN;
    l.positions[3 * 4 + 2] = -INFINITY;
    l.positions[3 * 4 + 0] = INFINITY;
    CHECK(mt_oracle_compute(&l, &o));
    CHECK_EQ(o.report.num_faces_valid, 1);
    CHECK_EQ(o.report.degenerate_faces, 4); /* sizes 0 and 2, repeated 3, repeated 9 */
    CHECK_EQ(o.report.out_of_range_indices, 3);
    CHECK_EQ(o.report.faces_with_out_of_range_indices, 1);
    CHECK_EQ(o.face_first_bad[2], 1);
    CHECK_EQ(o.face_distinct[2], 3);
    CHECK_EQ(o.report.isolated_vertices, 3);     /* 3, 4, 5 */
    CHECK_EQ(o.report.unreferenced_vertices, 1); /* 5 */
    CHECK_EQ(o.report.nonfinite_vertices, 2);
    CHECK_EQ(o.nonfinite_axis[1], 1);
    CHECK_EQ(o.nonfinite_axis[4], 0);
    CHECK_EQ(o.report.num_half_edges, 12);
    CHECK_EQ(o.report.num_face_size_bins, 4);
    CHECK_EQ(o.report.euler_characteristic, 6 - 3 + 1);
    CHECK_EQ(o.report.closed, 0);
    mt_oracle_free(&o);
    mt_face_list_free(&l);

    /* Moebius strip from the generator: non-orientable, one boundary loop. */
    CHECK_OK(mt_gen_moebius(5, &l));
    CHECK(mt_oracle_compute(&l, &o));
    CHECK_EQ(o.report.orientable, 0);
    CHECK_EQ(o.report.boundary_loops, 1);
    CHECK_EQ(o.report.manifold, 1);
    CHECK_EQ(o.report.components[0].genus_with_boundary, -1);
    mt_oracle_free(&o);
    mt_face_list_free(&l);

    /* The double torus: genus 2. */
    CHECK_OK(mt_gen_double_torus(4, &l));
    CHECK(mt_oracle_compute(&l, &o));
    CHECK_EQ(o.report.genus, 2);
    CHECK_EQ(o.report.consistently_oriented, 1);
    CHECK(!mt_oracle_has_defect(&o));
    mt_oracle_free(&o);
    mt_face_list_free(&l);

    /* Inconsistent sizes are refused. */
    static const uint32_t two[] = {3, 3};
    static const uint32_t six[] = {0, 1, 2, 0, 2, 3};
    mt_face_list bad = {4, 2, 5, NULL, (uint32_t *)two, (uint32_t *)six};
    CHECK(!mt_oracle_compute(&bad, &o));
}

/* ==== property tests =================================================== */

static void test_random_soups(void)
{
    run_family("soup", make_soup, 1500, CHECK_PLAIN);
}

static void test_closed_subsets(void)
{
    run_family("subset", make_subset, 400, CHECK_PLAIN);
}

static void test_index_noise(void)
{
    run_family("noise", make_noise, 400, CHECK_PLAIN);
}

static void test_face_flips(void)
{
    run_family("flips", make_flips, 400, CHECK_PLAIN);
}

static void test_duplicates_fins_pinches(void)
{
    run_family("glued", make_glued, 400, CHECK_PLAIN);
}

static void test_large_inputs(void)
{
    run_family("large", make_large, 8, CHECK_PLAIN);
    run_family("large soup", make_large_soup, 3, CHECK_PLAIN);
    run_family("large", make_large, 2, CHECK_PERMUTED);
}

static void test_permuted(void)
{
    run_family("soup", make_soup, 300, CHECK_PERMUTED);
    run_family("any", make_any, 300, CHECK_PERMUTED);
}

static void test_strict_mode(void)
{
    run_family("soup", make_soup, 300, CHECK_STRICT);
    run_family("any", make_any, 300, CHECK_STRICT);
    run_family("closed", make_closed, 60, CHECK_STRICT);
}

/* ==== malformed and degenerate inputs ================================== */

/* A build expected to fail with `want`, leaving *out NULL and diag filled. */
static void expect_build_fails(const char *what, const mt_face_list *in, mt_status want)
{
    mt_mesh *m = not_a_mesh();
    mt_diag diag;
    memset(&diag, 0, sizeof diag);
    mt_status st = mt_mesh_build(in, NULL, &m, &diag);
    if (st != want)
        mt_test_fail(__FILE__, __LINE__, "%s: mt_mesh_build returned %s, expected %s (%s)", what,
                     mt_strerror(st), mt_strerror(want), diag.message);
    if (m != NULL)
        mt_test_fail(__FILE__, __LINE__, "%s: failed build did not clear *out_mesh", what);
    if (st == want && (diag.status != want || diag.message[0] == 0))
        mt_test_fail(__FILE__, __LINE__, "%s: diag not filled (status %s, message \"%s\")", what,
                     mt_strerror(diag.status), diag.message);
    if (st == MT_OK && m && m != not_a_mesh()) mt_mesh_destroy(m);
}

/* Checks one small input in every mode, recording failures. */
static void expect_matches_reference(const char *what, const mt_face_list *in)
{
    check_case(in, what, false, CHECK_PLAIN, 1);
    check_case(in, what, false, CHECK_STRICT, 2);
    check_case(in, what, false, CHECK_PERMUTED, 3);
}

static void test_degenerate_inputs(void)
{
    static uint32_t sizes[4] = {3, 3, 3, 3};
    static uint32_t indices[12] = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};

    /* Empty: no vertices, no faces (NULL and non-NULL arrays). */
    mt_face_list empty = {0, 0, 0, NULL, NULL, NULL};
    expect_matches_reference("empty mesh", &empty);
    mt_face_list empty2 = {0, 0, 0, NULL, sizes, indices};
    expect_matches_reference("empty mesh with arrays", &empty2);
    mt_mesh *m = NULL;
    CHECK_OK(mt_mesh_build(&empty, NULL, &m, NULL));
    if (m) {
        const mt_report *r = mt_mesh_report(m);
        CHECK_EQ(r->connected_components, 0);
        CHECK_EQ(r->closed, 0);
        CHECK_EQ(r->genus, -1);
        CHECK_EQ(r->num_defects, 0);
        CHECK_OK(mt_mesh_validate(m, NULL));
    }
    mt_mesh_destroy(m);

    /* Vertices but no faces: all isolated. */
    double pos[3 * 5] = {0};
    mt_face_list verts_only = {5, 0, 0, pos, NULL, NULL};
    expect_matches_reference("vertices without faces", &verts_only);

    /* Zero-size faces only (no indices at all). */
    static uint32_t zeros[3] = {0, 0, 0};
    mt_face_list zero_faces = {3, 3, 0, NULL, zeros, NULL};
    expect_matches_reference("zero-size faces", &zero_faces);

    /* No geometry is allowed. */
    mt_face_list no_pos = {4, 4, 12, NULL, sizes, indices};
    expect_matches_reference("tetrahedron without positions", &no_pos);

    /* Face sizes that do not add up to num_indices. */
    mt_face_list short_sum = {4, 4, 13, NULL, sizes, indices};
    expect_build_fails("sizes add up to less than num_indices", &short_sum, MT_ERR_INVALID_ARG);
    mt_face_list long_sum = {4, 4, 11, NULL, sizes, indices};
    expect_build_fails("sizes add up to more than num_indices", &long_sum, MT_ERR_INVALID_ARG);

    /* num_faces = 2^31 over a 4-entry face_sizes array whose sizes pass
     * num_indices at entry 3: the build must stop there (ASan sees any
     * read past the array). The arrays are heap blocks of the exact size. */
    uint32_t *few_sizes = xrealloc(NULL, 4, sizeof *few_sizes);
    uint32_t *few_indices = xrealloc(NULL, 9, sizeof *few_indices);
    few_sizes[0] = few_sizes[1] = few_sizes[2] = 3;
    few_sizes[3] = 0x7fffffffu;
    memcpy(few_indices, indices, 9 * sizeof *few_indices);
    mt_face_list huge = {4, 0x80000000u, 9, NULL, few_sizes, few_indices};
    expect_build_fails("2^31 faces, sizes pass num_indices at face 3", &huge, MT_ERR_INVALID_ARG);
    few_sizes[0] = 0xffffffffu;
    huge.num_indices = 0;
    expect_build_fails("2^31 faces, first size past num_indices", &huge, MT_ERR_INVALID_ARG);
    few_sizes[0] = 10;
    huge.num_indices = 9;
    expect_build_fails("2^31 faces, first size past 9 indices", &huge, MT_ERR_INVALID_ARG);
    free(few_sizes);
    free(few_indices);

    /* NULL arrays with non-zero counts. */
    mt_face_list null_sizes = {4, 4, 12, NULL, NULL, indices};
    expect_build_fails("NULL face_sizes", &null_sizes, MT_ERR_INVALID_ARG);
    mt_face_list null_indices = {4, 4, 12, NULL, sizes, NULL};
    expect_build_fails("NULL face_indices", &null_indices, MT_ERR_INVALID_ARG);

    /* NULL input, NULL output. */
    expect_build_fails("NULL input", NULL, MT_ERR_INVALID_ARG);
    mt_diag diag;
    memset(&diag, 0, sizeof diag);
    mt_face_list tet = {4, 4, 12, NULL, sizes, indices};
    CHECK_STATUS(mt_mesh_build(&tet, NULL, NULL, &diag), MT_ERR_INVALID_ARG);
    CHECK(diag.message[0] != 0);
    CHECK_STATUS(mt_mesh_build(NULL, NULL, NULL, NULL), MT_ERR_INVALID_ARG);

    /* Many threads asked for: still the same answer. */
    mt_build_options many = {.strict = false, .threads = 1000};
    m = NULL;
    CHECK_OK(mt_mesh_build(&tet, &many, &m, NULL));
    if (m) {
        CHECK_OK(mt_mesh_validate(m, NULL));
        CHECK_EQ(mt_mesh_report(m)->genus, 0);
        CHECK_EQ(mt_mesh_report(m)->num_edges, 6);
    }
    mt_mesh_destroy(m);

    /* Non-finite positions: counted, listed, refused in strict mode. */
    double odd[3 * 4] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    odd[3 * 1 + 2] = NAN;
    odd[3 * 2 + 0] = INFINITY;
    odd[3 * 2 + 1] = NAN;
    odd[3 * 3 + 1] = -INFINITY;
    mt_face_list nonfinite = {4, 4, 12, odd, sizes, indices};
    expect_matches_reference("non-finite positions", &nonfinite);
    m = NULL;
    CHECK_OK(mt_mesh_build(&nonfinite, NULL, &m, NULL));
    if (m) {
        const mt_report *r = mt_mesh_report(m);
        CHECK_EQ(r->nonfinite_vertices, 3);
        CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_NONFINITE_COORD), 3);
        CHECK_EQ(r->closed, 1);
        CHECK_EQ(r->genus, 0);
        const double *p1 = mt_mesh_position(m, 1);
        CHECK(p1 && isnan(p1[2]));
    }
    mt_mesh_destroy(m);

    /* Index values at and past 2^31, MT_NONE among them. */
    static uint32_t wild_sizes[3] = {3, 3, 4};
    static uint32_t wild[10] = {0, 1, 0x80000000u, 0xffffffffu, 1, 2, 0, 1, 2, 0x7fffffffu};
    mt_face_list wild_list = {3, 3, 10, NULL, wild_sizes, wild};
    expect_matches_reference("indices past 2^31", &wild_list);
}

static const mt_test_case cases[] = {
    {"oracle_matches_corpus", test_oracle_matches_corpus},
    {"oracle_hand_cases", test_oracle_hand_cases},
    {"build_matches_oracle_on_corpus", test_build_matches_oracle_on_corpus},
    {"prop_random_soups", test_random_soups},
    {"prop_closed_subsets", test_closed_subsets},
    {"prop_index_noise", test_index_noise},
    {"prop_face_flips", test_face_flips},
    {"prop_duplicates_fins_pinches", test_duplicates_fins_pinches},
    {"prop_large_inputs", test_large_inputs},
    {"prop_permuted", test_permuted},
    {"prop_strict_mode", test_strict_mode},
    {"prop_degenerate_inputs", test_degenerate_inputs},
};
const mt_test_table mt_tests_test_property = {cases, sizeof cases / sizeof cases[0]};
