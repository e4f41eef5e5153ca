/* meshtopo measured in process: mt_mesh_build timed on the case's face list,
 * then a one-ring sweep over every internal vertex (MT_FOR_VERT_OUT over the
 * raw view, summing the heads so the loop cannot be optimised away). The
 * warm-up build is validated and its report gives the counts the peers are
 * checked against. A failing build is reported, never fatal. */
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"
#include "meshtopo/validate.h"

#ifndef MESHTOPO_BENCH_VERSION
#define MESHTOPO_BENCH_VERSION "dev"
#endif

typedef struct meshtopo_state {
    const mt__bench_case *bench_case;
    mt_build_options build_options;
} meshtopo_state;

static void sweep(const mt_mesh *mesh, uint64_t *out_neighbours, uint64_t *out_checksum)
{
    mt_mesh_view view;
    mt_mesh_get_view(mesh, &view);
    uint64_t neighbours = 0;
    uint64_t checksum = 0;
    for (uint32_t v = 0; v < view.num_verts_internal; v++) {
        MT_FOR_VERT_OUT(&view, v, it)
        {
            checksum += view.he_head[it.current];
            neighbours++;
        }
    }
    *out_neighbours = neighbours;
    *out_checksum = checksum;
}

static bool build(meshtopo_state *s, mt_mesh **out_mesh, mt__bench_result *result)
{
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_mesh_build(&s->bench_case->list, &s->build_options, out_mesh, &diag);
    if (st == MT_OK && *out_mesh) return true;
    snprintf(result->message, sizeof result->message, "mt_mesh_build failed: %s%s%.440s",
             mt_strerror(st), diag.message[0] ? ": " : "", diag.message);
    mt_mesh_destroy(*out_mesh);
    *out_mesh = NULL;
    return false;
}

static bool meshtopo_start(mt__bench_runner *runner, const mt__bench_case *bench_case,
                           const mt__bench_options *options, mt__bench_result *result)
{
    meshtopo_state *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(result->message, sizeof result->message, "out of memory");
        return false;
    }
    runner->state = s;
    s->bench_case = bench_case;
    s->build_options.threads = options->threads;
    snprintf(result->version, sizeof result->version, "%s", MESHTOPO_BENCH_VERSION);

    /* Warm-up: also the run that is checked and counted. */
    mt_mesh *mesh = NULL;
    if (!build(s, &mesh, result)) return false;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_mesh_validate(mesh, &diag);
    if (st != MT_OK) {
        snprintf(result->message, sizeof result->message, "mt_mesh_validate failed: %s: %.440s",
                 mt_strerror(st), diag.message);
        mt_mesh_destroy(mesh);
        return false;
    }
    const mt_report *report = mt_mesh_report(mesh);
    mt__bench_topology *t = &result->topology;
    t->verts = report->num_verts;
    t->edges = report->num_edges;
    t->faces = report->num_faces_valid;
    t->boundary_loops = report->boundary_loops;
    t->rejected_faces = report->num_faces - report->num_faces_valid;
    sweep(mesh, &t->neighbours, &t->checksum);
    result->structure_bytes = mt_mesh_memory_bytes(mesh);
    result->report_bytes = mt_mesh_report_memory_bytes(mesh);
    mt_mesh_destroy(mesh);
    return true;
}

static bool meshtopo_rep(mt__bench_runner *runner, mt__bench_sample *out, mt__bench_result *result)
{
    meshtopo_state *s = runner->state;
    mt_mesh *mesh = NULL;
    int64_t heap0 = mt__bench_heap_bytes();
    double t0 = mt__bench_now_ms();
    if (!build(s, &mesh, result)) return false;
    double t1 = mt__bench_now_ms();
    int64_t heap1 = mt__bench_heap_bytes();
    double t2 = mt__bench_now_ms();
    sweep(mesh, &out->neighbours, &out->checksum);
    double t3 = mt__bench_now_ms();
    mt_mesh_destroy(mesh);
    out->build_ms = t1 - t0;
    out->sweep_ms = t3 - t2;
    out->heap_bytes = heap0 < 0 || heap1 < 0 ? -1 : heap1 - heap0;
    return true;
}

static void meshtopo_stop(mt__bench_runner *runner)
{
    free(runner->state);
    runner->state = NULL;
}

void mt__bench_runner_meshtopo(mt__bench_runner *out)
{
    memset(out, 0, sizeof *out);
    out->library = "meshtopo";
    out->start = meshtopo_start;
    out->rep = meshtopo_rep;
    out->stop = meshtopo_stop;
}
