// meshtopo-bench selfx's CGAL peer: Polygon_mesh_processing::self_intersections
// on a Surface_mesh over Exact_predicates_inexact_constructions_kernel (exact
// predicates, as meshtopo's are), built once, untimed, from the benchmark's
// raw input file (bench_input.c, read by peer_common.hpp). Protocol, one line
// each way:
//   peer -> ready lib=CGAL version=V kernel=Epick faces=F failed_faces=N parallel=0|1
//   "run sequential" | "run parallel" -> rep ms=T pairs=N hash=H reported=R
//   "list" -> one "pair A B" line per pair of the last run, then "end pairs=N"
//   "quit" or the end of stdin ends it; "error TEXT" and exit status 1 on failure.
// Only the self_intersections call is timed. Its output is then turned into
// input face ids, a <= b, sorted, each pair once (pairs); reported is how
// many CGAL wrote. hash is the one bench_selfx.c computes over meshtopo's
// pairs. parallel=1 only when compiled with TBB (CGAL_LINKED_WITH_TBB).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/version.h>

#include <algorithm>
#include <iterator>
#include <utility>

#include "peer_common.hpp"

#define MT_BENCH_STR2(x) #x
#define MT_BENCH_STR(x) MT_BENCH_STR2(x)

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using V = Mesh::Vertex_index;
using F = Mesh::Face_index;
using FacePair = std::pair<uint32_t, uint32_t>;

#ifdef CGAL_LINKED_WITH_TBB
constexpr bool have_parallel = true;
#else
constexpr bool have_parallel = false;
#endif

// splitmix64's finaliser; the pair hash of bench_selfx.c (keep the two equal).
uint64_t mix(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

uint64_t pairs_hash(const std::vector<FacePair> &pairs)
{
    uint64_t h = 0;
    for (const FacePair &p : pairs) h = mix(h ^ (uint64_t(p.first) << 32 | p.second));
    return h;
}

// Every vertex, then each triangle that can be added; face_ids[k] is the
// input id of the mesh's face k. Anything else counts as failed.
bool build(const mtbench::Input &in, Mesh &mesh, std::vector<uint32_t> &face_ids, uint64_t &failed,
           std::string &err)
{
    if (!in.has_positions) {
        err = "the input has no positions";
        return false;
    }
    mesh.reserve(in.num_verts, 3 * size_t(in.num_faces) / 2 + 1, in.num_faces);
    const double *p = in.positions.data();
    for (uint32_t v = 0; v < in.num_verts; v++) {
        mesh.add_vertex(Point(p[3 * size_t(v)], p[3 * size_t(v) + 1], p[3 * size_t(v) + 2]));
    }
    const uint32_t *fv = in.indices.data();
    for (uint32_t f = 0; f < in.num_faces; fv += in.sizes[f], f++) {
        if (in.sizes[f] != 3 || !mtbench::face_usable(fv, 3, in.num_verts)) {
            failed++;
            continue;
        }
        F added = mesh.add_face(V(fv[0]), V(fv[1]), V(fv[2]));
        if (added == Mesh::null_face()) {
            failed++;
            continue;
        }
        face_ids.push_back(f);
    }
    return true;
}

// CGAL's pairs as input face ids, smaller first, sorted, duplicates removed.
void normalise(const std::vector<std::pair<F, F>> &raw, const std::vector<uint32_t> &face_ids,
               std::vector<FacePair> &out)
{
    out.clear();
    out.reserve(raw.size());
    for (const auto &r : raw) {
        uint32_t a = face_ids[r.first.idx()], b = face_ids[r.second.idx()];
        out.emplace_back(std::min(a, b), std::max(a, b));
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

template <class Tag>
double timed_run(const Mesh &mesh, std::vector<std::pair<F, F>> &raw)
{
    raw.clear();
    double t0 = mtbench::now_ms();
    CGAL::Polygon_mesh_processing::self_intersections<Tag>(mesh, std::back_inserter(raw));
    return mtbench::now_ms() - t0;
}

int run(const char *path)
{
    mtbench::Input in;
    std::string err;
    if (!mtbench::read_input(path, in, err)) {
        std::printf("error %s\n", err.c_str());
        return 1;
    }
    Mesh mesh;
    std::vector<uint32_t> face_ids;
    uint64_t failed = 0;
    if (!build(in, mesh, face_ids, failed, err)) {
        std::printf("error %s\n", err.c_str());
        return 1;
    }
    in = mtbench::Input();  // only the mesh is needed from here on
    std::printf("ready lib=CGAL version=%s kernel=Epick faces=%llu failed_faces=%llu parallel=%d\n",
                MT_BENCH_STR(CGAL_VERSION), (unsigned long long)mesh.number_of_faces(),
                (unsigned long long)failed, have_parallel ? 1 : 0);
    std::fflush(stdout);

    std::vector<std::pair<F, F>> raw;
    std::vector<FacePair> pairs;
    char line[256];
    while (std::fgets(line, sizeof line, stdin)) {
        line[std::strcspn(line, "\r\n")] = '\0';
        if (std::strcmp(line, "quit") == 0) break;
        if (std::strcmp(line, "list") == 0) {
            for (const FacePair &p : pairs) std::printf("pair %u %u\n", p.first, p.second);
            std::printf("end pairs=%zu\n", pairs.size());
            std::fflush(stdout);
            continue;
        }
        double ms;
        if (std::strcmp(line, "run sequential") == 0) {
            ms = timed_run<CGAL::Sequential_tag>(mesh, raw);
#ifdef CGAL_LINKED_WITH_TBB
        } else if (std::strcmp(line, "run parallel") == 0) {
            ms = timed_run<CGAL::Parallel_tag>(mesh, raw);
#endif
        } else {
            std::printf("error unknown command '%s'\n", line);
            return 1;
        }
        normalise(raw, face_ids, pairs);
        std::printf("rep ms=%.4f pairs=%zu hash=%llu reported=%zu\n", ms, pairs.size(),
                    (unsigned long long)pairs_hash(pairs), raw.size());
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc != 2) {
        std::fprintf(stderr,
                     "usage: %s INPUT\n"
                     "Reads a meshtopo-bench input file of triangles, builds a CGAL Surface_mesh,\n"
                     "then answers \"run sequential\" (or \"run parallel\") with one timed\n"
                     "Polygon_mesh_processing::self_intersections and \"list\" with its pairs.\n",
                     argv[0]);
        return 2;
    }
    try {
        return run(argv[1]);
    } catch (const std::exception &e) {
        std::printf("error %s\n", e.what());
        return 1;
    }
}
