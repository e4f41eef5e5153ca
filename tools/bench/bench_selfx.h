/* Shared declarations of `meshtopo-bench selfx`: mt_mesh_self_intersections
 * next to CGAL's Polygon_mesh_processing::self_intersections (a peer process,
 * peer_cgal_selfx.cpp) on meshes of about a million triangles with a few
 * hundred planted self-intersections, and the rate of mt_mesh_nonsimple_faces
 * on a mesh of polygons. bench_selfx.c runs and prints, selfx_input.c makes
 * the meshes, selfx_cgal.c talks to the peer. */
#ifndef MESHTOPO_BENCH_SELFX_H
#define MESHTOPO_BENCH_SELFX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "bench.h"
#include "meshtopo/face_list.h"
#include "meshtopo/geometry.h"

/* Entry point: `meshtopo-bench selfx [options]` (argv[0] is "selfx").
 * Returns 0 when every measurement ran and both libraries found the same
 * pairs (a missed target included), 1 when one failed or they disagree, 2 on
 * a usage error. */
int mt__bench_selfx_command(int argc, char **argv);

/* The hash both sides compute over their sorted pairs (peer_cgal_selfx.cpp
 * has the same): h = 0, then for each pair h = splitmix64-finaliser(h ^
 * (a << 32 | b)). */
uint64_t mt__selfx_pairs_hash(const mt_face_pair *pairs, size_t count);

/* ---- selfx_input.c -------------------------------------------------------- */

/* The planted meshes: 0 is a triangulated grid with a breaking wave (a bump
 * whose crest is pushed sideways and down through the flat grid and through
 * itself), 1 a closed torus with fingers pushed in from its outer equator
 * through the opposite (inner) wall. About `faces` triangles each. *out is
 * allocated (mt_face_list_free); name gets a short description. */
#define MT__SELFX_NUM_MESHES 2
bool mt__selfx_mesh_make(uint32_t which, uint64_t faces, uint64_t seed, mt_face_list *out,
                         char *name, size_t name_size, char *err, size_t err_size);

/* The polygon mesh of the mt_mesh_nonsimple_faces rate: the dual of the
 * finest icosphere whose dual has at most `faces` faces (pentagons and
 * hexagons), built. */
bool mt__selfx_polygon_mesh_make(uint64_t faces, mt_mesh **out, char *name, size_t name_size,
                                 char *err, size_t err_size);

/* ---- selfx_cgal.c --------------------------------------------------------- */

/* The CGAL peer of one input file. */
typedef struct mt__selfx_cgal {
    mt__bench_child child;
    bool started;
    bool parallel;    /* the peer was compiled with TBB: "run parallel" works */
    char version[32]; /* CGAL's */
    uint64_t faces, failed_faces;
} mt__selfx_cgal;

/* One run's answer. */
typedef struct mt__selfx_answer {
    double ms;
    uint64_t pairs, hash;
    uint64_t reported; /* pairs as CGAL wrote them, before duplicates were removed */
} mt__selfx_answer;

/* Starts the peer `exe` on a raw input file and reads its ready line. */
bool mt__selfx_cgal_start(mt__selfx_cgal *peer, const char *exe, const char *input_path, char *err,
                          size_t err_size);
/* One timed self_intersections call: Sequential_tag, or Parallel_tag. */
bool mt__selfx_cgal_run(mt__selfx_cgal *peer, bool parallel, mt__selfx_answer *out, char *err,
                        size_t err_size);
/* The pairs of the peer's last run (sorted, a <= b): *out is malloc'd. */
bool mt__selfx_cgal_list(mt__selfx_cgal *peer, mt_face_pair **out, size_t *out_count, char *err,
                         size_t err_size);
void mt__selfx_cgal_stop(mt__selfx_cgal *peer);

#endif
