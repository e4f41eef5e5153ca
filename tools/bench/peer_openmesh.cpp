// meshtopo-bench's OpenMesh peer: builds OpenMesh::TriMesh_ArrayKernelT<>
// (default traits: float points, prev half-edges) from the benchmark input:
// reserve() of the counts run_peer passes, add_vertex for every vertex, then
// add_face per face (three handles for a triangle, the vector form otherwise,
// which OpenMesh triangulates). Sweeps every vertex with the vertex-vertex
// circulator and every face's half-edges for the faces across them; walks
// boundary half-edges into loops; labels components by a breadth-first walk
// over faces (OpenMesh has no components function of its own).
#include <OpenMesh/Core/System/config.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "peer_common.hpp"

namespace {

struct OpenMeshPeer {
    using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

    static const char *library() { return "OpenMesh"; }
    static bool option(const char *) { return false; }
    static void prepare(const mtbench::Input &, uint64_t &) {}

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

    static mtbench::Sweep ring_sweep(const Mesh &mesh)
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

    static mtbench::Sweep adj_sweep(const Mesh &mesh)
    {
        mtbench::Sweep s;
        const int n = int(mesh.n_faces());
        for (int f = 0; f < n; f++) {
            for (auto h = mesh.cfh_iter(Mesh::FaceHandle(f)); h.is_valid(); ++h) {
                Mesh::FaceHandle across = mesh.opposite_face_handle(*h);
                if (!across.is_valid()) continue;
                s.checksum += uint64_t(across.idx());
                s.neighbours++;
            }
        }
        return s;
    }

    // Boundary loops: cycles of boundary half-edges under next, as vertex lists.
    static mtbench::Loops loops(const Mesh &mesh)
    {
        mtbench::Loops out;
        std::vector<char> seen(mesh.n_halfedges(), 0);
        std::vector<int> verts;
        for (size_t h = 0; h < seen.size(); h++) {
            Mesh::HalfedgeHandle start{int(h)};
            if (seen[h] || !mesh.is_boundary(start)) continue;
            out.loops++;
            Mesh::HalfedgeHandle cur = start;
            size_t steps = 0;
            do {
                seen[size_t(cur.idx())] = 1;
                verts.push_back(mesh.to_vertex_handle(cur).idx());
                cur = mesh.next_halfedge_handle(cur);
            } while (cur != start && cur.is_valid() && ++steps < seen.size());
        }
        out.verts = verts.size();
        return out;
    }

    // Components: breadth-first over faces sharing an edge.
    static uint64_t components(Mesh &mesh)
    {
        const size_t n = mesh.n_faces();
        std::vector<uint32_t> label(n, UINT32_MAX);
        std::vector<int> queue;
        queue.reserve(n);
        uint32_t count = 0;
        for (size_t seed = 0; seed < n; seed++) {
            if (label[seed] != UINT32_MAX) continue;
            queue.clear();
            queue.push_back(int(seed));
            label[seed] = count;
            for (size_t i = 0; i < queue.size(); i++) {
                for (auto h = mesh.cfh_iter(Mesh::FaceHandle(queue[i])); h.is_valid(); ++h) {
                    Mesh::FaceHandle across = mesh.opposite_face_handle(*h);
                    if (!across.is_valid() || label[size_t(across.idx())] != UINT32_MAX) continue;
                    label[size_t(across.idx())] = count;
                    queue.push_back(across.idx());
                }
            }
            count++;
        }
        return count;
    }

    static mtbench::Topology topology(const Mesh &mesh)
    {
        mtbench::Topology t;
        t.verts = mesh.n_vertices();
        t.edges = mesh.n_edges();
        t.faces = mesh.n_faces();
        return t;
    }
};

}  // namespace

int main(int argc, char **argv)
{
    omerr().disable();  // failed faces are counted and reported by the driver
    char version[32];
    std::snprintf(version, sizeof version, "%d.%d.%d", OM_GET_VER, OM_GET_MAJ, OM_GET_MIN);
    return mtbench::run_peer<OpenMeshPeer>(argc, argv, version);
}
