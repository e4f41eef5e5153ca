/* A C++ peer program (OpenMesh, CGAL) measured as a child process. The
 * driver starts it (bench_child.c) on one raw input file and talks to it
 * over two pipes, one line at a time (the protocol is in peer_common.hpp):
 *   peer -> "ready key=value ..."  after loading and one warm-up build
 *   "run"  -> "rep key=value ..."  one timed build, sweeps, loops, components
 *   "quit" (or EOF) -> exits 0;    "error <text>" and a non-zero exit on failure
 * Only the child started here is ever waited for. */
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* Reads one line from the peer into buf (newline removed). */
static bool peer_read_line(mt__bench_child *s, char *buf, size_t size, const char *library,
                           mt__bench_result *result)
{
    char err[480];
    if (mt__bench_child_read_line(s, buf, size, err, sizeof err)) return true;
    snprintf(result->message, sizeof result->message, "%s peer: %.440s", library, err);
    return false;
}

static void peer_stop(mt__bench_runner *runner)
{
    mt__bench_child *s = runner->state;
    if (!s) return;
    mt__bench_child_stop(s, runner->library);
    free(s);
    runner->state = NULL;
}

static bool peer_spawn(mt__bench_runner *runner, mt__bench_child *s, const char *input_path,
                       bool no_reserve, mt__bench_result *result)
{
    char no_reserve_flag[] = "--no-reserve";
    char *argv[5] = {runner->exe, (char *)input_path, NULL, NULL, NULL};
    int argc = 2;
    if (runner->peer_flag) argv[argc++] = (char *)runner->peer_flag;
    if (no_reserve) argv[argc++] = no_reserve_flag;
    return mt__bench_child_start(s, argv, result->message, sizeof result->message);
}

/* The counts and sweep totals both protocol lines carry. */
static bool seen_parse(const char *line, mt__bench_topology *t)
{
    return mt__bench_field_u64(line, "boundary_loops", &t->boundary_loops) &&
           mt__bench_field_u64(line, "components", &t->components) &&
           mt__bench_field_u64(line, "loop_verts", &t->loop_verts) &&
           mt__bench_field_u64(line, "ring_neighbours", &t->ring_neighbours) &&
           mt__bench_field_u64(line, "ring_sum", &t->ring_sum) &&
           mt__bench_field_u64(line, "adj_neighbours", &t->adj_neighbours) &&
           mt__bench_field_u64(line, "adj_sum", &t->adj_sum);
}

static bool peer_start(mt__bench_runner *runner, const mt__bench_case *bench_case,
                       const mt__bench_options *options, mt__bench_result *result)
{
    mt__bench_child *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(result->message, sizeof result->message, "out of memory");
        return false;
    }
    runner->state = s;
    if (!peer_spawn(runner, s, bench_case->path, options->peer_no_reserve, result)) return false;

    char line[1024];
    if (!peer_read_line(s, line, sizeof line, runner->library, result)) return false;
    mt__bench_topology *t = &result->topology;
    const char *version = mt__bench_field(line, "version");
    if (strncmp(line, "ready ", 6) != 0 || !version || !mt__bench_field_u64(line, "V", &t->verts) ||
        !mt__bench_field_u64(line, "E", &t->edges) || !mt__bench_field_u64(line, "F", &t->faces) ||
        !mt__bench_field_u64(line, "failed_faces", &t->rejected_faces) || !seen_parse(line, t)) {
        snprintf(result->message, sizeof result->message, "%s peer: unexpected line '%.400s'",
                 runner->library, line);
        return false;
    }
    snprintf(result->version, sizeof result->version, "%.*s", (int)strcspn(version, " "), version);
    return true;
}

static bool peer_rep(mt__bench_runner *runner, mt__bench_sample *out, mt__bench_result *result)
{
    mt__bench_child *s = runner->state;
    char err[480];
    if (!mt__bench_child_send(s, "run", err, sizeof err)) {
        snprintf(result->message, sizeof result->message, "%s peer: %.440s", runner->library, err);
        return false;
    }
    char line[1024];
    if (!peer_read_line(s, line, sizeof line, runner->library, result)) return false;
    memset(out, 0, sizeof *out);
    if (strncmp(line, "rep ", 4) != 0 ||
        !mt__bench_field_double(line, "build_ms", &out->build_ms) ||
        !mt__bench_field_double(line, "ring_ms", &out->ring_ms) ||
        !mt__bench_field_double(line, "adj_ms", &out->adj_ms) ||
        !mt__bench_field_double(line, "loops_ms", &out->loops_ms) ||
        !mt__bench_field_double(line, "components_ms", &out->components_ms) ||
        !seen_parse(line, &out->seen) ||
        !mt__bench_field_i64(line, "heap_bytes", &out->heap_bytes)) {
        snprintf(result->message, sizeof result->message, "%s peer: unexpected line '%.400s'",
                 runner->library, line);
        return false;
    }
    return true;
}

void mt__bench_runner_peer(mt__bench_runner *out, const char *library, const char *peer_flag)
{
    memset(out, 0, sizeof *out);
    snprintf(out->library, sizeof out->library, "%s", library);
    out->kind = MT__BENCH_LIBRARY;
    out->peer_flag = peer_flag;
    out->start = peer_start;
    out->rep = peer_rep;
    out->stop = peer_stop;
}
