/* meshtopo measured in process: mt_mesh_build timed on the case's face list
 * with 1 or 2 threads and a build workspace kept across the repetitions (as
 * meshtopod keeps one: a program that builds repeatedly does not pay for
 * fresh scratch pages each time, as OpenMesh and CGAL get their memory
 * back from malloc). The main rows hand each mesh back to the workspace
 * once measured (mt_build_workspace_recycle), as a loop that builds a mesh
 * per frame would, so the next build writes into its arrays; the "-new"
 * row destroys it, so every mesh is new memory. Then a one-ring sweep over
 * every internal vertex (MT_FOR_VERT_OUT over the raw view), a face-
 * adjacency sweep over every face (its half-edge ring, the face across each
 * twin), boundary loops with mt_boundary_loops and the component of every
 * face with mt_face_component. Sweeps sum the ids they visit so no loop can
 * be optimised away. The warm-up build is validated and its report gives
 * the counts the peers are checked against. A failing build is reported,
 * never fatal. */
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "meshtopo/mesh.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"
#include "meshtopo/validate.h"

#ifndef MESHTOPO_BENCH_VERSION
#define MESHTOPO_BENCH_VERSION "dev"
#endif

typedef struct meshtopo_state {
    const mt__bench_case *bench_case;
    mt_build_options build_options;
    mt_build_workspace *workspace;
    bool recycle; /* meshes go back to the workspace, not to malloc */
} meshtopo_state;

/* Done with a mesh: recycled into the workspace or destroyed. */
static void mesh_release(meshtopo_state *s, mt_mesh *mesh)
{
    if (s->recycle) {
        mt_build_workspace_recycle(s->workspace, mesh);
    } else {
        mt_mesh_destroy(mesh);
    }
}

static void ring_sweep(const mt_mesh *mesh, mt__bench_topology *seen)
{
    mt_mesh_view view;
    mt_mesh_get_view(mesh, &view);
    uint64_t neighbours = 0;
    uint64_t sum = 0;
    for (uint32_t v = 0; v < view.num_verts_internal; v++) {
        MT_FOR_VERT_OUT(&view, v, it)
        {
            sum += view.he_head[it.current];
            neighbours++;
        }
    }
    seen->ring_neighbours = neighbours;
    seen->ring_sum = sum;
}

/* Every face's neighbours across its edges: the face of each twin. */
static void adj_sweep(const mt_mesh *mesh, mt__bench_topology *seen)
{
    mt_mesh_view view;
    mt_mesh_get_view(mesh, &view);
    uint64_t neighbours = 0;
    uint64_t sum = 0;
    for (uint32_t f = 0; f < view.num_faces; f++) {
        uint32_t start = view.face_he[f];
        if (start == MT_NONE) continue;
        uint32_t he = start;
        uint32_t steps = 0;
        do {
            uint32_t across = view.he_face[he ^ 1u];
            if (across != MT_NONE) {
                sum += across;
                neighbours++;
            }
            he = view.he_next[he];
        } while (he != start && ++steps < MT_RING_STEP_LIMIT);
    }
    seen->adj_neighbours = neighbours;
    seen->adj_sum = sum;
}

/* Boundary loops as vertex lists: size query, buffers, fill. */
static bool loops_extract(const mt_mesh *mesh, mt__bench_topology *seen, mt__bench_result *result)
{
    size_t num_verts = 0, num_loops = 0;
    mt_status st = mt_boundary_loops(mesh, NULL, 0, NULL, 0, &num_verts, &num_loops);
    uint32_t *verts = NULL, *offsets = NULL;
    if (st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL) {
        verts = malloc((num_verts ? num_verts : 1) * sizeof *verts);
        offsets = malloc((num_loops + 1) * sizeof *offsets);
        st = verts && offsets ? mt_boundary_loops(mesh, verts, num_verts, offsets, num_loops + 1,
                                                  &num_verts, &num_loops)
                              : MT_ERR_NOMEM;
    }
    free(verts);
    free(offsets);
    if (st != MT_OK) {
        snprintf(result->message, sizeof result->message, "mt_boundary_loops failed: %s",
                 mt_strerror(st));
        return false;
    }
    seen->boundary_loops = num_loops;
    seen->loop_verts = num_verts;
    return true;
}

/* The component of every face; the count is one more than the largest. */
static bool components_label(const mt_mesh *mesh, mt__bench_topology *seen,
                             mt__bench_result *result)
{
    uint32_t num_faces = mt_mesh_num_faces(mesh);
    uint64_t count = 0;
    for (uint32_t f = 0; f < num_faces; f++) {
        uint32_t c;
        mt_status st = mt_face_component(mesh, f, &c);
        if (st == MT_ERR_NOT_FOUND) continue;
        if (st != MT_OK) {
            snprintf(result->message, sizeof result->message, "mt_face_component(%u) failed: %s", f,
                     mt_strerror(st));
            return false;
        }
        if (c + 1ull > count) count = c + 1ull;
    }
    seen->components = count;
    return true;
}

/* Times the queries on a built mesh into out (times and what they saw). */
static bool queries_run(const mt_mesh *mesh, mt__bench_sample *out, mt__bench_result *result)
{
    double t0 = mt__bench_now_ms();
    ring_sweep(mesh, &out->seen);
    double t1 = mt__bench_now_ms();
    adj_sweep(mesh, &out->seen);
    double t2 = mt__bench_now_ms();
    if (!loops_extract(mesh, &out->seen, result)) return false;
    double t3 = mt__bench_now_ms();
    if (!components_label(mesh, &out->seen, result)) return false;
    double t4 = mt__bench_now_ms();
    out->ring_ms = t1 - t0;
    out->adj_ms = t2 - t1;
    out->loops_ms = t3 - t2;
    out->components_ms = t4 - t3;
    return true;
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
    s->recycle = !runner->fresh;
    s->build_options.threads = runner->threads;
    s->build_options.workspace = s->workspace = mt_build_workspace_create();
    if (!s->workspace) {
        snprintf(result->message, sizeof result->message, "out of memory");
        return false;
    }
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
    mt__bench_sample warm;
    memset(&warm, 0, sizeof warm);
    if (!queries_run(mesh, &warm, result)) {
        mt_mesh_destroy(mesh);
        return false;
    }
    const mt_report *report = mt_mesh_report(mesh);
    mt__bench_topology *t = &result->topology;
    *t = warm.seen;
    t->verts = report->num_verts;
    t->edges = report->num_edges;
    t->faces = report->num_faces_valid;
    t->boundary_loops = report->boundary_loops;
    t->components = report->connected_components;
    t->rejected_faces = report->num_faces - report->num_faces_valid;
    result->structure_bytes = mt_mesh_memory_bytes(mesh);
    result->report_bytes = mt_mesh_report_memory_bytes(mesh);
    mesh_release(s, mesh);
    return true;
}

/* heap_bytes: the heap's growth over the build less the workspace's (a
 * recycled array taken for the mesh moves from one to the other), which is
 * what the new mesh holds either way. */
static bool meshtopo_rep(mt__bench_runner *runner, mt__bench_sample *out, mt__bench_result *result)
{
    meshtopo_state *s = runner->state;
    mt_mesh *mesh = NULL;
    int64_t heap0 = mt__bench_heap_bytes();
    int64_t kept0 = (int64_t)mt_build_workspace_bytes(s->workspace);
    double t0 = mt__bench_now_ms();
    if (!build(s, &mesh, result)) return false;
    double t1 = mt__bench_now_ms();
    int64_t heap1 = mt__bench_heap_bytes();
    int64_t kept1 = (int64_t)mt_build_workspace_bytes(s->workspace);
    bool ok = queries_run(mesh, out, result);
    mesh_release(s, mesh);
    out->build_ms = t1 - t0;
    out->heap_bytes = heap0 < 0 || heap1 < 0 ? -1 : (heap1 - heap0) - (kept1 - kept0);
    return ok;
}

static void meshtopo_stop(mt__bench_runner *runner)
{
    meshtopo_state *s = runner->state;
    if (s) mt_build_workspace_destroy(s->workspace);
    free(runner->state);
    runner->state = NULL;
}

void mt__bench_runner_meshtopo(mt__bench_runner *out, uint32_t threads, bool recycle)
{
    memset(out, 0, sizeof *out);
    const char *suffix = recycle ? "" : "-new";
    if (threads == 0) {
        snprintf(out->library, sizeof out->library, "meshtopo-auto%s", suffix);
    } else {
        snprintf(out->library, sizeof out->library, "meshtopo-%ut%s", threads, suffix);
    }
    out->fresh = !recycle;
    out->kind = MT__BENCH_LIBRARY;
    out->is_meshtopo = true;
    out->threads = threads;
    out->start = meshtopo_start;
    out->rep = meshtopo_rep;
    out->stop = meshtopo_stop;
}
