// What the peer programs (OpenMesh, CGAL) share: reading the raw input file
// meshtopo-bench writes (layout in bench_input.c), the clock and heap meters,
// and the line protocol the driver speaks over stdin/stdout (bench_peer.c).
// A peer supplies build, the sweeps, boundary loops, components and counts
// for its library; run_peer does the rest, so every library is timed over
// exactly the same steps.
#ifndef MESHTOPO_BENCH_PEER_COMMON_HPP
#define MESHTOPO_BENCH_PEER_COMMON_HPP

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
#include <malloc.h>
#define MT_BENCH_HAVE_MALLINFO2 1
#endif

namespace mtbench {

// The face list as read from the raw file.
struct Input {
    uint32_t num_verts = 0;
    uint32_t num_faces = 0;
    uint64_t num_indices = 0;
    bool has_positions = false;
    std::vector<double> positions;  // 3 * num_verts, or empty
    std::vector<uint32_t> sizes;    // num_faces
    std::vector<uint32_t> indices;  // num_indices
};

// Counts of the built mesh, compared by the driver across libraries (and
// the counts to reserve() before a build).
struct Topology {
    uint64_t verts = 0, edges = 0, faces = 0;
};

// Totals of one sweep: elements visited and the sum of their ids.
struct Sweep {
    uint64_t neighbours = 0, checksum = 0;
};

// Boundary loops extracted as vertex lists: how many, and their vertices.
struct Loops {
    uint64_t loops = 0, verts = 0;
};

inline double now_ms()
{
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

// Heap bytes in use (all arenas plus mmapped blocks), -1 when unknown. The
// difference around a build is the memory the built mesh keeps, spare
// vector capacity included.
inline int64_t heap_bytes()
{
#ifdef MT_BENCH_HAVE_MALLINFO2
    struct mallinfo2 info = mallinfo2();
    return int64_t(info.uordblks + info.hblkhd);
#else
    return -1;
#endif
}

inline bool read_exact(std::FILE *f, void *data, size_t elem, uint64_t count)
{
    return count == 0 || std::fread(data, elem, size_t(count), f) == size_t(count);
}

inline bool read_input(const char *path, Input &in, std::string &err)
{
    std::FILE *f = std::fopen(path, "rb");
    if (!f) {
        err = std::string("cannot open ") + path + ": " + std::strerror(errno);
        return false;
    }
    char magic[8];
    uint32_t has_positions = 0, reserved = 0;
    bool ok = read_exact(f, magic, 1, 8) && std::memcmp(magic, "MTBENCH1", 8) == 0 &&
              read_exact(f, &in.num_verts, 4, 1) && read_exact(f, &in.num_faces, 4, 1) &&
              read_exact(f, &in.num_indices, 8, 1) && read_exact(f, &has_positions, 4, 1) &&
              read_exact(f, &reserved, 4, 1) && has_positions <= 1;
    if (ok) {
        // Check the size before allocating anything from the header.
        uint64_t tail = (has_positions ? 24ull * in.num_verts : 0) + 4ull * in.num_faces;
        ok = in.num_indices <= (UINT64_MAX - tail) / 4;
        tail += 4 * in.num_indices;
        long here = std::ftell(f);
        ok = ok && here >= 0 && std::fseek(f, 0, SEEK_END) == 0 &&
             uint64_t(std::ftell(f) - here) == tail && std::fseek(f, here, SEEK_SET) == 0;
    }
    if (ok) {
        in.has_positions = has_positions != 0;
        if (in.has_positions) in.positions.resize(3 * size_t(in.num_verts));
        in.sizes.resize(in.num_faces);
        in.indices.resize(size_t(in.num_indices));
        ok = read_exact(f, in.positions.data(), sizeof(double), in.positions.size()) &&
             read_exact(f, in.sizes.data(), 4, in.sizes.size()) &&
             read_exact(f, in.indices.data(), 4, in.indices.size());
        uint64_t total = 0;
        for (uint32_t s : in.sizes) total += s;
        ok = ok && total == in.num_indices;
    }
    std::fclose(f);
    if (!ok) err = std::string(path) + " is not a well-formed meshtopo-bench input file";
    return ok;
}

// True when the face can be handed to a half-edge library at all: at least
// three entries, every index in range, no vertex twice in a triangle.
// Libraries given such a face may fail their own checks or crash, so the
// peers count it as failed instead (the driver compares counts).
inline bool face_usable(const uint32_t *fv, uint32_t size, uint32_t num_verts)
{
    if (size < 3) return false;
    for (uint32_t i = 0; i < size; i++) {
        if (fv[i] >= num_verts) return false;
    }
    if (size == 3 && (fv[0] == fv[1] || fv[1] == fv[2] || fv[0] == fv[2])) return false;
    return true;
}

// Runs the protocol for one library. Peer provides:
//   typename Peer::Mesh
//   static const char *library()                  (row name, may depend on options)
//   static bool option(const char *arg)           (true when it takes a flag)
//   static void prepare(const Input &, uint64_t &failed_faces)   (once, untimed)
//   static std::unique_ptr<Mesh> build(const Input &, const Topology &reserve,
//                                      uint64_t &failed_faces)
//       (reserve: counts to reserve() before adding, all zero for none)
//   static Sweep ring_sweep(const Mesh &)         (neighbour vertices of every vertex)
//   static Sweep adj_sweep(const Mesh &)          (faces across every face's edges)
//   static Loops loops(const Mesh &)              (boundary loops as vertex lists)
//   static uint64_t components(Mesh &)            (labels every face, returns the count)
//   static Topology topology(const Mesh &)        (V, E, F)
// Command line: PEER INPUT [--no-reserve] [peer flags]. By default every
// timed build reserves the exact V, E, F its warm-up build found (the best
// case for the library, what a caller knowing the counts would do);
// --no-reserve times the plain add loop. Output lines (stdout, one per event):
//   ready lib=NAME version=X reserve=0|1 V= E= F= boundary_loops= components=
//         failed_faces= loop_verts= ring_neighbours= ring_sum= adj_neighbours= adj_sum=
//   rep build_ms= ring_ms= adj_ms= loops_ms= components_ms= boundary_loops= loop_verts=
//       components= ring_neighbours= ring_sum= adj_neighbours= adj_sum= heap_bytes=
//                                                   (one per "run" on stdin)
//   error TEXT                                      (then exit status 1)
// "quit" or the end of stdin ends the program. The warm-up build is untimed;
// each mesh is freed (untimed) before the next build starts.
struct Measured {
    double ring_ms = 0, adj_ms = 0, loops_ms = 0, components_ms = 0;
    Sweep ring, adj;
    Loops loops;
    uint64_t components = 0;
};

template <class Peer>
Measured measure_queries(typename Peer::Mesh &mesh)
{
    Measured m;
    double t0 = now_ms();
    m.ring = Peer::ring_sweep(mesh);
    double t1 = now_ms();
    m.adj = Peer::adj_sweep(mesh);
    double t2 = now_ms();
    m.loops = Peer::loops(mesh);
    double t3 = now_ms();
    m.components = Peer::components(mesh);
    double t4 = now_ms();
    m.ring_ms = t1 - t0;
    m.adj_ms = t2 - t1;
    m.loops_ms = t3 - t2;
    m.components_ms = t4 - t3;
    return m;
}

template <class Peer>
int run_peer(int argc, char **argv, const char *version)
{
    bool reserve = true;
    bool usage_ok = argc >= 2;
    for (int i = 2; i < argc; i++) {
        if (std::strcmp(argv[i], "--no-reserve") == 0) {
            reserve = false;
        } else if (!Peer::option(argv[i])) {
            usage_ok = false;
        }
    }
    if (!usage_ok) {
        std::fprintf(stderr,
                     "usage: %s INPUT [--no-reserve] [peer options]\n"
                     "Reads a meshtopo-bench input file, builds it once as a warm-up, then\n"
                     "answers each \"run\" line on stdin with one timed build and its queries.\n",
                     argv[0]);
        return 2;
    }
    try {
        Input in;
        std::string err;
        if (!read_input(argv[1], in, err)) {
            std::printf("error %s\n", err.c_str());
            return 1;
        }
        uint64_t failed = 0;
        Peer::prepare(in, failed);
        Topology hint;
        auto mesh = Peer::build(in, hint, failed);
        Measured warm = measure_queries<Peer>(*mesh);
        Topology t = Peer::topology(*mesh);
        mesh.reset();
        if (reserve) hint = t;
        std::printf(
            "ready lib=%s version=%s reserve=%d V=%llu E=%llu F=%llu boundary_loops=%llu "
            "components=%llu failed_faces=%llu loop_verts=%llu ring_neighbours=%llu "
            "ring_sum=%llu adj_neighbours=%llu adj_sum=%llu\n",
            Peer::library(), version, reserve ? 1 : 0, (unsigned long long)t.verts,
            (unsigned long long)t.edges, (unsigned long long)t.faces,
            (unsigned long long)warm.loops.loops, (unsigned long long)warm.components,
            (unsigned long long)failed, (unsigned long long)warm.loops.verts,
            (unsigned long long)warm.ring.neighbours, (unsigned long long)warm.ring.checksum,
            (unsigned long long)warm.adj.neighbours, (unsigned long long)warm.adj.checksum);
        std::fflush(stdout);

        char line[256];
        while (std::fgets(line, sizeof line, stdin)) {
            line[std::strcspn(line, "\r\n")] = '\0';
            if (std::strcmp(line, "quit") == 0) break;
            if (std::strcmp(line, "run") != 0) {
                std::printf("error unknown command '%s'\n", line);
                return 1;
            }
            uint64_t failed_rep = 0;
            int64_t heap0 = heap_bytes();
            double t0 = now_ms();
            mesh = Peer::build(in, hint, failed_rep);
            double t1 = now_ms();
            int64_t heap1 = heap_bytes();
            Measured m = measure_queries<Peer>(*mesh);
            mesh.reset();
            std::printf(
                "rep build_ms=%.4f ring_ms=%.4f adj_ms=%.4f loops_ms=%.4f components_ms=%.4f "
                "boundary_loops=%llu loop_verts=%llu components=%llu ring_neighbours=%llu "
                "ring_sum=%llu adj_neighbours=%llu adj_sum=%llu heap_bytes=%lld\n",
                t1 - t0, m.ring_ms, m.adj_ms, m.loops_ms, m.components_ms,
                (unsigned long long)m.loops.loops, (unsigned long long)m.loops.verts,
                (unsigned long long)m.components, (unsigned long long)m.ring.neighbours,
                (unsigned long long)m.ring.checksum, (unsigned long long)m.adj.neighbours,
                (unsigned long long)m.adj.checksum,
                (long long)(heap0 < 0 || heap1 < 0 ? -1 : heap1 - heap0));
            std::fflush(stdout);
        }
    } catch (const std::exception &e) {
        std::printf("error %s\n", e.what());
        return 1;
    }
    return 0;
}

}  // namespace mtbench

#endif
