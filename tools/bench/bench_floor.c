/* The bandwidth floor measured in process: the time memcpy takes to stream
 * a case's input bytes (positions, face sizes, indices) and write as many
 * bytes as meshtopo's built structure holds (mt_mesh_memory_bytes), into
 * fresh memory each repetition (a new anonymous mapping, so every page is
 * faulted in and zeroed by the kernel as a build's new arrays are; malloc
 * would hand back the pages the previous repetition freed) or into one
 * buffer touched before. No build can move less data,
 * so the ratio of a build to the floor says how far it is from the limit. */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "bench.h"
#include "meshtopo/mesh.h"

typedef struct floor_state {
    const mt__bench_case *bench_case;
    size_t out_bytes;
    unsigned char *reused; /* the reused-memory buffer, touched at start */
} floor_state;

/* Copies max(input, out_bytes) bytes: the input arrays in turn, again from
 * the first when the output is larger, into dst, wrapping when it is
 * smaller. Every input byte is read and every output byte written. */
static void stream(const mt_face_list *l, unsigned char *dst, size_t out_bytes)
{
    const void *src[3] = {l->positions, l->face_sizes, l->face_indices};
    size_t len[3] = {l->positions ? 3 * sizeof(double) * (size_t)l->num_verts : 0,
                     sizeof(uint32_t) * (size_t)l->num_faces,
                     sizeof(uint32_t) * (size_t)l->num_indices};
    size_t in_bytes = len[0] + len[1] + len[2];
    if (in_bytes == 0 || out_bytes == 0) return;
    size_t total = in_bytes > out_bytes ? in_bytes : out_bytes;
    size_t done = 0, at = 0, part = 0, part_at = 0;
    while (done < total) {
        if (part_at == len[part]) {
            part = (part + 1) % 3;
            part_at = 0;
            continue;
        }
        size_t n = len[part] - part_at;
        if (n > out_bytes - at) n = out_bytes - at;
        if (n > total - done) n = total - done;
        memcpy(dst + at, (const unsigned char *)src[part] + part_at, n);
        part_at += n;
        at += n;
        done += n;
        if (at == out_bytes) at = 0;
    }
}

static bool floor_start(mt__bench_runner *runner, const mt__bench_case *bench_case,
                        const mt__bench_options *options, mt__bench_result *result)
{
    (void)options;
    floor_state *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(result->message, sizeof result->message, "out of memory");
        return false;
    }
    runner->state = s;
    s->bench_case = bench_case;
    snprintf(result->version, sizeof result->version, "libc");

    /* The output size: what meshtopo's structure holds for this input. */
    mt_mesh *mesh = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_mesh_build(&bench_case->list, NULL, &mesh, &diag);
    if (st != MT_OK) {
        snprintf(result->message, sizeof result->message, "mt_mesh_build failed: %s: %.440s",
                 mt_strerror(st), diag.message);
        return false;
    }
    s->out_bytes = mt_mesh_memory_bytes(mesh);
    mt_mesh_destroy(mesh);
    result->structure_bytes = s->out_bytes;
    if (s->out_bytes == 0) s->out_bytes = 1;
    if (!runner->fresh) {
        s->reused = malloc(s->out_bytes);
        if (!s->reused) {
            snprintf(result->message, sizeof result->message, "out of memory (%zu bytes)",
                     s->out_bytes);
            return false;
        }
        memset(s->reused, 0, s->out_bytes);
    }
    /* Warm-up: one copy of each kind (its time is not kept). */
    mt__bench_sample warm;
    return runner->rep(runner, &warm, result);
}

static bool floor_rep(mt__bench_runner *runner, mt__bench_sample *out, mt__bench_result *result)
{
    floor_state *s = runner->state;
    memset(out, 0, sizeof *out);
    double t0 = mt__bench_now_ms();
    unsigned char *dst = s->reused;
    if (runner->fresh) {
        void *map =
            mmap(NULL, s->out_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        dst = map == MAP_FAILED ? NULL : map;
    }
    if (!dst) {
        snprintf(result->message, sizeof result->message, "out of memory (%zu bytes)",
                 s->out_bytes);
        return false;
    }
    stream(&s->bench_case->list, dst, s->out_bytes);
    double t1 = mt__bench_now_ms();
    /* Keep the copy observable so it cannot be dropped. */
    out->seen.ring_sum = dst[s->out_bytes - 1];
    if (runner->fresh) munmap(dst, s->out_bytes);
    out->build_ms = t1 - t0;
    out->ring_ms = out->adj_ms = out->loops_ms = out->components_ms = NAN;
    out->heap_bytes = -1;
    return true;
}

static void floor_stop(mt__bench_runner *runner)
{
    floor_state *s = runner->state;
    if (s) free(s->reused);
    free(s);
    runner->state = NULL;
}

void mt__bench_runner_floor(mt__bench_runner *out, bool fresh)
{
    memset(out, 0, sizeof *out);
    snprintf(out->library, sizeof out->library, "%s", fresh ? "memcpy-fresh" : "memcpy-reused");
    out->kind = MT__BENCH_FLOOR;
    out->fresh = fresh;
    out->start = floor_start;
    out->rep = floor_rep;
    out->stop = floor_stop;
}
