/* Corpus conformance through the library itself (no CLI, no JSON writer):
 * each corpus mesh is read with mt_read_file, built, validated, and every
 * key of its NAME.expected.json (shared/corpus/DEFINITIONS.md) is compared
 * with the report struct and with the query functions. One named test per
 * corpus mesh, plus one that fails when the corpus holds a mesh without a
 * row here, so new corpus files are never skipped silently. */
#include <cJSON.h>
#include <ctype.h>
#include <dirent.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "corpus_keys.h"
#include "harness.h"
#include "meshtopo/core.h"
#include "meshtopo/io.h"

extern const mt_test_table mt_tests_corpus;

/* ---- small helpers ---------------------------------------------------- */

typedef struct ctx {
    const char *name; /* corpus mesh name, for messages */
    const mt_mesh *mesh;
    const mt_report *report;
} ctx;

/* Records a failure naming the mesh and the key path. */
static void fail_key(const ctx *c, const char *key, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    mt_test_fail(__FILE__, __LINE__, "%s: %s: %s", c->name, key, msg);
}

static char *read_text_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 4096, len = 0;
    char *buf = malloc(cap);
    while (buf) {
        size_t got = fread(buf + len, 1, cap - len - 1, f);
        len += got;
        if (got == 0) break;
        if (len + 1 == cap) {
            char *bigger = realloc(buf, cap * 2);
            if (!bigger) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = bigger;
            cap *= 2;
        }
    }
    fclose(f);
    if (buf) buf[len] = '\0';
    return buf;
}

static bool json_int(const cJSON *item, long long *out)
{
    if (!cJSON_IsNumber(item)) return false;
    double d = item->valuedouble;
    long long v = (long long)d;
    if ((double)v != d) return false;
    *out = v;
    return true;
}

static void expect_int(const ctx *c, const char *key, const cJSON *item, long long actual)
{
    long long want;
    if (!json_int(item, &want))
        fail_key(c, key, "expected file has no integer here");
    else if (want != actual)
        fail_key(c, key, "expected %lld, got %lld", want, actual);
}

static void expect_bool(const ctx *c, const char *key, const cJSON *item, bool actual)
{
    if (!cJSON_IsBool(item))
        fail_key(c, key, "expected file has no boolean here");
    else if ((bool)cJSON_IsTrue(item) != actual)
        fail_key(c, key, "expected %s, got %s", cJSON_IsTrue(item) ? "true" : "false",
                 actual ? "true" : "false");
}

/* A genus: null in the file is -1 in the report. */
static void expect_genus(const ctx *c, const char *key, const cJSON *item, int32_t actual)
{
    long long want;
    if (cJSON_IsNull(item)) {
        if (actual != -1) fail_key(c, key, "expected null, got %d", (int)actual);
    } else if (!json_int(item, &want)) {
        fail_key(c, key, "expected file has neither an integer nor null here");
    } else if (want != actual) {
        fail_key(c, key, "expected %lld, got %d%s", want, (int)actual,
                 actual == -1 ? " (undefined)" : "");
    }
}

static void format_ids(char *buf, size_t size, const uint32_t *ids, size_t count)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < count && used + 16 < size; i++)
        used += (size_t)snprintf(buf + used, size - used, "%s%u", i ? "," : "", ids[i]);
    if (used + 16 >= size && count) snprintf(buf + used, size - used, ",...");
}

/* An array of ids in the file against ids computed here, in order. */
static void expect_ids(const ctx *c, const char *key, const cJSON *item, const uint32_t *ids,
                       size_t count)
{
    if (!cJSON_IsArray(item)) {
        fail_key(c, key, "expected file has no array here");
        return;
    }
    size_t n = (size_t)cJSON_GetArraySize(item);
    uint32_t *want = calloc(n + 1, sizeof *want);
    if (!want) {
        fail_key(c, key, "out of memory");
        return;
    }
    bool same = n == count;
    size_t i = 0;
    for (const cJSON *e = item->child; e; e = e->next, i++) {
        long long v;
        if (!json_int(e, &v) || v < 0 || v > UINT32_MAX) {
            fail_key(c, key, "expected file has a non-id entry at [%zu]", i);
            free(want);
            return;
        }
        want[i] = (uint32_t)v;
        if (i < count && want[i] != ids[i]) same = false;
    }
    if (!same) {
        char a[400], b[400];
        format_ids(a, sizeof a, want, n);
        format_ids(b, sizeof b, ids, count);
        fail_key(c, key, "expected [%s] (%zu), got [%s] (%zu)", a, n, b, count);
    }
    free(want);
}

static int compare_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* Sorts and removes repeats; drops `skip` (MT_NONE for none). Returns the count. */
static size_t sort_unique(uint32_t *ids, size_t count, uint32_t skip)
{
    qsort(ids, count, sizeof *ids, compare_u32);
    size_t out = 0;
    for (size_t i = 0; i < count; i++)
        if (ids[i] != skip && (out == 0 || ids[i] != ids[out - 1])) ids[out++] = ids[i];
    return out;
}

/* ---- report fields ------------------------------------------------------ */

static void expect_histogram(const ctx *c, const char *key, const cJSON *item,
                             const mt_histogram_bin *bins, size_t num_bins)
{
    if (!cJSON_IsObject(item)) {
        fail_key(c, key, "expected file has no object here");
        return;
    }
    size_t n = (size_t)cJSON_GetArraySize(item);
    if (n != num_bins) fail_key(c, key, "expected %zu bins, got %zu", n, num_bins);
    for (const cJSON *e = item->child; e; e = e->next) {
        char *end = NULL;
        unsigned long k = strtoul(e->string, &end, 10);
        long long want;
        if (*end != '\0' || !json_int(e, &want)) {
            fail_key(c, key, "expected file has a bad bin '%s'", e->string);
            continue;
        }
        const mt_histogram_bin *bin = NULL;
        for (size_t i = 0; i < num_bins; i++)
            if (bins[i].key == k) bin = &bins[i];
        if (!bin)
            fail_key(c, key, "bin %lu: expected %lld, missing", k, want);
        else if ((long long)bin->count != want)
            fail_key(c, key, "bin %lu: expected %lld, got %llu", k, want,
                     (unsigned long long)bin->count);
    }
    for (size_t i = 1; i < num_bins; i++)
        if (bins[i - 1].key >= bins[i].key) fail_key(c, key, "report bins not ascending");
}

static void expect_boundary_loops(const ctx *c, const cJSON *item)
{
    const mt_report *r = c->report;
    expect_int(c, "boundary_loops.count", cJSON_GetObjectItemCaseSensitive(item, "count"),
               r->boundary_loops);
    expect_ids(c, "boundary_loops.lengths", cJSON_GetObjectItemCaseSensitive(item, "lengths"),
               r->boundary_loop_lengths, r->boundary_loops);
    expect_bool(c, "boundary_loops.ambiguous", cJSON_GetObjectItemCaseSensitive(item, "ambiguous"),
                r->boundary_loops_ambiguous);
    if (cJSON_GetArraySize(item) != 3) fail_key(c, "boundary_loops", "unchecked keys");
}

/* The first 20 non-manifold vertices, from the report's defect list. */
static void expect_nonmanifold_head(const ctx *c, const cJSON *item)
{
    const mt_report *r = c->report;
    uint32_t *ids = calloc(r->num_defects + 1, sizeof *ids);
    if (!ids) return;
    size_t n = 0;
    for (size_t i = 0; i < r->num_defects; i++)
        if (r->defects[i].kind == MT_DEFECT_NONMANIFOLD_VERTEX) ids[n++] = r->defects[i].a;
    size_t distinct = sort_unique(ids, n, MT_NONE);
    if (distinct != n) fail_key(c, "defects", "a non-manifold vertex is listed twice");
    expect_ids(c, "nonmanifold_vertices_list_head", item, ids, distinct < 20 ? distinct : 20);
    free(ids);
}

static int compare_genus(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    if (x < 0 || y < 0) return (x < 0) - (y < 0); /* undefined last */
    return (x > y) - (x < y);
}

static void expect_component_genera(const ctx *c, const cJSON *item)
{
    const mt_report *r = c->report;
    if (!cJSON_IsArray(item)) {
        fail_key(c, "component_genera", "expected file has no array here");
        return;
    }
    int32_t *g = calloc((size_t)r->connected_components + 1, sizeof *g);
    if (!g) return;
    for (uint32_t i = 0; i < r->connected_components; i++) g[i] = r->components[i].genus;
    qsort(g, r->connected_components, sizeof *g, compare_genus);
    if ((size_t)cJSON_GetArraySize(item) != r->connected_components)
        fail_key(c, "component_genera", "expected %d entries, got %u", cJSON_GetArraySize(item),
                 r->connected_components);
    uint32_t i = 0;
    for (const cJSON *e = item->child; e && i < r->connected_components; e = e->next, i++) {
        char key[64];
        snprintf(key, sizeof key, "component_genera[%u]", i);
        expect_genus(c, key, e, g[i]);
    }
    free(g);
}

/* "components[i].name" in buf. */
static const char *component_key(char *buf, size_t size, uint32_t i, const char *name)
{
    snprintf(buf, size, "components[%u].%s", i, name);
    return buf;
}

static void expect_components(const ctx *c, const cJSON *item)
{
    const mt_report *r = c->report;
    if (!cJSON_IsArray(item)) {
        fail_key(c, "components", "expected file has no array here");
        return;
    }
    if ((size_t)cJSON_GetArraySize(item) != r->connected_components) {
        fail_key(c, "components", "expected %d components, got %u", cJSON_GetArraySize(item),
                 r->connected_components);
        return;
    }
    uint32_t i = 0;
    for (const cJSON *e = item->child; e; e = e->next, i++) {
        const mt_component_info *ci = &r->components[i];
        char key[96];
        expect_int(c, component_key(key, sizeof key, i, "faces"),
                   cJSON_GetObjectItemCaseSensitive(e, "faces"), ci->faces);
        expect_int(c, component_key(key, sizeof key, i, "vertices"),
                   cJSON_GetObjectItemCaseSensitive(e, "vertices"), ci->vertices);
        expect_int(c, component_key(key, sizeof key, i, "edges"),
                   cJSON_GetObjectItemCaseSensitive(e, "edges"), (long long)ci->edges);
        expect_int(c, component_key(key, sizeof key, i, "euler_characteristic"),
                   cJSON_GetObjectItemCaseSensitive(e, "euler_characteristic"),
                   ci->euler_characteristic);
        expect_int(c, component_key(key, sizeof key, i, "boundary_edges"),
                   cJSON_GetObjectItemCaseSensitive(e, "boundary_edges"),
                   (long long)ci->boundary_edges);
        expect_int(c, component_key(key, sizeof key, i, "boundary_loops"),
                   cJSON_GetObjectItemCaseSensitive(e, "boundary_loops"), ci->boundary_loops);
        expect_bool(c, component_key(key, sizeof key, i, "closed"),
                    cJSON_GetObjectItemCaseSensitive(e, "closed"), ci->closed);
        expect_bool(c, component_key(key, sizeof key, i, "manifold"),
                    cJSON_GetObjectItemCaseSensitive(e, "manifold"), ci->manifold);
        expect_bool(c, component_key(key, sizeof key, i, "orientable"),
                    cJSON_GetObjectItemCaseSensitive(e, "orientable"), ci->orientable);
        expect_genus(c, component_key(key, sizeof key, i, "genus"),
                     cJSON_GetObjectItemCaseSensitive(e, "genus"), ci->genus);
        expect_genus(c, component_key(key, sizeof key, i, "genus_with_boundary"),
                     cJSON_GetObjectItemCaseSensitive(e, "genus_with_boundary"),
                     ci->genus_with_boundary);
        expect_int(c, component_key(key, sizeof key, i, "min_face_index"),
                   cJSON_GetObjectItemCaseSensitive(e, "min_face_index"), ci->min_face);
        if (cJSON_GetArraySize(e) != 12) fail_key(c, "components", "unchecked keys");

        /* The component query agrees with the numbering. */
        uint32_t comp = MT_NONE;
        CHECK_OK(mt_face_component(c->mesh, ci->min_face, &comp));
        if (comp != i)
            fail_key(c, "components", "mt_face_component(%u) = %u, expected %u", ci->min_face, comp,
                     i);
    }
}

/* ---- queries ----------------------------------------------------------- */

static void check_vertex_query(const ctx *c, size_t index, const cJSON *q)
{
    char key[96];
    long long v;
    if (!json_int(cJSON_GetObjectItemCaseSensitive(q, "vertex"), &v) || v < 0 ||
        v >= c->report->num_verts) {
        fail_key(c, "vertex_queries", "entry %zu has no valid vertex", index);
        return;
    }
    if (cJSON_GetArraySize(q) != 3) fail_key(c, "vertex_queries", "unchecked keys");

    /* Learn the sizes with empty buffers, then fill. */
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    mt_status st = mt_vert_ring(c->mesh, (uint32_t)v, &ring);
    CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
    ring.neighbors = calloc(ring.num_neighbors + 1, sizeof *ring.neighbors);
    ring.faces = calloc(ring.num_faces + 1, sizeof *ring.faces);
    ring.fans = calloc(ring.num_fans + 1, sizeof *ring.fans);
    ring.neighbors_capacity = ring.num_neighbors;
    ring.faces_capacity = ring.num_faces;
    ring.fans_capacity = ring.num_fans;
    CHECK(ring.neighbors && ring.faces && ring.fans);
    if (ring.neighbors && ring.faces && ring.fans) {
        CHECK_OK(mt_vert_ring(c->mesh, (uint32_t)v, &ring));
        /* The fans partition the buffers; an open fan has one more neighbour than faces. */
        size_t nsum = 0, fsum = 0;
        for (size_t k = 0; k < ring.num_fans; k++) {
            const mt_fan *fan = &ring.fans[k];
            CHECK_EQ(fan->neighbor_begin, nsum);
            CHECK_EQ(fan->face_begin, fsum);
            CHECK_EQ(fan->neighbor_count, fan->face_count + (fan->boundary ? 1 : 0));
            nsum += fan->neighbor_count;
            fsum += fan->face_count;
        }
        CHECK_EQ(nsum, ring.num_neighbors);
        CHECK_EQ(fsum, ring.num_faces);

        size_t nn = sort_unique(ring.neighbors, ring.num_neighbors, MT_NONE);
        size_t nf = sort_unique(ring.faces, ring.num_faces, MT_NONE);
        snprintf(key, sizeof key, "vertex_queries[%zu] (vertex %lld).neighbors", index, v);
        expect_ids(c, key, cJSON_GetObjectItemCaseSensitive(q, "neighbors"), ring.neighbors, nn);
        snprintf(key, sizeof key, "vertex_queries[%zu] (vertex %lld).faces", index, v);
        expect_ids(c, key, cJSON_GetObjectItemCaseSensitive(q, "faces"), ring.faces, nf);

        uint32_t valence = MT_NONE;
        CHECK_OK(mt_vert_valence(c->mesh, (uint32_t)v, &valence));
        snprintf(key, sizeof key, "vertex_queries[%zu] (vertex %lld) valence", index, v);
        if (valence != nn)
            fail_key(c, key, "mt_vert_valence(%lld) = %u, distinct ring neighbours %zu", v, valence,
                     nn);
    }
    free(ring.neighbors);
    free(ring.faces);
    free(ring.fans);
}

/* Adjacent faces of f through mt_face_neighbors, sorted, distinct, without
 * f; *out (malloc'ed) and the count. */
static size_t face_adjacent_by_neighbors(const ctx *c, uint32_t f, uint32_t **out)
{
    size_t num_faces = 0, num_edges = 0;
    mt_status st = mt_face_neighbors(c->mesh, f, NULL, 0, NULL, 0, &num_faces, &num_edges);
    CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
    uint32_t *faces = calloc(num_faces + 1, sizeof *faces);
    uint32_t *offsets = calloc(num_edges + 1, sizeof *offsets);
    *out = faces;
    if (!faces || !offsets) {
        free(offsets);
        return 0;
    }
    CHECK_OK(mt_face_neighbors(c->mesh, f, faces, num_faces, offsets, num_edges + 1, &num_faces,
                               &num_edges));
    CHECK_EQ(offsets[0], 0);
    CHECK_EQ(offsets[num_edges], num_faces);
    free(offsets);
    return sort_unique(faces, num_faces, f);
}

/* The same through mt_face_verts and mt_edge_faces on each side. */
static size_t face_adjacent_by_edges(const ctx *c, uint32_t f, uint32_t **out)
{
    *out = NULL;
    size_t n = 0;
    mt_status st = mt_face_verts(c->mesh, f, NULL, 0, &n);
    CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
    uint32_t *verts = calloc(n + 1, sizeof *verts);
    if (!verts) return 0;
    CHECK_OK(mt_face_verts(c->mesh, f, verts, n, &n));
    size_t cap = 16, count = 0;
    uint32_t *all = malloc(cap * sizeof *all);
    for (size_t i = 0; all && i < n; i++) {
        size_t k = 0;
        st = mt_edge_faces(c->mesh, verts[i], verts[(i + 1) % n], NULL, 0, &k);
        CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
        CHECK(k >= 1); /* f itself has this side */
        if (count + k > cap) {
            while (count + k > cap) cap *= 2;
            uint32_t *bigger = realloc(all, cap * sizeof *all);
            if (!bigger) {
                free(all);
                all = NULL;
                break;
            }
            all = bigger;
        }
        size_t got = 0;
        CHECK_OK(mt_edge_faces(c->mesh, verts[i], verts[(i + 1) % n], all + count, k, &got));
        CHECK_EQ(got, k);
        bool has_f = false;
        for (size_t j = 0; j < got && j < k; j++) {
            has_f |= all[count + j] == f;
            if (j > 0) CHECK(all[count + j - 1] < all[count + j]); /* ascending */
        }
        CHECK(has_f);
        count += got < k ? got : k;
    }
    free(verts);
    *out = all;
    return all ? sort_unique(all, count, f) : 0;
}

static void check_face_query(const ctx *c, size_t index, const cJSON *q)
{
    char key[96];
    long long f;
    if (!json_int(cJSON_GetObjectItemCaseSensitive(q, "face"), &f) || f < 0 ||
        f >= c->report->num_faces) {
        fail_key(c, "face_queries", "entry %zu has no valid face", index);
        return;
    }
    if (cJSON_GetArraySize(q) != 2) fail_key(c, "face_queries", "unchecked keys");
    const cJSON *want = cJSON_GetObjectItemCaseSensitive(q, "adjacent_faces");

    uint32_t *adj = NULL;
    size_t n = face_adjacent_by_neighbors(c, (uint32_t)f, &adj);
    snprintf(key, sizeof key, "face_queries[%zu] (face %lld).adjacent_faces", index, f);
    expect_ids(c, key, want, adj, n);
    free(adj);

    n = face_adjacent_by_edges(c, (uint32_t)f, &adj);
    snprintf(key, sizeof key, "face_queries[%zu] (face %lld).adjacent_faces via mt_edge_faces",
             index, f);
    expect_ids(c, key, want, adj, n);
    free(adj);
}

/* ---- defect list and boundary rings against the expected counts -------- */

static int compare_pair(const void *a, const void *b)
{
    const uint32_t *x = a, *y = b;
    if (x[0] != y[0]) return (x[0] > y[0]) - (x[0] < y[0]);
    return (x[1] > y[1]) - (x[1] < y[1]);
}

static void check_defect_list(const ctx *c, const cJSON *e)
{
    const mt_report *r = c->report;
    struct {
        const char *key;
        mt_defect_kind kind;
    } counted[] = {
        {"nonmanifold_vertices", MT_DEFECT_NONMANIFOLD_VERTEX},
        {"isolated_vertices", MT_DEFECT_ISOLATED_VERTEX},
        {"degenerate_faces", MT_DEFECT_DEGENERATE_FACE},
        {"faces_with_out_of_range_indices", MT_DEFECT_OUT_OF_RANGE_INDEX},
        {"nonmanifold_edges", MT_DEFECT_NONMANIFOLD_EDGE},
    };
    for (size_t i = 0; i < sizeof counted / sizeof counted[0]; i++) {
        char key[96];
        snprintf(key, sizeof key, "%s (entries of %s in the defect list)", counted[i].key,
                 mt_defect_key(counted[i].kind));
        expect_int(c, key, cJSON_GetObjectItemCaseSensitive(e, counted[i].key),
                   (long long)mt_report_count_defects(r, counted[i].kind));
    }

    size_t bowties = 0, same = 0;
    uint32_t *pairs = calloc(2 * r->num_defects + 2, sizeof *pairs);
    if (!pairs) return;
    for (size_t i = 0; i < r->num_defects; i++) {
        const mt_defect *d = &r->defects[i];
        if (i > 0) CHECK(r->defects[i - 1].kind <= d->kind); /* grouped by kind */
        if (d->kind == MT_DEFECT_NONMANIFOLD_VERTEX && d->b > 1) bowties++;
        if (d->kind == MT_DEFECT_SAME_DIRECTION_EDGE) {
            pairs[2 * same] = d->a < d->b ? d->a : d->b;
            pairs[2 * same + 1] = d->a < d->b ? d->b : d->a;
            same++;
        }
    }
    expect_int(c, "bowtie_vertices (non-manifold vertex entries with several fans)",
               cJSON_GetObjectItemCaseSensitive(e, "bowtie_vertices"), (long long)bowties);
    qsort(pairs, same, 2 * sizeof *pairs, compare_pair);
    size_t distinct = 0;
    for (size_t i = 0; i < same; i++)
        if (i == 0 || compare_pair(&pairs[2 * i], &pairs[2 * (i - 1)]) != 0) distinct++;
    expect_int(c, "duplicate_directed_edges (distinct edges of same_direction_edge entries)",
               cJSON_GetObjectItemCaseSensitive(e, "duplicate_directed_edges"),
               (long long)distinct);
    free(pairs);
}

/* Half-edge boundary rings match the boundary-edge graph's loops when no
 * edge is non-manifold or doubly directed and no loop is pinched. */
static void check_boundary_rings(const ctx *c)
{
    const mt_report *r = c->report;
    size_t num_verts = 0, num_loops = 0;
    mt_status st = mt_boundary_loops(c->mesh, NULL, 0, NULL, 0, &num_verts, &num_loops);
    CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
    uint32_t *verts = calloc(num_verts + 1, sizeof *verts);
    uint32_t *offsets = calloc(num_loops + 1, sizeof *offsets);
    if (verts && offsets) {
        CHECK_OK(mt_boundary_loops(c->mesh, verts, num_verts, offsets, num_loops + 1, &num_verts,
                                   &num_loops));
        if (!r->boundary_loops_ambiguous && r->nonmanifold_edges == 0 &&
            r->duplicate_directed_edges == 0) {
            uint32_t *lengths = calloc(num_loops + 1, sizeof *lengths);
            if (lengths) {
                for (size_t i = 0; i < num_loops; i++) lengths[i] = offsets[i + 1] - offsets[i];
                qsort(lengths, num_loops, sizeof *lengths, compare_u32);
                if (num_loops != r->boundary_loops)
                    fail_key(c, "mt_boundary_loops", "%zu rings, report has %u loops", num_loops,
                             r->boundary_loops);
                for (size_t i = 0; i < num_loops && i < r->boundary_loops; i++)
                    if (lengths[i] != r->boundary_loop_lengths[i])
                        fail_key(c, "mt_boundary_loops",
                                 "ring %zu (by length) has %u vertices, "
                                 "report loop has %u edges",
                                 i, lengths[i], r->boundary_loop_lengths[i]);
                free(lengths);
            }
        }
    }
    free(verts);
    free(offsets);
}

/* ---- the shared checker ------------------------------------------------ */

static void check_report(const ctx *c, const cJSON *e)
{
    const mt_report *r = c->report;
    const struct {
        const char *key;
        long long value;
    } ints[] = {
        {"V", r->num_verts},
        {"F", r->num_faces},
        {"F_valid", r->num_faces_valid},
        {"E", (long long)r->num_edges},
        {"half_edges", (long long)r->num_half_edges},
        {"boundary_edges", (long long)r->boundary_edges},
        {"nonmanifold_edges", (long long)r->nonmanifold_edges},
        {"inconsistent_orientation_edges", (long long)r->inconsistent_orientation_edges},
        {"duplicate_directed_edges", (long long)r->duplicate_directed_edges},
        {"nonmanifold_vertices", r->nonmanifold_vertices},
        {"bowtie_vertices", r->bowtie_vertices},
        {"isolated_vertices", r->isolated_vertices},
        {"unreferenced_vertices", r->unreferenced_vertices},
        {"degenerate_faces", r->degenerate_faces},
        {"out_of_range_indices", (long long)r->out_of_range_indices},
        {"faces_with_out_of_range_indices", r->faces_with_out_of_range_indices},
        {"connected_components", r->connected_components},
        {"vertex_connected_components", r->vertex_connected_components},
        {"euler_characteristic", r->euler_characteristic},
    };
    for (size_t i = 0; i < sizeof ints / sizeof ints[0]; i++)
        expect_int(c, ints[i].key, cJSON_GetObjectItemCaseSensitive(e, ints[i].key), ints[i].value);
    const struct {
        const char *key;
        bool value;
    } bools[] = {
        {"closed", r->closed},
        {"manifold", r->manifold},
        {"orientable", r->orientable},
        {"consistently_oriented", r->consistently_oriented},
    };
    for (size_t i = 0; i < sizeof bools / sizeof bools[0]; i++)
        expect_bool(c, bools[i].key, cJSON_GetObjectItemCaseSensitive(e, bools[i].key),
                    bools[i].value);

    expect_histogram(c, "face_size_histogram",
                     cJSON_GetObjectItemCaseSensitive(e, "face_size_histogram"),
                     r->face_size_histogram, r->num_face_size_bins);
    expect_histogram(c, "edge_use_histogram",
                     cJSON_GetObjectItemCaseSensitive(e, "edge_use_histogram"),
                     r->edge_use_histogram, r->num_edge_use_bins);
    expect_boundary_loops(c, cJSON_GetObjectItemCaseSensitive(e, "boundary_loops"));
    expect_nonmanifold_head(c,
                            cJSON_GetObjectItemCaseSensitive(e, "nonmanifold_vertices_list_head"));
    expect_genus(c, "genus", cJSON_GetObjectItemCaseSensitive(e, "genus"), r->genus);
    expect_component_genera(c, cJSON_GetObjectItemCaseSensitive(e, "component_genera"));
    expect_components(c, cJSON_GetObjectItemCaseSensitive(e, "components"));

    const cJSON *q;
    size_t i = 0;
    cJSON_ArrayForEach(q, cJSON_GetObjectItemCaseSensitive(e, "vertex_queries"))
        check_vertex_query(c, i++, q);
    i = 0;
    cJSON_ArrayForEach(q, cJSON_GetObjectItemCaseSensitive(e, "face_queries"))
        check_face_query(c, i++, q);

    check_defect_list(c, e);
    check_boundary_rings(c);
}

static void check_corpus(const char *name)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.expected.json", mt_test_corpus_dir(), name);
    char *text = read_text_file(path);
    if (!text) {
        mt_test_fail(__FILE__, __LINE__, "%s: cannot read %s", name, path);
        return;
    }
    cJSON *expected = cJSON_Parse(text);
    free(text);
    if (!expected) {
        mt_test_fail(__FILE__, __LINE__, "%s: %s is not valid JSON", name, path);
        return;
    }
    ctx c = {name, NULL, NULL};
    for (const cJSON *e = expected->child; e; e = e->next) {
        bool known = false;
        for (size_t i = 0; i < mt_test_num_corpus_keys; i++)
            known |= strcmp(e->string, mt_test_corpus_keys[i]) == 0;
        if (!known) fail_key(&c, e->string, "key not checked by this test");
    }
    for (size_t i = 0; i < mt_test_num_corpus_keys; i++)
        if (!cJSON_HasObjectItem(expected, mt_test_corpus_keys[i]))
            fail_key(&c, mt_test_corpus_keys[i], "missing from the expected file");

    /* "file" names the mesh: NAME.off or NAME.off.gz. */
    const cJSON *file = cJSON_GetObjectItemCaseSensitive(expected, "file");
    size_t name_len = strlen(name);
    if (!cJSON_IsString(file) || strncmp(file->valuestring, name, name_len) != 0 ||
        file->valuestring[name_len] != '.') {
        fail_key(&c, "file", "does not name NAME.<extension>");
        cJSON_Delete(expected);
        return;
    }
    snprintf(path, sizeof path, "%s/%s", mt_test_corpus_dir(), file->valuestring);

    mt_face_list list;
    mt_diag diag;
    memset(&list, 0, sizeof list);
    mt_diag_clear(&diag);
    mt_status st = mt_read_file(path, MT_FORMAT_AUTO, &list, &diag);
    if (st != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: mt_read_file: %s (%s)", name, mt_strerror(st),
                     diag.message);
        cJSON_Delete(expected);
        return;
    }
    mt_mesh *mesh = NULL;
    mt_diag_clear(&diag);
    st = mt_mesh_build(&list, NULL, &mesh, &diag);
    if (st != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: mt_mesh_build: %s (%s)", name, mt_strerror(st),
                     diag.message);
    } else {
        mt_diag_clear(&diag);
        st = mt_mesh_validate(mesh, &diag);
        if (st != MT_OK)
            mt_test_fail(__FILE__, __LINE__, "%s: mt_mesh_validate: %s (%s)", name, mt_strerror(st),
                         diag.message);
        CHECK_EQ(mt_mesh_num_verts(mesh), list.num_verts);
        CHECK_EQ(mt_mesh_num_faces(mesh), list.num_faces);
        c.mesh = mesh;
        c.report = mt_mesh_report(mesh);
        CHECK(c.report != NULL);
        if (c.report) check_report(&c, expected);
    }
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    cJSON_Delete(expected);
}

/* ---- one test per corpus mesh ------------------------------------------ */

static void test_corpus_assimp_malformed(void)
{
    check_corpus("assimp_malformed");
}
static void test_corpus_cgal_blobby_3cc(void)
{
    check_corpus("cgal_blobby_3cc");
}
static void test_corpus_cgal_eight(void)
{
    check_corpus("cgal_eight");
}
static void test_corpus_cgal_elephant_with_holes(void)
{
    check_corpus("cgal_elephant_with_holes");
}
static void test_corpus_cgal_many_umbrellas(void)
{
    check_corpus("cgal_many_umbrellas");
}
static void test_corpus_cgal_prim(void)
{
    check_corpus("cgal_prim");
}
static void test_corpus_cgal_tetrahedron(void)
{
    check_corpus("cgal_tetrahedron");
}
static void test_corpus_cgal_torus_quad(void)
{
    check_corpus("cgal_torus_quad");
}
static void test_corpus_igl_camelhead(void)
{
    check_corpus("igl_camelhead");
}
static void test_corpus_igl_fertility(void)
{
    check_corpus("igl_fertility");
}
static void test_corpus_npm_bunny(void)
{
    check_corpus("npm_bunny");
}
static void test_corpus_npm_conway_djmed(void)
{
    check_corpus("npm_conway_djmeD");
}
static void test_corpus_npm_snowden(void)
{
    check_corpus("npm_snowden");
}
static void test_corpus_npm_teapot(void)
{
    check_corpus("npm_teapot");
}
static void test_corpus_openmesh_cube_minimal_quads(void)
{
    check_corpus("openmesh_cube_minimal_quads");
}
static void test_corpus_trimesh_joined_tetrahedra(void)
{
    check_corpus("trimesh_joined_tetrahedra");
}
static void test_corpus_trimesh_multibody_stl_soup(void)
{
    check_corpus("trimesh_multibody_stl_soup");
}
static void test_corpus_trimesh_multibody_stl_welded(void)
{
    check_corpus("trimesh_multibody_stl_welded");
}
static void test_corpus_trimesh_notenoughindices(void)
{
    check_corpus("trimesh_notenoughindices");
}
static void test_corpus_trimesh_two_objects(void)
{
    check_corpus("trimesh_two_objects");
}
static void test_corpus_vcg_moebius(void)
{
    check_corpus("vcg_moebius");
}
static void test_corpus_vcg_nonmanifold(void)
{
    check_corpus("vcg_nonmanifold");
}
static void test_corpus_vcg_quad5(void)
{
    check_corpus("vcg_quad5");
}

/* NAME of a corpus file (mesh or answers), or false for other files. */
static bool corpus_entry_name(const char *file, char *name, size_t size)
{
    static const char *const suffixes[] = {
        ".expected.json", ".off.gz", ".obj.gz", ".ply.gz", ".stl.gz",
        ".off",           ".obj",    ".ply",    ".stl",
    };
    size_t len = strlen(file);
    for (size_t i = 0; i < sizeof suffixes / sizeof suffixes[0]; i++) {
        size_t sl = strlen(suffixes[i]);
        if (len > sl && strcmp(file + len - sl, suffixes[i]) == 0 && len - sl < size) {
            memcpy(name, file, len - sl);
            name[len - sl] = '\0';
            return true;
        }
    }
    return false;
}

/* Fails for every corpus mesh or answer file without a test row above. */
static void test_corpus_every_mesh_has_a_row(void)
{
    DIR *dir = opendir(mt_test_corpus_dir());
    CHECK(dir != NULL);
    if (!dir) return;
    size_t entries = 0;
    struct dirent *de;
    while ((de = readdir(dir)) != NULL) {
        char name[256], test_name[300];
        if (!corpus_entry_name(de->d_name, name, sizeof name)) continue;
        entries++;
        snprintf(test_name, sizeof test_name, "corpus_%s", name);
        for (char *p = test_name; *p; p++) *p = (char)tolower((unsigned char)*p);
        bool found = false;
        for (size_t i = 0; i < mt_tests_corpus.count; i++)
            found |= strcmp(mt_tests_corpus.cases[i].name, test_name) == 0;
        if (!found)
            mt_test_fail(__FILE__, __LINE__,
                         "corpus file %s has no test row: add {\"%s\", test_%s} to test_corpus.c",
                         de->d_name, test_name, test_name);
    }
    closedir(dir);
    CHECK(entries > 0);
}

static const mt_test_case cases[] = {
    {"corpus_assimp_malformed", test_corpus_assimp_malformed},
    {"corpus_cgal_blobby_3cc", test_corpus_cgal_blobby_3cc},
    {"corpus_cgal_eight", test_corpus_cgal_eight},
    {"corpus_cgal_elephant_with_holes", test_corpus_cgal_elephant_with_holes},
    {"corpus_cgal_many_umbrellas", test_corpus_cgal_many_umbrellas},
    {"corpus_cgal_prim", test_corpus_cgal_prim},
    {"corpus_cgal_tetrahedron", test_corpus_cgal_tetrahedron},
    {"corpus_cgal_torus_quad", test_corpus_cgal_torus_quad},
    {"corpus_igl_camelhead", test_corpus_igl_camelhead},
    {"corpus_igl_fertility", test_corpus_igl_fertility},
    {"corpus_npm_bunny", test_corpus_npm_bunny},
    {"corpus_npm_conway_djmed", test_corpus_npm_conway_djmed},
    {"corpus_npm_snowden", test_corpus_npm_snowden},
    {"corpus_npm_teapot", test_corpus_npm_teapot},
    {"corpus_openmesh_cube_minimal_quads", test_corpus_openmesh_cube_minimal_quads},
    {"corpus_trimesh_joined_tetrahedra", test_corpus_trimesh_joined_tetrahedra},
    {"corpus_trimesh_multibody_stl_soup", test_corpus_trimesh_multibody_stl_soup},
    {"corpus_trimesh_multibody_stl_welded", test_corpus_trimesh_multibody_stl_welded},
    {"corpus_trimesh_notenoughindices", test_corpus_trimesh_notenoughindices},
    {"corpus_trimesh_two_objects", test_corpus_trimesh_two_objects},
    {"corpus_vcg_moebius", test_corpus_vcg_moebius},
    {"corpus_vcg_nonmanifold", test_corpus_vcg_nonmanifold},
    {"corpus_vcg_quad5", test_corpus_vcg_quad5},
    {"corpus_every_mesh_has_a_row", test_corpus_every_mesh_has_a_row},
};

const mt_test_table mt_tests_corpus = {cases, sizeof cases / sizeof cases[0]};
