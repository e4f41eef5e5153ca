/* Tests of per-element attributes and hidden flags (meshtopo/attributes.h):
 * adding, reading, writing, listing and removing them and every refusal;
 * hidden flags; values kept through edits (split, flip, collapse,
 * triangulate, face split, deletions), new elements starting at zero, a
 * refused edit and an edit failing for memory leaving everything as it
 * was; compaction carrying each value to its element's new id; and the
 * seed's closed rectangle, whose queries leave its hidden faces and
 * diagonal out once asked to. */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "mesh/mesh_internal.h"
#include "meshtopo/core.h"

static mt_mesh *grid_mesh(uint32_t nx, uint32_t ny, bool triangles)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(nx, ny, triangles, &grid));
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(&grid, NULL, &mesh, NULL));
    mt_face_list_free(&grid);
    return mesh;
}

/* A value for element id of a kind that no other element of any kind has. */
static uint64_t tag(mt_element_kind kind, uint32_t id)
{
    return ((uint64_t)(kind + 1) << 40) | (id + 1u);
}

/* Adds attribute "tag" (8 bytes) to every kind and sets every element's. */
static void tag_everything(mt_mesh *mesh)
{
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT; k++) {
        const mt_element_kind kind = (mt_element_kind)k;
        CHECK_OK(mt_attribute_add(mesh, kind, "tag", 8, NULL));
        for (uint32_t i = 0; i < mt_mesh_num_elements(mesh, kind); i++) {
            const uint64_t v = tag(kind, i);
            CHECK_OK(mt_attribute_set(mesh, kind, "tag", i, &v, sizeof v, NULL));
        }
    }
}

static uint64_t tag_of(const mt_mesh *mesh, mt_element_kind kind, uint32_t id)
{
    uint64_t v = 0;
    CHECK_OK(mt_attribute_get(mesh, kind, "tag", id, &v, sizeof v, NULL));
    return v;
}

static void test_attributes_api(void)
{
    mt_mesh *mesh = grid_mesh(3, 2, true);
    mt_diag diag;
    CHECK_EQ(mt_attribute_count(mesh, MT_ELEMENT_FACE), 0);
    CHECK_OK(mt_attribute_add(mesh, MT_ELEMENT_FACE, "label", 4, &diag));
    CHECK_OK(mt_attribute_add(mesh, MT_ELEMENT_FACE, "normal.x-1", 8, &diag));
    CHECK_EQ(mt_attribute_count(mesh, MT_ELEMENT_FACE), 2);
    const char *name = NULL;
    uint32_t bytes = 0;
    CHECK_OK(mt_attribute_info(mesh, MT_ELEMENT_FACE, 1, &name, &bytes));
    CHECK(strcmp(name, "normal.x-1") == 0 && bytes == 8);
    CHECK_STATUS(mt_attribute_info(mesh, MT_ELEMENT_FACE, 2, &name, &bytes), MT_ERR_OUT_OF_RANGE);
    /* New values are zero; set and get; the whole array. */
    uint32_t label = 99;
    CHECK_OK(mt_attribute_get(mesh, MT_ELEMENT_FACE, "label", 5, &label, 4, &diag));
    CHECK_EQ(label, 0);
    label = 7;
    CHECK_OK(mt_attribute_set(mesh, MT_ELEMENT_FACE, "label", 5, &label, 4, &diag));
    uint8_t *values = NULL;
    uint32_t count = 0;
    CHECK_OK(mt_attribute_values(mesh, MT_ELEMENT_FACE, "label", &values, &bytes, &count, &diag));
    CHECK(bytes == 4 && count == mt_mesh_num_faces(mesh));
    memcpy(&label, values + 5 * 4, 4);
    CHECK_EQ(label, 7);
    /* Refusals. */
    CHECK_STATUS(mt_attribute_add(mesh, MT_ELEMENT_FACE, "label", 4, &diag), MT_ERR_INVALID_ARG);
    CHECK(strstr(diag.message, "already") != NULL);
    CHECK_STATUS(mt_attribute_add(mesh, MT_ELEMENT_FACE, "", 4, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_attribute_add(mesh, MT_ELEMENT_FACE, "a/b", 4, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_attribute_add(mesh, MT_ELEMENT_FACE, NULL, 4, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_attribute_add(mesh, MT_ELEMENT_FACE, "zero", 0, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_attribute_add(mesh, MT_ELEMENT_FACE, "huge", MT_ATTRIBUTE_VALUE_MAX + 1, &diag),
                 MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_attribute_add(mesh, (mt_element_kind)7, "x", 4, &diag), MT_ERR_INVALID_ARG);
    char long_name[MT_ATTRIBUTE_NAME_MAX + 2];
    memset(long_name, 'n', sizeof long_name - 1);
    long_name[sizeof long_name - 1] = '\0';
    CHECK_STATUS(mt_attribute_add(mesh, MT_ELEMENT_FACE, long_name, 4, &diag), MT_ERR_INVALID_ARG);
    long_name[MT_ATTRIBUTE_NAME_MAX] = '\0';
    CHECK_OK(mt_attribute_add(mesh, MT_ELEMENT_FACE, long_name, 1, &diag));
    CHECK_STATUS(mt_attribute_get(mesh, MT_ELEMENT_FACE, "label", count, &label, 4, &diag),
                 MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_attribute_get(mesh, MT_ELEMENT_FACE, "label", 0, &label, 2, &diag),
                 MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_attribute_get(mesh, MT_ELEMENT_VERTEX, "label", 0, &label, 4, &diag),
                 MT_ERR_NOT_FOUND);
    /* At most MT_ATTRIBUTES_PER_KIND per kind. */
    for (int i = 0; i < MT_ATTRIBUTES_PER_KIND; i++) {
        char n[16];
        snprintf(n, sizeof n, "v%d", i);
        CHECK_OK(mt_attribute_add(mesh, MT_ELEMENT_VERTEX, n, 2, &diag));
    }
    CHECK_STATUS(mt_attribute_add(mesh, MT_ELEMENT_VERTEX, "one_more", 2, &diag), MT_ERR_TOO_LARGE);
    /* Removal keeps the order of the rest. */
    CHECK_OK(mt_attribute_remove(mesh, MT_ELEMENT_FACE, "label", &diag));
    CHECK_STATUS(mt_attribute_remove(mesh, MT_ELEMENT_FACE, "label", &diag), MT_ERR_NOT_FOUND);
    CHECK_OK(mt_attribute_info(mesh, MT_ELEMENT_FACE, 0, &name, &bytes));
    CHECK(strcmp(name, "normal.x-1") == 0);
    CHECK_EQ(mt_attribute_count(mesh, MT_ELEMENT_FACE), 2);
    mt_mesh_destroy(mesh);
}

static void test_attributes_hidden(void)
{
    mt_mesh *mesh = grid_mesh(2, 2, true);
    mt_diag diag;
    CHECK(!mt_is_hidden(mesh, MT_ELEMENT_FACE, 0));
    CHECK_OK(mt_set_hidden(mesh, MT_ELEMENT_FACE, 3, true, &diag));
    CHECK_OK(mt_set_hidden(mesh, MT_ELEMENT_EDGE, 1, true, &diag));
    CHECK(mt_is_hidden(mesh, MT_ELEMENT_FACE, 3) && !mt_is_hidden(mesh, MT_ELEMENT_FACE, 2));
    CHECK(mt_is_hidden(mesh, MT_ELEMENT_EDGE, 1) && !mt_is_hidden(mesh, MT_ELEMENT_HALF_EDGE, 2));
    CHECK_OK(mt_set_hidden(mesh, MT_ELEMENT_FACE, 3, false, &diag));
    CHECK(!mt_is_hidden(mesh, MT_ELEMENT_FACE, 3));
    /* The flags are the attribute "hidden", listed with the others. */
    const char *name = NULL;
    CHECK_OK(mt_attribute_info(mesh, MT_ELEMENT_EDGE, 0, &name, NULL));
    CHECK(strcmp(name, MT_ATTRIBUTE_HIDDEN) == 0);
    CHECK_STATUS(mt_set_hidden(mesh, MT_ELEMENT_FACE, 1000, true, &diag), MT_ERR_OUT_OF_RANGE);
    CHECK(!mt_is_hidden(mesh, MT_ELEMENT_FACE, 1000));
    CHECK(!mt_is_hidden(NULL, MT_ELEMENT_FACE, 0));
    mt_mesh_destroy(mesh);
}

/* The endpoints (caller ids) of every edge, 2 per edge; deleted edges MT_NONE. */
static uint32_t *edge_ends(const mt_mesh *mesh)
{
    mt_mesh_view v;
    mt_mesh_get_view(mesh, &v);
    uint32_t *ends = malloc((v.num_half_edges + 1) * sizeof *ends);
    for (uint32_t h = 0; h < v.num_half_edges; h++)
        ends[h] = v.he_head[h] == MT_NONE ? MT_NONE : mt_vert_original(mesh, v.he_head[h]);
    return ends;
}

/* Every element's "tag" value, kind by kind (freed with free_values). */
typedef struct tag_values {
    uint64_t *of[MT_ELEMENT_KIND_COUNT];
    uint32_t count[MT_ELEMENT_KIND_COUNT];
} tag_values;

static void take_values(const mt_mesh *mesh, tag_values *out)
{
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT; k++) {
        const mt_element_kind kind = (mt_element_kind)k;
        out->count[k] = mt_mesh_num_elements(mesh, kind);
        out->of[k] = malloc((out->count[k] + 1) * sizeof(uint64_t));
        for (uint32_t i = 0; i < out->count[k]; i++) out->of[k][i] = tag_of(mesh, kind, i);
    }
}

static void free_values(tag_values *v)
{
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT; k++) free(v->of[k]);
}

/* After an edit: every element the mesh had before and still has with the
 * same ends keeps its value, every element added has value zero. Counts the
 * edges kept in *kept_edges. */
static void check_values_after(const mt_mesh *mesh, const tag_values *before,
                               const uint32_t *ends_before, uint32_t *kept_edges)
{
    uint32_t *ends = edge_ends(mesh);
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT; k++) {
        const mt_element_kind kind = (mt_element_kind)k;
        const uint32_t n = mt_mesh_num_elements(mesh, kind);
        for (uint32_t i = 0; i < n; i++) {
            const uint64_t v = tag_of(mesh, kind, i);
            if (i >= before->count[k]) {
                CHECK_EQ(v, 0);
                continue;
            }
            if (kind == MT_ELEMENT_EDGE || kind == MT_ELEMENT_HALF_EDGE) {
                const uint32_t h = kind == MT_ELEMENT_EDGE ? 2 * i : i;
                if (ends[h] != ends_before[h] || ends[h ^ 1u] != ends_before[h ^ 1u]) continue;
                if (kind == MT_ELEMENT_EDGE) ++*kept_edges;
            }
            CHECK_EQ(v, before->of[k][i]);
        }
    }
    free(ends);
}

static void count_elements(const mt_mesh *mesh, uint32_t out[MT_ELEMENT_KIND_COUNT])
{
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT; k++)
        out[k] = mt_mesh_num_elements(mesh, (mt_element_kind)k);
}

static void test_attributes_survive_edits(void)
{
    mt_mesh *mesh = grid_mesh(6, 6, true);
    tag_everything(mesh);
    mt_diag diag;
    /* A sequence of edits, checking after each one. */
    for (int step = 0; step < 6; step++) {
        tag_values before;
        take_values(mesh, &before);
        uint32_t kept = 0, *ends = edge_ends(mesh);
        mt_mesh_view v;
        mt_mesh_get_view(mesh, &v);
        /* An interior edge: one whose two half-edges have faces. */
        uint32_t h = 0;
        while (h < v.num_half_edges &&
               (v.he_head[h] == MT_NONE || v.he_face[h] == MT_NONE || v.he_face[h ^ 1u] == MT_NONE))
            h += 2;
        const uint32_t a = mt_vert_original(mesh, v.he_head[h ^ 1u]);
        const uint32_t b = mt_vert_original(mesh, v.he_head[h]);
        uint32_t out = 0;
        switch (step) {
            case 0:
                CHECK_OK(mt_edge_split(mesh, a, b, NULL, &out, &diag));
                break;
            case 1:
                CHECK_OK(mt_edge_flip(mesh, a, b, &diag));
                break;
            case 2: { /* the first interior edge the link condition lets collapse */
                mt_status st = MT_ERR_REFUSED;
                for (uint32_t g = h; g < v.num_half_edges && st == MT_ERR_REFUSED; g += 2)
                    if (v.he_head[g] != MT_NONE && v.he_face[g] != MT_NONE &&
                        v.he_face[g ^ 1u] != MT_NONE)
                        st = mt_edge_collapse(mesh, mt_vert_original(mesh, v.he_head[g ^ 1u]),
                                              mt_vert_original(mesh, v.he_head[g]), NULL, &diag);
                CHECK_OK(st);
                break;
            }
            case 3:
                CHECK_OK(mt_face_delete(mesh, v.he_face[h], &diag));
                break;
            case 4: { /* a new quad of new vertices, triangulated */
                const double p[4][3] = {{9, 9, 0}, {10, 9, 0}, {10, 10, 0}, {9, 10, 0}};
                uint32_t w[4];
                for (int i = 0; i < 4; i++) CHECK_OK(mt_mesh_add_vert(mesh, p[i], &w[i], &diag));
                CHECK_OK(mt_mesh_add_face(mesh, w, 4, &out, &diag));
                CHECK_OK(mt_face_triangulate(mesh, out, NULL, &diag));
                break;
            }
            default: { /* a refused edit: flipping a boundary edge */
                uint32_t g = 0;
                while (v.he_head[g] == MT_NONE || v.he_face[g] != MT_NONE) g++;
                CHECK_STATUS(mt_edge_flip(mesh, mt_vert_original(mesh, v.he_head[g ^ 1u]),
                                          mt_vert_original(mesh, v.he_head[g]), &diag),
                             MT_ERR_REFUSED);
                break;
            }
        }
        check_values_after(mesh, &before, ends, &kept);
        CHECK(kept > 0);
        if (step == 1) /* the flipped diagonal keeps the edge's id and values */
            CHECK_EQ(tag_of(mesh, MT_ELEMENT_EDGE, h / 2), before.of[MT_ELEMENT_EDGE][h / 2]);
        free_values(&before);
        free(ends);
    }
    CHECK_OK(mt_mesh_validate(mesh, &diag));
    mt_mesh_destroy(mesh);
}

static void test_attributes_edit_out_of_memory(void)
{
    mt_mesh *mesh = grid_mesh(4, 4, true);
    tag_everything(mesh);
    mt_diag diag;
    /* Each allocation in turn fails: the split either goes through or
     * leaves every value (and count) as it was. */
    for (long n = 0; n < 40; n++) {
        tag_values before;
        take_values(mesh, &before);
        uint32_t kept = 0, *ends = edge_ends(mesh);
        mt__test_fail_alloc_after(n);
        uint32_t out = 0;
        mt_status s = mt_edge_split(mesh, 6, 7, NULL, &out, &diag);
        mt__test_fail_alloc_after(-1);
        CHECK(s == MT_OK || s == MT_ERR_NOMEM);
        if (s == MT_ERR_NOMEM) {
            uint32_t after[MT_ELEMENT_KIND_COUNT];
            count_elements(mesh, after);
            CHECK(memcmp(before.count, after, sizeof after) == 0);
        }
        check_values_after(mesh, &before, ends, &kept);
        free_values(&before);
        free(ends);
        CHECK_OK(mt_mesh_validate(mesh, &diag));
        if (s == MT_OK) break;
    }
    mt_mesh_destroy(mesh);
}

static void test_attributes_compaction(void)
{
    mt_mesh *mesh = grid_mesh(5, 4, true);
    mt_diag diag;
    CHECK_OK(mt_edge_collapse(mesh, 7, 8, NULL, &diag));
    uint32_t doomed = 0; /* a face the collapse left */
    mt_mesh_view before;
    mt_mesh_get_view(mesh, &before);
    while (before.face_he[doomed] == MT_NONE) doomed++;
    CHECK_OK(mt_face_delete(mesh, doomed, &diag));
    tag_everything(mesh);
    const uint32_t nv = mt_mesh_num_verts(mesh), nf = mt_mesh_num_faces(mesh);
    uint32_t *ends = edge_ends(mesh);
    const uint32_t num_half_edges = mt_mesh_num_elements(mesh, MT_ELEMENT_HALF_EDGE);
    uint32_t *vmap = malloc(nv * sizeof *vmap), *fmap = malloc(nf * sizeof *fmap);
    CHECK_OK(mt_mesh_compact(mesh, vmap, nv, fmap, nf, &diag));
    CHECK_OK(mt_mesh_validate(mesh, &diag));
    for (uint32_t v = 0; v < nv; v++)
        if (vmap[v] != MT_NONE)
            CHECK_EQ(tag_of(mesh, MT_ELEMENT_VERTEX, vmap[v]), tag(MT_ELEMENT_VERTEX, v));
    for (uint32_t f = 0; f < nf; f++)
        if (fmap[f] != MT_NONE)
            CHECK_EQ(tag_of(mesh, MT_ELEMENT_FACE, fmap[f]), tag(MT_ELEMENT_FACE, f));
    /* Each live half-edge a -> b is found again as vmap[a] -> vmap[b]. */
    mt_mesh_view v;
    mt_mesh_get_view(mesh, &v);
    uint32_t found = 0;
    for (uint32_t h = 0; h < num_half_edges; h++) {
        if (ends[h] == MT_NONE) continue;
        const uint32_t a = vmap[ends[h ^ 1u]], b = vmap[ends[h]];
        for (uint32_t g = 0; g < v.num_half_edges; g++) {
            if (v.he_head[g] != b || v.he_head[g ^ 1u] != a) continue;
            CHECK_EQ(tag_of(mesh, MT_ELEMENT_HALF_EDGE, g), tag(MT_ELEMENT_HALF_EDGE, h));
            if (h % 2 == 0) /* an edge's values follow its first half-edge */
                CHECK_EQ(tag_of(mesh, MT_ELEMENT_EDGE, g / 2), tag(MT_ELEMENT_EDGE, h / 2));
            found++;
        }
    }
    CHECK_EQ(found, v.num_half_edges);
    free(ends);
    free(vmap);
    free(fmap);
    mt_mesh_destroy(mesh);
}

/* Sorted ids of a list, as text ("1 3"). */
static void ids_text(const uint32_t *ids, size_t n, char *out, size_t size)
{
    uint32_t sorted[64];
    for (size_t i = 0; i < n && i < 64; i++) sorted[i] = ids[i];
    for (size_t i = 1; i < n && i < 64; i++)
        for (size_t j = i; j > 0 && sorted[j - 1] > sorted[j]; j--) {
            uint32_t t = sorted[j];
            sorted[j] = sorted[j - 1];
            sorted[j - 1] = t;
        }
    size_t used = 0;
    out[0] = '\0';
    for (size_t i = 0; i < n && i < 64; i++)
        used += (size_t)snprintf(out + used, size - used, "%s%u", i ? " " : "", sorted[i]);
}

/* The neighbours and faces of vertex v's ring, sorted, as "1 3 | 0 1". */
static void ring_text(const mt_mesh *mesh, uint32_t v, char *out, size_t size)
{
    uint32_t neighbors[32], faces[32];
    mt_fan fans[8];
    mt_ring ring = {neighbors, 32, faces, 32, fans, 8, 0, 0, 0};
    CHECK_OK(mt_vert_ring(mesh, v, &ring));
    char a[128], b[128];
    ids_text(neighbors, ring.num_neighbors, a, sizeof a);
    ids_text(faces, ring.num_faces, b, sizeof b);
    snprintf(out, size, "%s | %s", a, b);
}

#define CHECK_TEXT(got, want)                                                               \
    do {                                                                                    \
        if (strcmp((got), (want)) != 0)                                                     \
            mt_test_fail(__FILE__, __LINE__, "got \"%s\", expected \"%s\"", (got), (want)); \
    } while (0)

static void test_attributes_closed_rectangle_skips_hidden(void)
{
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(mt_gen_closed_rectangle(2, 1, &mesh, &diag));
    if (!mesh) return;
    const mt_report *r = mt_mesh_report(mesh);
    CHECK(r->num_verts == 4 && r->num_edges == 6 && r->num_faces_valid == 4);
    CHECK(r->closed && r->manifold && r->consistently_oriented && r->euler_characteristic == 2);
    CHECK(mt_is_hidden(mesh, MT_ELEMENT_FACE, 2) && mt_is_hidden(mesh, MT_ELEMENT_FACE, 3));
    CHECK(!mt_is_hidden(mesh, MT_ELEMENT_FACE, 0) && !mt_is_hidden(mesh, MT_ELEMENT_FACE, 1));
    size_t hidden_edges = 0;
    for (uint32_t e = 0; e < mt_mesh_num_elements(mesh, MT_ELEMENT_EDGE); e++)
        hidden_edges += mt_is_hidden(mesh, MT_ELEMENT_EDGE, e);
    CHECK_EQ(hidden_edges, 1);
    char text[512];
    /* Everything is listed until the mesh is asked to skip. */
    ring_text(mesh, 0, text, sizeof text);
    CHECK_TEXT(text, "1 2 3 | 0 1 2");
    CHECK_OK(mt_mesh_skip_hidden(mesh, true));
    /* Vertex 0: the diagonal to 2 and face 2 behind are left out. */
    ring_text(mesh, 0, text, sizeof text);
    CHECK_TEXT(text, "1 3 | 0 1");
    uint32_t valence = 0;
    CHECK_OK(mt_vert_valence(mesh, 0, &valence));
    CHECK_EQ(valence, 2);
    ring_text(mesh, 1, text, sizeof text); /* 1-3 is shown: only faces behind hold it */
    CHECK_TEXT(text, "0 2 3 | 0");
    /* Face 0 (0, 1, 2): nothing shown across 0-1 and 1-2, face 1 across 2-0. */
    uint32_t across[8], offsets[4];
    size_t num_faces = 0, num_sides = 0;
    CHECK_OK(mt_face_neighbors(mesh, 0, across, 8, offsets, 4, &num_faces, &num_sides));
    CHECK(num_sides == 3 && num_faces == 1 && offsets[2] == 0 && across[0] == 1);
    size_t n = 0;
    CHECK_STATUS(mt_face_neighbors(mesh, 2, across, 8, offsets, 4, &num_faces, &num_sides),
                 MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_face_verts(mesh, 3, across, 8, &n), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_edge_faces(mesh, 0, 2, across, 8, &n), MT_ERR_NOT_FOUND); /* hidden edge */
    CHECK_OK(mt_edge_faces(mesh, 0, 1, across, 8, &n));
    CHECK(n == 1 && across[0] == 0);
    CHECK_STATUS(mt_edge_faces(mesh, 1, 3, across, 8, &n), MT_ERR_NOT_FOUND); /* faces hidden */
    /* The setting survives compaction. */
    CHECK_OK(mt_mesh_compact(mesh, NULL, 0, NULL, 0, &diag));
    ring_text(mesh, 0, text, sizeof text);
    CHECK_TEXT(text, "1 3 | 0 1");
    CHECK_OK(mt_mesh_skip_hidden(mesh, false));
    ring_text(mesh, 0, text, sizeof text);
    CHECK_TEXT(text, "1 2 3 | 0 1 2");
    CHECK_STATUS(mt_mesh_skip_hidden(NULL, true), MT_ERR_INVALID_ARG);
    mt_mesh_destroy(mesh);
    mt_mesh *none = mesh;
    CHECK_STATUS(mt_gen_closed_rectangle(0, 1, &none, &diag), MT_ERR_INVALID_ARG);
    CHECK(none == NULL);
}

static const mt_test_case cases[] = {
    {"attributes_api", test_attributes_api},
    {"attributes_hidden", test_attributes_hidden},
    {"attributes_survive_edits", test_attributes_survive_edits},
    {"attributes_edit_out_of_memory", test_attributes_edit_out_of_memory},
    {"attributes_compaction", test_attributes_compaction},
    {"attributes_closed_rectangle_skips_hidden", test_attributes_closed_rectangle_skips_hidden},
};
const mt_test_table mt_tests_attributes = {cases, sizeof cases / sizeof cases[0]};
