// core.intersect_vs_cgal: meshtopo's exact triangle intersection test
// (mt_triangles_intersect, meshtopo/predicates.h) against CGAL's
// do_intersect with exact predicates, on random non-degenerate triangles:
// small integer coordinates (touching, coplanar and shared corners are
// frequent), and triangles moved by one representable step off touching
// far from the origin. Any disagreement fails, naming the two triangles.
// Built only where CGAL's headers are found (libcgal-dev).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "meshtopo/predicates.h"

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;

static uint64_t state = 20261126;

static uint64_t next_random()
{
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static K::Triangle_3 cgal_triangle(const double t[3][3])
{
    return K::Triangle_3(K::Point_3(t[0][0], t[0][1], t[0][2]), K::Point_3(t[1][0], t[1][1], t[1][2]),
                         K::Point_3(t[2][0], t[2][1], t[2][2]));
}

static void print_triangle(const double t[3][3])
{
    for (int i = 0; i < 3; i++) std::printf(" (%.17g %.17g %.17g)", t[i][0], t[i][1], t[i][2]);
}

// Compares one pair; returns 1 when they disagree.
static int compare(const double a[3][3], const double b[3][3], long *hits, long *pairs)
{
    K::Triangle_3 ta = cgal_triangle(a), tb = cgal_triangle(b);
    if (ta.is_degenerate() || tb.is_degenerate()) return 0;
    bool theirs = CGAL::do_intersect(ta, tb);
    bool ours = mt_triangles_intersect(a, b);
    (*pairs)++;
    *hits += ours;
    if (ours == theirs) return 0;
    std::printf("disagree: meshtopo %d, CGAL %d:", ours, theirs);
    print_triangle(a);
    std::printf(" vs");
    print_triangle(b);
    std::printf("\n");
    return 1;
}

int main()
{
    int wrong = 0;
    long hits = 0, pairs = 0;
    // Small integer coordinates: lots of touching and coplanar pairs.
    for (int round = 0; round < 200000 && wrong < 10; round++) {
        double a[3][3], b[3][3];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) {
                a[i][k] = (double)(next_random() % 4);
                b[i][k] = (double)(next_random() % 4);
            }
        wrong += compare(a, b, &hits, &pairs);
    }
    // Far from the origin: b's first corner on a's plane (exactly, by
    // construction from a's corners with dyadic weights) then moved by
    // one representable step in a random direction.
    const double o = 1048576.0;
    for (int round = 0; round < 100000 && wrong < 10; round++) {
        double a[3][3], b[3][3];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) a[i][k] = o + (double)(next_random() % 1024);
        double s = (double)(next_random() % 9) / 8, t = (double)(next_random() % 9) / 8;
        for (int k = 0; k < 3; k++) {
            b[0][k] = a[0][k] + s * (a[1][k] - a[0][k]) + t * (a[2][k] - a[0][k]);
            int dir = (int)(next_random() % 3) - 1;
            if (dir) b[0][k] = std::nextafter(b[0][k], dir > 0 ? INFINITY : -INFINITY);
        }
        for (int i = 1; i < 3; i++)
            for (int k = 0; k < 3; k++) b[i][k] = b[0][k] + (double)(next_random() % 64) - 32;
        wrong += compare(a, b, &hits, &pairs);
    }
    std::printf("core.intersect_vs_cgal: %ld pairs of triangles, %ld intersecting, %d disagreements "
                "with CGAL\n",
                pairs, hits, wrong);
    return wrong ? 1 : 0;
}
