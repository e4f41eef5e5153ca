// meshtopo-bench's CGAL peer: builds CGAL::Surface_mesh<Point_3> over
// Simple_cartesian<double> from the benchmark input: reserve() of the counts
// run_peer passes, add_vertex for every vertex, add_face per face. Sweeps
// every vertex with vertices_around_target. Simple_cartesian<double> needs
// neither GMP nor MPFR.
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/version.h>

#include "peer_common.hpp"

#define MT_BENCH_STR2(x) #x
#define MT_BENCH_STR(x) MT_BENCH_STR2(x)

namespace {

struct CgalPeer {
    using Kernel = CGAL::Simple_cartesian<double>;
    using Point = Kernel::Point_3;
    using Mesh = CGAL::Surface_mesh<Point>;
    using V = Mesh::Vertex_index;

    static std::unique_ptr<Mesh> build(const mtbench::Input &in, const mtbench::Topology &reserve,
                                       uint64_t &failed_faces)
    {
        auto mesh = std::make_unique<Mesh>();
        if (reserve.verts) mesh->reserve(reserve.verts, reserve.edges, reserve.faces);
        const double *p = in.positions.data();
        for (uint32_t v = 0; v < in.num_verts; v++) {
            if (in.has_positions) {
                mesh->add_vertex(
                    Point(p[3 * size_t(v)], p[3 * size_t(v) + 1], p[3 * size_t(v) + 2]));
            } else {
                mesh->add_vertex(Point(0, 0, 0));
            }
        }
        std::vector<V> polygon;
        const uint32_t *fv = in.indices.data();
        for (uint32_t f = 0; f < in.num_faces; fv += in.sizes[f], f++) {
            uint32_t size = in.sizes[f];
            if (!mtbench::face_usable(fv, size, in.num_verts)) {
                failed_faces++;
                continue;
            }
            Mesh::Face_index fi;
            if (size == 3) {
                fi = mesh->add_face(V(fv[0]), V(fv[1]), V(fv[2]));
            } else {
                polygon.clear();
                for (uint32_t i = 0; i < size; i++) polygon.emplace_back(fv[i]);
                fi = mesh->add_face(polygon);
            }
            if (fi == Mesh::null_face()) failed_faces++;
        }
        return mesh;
    }

    static mtbench::Sweep sweep(const Mesh &mesh)
    {
        mtbench::Sweep s;
        for (V v : mesh.vertices()) {
            Mesh::Halfedge_index h = mesh.halfedge(v);
            if (h == Mesh::null_halfedge()) continue;
            for (V u : CGAL::vertices_around_target(h, mesh)) {
                s.checksum += uint64_t(u.idx());
                s.neighbours++;
            }
        }
        return s;
    }

    // Boundary loops: cycles of border half-edges under next.
    static mtbench::Topology topology(const Mesh &mesh)
    {
        mtbench::Topology t;
        t.verts = mesh.number_of_vertices();
        t.edges = mesh.number_of_edges();
        t.faces = mesh.number_of_faces();
        std::vector<char> seen(mesh.number_of_halfedges(), 0);
        for (Mesh::Halfedge_index start : mesh.halfedges()) {
            if (seen[start.idx()] || !mesh.is_border(start)) continue;
            t.boundary_loops++;
            Mesh::Halfedge_index cur = start;
            size_t steps = 0;
            do {
                seen[cur.idx()] = 1;
                cur = mesh.next(cur);
            } while (cur != start && ++steps < seen.size());
        }
        return t;
    }
};

}  // namespace

int main(int argc, char **argv)
{
    return mtbench::run_peer<CgalPeer>(argc, argv, "CGAL", MT_BENCH_STR(CGAL_VERSION));
}
