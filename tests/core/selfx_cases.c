/* Hand-made and generated meshes for the self-intersection oracle
 * (selfx_cases.h): one case per rule (touching, folding, duplicates, a
 * vertex in another face, a quad whose diagonal is another face's edge),
 * self-crossing and warped faces and loops, solids from the generators, and
 * random faces on a few grid points, where touching, coplanar and
 * coincident corners are the rule rather than the exception. */
#include "selfx_cases.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "meshtopo/generate.h"

typedef struct case_list {
    sx_case *cases;
    size_t count, capacity;
    bool failed;
} case_list;

/* The next free case, named and with nothing stated; NULL when full. */
static sx_case *next_case(case_list *l, const char *name)
{
    if (l->count == l->capacity) {
        l->failed = true;
        return NULL;
    }
    sx_case *c = &l->cases[l->count];
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "%s", name);
    c->pairs = c->undecided = c->nonsimple = c->loops = -1;
    return c;
}

/* A case from positions (3 per vertex) and faces (sizes, then indices). */
static sx_case *add_mesh(case_list *l, const char *name, const double *pos, uint32_t num_verts,
                         const uint32_t *sizes, uint32_t num_faces, const uint32_t *indices)
{
    uint64_t num_indices = 0;
    for (uint32_t f = 0; f < num_faces; f++) num_indices += sizes[f];
    sx_case *c = next_case(l, name);
    if (!c) return NULL;
    if (mt_face_list_alloc(&c->list, num_verts, num_faces, num_indices, NULL) != MT_OK) {
        l->failed = true;
        return NULL;
    }
    memcpy(c->list.positions, pos, 3 * (size_t)num_verts * sizeof *pos);
    memcpy(c->list.face_sizes, sizes, num_faces * sizeof *sizes);
    memcpy(c->list.face_indices, indices, num_indices * sizeof *indices);
    l->count++;
    return c;
}

static void set_expected(sx_case *c, long pairs, long undecided, long nonsimple, long loops)
{
    if (!c) return;
    c->pairs = pairs;
    c->undecided = undecided;
    c->nonsimple = nonsimple;
    c->loops = loops;
}

static void add_generated(case_list *l, const char *name, mt_status status, mt_face_list *list,
                          long pairs)
{
    sx_case *c = status == MT_OK ? next_case(l, name) : NULL;
    if (!c) {
        mt_face_list_free(list);
        l->failed = true;
        return;
    }
    c->list = *list;
    c->pairs = pairs;
    c->undecided = 0;
    l->count++;
}

/* ---- one rule each ---------------------------------------------------------- */

static void add_rule_cases(case_list *l)
{
    /* An octahedron whose top apex is pushed below the bottom one, off the
     * axis: the bottom pyramid pokes through the upper faces. */
    static const double octa[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0.5, 0.5, -1.5, 0, 0, -1};
    static const uint32_t octa_sizes[] = {3, 3, 3, 3, 3, 3, 3, 3};
    static const uint32_t octa_faces[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                          2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    sx_case *c = add_mesh(l, "octahedron_pushed", octa, 6, octa_sizes, 8, octa_faces);
    set_expected(c, -1, 0, 0, 0);

    /* Two tetrahedra, the second moved by (0.5, 0.5, 0.5) into the first. */
    static const double tetras[] = {0,   0,   0,   2,   0,   0,   0,   2,   0,   0,   0,   2,
                                    0.5, 0.5, 0.5, 2.5, 0.5, 0.5, 0.5, 2.5, 0.5, 0.5, 0.5, 2.5};
    static const uint32_t tetra_sizes[] = {3, 3, 3, 3, 3, 3, 3, 3};
    static const uint32_t tetra_faces[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3,
                                           4, 6, 5, 4, 5, 7, 4, 7, 6, 5, 6, 7};
    c = add_mesh(l, "two_tetrahedra", tetras, 8, tetra_sizes, 8, tetra_faces);
    set_expected(c, -1, 0, 0, 0);

    /* Two coplanar triangles on the same side of their shared edge 0-1. */
    static const double fold[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.5, 0};
    static const uint32_t two_tris[] = {3, 3};
    static const uint32_t fold_faces[] = {0, 1, 2, 1, 0, 3};
    set_expected(add_mesh(l, "fold", fold, 4, two_tris, 2, fold_faces), 1, 0, 0, 0);

    /* A face and its reverse (a duplicate), and a triangle far away. */
    static const double dup[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 5, 1, 0, 5, 0, 1, 5};
    static const uint32_t three_tris[] = {3, 3, 3};
    static const uint32_t dup_faces[] = {0, 1, 2, 2, 1, 0, 3, 4, 5};
    set_expected(add_mesh(l, "duplicate", dup, 6, three_tris, 3, dup_faces), 1, 0, 0, 0);

    /* A soup: B touches A at A's corner, C touches A's side (no shared ids). */
    static const double touch[] = {0, 0, 0, 1, 0,   0, 0, 1,   0,  1, 0,   0,  2, 0,
                                   1, 2, 1, 1, 0.5, 0, 0, 0.5, -1, 1, 0.5, -1, -1};
    static const uint32_t touch_faces[] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    set_expected(add_mesh(l, "touching_soup", touch, 9, three_tris, 3, touch_faces), 2, 0, 0, 0);

    /* D shares corner 0 with A and has its opposite side end inside A; E
     * shares corner 0 and meets A nowhere else. */
    static const double vin[] = {0, 0,    0,    1, 0,  0, 0, 1, 0,  0.25, 0.25,
                                 0, 0.25, 0.25, 1, -1, 0, 1, 0, -1, 1};
    static const uint32_t vin_faces[] = {0, 1, 2, 0, 3, 4, 0, 5, 6};
    set_expected(add_mesh(l, "vertex_in_face", vin, 7, three_tris, 3, vin_faces), 1, 0, 0, 0);

    /* The triangle's side 0-2 is the square's diagonal: whether the pair is
     * reported depends on which diagonal the square is cut along (with 0-2
     * the two triangles share only a non-coplanar edge; with 1-3 the side
     * 1-3 crosses it), so the oracle calls it undecided. */
    static const double diag[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1};
    static const uint32_t diag_sizes[] = {4, 3};
    static const uint32_t diag_faces[] = {0, 1, 2, 3, 0, 2, 4};
    set_expected(add_mesh(l, "diagonal_is_edge", diag, 5, diag_sizes, 2, diag_faces), 0, 1, 0, 0);

    /* A triangle on a line with the shared corner 0 in the middle of its
     * opposite side: by the one-shared-corner rule that side meets the
     * other triangle (at corner 0 itself), so the pair counts, though the
     * two meet nowhere else. */
    static const double through[] = {0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 1, 1, 0, -1, 1};
    static const uint32_t through_faces[] = {0, 1, 2, 0, 3, 4};
    set_expected(
        add_mesh(l, "segment_through_shared_corner", through, 5, two_tris, 2, through_faces), 1, 0,
        0, -1);

    /* A face with a NaN corner is not judged, though it pierces A. */
    static const double nan_pos[] = {0,   0,   0,  1,   0,   0, 0,   1, 0,
                                     0.2, 0.2, -1, 0.2, 0.2, 1, NAN, 0, 0};
    static const uint32_t nan_faces[] = {0, 1, 2, 3, 4, 5};
    set_expected(add_mesh(l, "nan_corner", nan_pos, 6, two_tris, 2, nan_faces), 0, 0, 0, 0);

    /* Shared corners 0 and 1 at one point: both triangles are segments from
     * it, to (1, 0, 0) and to (1, 1, 0), meeting only there; then, with
     * the second one along the first, overlapping beyond it. */
    static const double pinch[] = {0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0};
    static const uint32_t pinch_faces[] = {0, 1, 2, 1, 0, 3};
    set_expected(add_mesh(l, "coincident_shared_edge", pinch, 4, two_tris, 2, pinch_faces), 0, 0, 0,
                 -1);
    static const double along[] = {0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0};
    set_expected(add_mesh(l, "coincident_shared_edge_along", along, 4, two_tris, 2, pinch_faces), 1,
                 0, 0, -1);
    /* Two segments along their shared side 0-1, both past corner 1. */
    static const double past[] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
    set_expected(add_mesh(l, "segments_past_one_end", past, 4, two_tris, 2, pinch_faces), 1, 0, 0,
                 -1);
}

/* ---- face and loop shapes ----------------------------------------------------- */

static void add_shape_cases(case_list *l)
{
    static const uint32_t one_quad[] = {4};
    static const uint32_t quad[] = {0, 1, 2, 3};
    /* Sides 0 and 2 cross at (0.5, 0.5); the boundary loop is the same. */
    static const double crossed[] = {0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0};
    set_expected(add_mesh(l, "crossed_quad", crossed, 4, one_quad, 1, quad), 0, 0, 1, 1);
    /* Side 1 runs back over side 0. */
    static const double folded[] = {0, 0, 0, 2, 0, 0, 1, 0, 0, 1, 1, 0};
    set_expected(add_mesh(l, "folded_sides", folded, 4, one_quad, 1, quad), 0, 0, 1, 1);
    /* One corner 0.2 off the others' plane: warped, simple in its plane. */
    static const double warped[] = {0, 0, 0, 1, 0, 0, 1, 1, 0.2, 0, 1, 0};
    set_expected(add_mesh(l, "warped_quad", warped, 4, one_quad, 1, quad), 0, 0, 1, 0);
    /* Corners 1 and 2 at one position: side 1 has no length, and sides 0
     * and 2 meet there. */
    static const double repeated[] = {0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0};
    set_expected(add_mesh(l, "repeated_corner_position", repeated, 4, one_quad, 1, quad), 0, 0, 1,
                 1);
    /* Corner 3 lies below the line of side 0 by 7e-18 (exactly; the
     * doubles' 3 * 0.0333.. - 0.1 rounds to 0): simple, though a test in
     * doubles finds it on that line (touching side 0, folding with side 3). */
    static const double near[] = {0, 0, 0, 3, 1, 0, 3, -1, 0, 0.1, 0.03333333333333333, 0};
    set_expected(add_mesh(l, "near_touching_quad", near, 4, one_quad, 1, quad), 0, 0, 0, 0);
    /* The same with the zero-length side between the two that touch in a
     * sweep's order: sides 0 and 2 meet at (0, 1, 0). */
    static const double hidden[] = {0, 0, 0, 0, 1, 0, 0, 1, 0, 2, 1, 0};
    set_expected(add_mesh(l, "repeated_corner_hidden", hidden, 4, one_quad, 1, quad), 0, 0, 1, 1);
    /* Two corners at one position (different ids): the sides touch. */
    static const double pinched[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0.5, 0.5, 0, 0, 1, 0, 1, 0, 0};
    static const uint32_t one_hexagon[] = {6};
    static const uint32_t hexagon[] = {0, 1, 2, 3, 4, 5};
    set_expected(add_mesh(l, "pinched_polygon", pinched, 6, one_hexagon, 1, hexagon), 0, 0, 1, 1);

    /* A pentagram: corners of a regular pentagon taken every other one. */
    double star[15];
    for (int k = 0; k < 5; k++) {
        double angle = 1.5707963267948966 + 2 * 3.141592653589793 * (2 * k % 5) / 5;
        star[3 * k] = cos(angle);
        star[3 * k + 1] = sin(angle);
        star[3 * k + 2] = 0;
    }
    static const uint32_t one_pentagon[] = {5};
    static const uint32_t pentagon[] = {0, 1, 2, 3, 4};
    set_expected(add_mesh(l, "pentagram", star, 5, one_pentagon, 1, pentagon), 0, 0, 1, 1);

    /* A flat fan that winds one and a half times around its centre:
     * triangles six apart overlap, and the loop's last side (from p9 back
     * to the centre) crosses the spiral near p3. */
    double fan[3 * 11] = {0};
    uint32_t fan_sizes[9], fan_faces[27];
    for (int i = 0; i < 10; i++) {
        double angle = 3.141592653589793 / 3 * i, radius = 1 + 0.125 * i;
        fan[3 * (i + 1)] = radius * cos(angle);
        fan[3 * (i + 1) + 1] = radius * sin(angle);
    }
    for (uint32_t i = 0; i < 9; i++) {
        fan_sizes[i] = 3;
        fan_faces[3 * i] = 0;
        fan_faces[3 * i + 1] = i + 1;
        fan_faces[3 * i + 2] = i + 2;
    }
    set_expected(add_mesh(l, "spiral_fan", fan, 11, fan_sizes, 9, fan_faces), -1, 0, 0, 1);
}

/* ---- generated solids ----------------------------------------------------------- */

static void add_generated_cases(case_list *l)
{
    mt_face_list list;
    memset(&list, 0, sizeof list);
    add_generated(l, "gen_cube", mt_gen_platonic(MT_CUBE, &list), &list, 0);
    add_generated(l, "gen_dodecahedron", mt_gen_platonic(MT_DODECAHEDRON, &list), &list, 0);
    add_generated(l, "gen_icosphere_2", mt_gen_icosphere(2, &list), &list, 0);
    add_generated(l, "gen_torus_16x8", mt_gen_torus(16, 8, &list), &list, 0);
    add_generated(l, "gen_grid_quads", mt_gen_grid(5, 3, false, &list), &list, 0);
    add_generated(l, "gen_grid_triangles", mt_gen_grid(5, 3, true, &list), &list, 0);
    add_generated(l, "gen_double_torus_8", mt_gen_double_torus(8, &list), &list, -1);
    add_generated(l, "gen_moebius_24", mt_gen_moebius(24, &list), &list, -1);
    add_generated(l, "gen_fin", mt_gen_fin(&list), &list, -1);
    add_generated(l, "gen_bowtie", mt_gen_bowtie(&list), &list, -1);
}

/* ---- random faces on a few points ------------------------------------------------- */

static uint64_t random_state;

static uint64_t next_random(void)
{
    uint64_t z = (random_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* num_faces random faces (one in five a quad) on num_verts random points
 * with coordinates origin + step * {0, 1, 2} (flat: z = origin). */
static void add_random(case_list *l, const char *name, uint64_t seed, uint32_t num_verts,
                       uint32_t num_faces, double origin, double step, bool flat)
{
    random_state = seed;
    double pos[3 * 16];
    uint32_t sizes[64], indices[4 * 64];
    if (num_verts > 16 || num_faces > 64) {
        l->failed = true;
        return;
    }
    for (uint32_t i = 0; i < 3 * num_verts; i++)
        pos[i] = flat && i % 3 == 2 ? origin : origin + step * (double)(next_random() % 3);
    uint32_t at = 0;
    for (uint32_t f = 0; f < num_faces; f++) {
        sizes[f] = next_random() % 5 == 0 ? 4 : 3;
        for (uint32_t k = 0; k < sizes[f]; k++) {
            uint32_t v;
            bool repeated;
            do { /* distinct corners, so that the build keeps the face */
                v = (uint32_t)(next_random() % num_verts);
                repeated = false;
                for (uint32_t m = 0; m < k; m++) repeated = repeated || indices[at + m] == v;
            } while (repeated);
            indices[at + k] = v;
        }
        at += sizes[f];
    }
    add_mesh(l, name, pos, num_verts, sizes, num_faces, indices);
}

static void add_random_cases(case_list *l)
{
    char name[48];
    for (uint64_t seed = 1; seed <= 8; seed++) {
        snprintf(name, sizeof name, "random_grid_%u", (unsigned)seed);
        add_random(l, name, seed, 10, 24, 0, 1, false);
        snprintf(name, sizeof name, "random_flat_%u", (unsigned)seed);
        add_random(l, name, 100 + seed, 9, 16, 0, 1, true);
        /* Far from the origin, a grid of 2^-30: doubles cannot evaluate
         * the predicates here without the exact fallback. */
        snprintf(name, sizeof name, "random_far_%u", (unsigned)seed);
        add_random(l, name, 200 + seed, 10, 24, 1048576.0, 1.0 / 1073741824.0, false);
    }
}

size_t sx_make_cases(sx_case *out, size_t capacity)
{
    case_list l = {out, 0, capacity, false};
    add_rule_cases(&l);
    add_shape_cases(&l);
    add_generated_cases(&l);
    add_random_cases(&l);
    if (l.failed) {
        for (size_t i = 0; i < l.count; i++) mt_face_list_free(&out[i].list);
        return 0;
    }
    return l.count;
}
