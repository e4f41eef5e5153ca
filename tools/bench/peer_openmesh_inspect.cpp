// The OpenMesh peer of `meshtopo-bench inspect`: what `meshtopo inspect
// FILE` does, with OpenMesh 9: reads FILE with OpenMesh::IO::read_mesh into a
// TriMesh_ArrayKernelT<> (default traits), then counts vertices, edges and
// faces, boundary loops (cycles of boundary half-edges under next) and
// connected components (faces sharing an edge, breadth-first), and prints
// them on one line with the read and total times in milliseconds:
//   verts=V edges=E faces=F boundary_loops=L components=C read_ms=R total_ms=T
// With --read-only it stops after reading (read_ms only). Exit 1 when the file
// cannot be read.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

uint64_t boundary_loops(const Mesh &mesh)
{
    std::vector<char> seen(mesh.n_halfedges(), 0);
    uint64_t loops = 0;
    for (size_t h = 0; h < seen.size(); h++) {
        Mesh::HalfedgeHandle start{int(h)};
        if (seen[h] || !mesh.is_boundary(start)) continue;
        loops++;
        Mesh::HalfedgeHandle cur = start;
        size_t steps = 0;
        do {
            seen[size_t(cur.idx())] = 1;
            cur = mesh.next_halfedge_handle(cur);
        } while (cur != start && cur.is_valid() && ++steps < seen.size());
    }
    return loops;
}

uint64_t components(const Mesh &mesh)
{
    const size_t n = mesh.n_faces();
    std::vector<char> seen(n, 0);
    std::vector<int> queue;
    queue.reserve(n);
    uint64_t count = 0;
    for (size_t seed = 0; seed < n; seed++) {
        if (seen[seed]) continue;
        queue.clear();
        queue.push_back(int(seed));
        seen[seed] = 1;
        for (size_t i = 0; i < queue.size(); i++) {
            for (auto h = mesh.cfh_iter(Mesh::FaceHandle(queue[i])); h.is_valid(); ++h) {
                Mesh::FaceHandle across = mesh.opposite_face_handle(*h);
                if (!across.is_valid() || seen[size_t(across.idx())]) continue;
                seen[size_t(across.idx())] = 1;
                queue.push_back(across.idx());
            }
        }
        count++;
    }
    return count;
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3 || (argc == 3 && std::strcmp(argv[2], "--read-only") != 0)) {
        std::fprintf(stderr, "usage: %s FILE [--read-only]\n", argv[0]);
        return 2;
    }
    const bool read_only = argc == 3;
    auto t0 = Clock::now();
    Mesh mesh;
    OpenMesh::IO::Options options;
    if (!OpenMesh::IO::read_mesh(mesh, argv[1], options)) {
        std::fprintf(stderr, "%s: OpenMesh cannot read %s\n", argv[0], argv[1]);
        return 1;
    }
    double read_ms = ms_since(t0);
    if (read_only) {
        std::printf("verts=%zu faces=%zu read_ms=%.3f\n", size_t(mesh.n_vertices()),
                    size_t(mesh.n_faces()), read_ms);
        return 0;
    }
    uint64_t loops = boundary_loops(mesh);
    uint64_t comps = components(mesh);
    double total_ms = ms_since(t0);
    std::printf(
        "verts=%zu edges=%zu faces=%zu boundary_loops=%llu components=%llu read_ms=%.3f "
        "total_ms=%.3f\n",
        size_t(mesh.n_vertices()), size_t(mesh.n_edges()), size_t(mesh.n_faces()),
        (unsigned long long)loops, (unsigned long long)comps, read_ms, total_ms);
    return 0;
}
