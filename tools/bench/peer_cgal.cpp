// meshtopo-bench's CGAL peer: builds CGAL::Surface_mesh<Point_3> over
// Simple_cartesian<double> from the benchmark input, in one of two ways:
// the add loop (reserve() of the counts run_peer passes, add_vertex for every
// vertex, add_face per face), or with --soup Polygon_mesh_processing's
// polygon_soup_to_polygon_mesh on points and polygons prepared once, untimed.
// Queries: vertices_around_target on every vertex, the faces across every
// face's half-edges, border cycles as vertex lists, and
// Polygon_mesh_processing::connected_components. Needs neither GMP nor MPFR.
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/version.h>

#include <array>

#include "peer_common.hpp"

#define MT_BENCH_STR2(x) #x
#define MT_BENCH_STR(x) MT_BENCH_STR2(x)

namespace {

struct CgalPeer {
    using Kernel = CGAL::Simple_cartesian<double>;
    using Point = Kernel::Point_3;
    using Mesh = CGAL::Surface_mesh<Point>;
    using V = Mesh::Vertex_index;
    using F = Mesh::Face_index;
    using H = Mesh::Halfedge_index;

    static bool soup;
    static std::vector<Point> soup_points;
    static std::vector<std::array<uint32_t, 3>> soup_triangles;  // when every face is a triangle
    static std::vector<std::vector<uint32_t>> soup_polygons;     // otherwise

    static const char *library() { return soup ? "CGAL-soup" : "CGAL"; }

    static bool option(const char *arg)
    {
        if (std::strcmp(arg, "--soup") != 0) return false;
        soup = true;
        return true;
    }

    // The soup is made once: points, and the usable faces as index lists.
    static void prepare(const mtbench::Input &in, uint64_t &failed_faces)
    {
        if (!soup) return;
        const double *p = in.positions.data();
        soup_points.reserve(in.num_verts);
        for (uint32_t v = 0; v < in.num_verts; v++) {
            if (in.has_positions) {
                soup_points.emplace_back(p[3 * size_t(v)], p[3 * size_t(v) + 1],
                                         p[3 * size_t(v) + 2]);
            } else {
                soup_points.emplace_back(0, 0, 0);
            }
        }
        bool all_triangles = true;
        for (uint32_t size : in.sizes) all_triangles = all_triangles && size == 3;
        const uint32_t *fv = in.indices.data();
        for (uint32_t f = 0; f < in.num_faces; fv += in.sizes[f], f++) {
            uint32_t size = in.sizes[f];
            if (!mtbench::face_usable(fv, size, in.num_verts)) {
                failed_faces++;
                continue;
            }
            if (all_triangles) {
                soup_triangles.push_back({fv[0], fv[1], fv[2]});
            } else {
                soup_polygons.emplace_back(fv, fv + size);
            }
        }
    }

    static std::unique_ptr<Mesh> build(const mtbench::Input &in, const mtbench::Topology &reserve,
                                       uint64_t &failed_faces)
    {
        auto mesh = std::make_unique<Mesh>();
        if (soup) {
            if (!soup_polygons.empty()) {
                CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(soup_points,
                                                                            soup_polygons, *mesh);
            } else {
                CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(soup_points,
                                                                            soup_triangles, *mesh);
            }
            return mesh;
        }
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
            F fi;
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

    static mtbench::Sweep ring_sweep(const Mesh &mesh)
    {
        mtbench::Sweep s;
        for (V v : mesh.vertices()) {
            H h = mesh.halfedge(v);
            if (h == Mesh::null_halfedge()) continue;
            for (V u : CGAL::vertices_around_target(h, mesh)) {
                s.checksum += uint64_t(u.idx());
                s.neighbours++;
            }
        }
        return s;
    }

    static mtbench::Sweep adj_sweep(const Mesh &mesh)
    {
        mtbench::Sweep s;
        for (F f : mesh.faces()) {
            for (H h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh)) {
                F across = mesh.face(mesh.opposite(h));
                if (across == Mesh::null_face()) continue;
                s.checksum += uint64_t(across.idx());
                s.neighbours++;
            }
        }
        return s;
    }

    // Boundary loops: cycles of border half-edges under next, as vertex lists.
    static mtbench::Loops loops(const Mesh &mesh)
    {
        mtbench::Loops out;
        std::vector<char> seen(mesh.number_of_halfedges(), 0);
        std::vector<uint32_t> verts;
        for (H start : mesh.halfedges()) {
            if (seen[start.idx()] || !mesh.is_border(start)) continue;
            out.loops++;
            H cur = start;
            size_t steps = 0;
            do {
                seen[cur.idx()] = 1;
                verts.push_back(uint32_t(mesh.target(cur).idx()));
                cur = mesh.next(cur);
            } while (cur != start && ++steps < seen.size());
        }
        out.verts = verts.size();
        return out;
    }

    static uint64_t components(Mesh &mesh)
    {
        auto map = mesh.add_property_map<F, std::size_t>("f:mtbench_cc", 0).first;
        std::size_t count = CGAL::Polygon_mesh_processing::connected_components(mesh, map);
        mesh.remove_property_map(map);
        return count;
    }

    static mtbench::Topology topology(const Mesh &mesh)
    {
        mtbench::Topology t;
        t.verts = mesh.number_of_vertices();
        t.edges = mesh.number_of_edges();
        t.faces = mesh.number_of_faces();
        return t;
    }
};

bool CgalPeer::soup = false;
std::vector<CgalPeer::Point> CgalPeer::soup_points;
std::vector<std::array<uint32_t, 3>> CgalPeer::soup_triangles;
std::vector<std::vector<uint32_t>> CgalPeer::soup_polygons;

}  // namespace

int main(int argc, char **argv)
{
    return mtbench::run_peer<CgalPeer>(argc, argv, MT_BENCH_STR(CGAL_VERSION));
}
