/* The driver's side of meshtopo-bench-cgal-selfx (peer_cgal_selfx.cpp, which
 * documents the protocol): start it on one raw input file, ask for timed
 * self_intersections runs, fetch the pairs of the last run when they have to
 * be compared one by one, stop it. A line that does not parse is an error
 * naming the line. */
#include <stdlib.h>
#include <string.h>

#include "bench_selfx.h"

bool mt__selfx_cgal_start(mt__selfx_cgal *peer, const char *exe, const char *input_path, char *err,
                          size_t err_size)
{
    memset(peer, 0, sizeof *peer);
    char *argv[3] = {(char *)exe, (char *)input_path, NULL};
    if (!mt__bench_child_start(&peer->child, argv, err, err_size)) return false;
    peer->started = true;
    char line[512];
    if (!mt__bench_child_read_line(&peer->child, line, sizeof line, err, err_size)) return false;
    const char *version = mt__bench_field(line, "version");
    uint64_t parallel = 0;
    if (strncmp(line, "ready ", 6) != 0 || !version ||
        !mt__bench_field_u64(line, "faces", &peer->faces) ||
        !mt__bench_field_u64(line, "failed_faces", &peer->failed_faces) ||
        !mt__bench_field_u64(line, "parallel", &parallel)) {
        snprintf(err, err_size, "unexpected line '%.400s'", line);
        return false;
    }
    peer->parallel = parallel == 1;
    snprintf(peer->version, sizeof peer->version, "%.*s", (int)strcspn(version, " "), version);
    return true;
}

bool mt__selfx_cgal_run(mt__selfx_cgal *peer, bool parallel, mt__selfx_answer *out, char *err,
                        size_t err_size)
{
    memset(out, 0, sizeof *out);
    if (!mt__bench_child_send(&peer->child, parallel ? "run parallel" : "run sequential", err,
                              err_size)) {
        return false;
    }
    char line[512];
    if (!mt__bench_child_read_line(&peer->child, line, sizeof line, err, err_size)) return false;
    if (strncmp(line, "rep ", 4) != 0 || !mt__bench_field_double(line, "ms", &out->ms) ||
        !mt__bench_field_u64(line, "pairs", &out->pairs) ||
        !mt__bench_field_u64(line, "hash", &out->hash) ||
        !mt__bench_field_u64(line, "reported", &out->reported)) {
        snprintf(err, err_size, "unexpected line '%.400s'", line);
        return false;
    }
    return true;
}

bool mt__selfx_cgal_list(mt__selfx_cgal *peer, mt_face_pair **out, size_t *out_count, char *err,
                         size_t err_size)
{
    *out = NULL;
    *out_count = 0;
    if (!mt__bench_child_send(&peer->child, "list", err, err_size)) return false;
    size_t count = 0, capacity = 0;
    mt_face_pair *pairs = NULL;
    char line[128];
    for (;;) {
        if (!mt__bench_child_read_line(&peer->child, line, sizeof line, err, err_size)) break;
        uint64_t expected;
        if (strncmp(line, "end ", 4) == 0 && mt__bench_field_u64(line, "pairs", &expected)) {
            if (expected == count) {
                *out = pairs;
                *out_count = count;
                return true;
            }
            snprintf(err, err_size, "listed %zu pairs, then said %llu", count,
                     (unsigned long long)expected);
            break;
        }
        unsigned a, b;
        char extra;
        if (sscanf(line, "pair %u %u%c", &a, &b, &extra) != 2) {
            snprintf(err, err_size, "unexpected line '%.100s'", line);
            break;
        }
        if (count == capacity) {
            size_t grown = capacity ? 2 * capacity : 1024;
            mt_face_pair *more = realloc(pairs, grown * sizeof *pairs);
            if (!more) {
                snprintf(err, err_size, "out of memory");
                break;
            }
            pairs = more;
            capacity = grown;
        }
        pairs[count].a = a;
        pairs[count].b = b;
        count++;
    }
    free(pairs);
    return false;
}

void mt__selfx_cgal_stop(mt__selfx_cgal *peer)
{
    if (peer->started) mt__bench_child_stop(&peer->child, "CGAL selfx");
    peer->started = false;
}
