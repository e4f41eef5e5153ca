// What the peer programs (OpenMesh, CGAL) share: reading the raw input file
// meshtopo-bench writes (layout in bench_input.c), the clock and heap meters,
// and the line protocol the driver speaks over stdin/stdout (bench_peer.c).
// A peer supplies build, sweep and topology for its library; run_peer does
// the rest, so every library is timed over exactly the same steps.
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

// Counts of the built mesh, compared by the driver across libraries.
struct Topology {
    uint64_t verts = 0, edges = 0, faces = 0, boundary_loops = 0;
};

// Totals of one one-ring sweep: neighbours visited and the sum of their ids.
struct Sweep {
    uint64_t neighbours = 0, checksum = 0;
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
//   static std::unique_ptr<Mesh> build(const Input &, const Topology &reserve,
//                                      uint64_t &failed_faces)
//       (reserve: counts to reserve() before adding, all zero for none)
//   static Sweep sweep(const Mesh &)
//   static Topology topology(const Mesh &)
// Command line: PEER INPUT [--no-reserve]. By default every timed build
// reserves the exact V, E, F its warm-up build found (the best case for the
// library, what a caller knowing the counts would do); --no-reserve times
// the plain add loop. Output lines (stdout, one per event):
//   ready lib=NAME version=X reserve=0|1 V= E= F= boundary_loops= failed_faces=
//         neighbours= checksum=
//   rep build_ms= sweep_ms= neighbours= checksum= heap_bytes=   (one per "run" on stdin)
//   error TEXT                                                 (then exit status 1)
// "quit" or the end of stdin ends the program. The warm-up build is untimed;
// each mesh is freed before the next build starts.
template <class Peer>
int run_peer(int argc, char **argv, const char *library, const char *version)
{
    bool reserve = true;
    if (argc == 3 && std::strcmp(argv[2], "--no-reserve") == 0) reserve = false;
    if (argc < 2 || argc > 3 || (argc == 3 && reserve)) {
        std::fprintf(stderr,
                     "usage: %s INPUT [--no-reserve]\n"
                     "Reads a meshtopo-bench input file, builds it once as a warm-up, then\n"
                     "answers each \"run\" line on stdin with one timed build and sweep.\n",
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
        Topology hint;
        auto mesh = Peer::build(in, hint, failed);
        Sweep warm = Peer::sweep(*mesh);
        Topology t = Peer::topology(*mesh);
        mesh.reset();
        if (reserve) hint = t;
        std::printf(
            "ready lib=%s version=%s reserve=%d V=%llu E=%llu F=%llu boundary_loops=%llu "
            "failed_faces=%llu neighbours=%llu checksum=%llu\n",
            library, version, reserve ? 1 : 0, (unsigned long long)t.verts,
            (unsigned long long)t.edges, (unsigned long long)t.faces,
            (unsigned long long)t.boundary_loops, (unsigned long long)failed,
            (unsigned long long)warm.neighbours, (unsigned long long)warm.checksum);
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
            double t2 = now_ms();
            Sweep s = Peer::sweep(*mesh);
            double t3 = now_ms();
            mesh.reset();
            std::printf(
                "rep build_ms=%.4f sweep_ms=%.4f neighbours=%llu checksum=%llu "
                "heap_bytes=%lld\n",
                t1 - t0, t3 - t2, (unsigned long long)s.neighbours, (unsigned long long)s.checksum,
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
