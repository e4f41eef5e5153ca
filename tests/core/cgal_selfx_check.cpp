// core.self_intersections_vs_cgal: mt_mesh_self_intersections against
// CGAL::Polygon_mesh_processing::self_intersections (exact predicates) on
// every corpus triangle mesh that CGAL reads as a Surface_mesh
// (CGAL::IO::read_OFF, no repair; the gzip one is read by meshtopo and
// handed over face by face), and on a few meshes made to intersect. Face
// ids must correspond: the same faces in the same order on both sides, or
// the mesh is skipped with a message. CGAL reports a degenerate face only
// as the pair (f, f); pairs with such a face are left out and counted.
// Built only where CGAL's headers are found (libcgal-dev).
// CGAL 5.5's OFF reader passes default-constructed property maps around,
// which GCC's -Wmaybe-uninitialized flags when it inlines them (-O2, ASan).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#pragma GCC diagnostic pop

#include <dirent.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <utility>
#include <vector>

extern "C" {
#include "harness.h"
}
#include "meshtopo/core.h"
#include "meshtopo/io.h"

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef std::vector<std::pair<uint32_t, uint32_t>> Pairs;

// A face list of positions and faces (sizes, then indices), freed by the
// caller with mt_face_list_free.
static bool make_list(const std::vector<double> &pos, const std::vector<uint32_t> &sizes,
                      const std::vector<uint32_t> &indices, mt_face_list *out)
{
    if (mt_face_list_alloc(out, (uint32_t)(pos.size() / 3), (uint32_t)sizes.size(), indices.size(),
                           nullptr) != MT_OK)
        return false;
    std::copy(pos.begin(), pos.end(), out->positions);
    std::copy(sizes.begin(), sizes.end(), out->face_sizes);
    std::copy(indices.begin(), indices.end(), out->face_indices);
    return true;
}

// The Surface_mesh of a face list, vertex for vertex and face for face;
// false when a face cannot be added (non-manifold, bad index).
static bool mesh_from_list(const mt_face_list &list, Mesh *out)
{
    for (uint32_t v = 0; v < list.num_verts; v++) {
        const double *p = list.positions + 3 * (size_t)v;
        out->add_vertex(K::Point_3(p[0], p[1], p[2]));
    }
    uint64_t at = 0;
    for (uint32_t f = 0; f < list.num_faces; f++) {
        std::vector<Mesh::Vertex_index> corners;
        for (uint32_t k = 0; k < list.face_sizes[f]; k++) {
            uint32_t v = list.face_indices[at + k];
            if (v >= list.num_verts) return false;
            corners.push_back(Mesh::Vertex_index(v));
        }
        at += list.face_sizes[f];
        if (out->add_face(corners) == Mesh::null_face()) return false;
    }
    return true;
}

// Whether CGAL's face f has the corners of the list's face f, in the same
// cyclic order; an empty string when every face does, else why not.
static std::string same_faces(const Mesh &sm, const mt_face_list &list)
{
    if (sm.number_of_faces() != list.num_faces || sm.number_of_vertices() != list.num_verts)
        return "CGAL has " + std::to_string(sm.number_of_vertices()) + " vertices and " +
               std::to_string(sm.number_of_faces()) + " faces";
    uint64_t at = 0;
    for (uint32_t f = 0; f < list.num_faces; f++) {
        std::vector<uint32_t> theirs;
        for (Mesh::Vertex_index v :
             CGAL::vertices_around_face(sm.halfedge(Mesh::Face_index(f)), sm))
            theirs.push_back((uint32_t)v);
        const uint32_t n = list.face_sizes[f];
        const uint32_t *ours = list.face_indices + at;
        at += n;
        bool same = theirs.size() == n;
        for (uint32_t shift = 0; same && shift < n; shift++) {
            bool rotated = true;
            for (uint32_t k = 0; k < n && rotated; k++)
                rotated = theirs[(k + shift) % n] == ours[k];
            if (rotated) break;
            if (shift + 1 == n) same = false;
        }
        if (!same) return "face " + std::to_string(f) + " differs";
    }
    return "";
}

static void print_face(const mt_face_list &list, uint32_t f)
{
    uint64_t at = 0;
    for (uint32_t g = 0; g < f; g++) at += list.face_sizes[g];
    std::printf("    face %u:", f);
    for (uint32_t k = 0; k < list.face_sizes[f]; k++) {
        uint32_t v = list.face_indices[at + k];
        const double *p = list.positions + 3 * (size_t)v;
        std::printf(" %u (%.17g %.17g %.17g)", v, p[0], p[1], p[2]);
    }
    std::printf("\n");
}

// meshtopo's pairs: 1, or 0 (with a message) when it left a face out so
// that face ids would not correspond, -1 when it fails.
static int meshtopo_pairs(const char *name, const mt_face_list &list, Pairs *out)
{
    mt_mesh *mesh = nullptr;
    mt_diag diag;
    if (mt_mesh_build(&list, nullptr, &mesh, &diag) != MT_OK) {
        std::printf("%s: mt_mesh_build: %s\n", name, diag.message);
        return -1;
    }
    for (uint32_t f = 0; f < list.num_faces; f++) {
        size_t n = 0;
        if (mt_face_verts(mesh, f, nullptr, 0, &n) == MT_ERR_NOT_FOUND) {
            std::printf(
                "%s: skipped: meshtopo rejected face %u, so face ids would not "
                "correspond\n",
                name, f);
            mt_mesh_destroy(mesh);
            return 0;
        }
    }
    size_t count = 0;
    mt_status s = mt_mesh_self_intersections(mesh, nullptr, 0, &count, &diag);
    std::vector<mt_face_pair> pairs(count);
    if (s == MT_OK || s == MT_ERR_BUFFER_TOO_SMALL)
        s = mt_mesh_self_intersections(mesh, pairs.data(), count, &count, &diag);
    mt_mesh_destroy(mesh);
    if (s != MT_OK) {
        std::printf("%s: mt_mesh_self_intersections: %s (%s)\n", name, mt_strerror(s),
                    diag.message);
        return -1;
    }
    for (const mt_face_pair &p : pairs) out->push_back({p.a, p.b});
    return 1;
}

// Compares both answers on one mesh; returns 1 when they disagree (or
// meshtopo fails), 0 when they agree or the mesh is skipped.
static int compare(const char *name, const Mesh &sm, const mt_face_list &list, int *compared)
{
    std::string why = same_faces(sm, list);
    if (!why.empty()) {
        std::printf("%s: skipped: faces do not correspond (%s)\n", name, why.c_str());
        return 0;
    }
    Pairs ours;
    const int got = meshtopo_pairs(name, list, &ours);
    if (got <= 0) return got < 0 ? 1 : 0;
    std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> found;
    CGAL::Polygon_mesh_processing::self_intersections<CGAL::Sequential_tag>(
        sm, std::back_inserter(found));
    std::set<uint32_t> degenerate;
    Pairs theirs;
    for (const auto &p : found) {
        uint32_t a = (uint32_t)p.first, b = (uint32_t)p.second;
        if (a == b)
            degenerate.insert(a);
        else
            theirs.push_back({std::min(a, b), std::max(a, b)});
    }
    std::sort(theirs.begin(), theirs.end());
    theirs.erase(std::unique(theirs.begin(), theirs.end()), theirs.end());
    size_t left_out = 0;
    Pairs kept;
    for (const auto &p : ours) {
        if (degenerate.count(p.first) || degenerate.count(p.second))
            left_out++;
        else
            kept.push_back(p);
    }
    Pairs only_ours, only_theirs;
    std::set_difference(kept.begin(), kept.end(), theirs.begin(), theirs.end(),
                        std::back_inserter(only_ours));
    std::set_difference(theirs.begin(), theirs.end(), kept.begin(), kept.end(),
                        std::back_inserter(only_theirs));
    const bool agree = only_ours.empty() && only_theirs.empty();
    std::printf("%s: %u faces, CGAL %zu pairs, meshtopo %zu pairs", name, list.num_faces,
                theirs.size(), ours.size());
    if (!degenerate.empty())
        std::printf(" (%zu degenerate faces, %zu of meshtopo's pairs with them left out)",
                    degenerate.size(), left_out);
    std::printf(": %s\n", agree ? "agree" : "DISAGREE");
    (*compared)++;
    for (size_t i = 0; i < only_ours.size() && i < 8; i++) {
        std::printf("  meshtopo only: faces %u and %u\n", only_ours[i].first, only_ours[i].second);
        print_face(list, only_ours[i].first);
        print_face(list, only_ours[i].second);
    }
    for (size_t i = 0; i < only_theirs.size() && i < 8; i++) {
        std::printf("  CGAL only: faces %u and %u\n", only_theirs[i].first, only_theirs[i].second);
        print_face(list, only_theirs[i].first);
        print_face(list, only_theirs[i].second);
    }
    return agree ? 0 : 1;
}

static int compare_made(const char *name, const std::vector<double> &pos,
                        const std::vector<uint32_t> &sizes, const std::vector<uint32_t> &indices,
                        int *compared)
{
    mt_face_list list;
    Mesh sm;
    if (!make_list(pos, sizes, indices, &list)) return 1;
    int wrong = 1;
    if (mesh_from_list(list, &sm))
        wrong = compare(name, sm, list, compared);
    else
        std::printf("%s: CGAL cannot add its faces\n", name);
    mt_face_list_free(&list);
    return wrong;
}

// Meshes made to intersect, so that the comparison is not vacuous.
static int made_meshes(int *compared)
{
    int wrong = 0;
    // An octahedron whose top apex is pushed below the bottom one, off the
    // axis: the bottom pyramid pokes through the upper faces.
    wrong += compare_made(
        "octahedron_pushed", {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0.5, 0.5, -1.5, 0, 0, -1},
        {3, 3, 3, 3, 3, 3, 3, 3},
        {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5}, compared);
    // Two tetrahedra in one mesh, the second moved by (0.5, 0.5, 0.5).
    wrong += compare_made(
        "two_tetrahedra", {0,   0,   0,   2,   0,   0,   0,   2,   0,   0,   0,   2,
                           0.5, 0.5, 0.5, 2.5, 0.5, 0.5, 0.5, 2.5, 0.5, 0.5, 0.5, 2.5},
        {3, 3, 3, 3, 3, 3, 3, 3},
        {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 4, 6, 5, 4, 5, 7, 4, 7, 6, 5, 6, 7}, compared);
    // Two tetrahedra, the second's corner on the first's face (no shared ids).
    wrong += compare_made(
        "touching_tetrahedra",
        {0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0, 2, 0.5, 0.5, 1, 1, 1, 2, 2, 1, 2, 1, 2, 2},
        {3, 3, 3, 3, 3, 3, 3, 3},
        {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 4, 6, 5, 4, 5, 7, 4, 7, 6, 5, 6, 7}, compared);
    // Two triangles folded onto each other across their shared edge, and a
    // flat fan of three around vertex 4 whose last triangle overlaps the first.
    wrong += compare_made("fold_and_fan", {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.5, 0,   5, 5,
                                           0, 7, 5, 0, 5, 7, 0, 3, 4, 0,    7,   5.5, 0},
                          {3, 3, 3, 3, 3}, {0, 1, 2, 1, 0, 3, 4, 5, 6, 4, 6, 7, 4, 7, 8}, compared);
    return wrong;
}

static bool ends_with(const std::string &s, const std::string &tail)
{
    return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

int main()
{
    int wrong = 0, compared = 0;
    wrong += made_meshes(&compared);
    const char *dir = mt_test_corpus_dir();
    std::vector<std::string> names;
    if (DIR *d = opendir(dir)) {
        while (dirent *e = readdir(d))
            if (ends_with(e->d_name, ".off") || ends_with(e->d_name, ".off.gz"))
                names.push_back(e->d_name);
        closedir(d);
    }
    std::sort(names.begin(), names.end());
    if (names.empty()) {
        std::printf("no meshes in the corpus directory %s\n", dir);
        wrong++;
    }
    for (const std::string &name : names) {
        const std::string path = std::string(dir) + "/" + name;
        mt_face_list list;
        mt_diag diag;
        if (mt_read_file(path.c_str(), MT_FORMAT_AUTO, &list, &diag) != MT_OK) {
            std::printf("%s: meshtopo cannot read it: %s\n", name.c_str(), diag.message);
            wrong++;
            continue;
        }
        Mesh sm;
        bool loaded;
        if (ends_with(name, ".gz"))  // read_OFF reads no gzip: meshtopo's face list instead
            loaded = mesh_from_list(list, &sm);
        else
            loaded = CGAL::IO::read_OFF(path, sm, CGAL::parameters::verbose(false));
        if (!loaded)
            std::printf("%s: skipped: CGAL does not load it as a Surface_mesh\n", name.c_str());
        else if (!CGAL::is_triangle_mesh(sm))
            std::printf("%s: skipped: not a triangle mesh\n", name.c_str());
        else
            wrong += compare(name.c_str(), sm, list, &compared);
        mt_face_list_free(&list);
    }
    std::printf("core.self_intersections_vs_cgal: %d meshes compared, %d disagree\n", compared,
                wrong);
    return wrong ? 1 : 0;
}
