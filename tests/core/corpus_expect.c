/* Comparing a topology report with a corpus reference file
 * (NAME.expected.json, tests/corpus/DEFINITIONS.md), shared by test_core's
 * corpus tests and daemon.corpus.* (tests/daemon/lcm): reading the file,
 * checking its keys against corpus_keys.h, and every report-level key
 * against an mt_report. Failures name the mesh and the key path. */
#include "corpus_expect.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "corpus_keys.h"
#include "harness.h"
#include "meshtopo/core.h"

/* ---- small helpers ---------------------------------------------------- */

typedef struct ctx {
    const char *name; /* corpus mesh name, for messages */
    const mt_report *report;
} ctx;

void mt_test_corpus_fail(const char *name, const char *key, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    mt_test_fail(__FILE__, __LINE__, "%s: %s: %s", name, key, msg);
}

/* Records a failure naming the mesh and the key path. */
#define fail_key(c, ...) mt_test_corpus_fail((c)->name, __VA_ARGS__)

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

bool mt_test_json_int(const cJSON *item, long long *out)
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
    if (!mt_test_json_int(item, &want))
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
    } else if (!mt_test_json_int(item, &want)) {
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
        if (!mt_test_json_int(e, &v) || v < 0 || v > UINT32_MAX) {
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

int mt_test_compare_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* Sorts and removes repeats; drops `skip` (MT_NONE for none). Returns the count. */
size_t mt_test_sort_unique(uint32_t *ids, size_t count, uint32_t skip)
{
    qsort(ids, count, sizeof *ids, mt_test_compare_u32);
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
        if (*end != '\0' || !mt_test_json_int(e, &want)) {
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
    size_t distinct = mt_test_sort_unique(ids, n, MT_NONE);
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
    }
}

/* ---- the defect list against the expected counts ----------------------- */

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

/* ---- the entry points ---------------------------------------------------- */

void mt_test_expect_ids(const char *name, const char *key, const cJSON *item, const uint32_t *ids,
                        size_t count)
{
    ctx c = {name, NULL};
    expect_ids(&c, key, item, ids, count);
}

void mt_test_corpus_check_report(const char *name, const mt_report *r, const cJSON *e)
{
    const ctx c_ = {name, r}, *c = &c_;
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
    check_defect_list(c, e);
}

cJSON *mt_test_corpus_load(const char *name, char *mesh_path, size_t mesh_path_size)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.expected.json", mt_test_corpus_dir(), name);
    char *text = read_text_file(path);
    if (!text) {
        mt_test_fail(__FILE__, __LINE__, "%s: cannot read %s", name, path);
        return NULL;
    }
    cJSON *expected = cJSON_Parse(text);
    free(text);
    if (!expected) {
        mt_test_fail(__FILE__, __LINE__, "%s: %s is not valid JSON", name, path);
        return NULL;
    }
    for (const cJSON *e = expected->child; e; e = e->next) {
        bool known = false;
        for (size_t i = 0; i < mt_test_num_corpus_keys; i++)
            known |= strcmp(e->string, mt_test_corpus_keys[i]) == 0;
        if (!known) mt_test_corpus_fail(name, e->string, "key not checked by this test");
    }
    for (size_t i = 0; i < mt_test_num_corpus_keys; i++)
        if (!cJSON_HasObjectItem(expected, mt_test_corpus_keys[i]))
            mt_test_corpus_fail(name, mt_test_corpus_keys[i], "missing from the expected file");

    /* "file" names the mesh: NAME.off or NAME.off.gz. */
    const cJSON *file = cJSON_GetObjectItemCaseSensitive(expected, "file");
    size_t name_len = strlen(name);
    if (!cJSON_IsString(file) || strncmp(file->valuestring, name, name_len) != 0 ||
        file->valuestring[name_len] != '.') {
        mt_test_corpus_fail(name, "file", "does not name NAME.<extension>");
        cJSON_Delete(expected);
        return NULL;
    }
    snprintf(mesh_path, mesh_path_size, "%s/%s", mt_test_corpus_dir(), file->valuestring);
    return expected;
}
