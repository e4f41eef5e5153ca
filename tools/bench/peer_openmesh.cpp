// meshtopo-bench's OpenMesh peer: builds OpenMesh::TriMesh_ArrayKernelT<>
// (default traits: float points, prev half-edges) from the benchmark input:
// reserve() of the counts run_peer passes, add_vertex for every vertex, then
// add_face per face (three handles for a triangle, the vector form otherwise,
// which OpenMesh triangulates). Sweeps every vertex with the vertex-vertex
// circulator.
#include <OpenMesh/Core/System/config.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "peer_common.hpp"

namespace {

struct OpenMeshPeer {
    using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

    static std::unique_ptr<Mesh> build(const mtbench::Input &in, const mtbench::Topology &reserve,
                                       uint64_t &failed_faces)
    {
        auto mesh = std::make_unique<Mesh>();
        if (reserve.verts) mesh->reserve(reserve.verts, reserve.edges, reserve.faces);
        const double *p = in.positions.data();
        for (uint32_t v = 0; v < in.num_verts; v++) {
            if (in.has_positions) {
                mesh->add_vertex(Mesh::Point(float(p[3 * size_t(v)]), float(p[3 * size_t(v) + 1]),
                                             float(p[3 * size_t(v) + 2])));
            } else {
                mesh->add_vertex(Mesh::Point(0.0f, 0.0f, 0.0f));
            }
        }
        std::vector<Mesh::VertexHandle> polygon;
        const uint32_t *fv = in.indices.data();
        for (uint32_t f = 0; f < in.num_faces; fv += in.sizes[f], f++) {
            uint32_t size = in.sizes[f];
            if (!mtbench::face_usable(fv, size, in.num_verts)) {
                failed_faces++;
                continue;
            }
            Mesh::FaceHandle fh;
            if (size == 3) {
                fh = mesh->add_face(Mesh::VertexHandle(int(fv[0])), Mesh::VertexHandle(int(fv[1])),
                                    Mesh::VertexHandle(int(fv[2])));
            } else {
                polygon.clear();
                for (uint32_t i = 0; i < size; i++) polygon.emplace_back(int(fv[i]));
                fh = mesh->add_face(polygon);
            }
            if (!fh.is_valid()) failed_faces++;
        }
        return mesh;
    }

    static mtbench::Sweep sweep(const Mesh &mesh)
    {
        mtbench::Sweep s;
        const int n = int(mesh.n_vertices());
        for (int v = 0; v < n; v++) {
            for (auto vv = mesh.cvv_iter(Mesh::VertexHandle(v)); vv.is_valid(); ++vv) {
                s.checksum += uint64_t(vv->idx());
                s.neighbours++;
            }
        }
        return s;
    }

    // Boundary loops: cycles of boundary half-edges under next.
    static mtbench::Topology topology(const Mesh &mesh)
    {
        mtbench::Topology t;
        t.verts = mesh.n_vertices();
        t.edges = mesh.n_edges();
        t.faces = mesh.n_faces();
        std::vector<char> seen(mesh.n_halfedges(), 0);
        for (size_t h = 0; h < seen.size(); h++) {
            Mesh::HalfedgeHandle start{int(h)};
            if (seen[h] || !mesh.is_boundary(start)) continue;
            t.boundary_loops++;
            Mesh::HalfedgeHandle cur = start;
            size_t steps = 0;
            do {
                seen[size_t(cur.idx())] = 1;
                cur = mesh.next_halfedge_handle(cur);
            } while (cur != start && cur.is_valid() && ++steps < seen.size());
        }
        return t;
    }
};

}  // namespace

int main(int argc, char **argv)
{
    omerr().disable();  // failed faces are counted and reported by the driver
    char version[32];
    std::snprintf(version, sizeof version, "%d.%d.%d", OM_GET_VER, OM_GET_MAJ, OM_GET_MIN);
    return mtbench::run_peer<OpenMeshPeer>(argc, argv, "OpenMesh", version);
}
