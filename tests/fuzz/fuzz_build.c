/* libFuzzer target for mt_mesh_build and the queries: the input bytes become
 * a small face list (any face sizes, any indices, optional positions with NaN
 * and infinities), built leniently and strictly. The lenient build must
 * succeed and validate, the strict one must succeed exactly when the report
 * lists no defect, and the report and every query must agree with a direct
 * reading of the face list (tests/corpus/DEFINITIONS.md), whatever the
 * number of build threads. Any disagreement
 * calls abort() so the fuzzer keeps the input.
 *
 * Input layout (missing bytes read as 0, so every input is a mesh):
 *   byte 0    flags: bit 0 = positions given, bits 1-2 = build threads 1, 2, 3 or
 *             0 (automatic); a build on several threads must give the same report
 *             as one on the calling thread
 *   byte 1    V = byte % 65
 *   byte 2    F = byte % 65
 *   F faces   size byte (n = byte % 10, so records of 0..9 entries), then n index
 *             bytes: 0xFF = UINT32_MAX, 0xFE = 0x80000000 (a negative index),
 *             0xF0..0xFD = V + (byte - 0xF0) (out of range), else byte % V
 *   the rest  pairs (vertex byte, kind byte) overwriting one coordinate of vertex
 *             byte % V, axis kind % 3, with NaN, +Inf, -Inf, -0.0, DBL_MAX or the
 *             smallest denormal (kind / 3 % 6); then edge_faces probes.
 */
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/core.h"

#define MAX_VERTS 64
#define MAX_FACES 64
#define MAX_FACE_SIZE 9
#define MAX_INDICES (MAX_FACES * MAX_FACE_SIZE)
/* Elements each query is tried on (plus one id out of range). */
#define QUERY_VERTS 8
#define QUERY_FACES 8

static void require(bool ok, const char *what, int line)
{
    if (ok) return;
    fprintf(stderr, "fuzz_build.c:%d: invariant violated: %s\n", line, what);
    abort();
}

#define REQUIRE(cond) require((cond), #cond, __LINE__)

/* A query without buffers only reports sizes: MT_OK, or MT_ERR_BUFFER_TOO_SMALL
 * when something would have been written (query.h allows either reading). */
static bool size_query_ok(mt_status s)
{
    return s == MT_OK || s == MT_ERR_BUFFER_TOO_SMALL;
}

/* Reads the input byte by byte; past the end every byte is 0. */
typedef struct byte_reader {
    const uint8_t *data;
    size_t size, pos;
} byte_reader;

static uint8_t next_byte(byte_reader *r)
{
    return r->pos < r->size ? r->data[r->pos++] : 0;
}

static bool reader_done(const byte_reader *r)
{
    return r->pos >= r->size;
}

/* Allocates n elements of size each, exactly (so ASan sees any overrun);
 * NULL for n == 0. */
static void *alloc_exact(size_t n, size_t size)
{
    if (n == 0) return NULL;
    void *p = malloc(n * size);
    REQUIRE(p != NULL);
    return p;
}

/* The face list plus everything the checks derive from it directly. */
typedef struct model {
    mt_face_list list;
    uint32_t sizes[MAX_FACES];
    uint32_t indices[MAX_INDICES];
    uint32_t offsets[MAX_FACES + 1]; /* face f uses indices[offsets[f] .. offsets[f+1]) */
    bool valid[MAX_FACES];
    uint32_t num_valid;
    uint32_t degenerate;         /* < 3 entries or a repeated index */
    uint64_t out_of_range;       /* entries >= V */
    uint32_t faces_out_of_range; /* records with such an entry */
    uint32_t nonfinite;          /* vertices with a non-finite coordinate */
    uint32_t isolated;           /* vertices in no valid face */
    /* Undirected edges of valid faces, sorted, with their use counts. */
    uint32_t edge_a[MAX_INDICES], edge_b[MAX_INDICES], edge_uses[MAX_INDICES];
    uint32_t num_edges;
} model;

static uint32_t face_size(const model *m, uint32_t f)
{
    return m->sizes[f];
}

static const uint32_t *face_at(const model *m, uint32_t f)
{
    return m->indices + m->offsets[f];
}

static int compare_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

static int compare_pair(const void *a, const void *b)
{
    const uint32_t *x = a, *y = b;
    if (x[0] != y[0]) return x[0] < y[0] ? -1 : 1;
    return x[1] < y[1] ? -1 : x[1] > y[1];
}

static uint32_t decode_index(uint8_t b, uint32_t num_verts)
{
    if (b == 0xFF) return UINT32_MAX;
    if (b == 0xFE) return 0x80000000u;
    if (b >= 0xF0) return num_verts + (uint32_t)(b - 0xF0);
    return num_verts ? b % num_verts : 0;
}

static double special_value(uint32_t kind)
{
    switch (kind % 6) {
        case 0:
            return NAN;
        case 1:
            return INFINITY;
        case 2:
            return -INFINITY;
        case 3:
            return -0.0;
        case 4:
            return DBL_MAX;
        default:
            return 4.9406564584124654e-324;
    }
}

/* Builds the face list from the input and the derived counts. */
static void model_read(model *m, byte_reader *r, bool with_positions)
{
    uint32_t num_verts = next_byte(r) % (MAX_VERTS + 1);
    uint32_t num_faces = next_byte(r) % (MAX_FACES + 1);
    uint32_t num_indices = 0;
    for (uint32_t f = 0; f < num_faces; f++) {
        uint32_t n = next_byte(r) % (MAX_FACE_SIZE + 1);
        m->sizes[f] = n;
        m->offsets[f] = num_indices;
        for (uint32_t i = 0; i < n; i++)
            m->indices[num_indices++] = decode_index(next_byte(r), num_verts);
    }
    m->offsets[num_faces] = num_indices;

    m->list.num_verts = num_verts;
    m->list.num_faces = num_faces;
    m->list.num_indices = num_indices;
    m->list.face_sizes = alloc_exact(num_faces, sizeof(uint32_t));
    m->list.face_indices = alloc_exact(num_indices, sizeof(uint32_t));
    if (num_faces) memcpy(m->list.face_sizes, m->sizes, num_faces * sizeof(uint32_t));
    if (num_indices) memcpy(m->list.face_indices, m->indices, num_indices * sizeof(uint32_t));
    m->list.positions = NULL;
    if (with_positions && num_verts > 0) {
        m->list.positions = alloc_exact(3 * (size_t)num_verts, sizeof(double));
        for (uint32_t i = 0; i < 3 * num_verts; i++)
            m->list.positions[i] = (double)(i * 7 % 11) - 5.0;
        /* Two bytes per special coordinate; stop early to leave bytes for probes. */
        for (int k = 0; k < 8 && !reader_done(r); k++) {
            uint32_t v = next_byte(r) % num_verts;
            uint32_t kind = next_byte(r);
            m->list.positions[3 * v + kind % 3] = special_value(kind / 3);
        }
        for (uint32_t v = 0; v < num_verts; v++) {
            const double *p = m->list.positions + 3 * v;
            if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) m->nonfinite++;
        }
    }
}

/* Validity of each record and the record-level counts. */
static void model_classify(model *m)
{
    uint32_t num_verts = m->list.num_verts;
    bool used[MAX_VERTS] = {false};
    for (uint32_t f = 0; f < m->list.num_faces; f++) {
        const uint32_t *idx = face_at(m, f);
        uint32_t n = face_size(m, f);
        bool bad_index = false, repeated = false;
        for (uint32_t i = 0; i < n; i++) {
            if (idx[i] >= num_verts) {
                bad_index = true;
                m->out_of_range++;
            }
            for (uint32_t j = 0; j < i; j++)
                if (idx[j] == idx[i]) repeated = true;
        }
        if (bad_index) m->faces_out_of_range++;
        bool degenerate = n < 3 || repeated;
        if (degenerate) m->degenerate++;
        m->valid[f] = !degenerate && !bad_index;
        if (!m->valid[f]) continue;
        m->num_valid++;
        for (uint32_t i = 0; i < n; i++) used[idx[i]] = true;
    }
    for (uint32_t v = 0; v < num_verts; v++)
        if (!used[v]) m->isolated++;
}

/* Distinct undirected edges of valid faces with their use counts. */
static void model_edges(model *m)
{
    static uint32_t pairs[MAX_INDICES][2];
    uint32_t count = 0;
    for (uint32_t f = 0; f < m->list.num_faces; f++) {
        if (!m->valid[f]) continue;
        const uint32_t *idx = face_at(m, f);
        uint32_t n = face_size(m, f);
        for (uint32_t i = 0; i < n; i++) {
            uint32_t a = idx[i], b = idx[(i + 1) % n];
            pairs[count][0] = a < b ? a : b;
            pairs[count][1] = a < b ? b : a;
            count++;
        }
    }
    qsort(pairs, count, sizeof pairs[0], compare_pair);
    m->num_edges = 0;
    for (uint32_t i = 0; i < count; i++) {
        if (m->num_edges > 0 && m->edge_a[m->num_edges - 1] == pairs[i][0] &&
            m->edge_b[m->num_edges - 1] == pairs[i][1]) {
            m->edge_uses[m->num_edges - 1]++;
            continue;
        }
        m->edge_a[m->num_edges] = pairs[i][0];
        m->edge_b[m->num_edges] = pairs[i][1];
        m->edge_uses[m->num_edges] = 1;
        m->num_edges++;
    }
}

/* Position of v in valid face f, or MT_NONE. */
static uint32_t face_find(const model *m, uint32_t f, uint32_t v)
{
    const uint32_t *idx = face_at(m, f);
    for (uint32_t i = 0; i < face_size(m, f); i++)
        if (idx[i] == v) return i;
    return MT_NONE;
}

/* Whether valid face f has {a, b} as a side. */
static bool face_has_side(const model *m, uint32_t f, uint32_t a, uint32_t b)
{
    const uint32_t *idx = face_at(m, f);
    uint32_t n = face_size(m, f);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t x = idx[i], y = idx[(i + 1) % n];
        if ((x == a && y == b) || (x == b && y == a)) return true;
    }
    return false;
}

/* Valid faces with side {a, b}, ascending, except `skip`. */
static uint32_t faces_on_edge(const model *m, uint32_t a, uint32_t b, uint32_t skip, uint32_t *out)
{
    uint32_t count = 0;
    for (uint32_t f = 0; f < m->list.num_faces; f++)
        if (m->valid[f] && f != skip && face_has_side(m, f, a, b)) out[count++] = f;
    return count;
}

static void check_report(const model *m, const mt_mesh *mesh)
{
    const mt_report *rep = mt_mesh_report(mesh);
    REQUIRE(rep != NULL);
    uint64_t boundary = 0, nonmanifold = 0;
    for (uint32_t e = 0; e < m->num_edges; e++) {
        if (m->edge_uses[e] == 1) boundary++;
        if (m->edge_uses[e] > 2) nonmanifold++;
    }
    REQUIRE(rep->num_verts == m->list.num_verts);
    REQUIRE(rep->num_faces == m->list.num_faces);
    REQUIRE(rep->num_faces_valid == m->num_valid);
    REQUIRE(rep->num_half_edges == m->list.num_indices);
    REQUIRE(rep->num_edges == m->num_edges);
    REQUIRE(rep->boundary_edges == boundary);
    REQUIRE(rep->nonmanifold_edges == nonmanifold);
    REQUIRE(rep->degenerate_faces == m->degenerate);
    REQUIRE(rep->out_of_range_indices == m->out_of_range);
    REQUIRE(rep->faces_with_out_of_range_indices == m->faces_out_of_range);
    REQUIRE(rep->isolated_vertices == m->isolated);
    REQUIRE(rep->nonfinite_vertices == m->nonfinite);
    REQUIRE(rep->euler_characteristic ==
            (int64_t)m->list.num_verts - (int64_t)m->num_edges + (int64_t)m->num_valid);
    REQUIRE(rep->inconsistent_orientation_edges <= rep->duplicate_directed_edges);
    REQUIRE(rep->connected_components <= m->num_valid);
    REQUIRE(rep->vertex_connected_components <= rep->connected_components);
    REQUIRE(rep->closed == (boundary == 0 && m->num_valid > 0));
    REQUIRE(rep->boundary_loops <= boundary);

    /* Every defect is listed once per kind's count, and every rejected record
     * is named by an out-of-range or degenerate entry: nothing is dropped
     * without being reported. */
    size_t total = 0;
    for (uint32_t k = 0; k < MT_DEFECT_KIND_COUNT; k++)
        total += mt_report_count_defects(rep, (mt_defect_kind)k);
    REQUIRE(total == rep->num_defects);
    for (uint32_t f = 0; f < m->list.num_faces; f++) {
        bool named = false;
        for (size_t d = 0; d < rep->num_defects && !named; d++) {
            const mt_defect *def = &rep->defects[d];
            named = def->a == f && (def->kind == MT_DEFECT_OUT_OF_RANGE_INDEX ||
                                    def->kind == MT_DEFECT_DEGENERATE_FACE);
        }
        REQUIRE(named == !m->valid[f]);
    }
    char text[256];
    for (size_t d = 0; d < rep->num_defects; d++) {
        REQUIRE(rep->defects[d].kind < MT_DEFECT_KIND_COUNT);
        size_t len = mt_defect_describe(&rep->defects[d], text, sizeof text);
        REQUIRE(len > 0 && strlen(text) == (len < sizeof text ? len : sizeof text - 1));
    }
}

/* Two reports of the same face list agree field by field and list by list. */
static void check_same_report(const mt_report *a, const mt_report *b)
{
    REQUIRE(a->num_verts == b->num_verts && a->num_faces == b->num_faces);
    REQUIRE(a->num_faces_valid == b->num_faces_valid && a->num_edges == b->num_edges);
    REQUIRE(a->num_half_edges == b->num_half_edges);
    REQUIRE(a->boundary_edges == b->boundary_edges && a->boundary_loops == b->boundary_loops);
    REQUIRE(a->boundary_loops_ambiguous == b->boundary_loops_ambiguous);
    REQUIRE(a->nonmanifold_edges == b->nonmanifold_edges);
    REQUIRE(a->inconsistent_orientation_edges == b->inconsistent_orientation_edges);
    REQUIRE(a->duplicate_directed_edges == b->duplicate_directed_edges);
    REQUIRE(a->nonmanifold_vertices == b->nonmanifold_vertices);
    REQUIRE(a->bowtie_vertices == b->bowtie_vertices);
    REQUIRE(a->isolated_vertices == b->isolated_vertices);
    REQUIRE(a->unreferenced_vertices == b->unreferenced_vertices);
    REQUIRE(a->degenerate_faces == b->degenerate_faces);
    REQUIRE(a->duplicate_faces == b->duplicate_faces);
    REQUIRE(a->out_of_range_indices == b->out_of_range_indices);
    REQUIRE(a->faces_with_out_of_range_indices == b->faces_with_out_of_range_indices);
    REQUIRE(a->nonfinite_vertices == b->nonfinite_vertices);
    REQUIRE(a->connected_components == b->connected_components);
    REQUIRE(a->vertex_connected_components == b->vertex_connected_components);
    REQUIRE(a->euler_characteristic == b->euler_characteristic);
    REQUIRE(a->closed == b->closed && a->manifold == b->manifold);
    REQUIRE(a->orientable == b->orientable);
    REQUIRE(a->consistently_oriented == b->consistently_oriented && a->genus == b->genus);
    for (uint32_t i = 0; i < a->boundary_loops; i++)
        REQUIRE(a->boundary_loop_lengths[i] == b->boundary_loop_lengths[i]);
    for (uint32_t i = 0; i < a->connected_components; i++) {
        const mt_component_info *x = &a->components[i], *y = &b->components[i];
        REQUIRE(x->min_face == y->min_face && x->faces == y->faces);
        REQUIRE(x->vertices == y->vertices && x->edges == y->edges);
        REQUIRE(x->euler_characteristic == y->euler_characteristic);
        REQUIRE(x->boundary_edges == y->boundary_edges && x->boundary_loops == y->boundary_loops);
        REQUIRE(x->closed == y->closed && x->manifold == y->manifold);
        REQUIRE(x->orientable == y->orientable && x->genus == y->genus);
        REQUIRE(x->genus_with_boundary == y->genus_with_boundary);
    }
    REQUIRE(a->num_face_size_bins == b->num_face_size_bins);
    for (size_t i = 0; i < a->num_face_size_bins; i++) {
        REQUIRE(a->face_size_histogram[i].key == b->face_size_histogram[i].key);
        REQUIRE(a->face_size_histogram[i].count == b->face_size_histogram[i].count);
    }
    REQUIRE(a->num_edge_use_bins == b->num_edge_use_bins);
    for (size_t i = 0; i < a->num_edge_use_bins; i++) {
        REQUIRE(a->edge_use_histogram[i].key == b->edge_use_histogram[i].key);
        REQUIRE(a->edge_use_histogram[i].count == b->edge_use_histogram[i].count);
    }
    REQUIRE(a->num_defects == b->num_defects);
    for (size_t i = 0; i < a->num_defects; i++) {
        const mt_defect *x = &a->defects[i], *y = &b->defects[i];
        REQUIRE(x->kind == y->kind && x->a == y->a && x->b == y->b && x->c == y->c);
    }
}

static void check_positions(const model *m, const mt_mesh *mesh)
{
    REQUIRE(mt_mesh_num_verts(mesh) == m->list.num_verts);
    REQUIRE(mt_mesh_num_faces(mesh) == m->list.num_faces);
    for (uint32_t v = 0; v < m->list.num_verts; v++) {
        const double *p = mt_mesh_position(mesh, v);
        if (!m->list.positions) {
            REQUIRE(p == NULL);
        } else {
            REQUIRE(p != NULL && memcmp(p, m->list.positions + 3 * v, 3 * sizeof(double)) == 0);
        }
    }
    REQUIRE(mt_mesh_position(mesh, m->list.num_verts) == NULL);
}

/* Vertices to query: the first few, the last, and those of the first face. */
static uint32_t pick_verts(const model *m, uint32_t *out)
{
    uint32_t count = 0;
    uint32_t num_verts = m->list.num_verts;
    for (uint32_t v = 0; v < num_verts && v < QUERY_VERTS / 2; v++) out[count++] = v;
    if (num_verts > QUERY_VERTS / 2) out[count++] = num_verts - 1;
    if (m->list.num_faces > 0) {
        const uint32_t *idx = face_at(m, 0);
        for (uint32_t i = 0; i < face_size(m, 0) && count < QUERY_VERTS; i++)
            if (idx[i] < num_verts) out[count++] = idx[i];
    }
    return count;
}

static void check_vert_ring(const model *m, const mt_mesh *mesh, uint32_t v)
{
    /* Reference: the valid faces holding v, and v's neighbours. */
    uint32_t incident[MAX_FACES], neighbors[2 * MAX_FACES];
    uint32_t num_incident = 0, num_neighbors = 0;
    for (uint32_t f = 0; f < m->list.num_faces; f++) {
        if (!m->valid[f]) continue;
        uint32_t i = face_find(m, f, v);
        if (i == MT_NONE) continue;
        uint32_t n = face_size(m, f);
        incident[num_incident++] = f;
        neighbors[num_neighbors++] = face_at(m, f)[(i + 1) % n];
        neighbors[num_neighbors++] = face_at(m, f)[(i + n - 1) % n];
    }
    qsort(neighbors, num_neighbors, sizeof neighbors[0], compare_u32);
    uint32_t distinct = 0;
    for (uint32_t i = 0; i < num_neighbors; i++)
        if (i == 0 || neighbors[i] != neighbors[i - 1]) neighbors[distinct++] = neighbors[i];

    /* Size query, then a fill with exactly that much room. */
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    mt_status s = mt_vert_ring(mesh, v, &ring);
    REQUIRE(size_query_ok(s));
    REQUIRE(ring.num_faces == num_incident);
    size_t want_neighbors = ring.num_neighbors, want_faces = ring.num_faces,
           want_fans = ring.num_fans;
    ring.neighbors = alloc_exact(want_neighbors, sizeof(uint32_t));
    ring.neighbors_capacity = want_neighbors;
    ring.faces = alloc_exact(want_faces, sizeof(uint32_t));
    ring.faces_capacity = want_faces;
    ring.fans = alloc_exact(want_fans, sizeof(mt_fan));
    ring.fans_capacity = want_fans;
    REQUIRE(mt_vert_ring(mesh, v, &ring) == MT_OK);
    REQUIRE(ring.num_neighbors == want_neighbors && ring.num_faces == want_faces &&
            ring.num_fans == want_fans);

    /* Fans follow each other, and each face lies between two neighbours that
     * are its vertices next to v. */
    uint32_t neighbor_next = 0, face_next = 0;
    for (size_t k = 0; k < ring.num_fans; k++) {
        const mt_fan *fan = &ring.fans[k];
        REQUIRE(fan->neighbor_begin == neighbor_next && fan->face_begin == face_next);
        REQUIRE(fan->face_count >= 1);
        REQUIRE(fan->neighbor_count == fan->face_count + (fan->boundary ? 1 : 0));
        neighbor_next += fan->neighbor_count;
        face_next += fan->face_count;
        REQUIRE(neighbor_next <= ring.num_neighbors && face_next <= ring.num_faces);
        for (uint32_t i = 0; i < fan->face_count; i++) {
            uint32_t f = ring.faces[fan->face_begin + i];
            REQUIRE(f < m->list.num_faces && m->valid[f]);
            uint32_t pos = face_find(m, f, v);
            REQUIRE(pos != MT_NONE);
            uint32_t n = face_size(m, f);
            uint32_t after = face_at(m, f)[(pos + 1) % n],
                     before = face_at(m, f)[(pos + n - 1) % n];
            uint32_t x = ring.neighbors[fan->neighbor_begin + i];
            uint32_t y = ring.neighbors[fan->neighbor_begin + (i + 1) % fan->neighbor_count];
            REQUIRE((x == after && y == before) || (x == before && y == after));
        }
    }
    REQUIRE(neighbor_next == ring.num_neighbors && face_next == ring.num_faces);

    /* The same faces as the reference, each once; the same neighbour set. */
    if (ring.num_faces > 0) qsort(ring.faces, ring.num_faces, sizeof(uint32_t), compare_u32);
    for (uint32_t i = 0; i < num_incident; i++) REQUIRE(ring.faces[i] == incident[i]);
    if (ring.num_neighbors > 0)
        qsort(ring.neighbors, ring.num_neighbors, sizeof(uint32_t), compare_u32);
    uint32_t ring_distinct = 0;
    for (size_t i = 0; i < ring.num_neighbors; i++) {
        if (i > 0 && ring.neighbors[i] == ring.neighbors[i - 1]) continue;
        REQUIRE(ring_distinct < distinct && ring.neighbors[i] == neighbors[ring_distinct]);
        ring_distinct++;
    }
    REQUIRE(ring_distinct == distinct);
    uint32_t valence = MT_NONE;
    REQUIRE(mt_vert_valence(mesh, v, &valence) == MT_OK);
    REQUIRE(valence == distinct);

    /* One element too little room is refused. */
    if (want_faces > 0) {
        ring.faces_capacity = want_faces - 1;
        REQUIRE(mt_vert_ring(mesh, v, &ring) == MT_ERR_BUFFER_TOO_SMALL);
        REQUIRE(ring.num_faces == want_faces);
    }
    free(ring.neighbors);
    free(ring.faces);
    free(ring.fans);
}

static void check_face(const model *m, const mt_mesh *mesh, uint32_t f)
{
    size_t count = MT_NONE, num_faces = 0, num_edges = 0;
    mt_status s = mt_face_verts(mesh, f, NULL, 0, &count);
    if (!m->valid[f]) {
        REQUIRE(s == MT_ERR_NOT_FOUND);
        REQUIRE(mt_face_neighbors(mesh, f, NULL, 0, NULL, 0, &num_faces, &num_edges) != MT_OK);
        uint32_t component = 0;
        REQUIRE(mt_face_component(mesh, f, &component) == MT_ERR_NOT_FOUND);
        return;
    }
    uint32_t n = face_size(m, f);
    const uint32_t *idx = face_at(m, f);
    REQUIRE(size_query_ok(s) && count == n);
    uint32_t *verts = alloc_exact(n, sizeof(uint32_t));
    REQUIRE(mt_face_verts(mesh, f, verts, n, &count) == MT_OK && count == n);
    REQUIRE(memcmp(verts, idx, n * sizeof(uint32_t)) == 0);
    free(verts);

    s = mt_face_neighbors(mesh, f, NULL, 0, NULL, 0, &num_faces, &num_edges);
    REQUIRE(size_query_ok(s));
    REQUIRE(num_edges == n);
    uint32_t *across = alloc_exact(num_faces, sizeof(uint32_t));
    uint32_t *offsets = alloc_exact(n + 1, sizeof(uint32_t));
    REQUIRE(mt_face_neighbors(mesh, f, across, num_faces, offsets, n + 1, &num_faces, &num_edges) ==
            MT_OK);
    REQUIRE(offsets[0] == 0 && offsets[n] == num_faces);

    uint32_t component = MT_NONE, other_component = MT_NONE;
    REQUIRE(mt_face_component(mesh, f, &component) == MT_OK);
    REQUIRE(component < mt_mesh_report(mesh)->connected_components);

    uint32_t expected[MAX_FACES], listed[MAX_FACES], on_edge[MAX_FACES];
    for (uint32_t i = 0; i < n; i++) {
        uint32_t a = idx[i], b = idx[(i + 1) % n];
        REQUIRE(offsets[i] <= offsets[i + 1] && offsets[i + 1] <= num_faces);
        uint32_t count_listed = offsets[i + 1] - offsets[i];
        uint32_t count_expected = faces_on_edge(m, a, b, f, expected);
        REQUIRE(count_listed == count_expected);
        if (count_listed > 0) {
            memcpy(listed, across + offsets[i], count_listed * sizeof(uint32_t));
            qsort(listed, count_listed, sizeof(uint32_t), compare_u32);
        }
        for (uint32_t k = 0; k < count_listed; k++) {
            REQUIRE(listed[k] == expected[k]);
            REQUIRE(mt_face_component(mesh, listed[k], &other_component) == MT_OK);
            REQUIRE(other_component == component);
        }

        /* mt_edge_faces on the same side: the face itself plus its neighbours. */
        size_t edge_count = 0;
        REQUIRE(size_query_ok(mt_edge_faces(mesh, a, b, NULL, 0, &edge_count)));
        uint32_t want = faces_on_edge(m, a, b, MT_NONE, expected);
        REQUIRE(edge_count == want);
        REQUIRE(mt_edge_faces(mesh, b, a, on_edge, want, &edge_count) == MT_OK);
        REQUIRE(edge_count == want);
        for (uint32_t k = 0; k < want; k++) REQUIRE(on_edge[k] == expected[k]);
        if (want > 1) {
            REQUIRE(mt_edge_faces(mesh, a, b, on_edge, want - 1, &edge_count) ==
                    MT_ERR_BUFFER_TOO_SMALL);
        }
    }
    free(across);
    free(offsets);
}

/* mt_edge_faces on vertex pairs taken from the input: an edge or not. */
static void check_edge_probes(const model *m, const mt_mesh *mesh, byte_reader *r)
{
    uint32_t num_verts = m->list.num_verts;
    for (int k = 0; k < 8 && !reader_done(r); k++) {
        uint32_t a = decode_index(next_byte(r), num_verts);
        uint32_t b = decode_index(next_byte(r), num_verts);
        uint32_t expected[MAX_FACES], got[MAX_FACES];
        uint32_t want = (a < num_verts && b < num_verts && a != b)
                            ? faces_on_edge(m, a, b, MT_NONE, expected)
                            : 0;
        size_t count = 0;
        mt_status s = mt_edge_faces(mesh, a, b, got, MAX_FACES, &count);
        if (want == 0) {
            REQUIRE(s != MT_OK);
            continue;
        }
        REQUIRE(s == MT_OK && count == want);
        for (uint32_t i = 0; i < want; i++) REQUIRE(got[i] == expected[i]);
    }
}

static void check_boundary_loops(const model *m, const mt_mesh *mesh)
{
    const mt_report *rep = mt_mesh_report(mesh);
    size_t num_verts = 0, num_loops = 0;
    REQUIRE(size_query_ok(mt_boundary_loops(mesh, NULL, 0, NULL, 0, &num_verts, &num_loops)));
    REQUIRE((num_verts == 0) == (num_loops == 0));
    uint32_t *verts = alloc_exact(num_verts, sizeof(uint32_t));
    uint32_t *offsets = alloc_exact(num_loops + 1, sizeof(uint32_t));
    REQUIRE(mt_boundary_loops(mesh, verts, num_verts, offsets, num_loops + 1, &num_verts,
                              &num_loops) == MT_OK);
    REQUIRE(offsets[0] == 0 && offsets[num_loops] == num_verts);
    for (size_t l = 0; l < num_loops; l++) {
        uint32_t begin = offsets[l], end = offsets[l + 1];
        REQUIRE(begin < end && end <= num_verts && end - begin >= 2);
        for (uint32_t i = begin; i < end; i++) {
            uint32_t a = verts[i], b = verts[i + 1 < end ? i + 1 : begin];
            REQUIRE(a < m->list.num_verts && b < m->list.num_verts && a != b);
            uint32_t on_edge[MAX_FACES];
            REQUIRE(faces_on_edge(m, a, b, MT_NONE, on_edge) > 0);
        }
    }
    /* Each edge used once gives one boundary half-edge; clashing edges give more. */
    REQUIRE(num_verts >= rep->boundary_edges);
    if (rep->nonmanifold_edges == 0 && rep->duplicate_directed_edges == 0) {
        REQUIRE(num_verts == rep->boundary_edges);
        if (!rep->boundary_loops_ambiguous) REQUIRE(num_loops == rep->boundary_loops);
    }
    free(verts);
    free(offsets);
}

static void check_queries(const model *m, const mt_mesh *mesh, byte_reader *r)
{
    uint32_t verts[QUERY_VERTS];
    uint32_t count = pick_verts(m, verts);
    for (uint32_t i = 0; i < count; i++) check_vert_ring(m, mesh, verts[i]);
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    REQUIRE(mt_vert_ring(mesh, m->list.num_verts, &ring) == MT_ERR_OUT_OF_RANGE);

    for (uint32_t f = 0; f < m->list.num_faces && f < QUERY_FACES; f++) check_face(m, mesh, f);
    if (m->list.num_faces > QUERY_FACES) check_face(m, mesh, m->list.num_faces - 1);
    size_t n = 0, e = 0;
    REQUIRE(mt_face_verts(mesh, m->list.num_faces, NULL, 0, &n) != MT_OK);
    REQUIRE(mt_face_neighbors(mesh, m->list.num_faces, NULL, 0, NULL, 0, &n, &e) != MT_OK);

    check_boundary_loops(m, mesh);
    check_edge_probes(m, mesh, r);
}

/* Face shapes (the sweep line over every polygon face and boundary loop):
 * the size query and the fill agree, each face listed is valid and not
 * simple, named sides are two distinct sides of it, loop ids are in range;
 * without positions, MT_ERR_NO_GEOMETRY. */
static void check_face_shapes(const model *m, const mt_mesh *mesh)
{
    size_t count = 0;
    mt_status s = mt_mesh_nonsimple_faces(mesh, NULL, 0, &count, NULL);
    if (!m->list.positions) {
        REQUIRE(s == MT_ERR_NO_GEOMETRY);
        return;
    }
    REQUIRE(s == MT_OK);
    mt_face_shape *shapes = count ? calloc(count, sizeof *shapes) : NULL;
    size_t again = 0;
    REQUIRE(mt_mesh_nonsimple_faces(mesh, shapes, count, &again, NULL) == MT_OK && again == count);
    for (size_t i = 0; i < count; i++) {
        const mt_face_shape *f = &shapes[i];
        size_t n = 0;
        REQUIRE(mt_face_verts(mesh, f->face, NULL, 0, &n) != MT_ERR_NOT_FOUND);
        REQUIRE(n >= 4 && f->kind != MT_FACE_SIMPLE);
        if (f->kind == MT_FACE_SELF_CROSSING) REQUIRE(f->side_a < f->side_b && f->side_b < n);
        mt_face_shape one;
        REQUIRE(mt_face_shape_of(mesh, f->face, &one, NULL) == MT_OK && one.kind == f->kind);
    }
    free(shapes);
    /* Boundary loops crossing themselves: the same rules, loop ids in range. */
    size_t loops = 0, loop_verts = 0;
    mt_boundary_loops(mesh, NULL, 0, NULL, 0, &loop_verts, &loops);
    REQUIRE(mt_mesh_boundary_loop_crossings(mesh, NULL, 0, &count, NULL) == MT_OK);
    REQUIRE(count <= loops);
    mt_loop_crossing *crossings = count ? calloc(count, sizeof *crossings) : NULL;
    REQUIRE(mt_mesh_boundary_loop_crossings(mesh, crossings, count, &again, NULL) == MT_OK &&
            again == count);
    for (size_t i = 0; i < count; i++) REQUIRE(crossings[i].loop < loops);
    free(crossings);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static model m;
    memset(&m, 0, sizeof m);
    byte_reader r = {data, size, 0};
    uint8_t flags = next_byte(&r);
    model_read(&m, &r, (flags & 1) != 0);
    model_classify(&m);
    model_edges(&m);

    mt_build_options options;
    memset(&options, 0, sizeof options);
    static const uint32_t thread_choices[4] = {1, 2, 3, 0};
    options.threads = thread_choices[(flags >> 1) & 3];
    mt_mesh *mesh = NULL;
    mt_diag diag;
    mt_status s = mt_mesh_build(&m.list, &options, &mesh, &diag);
    if (s != MT_OK) fprintf(stderr, "mt_mesh_build: %s: %s\n", mt_strerror(s), diag.message);
    REQUIRE(s == MT_OK && mesh != NULL);
    s = mt_mesh_validate(mesh, &diag);
    if (s != MT_OK) fprintf(stderr, "mt_mesh_validate: %s\n", diag.message);
    REQUIRE(s == MT_OK);
    check_report(&m, mesh);
    check_positions(&m, mesh);
    check_queries(&m, mesh, &r);
    check_face_shapes(&m, mesh);

    /* The report does not depend on how many threads built the mesh. */
    if (options.threads != 1) {
        mt_build_options single = options;
        single.threads = 1;
        mt_mesh *reference = NULL;
        REQUIRE(mt_mesh_build(&m.list, &single, &reference, NULL) == MT_OK);
        check_same_report(mt_mesh_report(reference), mt_mesh_report(mesh));
        mt_mesh_destroy(reference);
    }

    /* Strict mode refuses exactly the meshes whose report lists a defect. */
    options.strict = true;
    mt_mesh *strict_mesh = NULL;
    s = mt_mesh_build(&m.list, &options, &strict_mesh, &diag);
    if (mt_mesh_report(mesh)->num_defects == 0) {
        REQUIRE(s == MT_OK && strict_mesh != NULL);
        REQUIRE(mt_mesh_validate(strict_mesh, NULL) == MT_OK);
        REQUIRE(mt_mesh_report(strict_mesh)->num_edges == mt_mesh_report(mesh)->num_edges);
    } else {
        REQUIRE(s == MT_ERR_DEFECT && strict_mesh == NULL);
        REQUIRE(diag.status == MT_ERR_DEFECT && diag.message[0] != '\0');
    }
    mt_mesh_destroy(strict_mesh);
    mt_mesh_destroy(mesh);
    free(m.list.positions);
    free(m.list.face_sizes);
    free(m.list.face_indices);
    return 0;
}
