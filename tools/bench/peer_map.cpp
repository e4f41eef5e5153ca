// The peers of `meshtopo-bench map`: the same first build and steps as the
// driver (map_surface.h, generated here from the same parameters) done with
// OpenMesh's dynamic TriMesh (MT_MAP_PEER_OPENMESH) or CGAL Surface_mesh
// (MT_MAP_PEER_CGAL): delete a block's old faces (and the vertices left
// isolated), weld the new version's vertices through a position hash, add its
// faces; garbage collection only when deleted faces pass 10 % of the live ones.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <unordered_map>
#include <vector>

#include "map_surface.h"  // static inline only: no C linkage needed

#if defined(MT_MAP_PEER_OPENMESH)
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#elif defined(MT_MAP_PEER_CGAL)
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#else
#error "define MT_MAP_PEER_OPENMESH or MT_MAP_PEER_CGAL"
#endif

namespace {

double now_ms()
{
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

// A position as a hash key: bitwise, with -0.0 taken as 0.0 (the map's
// exact weld; the surface has no NaN).
struct Key {
    double x, y, z;
    bool operator==(const Key &o) const { return x == o.x && y == o.y && z == o.z; }
};
struct KeyHash {
    size_t operator()(const Key &k) const
    {
        uint64_t b[3];
        double v[3] = {k.x + 0.0, k.y + 0.0, k.z + 0.0};
        std::memcpy(b, v, sizeof b);
        return size_t(mt__map_mix(b[0] ^ mt__map_mix(b[1] ^ mt__map_mix(b[2]))));
    }
};
Key key_of(const double *p)
{
    return Key{p[0] + 0.0, p[1] + 0.0, p[2] + 0.0};
}

#if defined(MT_MAP_PEER_OPENMESH)
// OpenMesh with double points (the weld hash is rebuilt from them after a
// collection); status attributes for deletion; a face property "block".
struct DoubleTraits : OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
struct Lib {
    using Mesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;
    Mesh m;
    OpenMesh::FPropHandleT<int> block;
    uint64_t deleted = 0;
    Lib()
    {
        m.request_vertex_status();
        m.request_edge_status();
        m.request_halfedge_status();
        m.request_face_status();
        m.add_property(block);
    }
    static const char *name() { return "OpenMesh"; }
    uint32_t add_vertex(const double *p)
    {
        return uint32_t(m.add_vertex(Mesh::Point(p[0], p[1], p[2])).idx());
    }
    bool add_face(uint32_t a, uint32_t b, uint32_t c, int blk, uint32_t *out)
    {
        auto f = m.add_face(m.vertex_handle(a), m.vertex_handle(b), m.vertex_handle(c));
        if (!f.is_valid()) return false;
        m.property(block, f) = blk;
        *out = uint32_t(f.idx());
        return true;
    }
    void face_verts(uint32_t f, std::vector<uint32_t> &out)
    {
        for (auto v : m.fv_range(m.face_handle(int(f)))) out.push_back(uint32_t(v.idx()));
    }
    void remove_face(uint32_t f)
    {
        m.delete_face(m.face_handle(int(f)), true);
        deleted++;
    }
    bool vertex_removed(uint32_t v) { return m.status(m.vertex_handle(int(v))).deleted(); }
    void vert_pos(uint32_t v, double *out)
    {
        auto p = m.point(m.vertex_handle(int(v)));
        out[0] = p[0], out[1] = p[1], out[2] = p[2];
    }
    uint64_t live_faces() { return m.n_faces() - deleted; }
    void collect() { m.garbage_collection(), deleted = 0; }
    // After a collection: every live face with its block, every vertex.
    template <class FF, class VF>
    void scan(FF on_face, VF on_vert)
    {
        for (auto f : m.faces()) on_face(uint32_t(f.idx()), m.property(block, f));
        for (auto v : m.vertices()) {
            auto p = m.point(v);
            double d[3] = {p[0], p[1], p[2]};
            on_vert(uint32_t(v.idx()), d);
        }
    }
    uint64_t live_verts()
    {
        uint64_t n = 0;
        for (auto v : m.vertices()) n += !m.status(v).deleted();
        return n;
    }
};
#else
// CGAL Surface_mesh: Euler::remove_face removes the face and what it leaves
// isolated; a face property "block".
struct Lib {
    using Kernel = CGAL::Simple_cartesian<double>;
    using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
    using V = Mesh::Vertex_index;
    using F = Mesh::Face_index;
    Mesh m;
    Mesh::Property_map<F, int> block;
    Lib() { block = m.add_property_map<F, int>("f:block", -1).first; }
    static const char *name() { return "CGAL"; }
    uint32_t add_vertex(const double *p)
    {
        return uint32_t(m.add_vertex(Kernel::Point_3(p[0], p[1], p[2])));
    }
    bool add_face(uint32_t a, uint32_t b, uint32_t c, int blk, uint32_t *out)
    {
        F f = m.add_face(V(a), V(b), V(c));
        if (f == Mesh::null_face()) return false;
        block[f] = blk;
        *out = uint32_t(f);
        return true;
    }
    void face_verts(uint32_t f, std::vector<uint32_t> &out)
    {
        for (V v : m.vertices_around_face(m.halfedge(F(f)))) out.push_back(uint32_t(v));
    }
    void remove_face(uint32_t f) { CGAL::Euler::remove_face(m.halfedge(F(f)), m); }
    bool vertex_removed(uint32_t v) { return m.is_removed(V(v)); }
    void vert_pos(uint32_t v, double *out)
    {
        const auto &p = m.point(V(v));
        out[0] = p.x(), out[1] = p.y(), out[2] = p.z();
    }
    uint64_t deleted_faces() { return m.number_of_removed_faces(); }
    uint64_t live_faces() { return m.number_of_faces(); }
    void collect() { m.collect_garbage(); }
    template <class FF, class VF>
    void scan(FF on_face, VF on_vert)
    {
        for (F f : m.faces()) on_face(uint32_t(f), block[f]);
        for (V v : m.vertices()) {
            const auto &p = m.point(v);
            double d[3] = {p.x(), p.y(), p.z()};
            on_vert(uint32_t(v), d);
        }
    }
    uint64_t live_verts() { return m.number_of_vertices(); }
};
#endif

uint64_t deleted_of(Lib &lib)
{
#if defined(MT_MAP_PEER_OPENMESH)
    return lib.deleted;
#else
    return lib.deleted_faces();
#endif
}

struct Peer {
    Lib lib;
    std::unordered_map<Key, uint32_t, KeyHash> weld;
    std::vector<std::vector<uint32_t>> block_faces;
    std::vector<uint32_t> old_verts, ids;
    uint64_t collections = 0;
    std::string error;

    // Replaces (or adds) block blk with the face list (pos, idx).
    bool put(int blk, const mt__map_surface &s, const double *pos, const uint32_t *idx)
    {
        std::vector<uint32_t> &faces = block_faces[size_t(blk)];
        old_verts.clear();
        for (uint32_t f : faces) lib.face_verts(f, old_verts);
        std::sort(old_verts.begin(), old_verts.end());
        old_verts.erase(std::unique(old_verts.begin(), old_verts.end()), old_verts.end());
        for (uint32_t f : faces) lib.remove_face(f);
        faces.clear();
        // The vertices the removal left isolated are gone: so are their
        // hash entries (CGAL may hand their indices out again). A removed
        // vertex keeps its point until its slot is reused or collected.
        double p[3];
        for (uint32_t v : old_verts) {
            if (!lib.vertex_removed(v)) continue;
            lib.vert_pos(v, p);
            auto it = weld.find(key_of(p));
            if (it != weld.end() && it->second == v) weld.erase(it);
        }
        uint32_t nv = mt__map_block_verts(&s), nf = mt__map_block_faces(&s);
        ids.resize(nv);
        for (uint32_t i = 0; i < nv; i++) {
            const double *p = pos + 3 * size_t(i);
            auto it = weld.find(key_of(p));
            if (it != weld.end()) {
                ids[i] = it->second;
            } else {
                ids[i] = lib.add_vertex(p);
                weld.emplace(key_of(p), ids[i]);
            }
        }
        faces.reserve(nf);
        for (uint32_t f = 0; f < nf; f++) {
            const uint32_t *t = idx + 3 * size_t(f);
            uint32_t id;
            if (!lib.add_face(ids[t[0]], ids[t[1]], ids[t[2]], blk, &id)) {
                error = "add_face refused face " + std::to_string(f) + " of block " +
                        std::to_string(blk);
                return false;
            }
            faces.push_back(id);
        }
        if (deleted_of(lib) * 10 > lib.live_faces()) collect();
        return true;
    }

    // Garbage collection, then the block lists and the hash rebuilt (the
    // handles changed): counted in the step that triggers it.
    void collect()
    {
        lib.collect();
        collections++;
        for (auto &f : block_faces) f.clear();
        weld.clear();
        lib.scan([&](uint32_t f, int b) { block_faces[size_t(b)].push_back(f); },
                 [&](uint32_t v, const double *p) { weld.emplace(key_of(p), v); });
    }
};

}  // namespace

int main(int argc, char **argv)
{
    mt__map_surface s{0, 0, 0, 0.0};
    uint64_t seed = 0;
    uint32_t steps = 0;
    for (int i = 1; i + 1 < argc; i += 2) {
        std::string a = argv[i];
        const char *v = argv[i + 1];
        if (a == "--tiles-x")
            s.tiles_x = uint32_t(std::strtoul(v, nullptr, 10));
        else if (a == "--tiles-y")
            s.tiles_y = uint32_t(std::strtoul(v, nullptr, 10));
        else if (a == "--cells")
            s.cells = uint32_t(std::strtoul(v, nullptr, 10));
        else if (a == "--voxel")
            s.voxel = std::strtod(v, nullptr);
        else if (a == "--seed")
            seed = std::strtoull(v, nullptr, 10);
        else if (a == "--steps")
            steps = uint32_t(std::strtoul(v, nullptr, 10));
    }
    if (!s.tiles_x || !s.tiles_y || !s.cells || !(s.voxel > 0) || !steps) {
        std::printf("error usage: --tiles-x --tiles-y --cells --voxel --seed --steps\n");
        return 2;
    }
    uint32_t nb = s.tiles_x * s.tiles_y, per_step = mt__map_step_count(&s);
    std::vector<double> pos(3 * size_t(mt__map_block_verts(&s)));
    std::vector<uint32_t> idx(3 * size_t(mt__map_block_faces(&s)));
    std::vector<uint32_t> picks(per_step);
    Peer peer;
    peer.block_faces.resize(nb);
    peer.weld.reserve(size_t(nb) * mt__map_block_verts(&s));
    bool ok = true;
    double first = 0;
    for (uint32_t b = 0; ok && b < nb; b++) {
        mt__map_block_fill(&s, b % s.tiles_x, b / s.tiles_x, 0, seed, pos.data(), idx.data());
        double t0 = now_ms();
        ok = peer.put(int(b), s, pos.data(), idx.data());
        first += now_ms() - t0;
    }
    std::vector<double> step_ms;
    double total = 0;
    for (uint32_t step = 0; ok && step < steps; step++) {
        mt__map_step_blocks(&s, seed, step, per_step, picks.data());
        double t = 0;
        for (uint32_t k = 0; ok && k < per_step; k++) {
            mt__map_block_fill(&s, picks[k] % s.tiles_x, picks[k] / s.tiles_x, step + 1, seed,
                               pos.data(), idx.data());
            double t0 = now_ms();
            ok = peer.put(int(picks[k]), s, pos.data(), idx.data());
            t += now_ms() - t0;
        }
        step_ms.push_back(t);
        total += t;
    }
    if (!ok) {
        std::printf("error %s: %s\n", Lib::name(), peer.error.c_str());
        std::fflush(stdout);
        return 1;
    }
    std::vector<double> sorted = step_ms;
    std::sort(sorted.begin(), sorted.end());
    size_t n = sorted.size();
    double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    std::printf(
        "result first_ms=%.6f step_ms=%.6f mean_ms=%.6f faces=%llu verts=%llu "
        "collections=%llu\n",
        first, median, total / double(steps), (unsigned long long)peer.lib.live_faces(),
        (unsigned long long)peer.lib.live_verts(), (unsigned long long)peer.collections);
    std::fflush(stdout);
    char line[256];
    while (std::fgets(line, sizeof line, stdin)) {
        if (std::strncmp(line, "quit", 4) == 0) break;
    }
    return 0;
}
