/* The numbers meshtopo-bench prints: medians of the repetitions, ratios to
 * meshtopo's fastest row of each case, the console table and the targets of
 * the benchmark issue. Every printer (here, bench_files.c, bench_svg.c) reads
 * its figures from one mt__bench_row so the outputs cannot drift. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

static double sample_metric(const mt__bench_sample *s, mt__bench_metric metric)
{
    switch (metric) {
        case MT__BENCH_BUILD:
            return s->build_ms;
        case MT__BENCH_RING:
            return s->ring_ms;
        case MT__BENCH_ADJ:
            return s->adj_ms;
        case MT__BENCH_LOOPS:
            return s->loops_ms;
        default:
            return s->components_ms;
    }
}

/* Median over the repetitions that measured the metric (NAN when none). */
double mt__bench_median(const mt__bench_result *result, mt__bench_metric metric)
{
    double values[MT__BENCH_MAX_REPS];
    uint32_t n = 0;
    for (uint32_t i = 0; i < result->num_samples; i++) {
        double x = sample_metric(&result->samples[i], metric);
        if (!isnan(x)) values[n++] = x;
    }
    return mt__bench_median_of(values, n);
}

/* Median heap growth of the build, NAN when unknown: mallinfo2 missing, or
 * answering zero because the allocator is replaced (AddressSanitizer). */
static double median_heap(const mt__bench_result *result)
{
    double values[MT__BENCH_MAX_REPS];
    uint32_t n = 0;
    for (uint32_t i = 0; i < result->num_samples; i++) {
        if (result->samples[i].heap_bytes > 0) values[n++] = (double)result->samples[i].heap_bytes;
    }
    return mt__bench_median_of(values, n);
}

static bool measured(const mt__bench_result *r)
{
    return r && r->state == MT__BENCH_OK && r->num_samples > 0;
}

const mt__bench_result *mt__bench_base(const mt__bench_result *row, uint32_t num_runners)
{
    const mt__bench_result *best = NULL;
    double best_ms = INFINITY;
    for (uint32_t k = 0; k < num_runners; k++) {
        if (!row[k].is_meshtopo || !measured(&row[k])) continue;
        double ms = mt__bench_median(&row[k], MT__BENCH_BUILD);
        if (ms < best_ms) {
            best_ms = ms;
            best = &row[k];
        }
    }
    return best;
}

mt__bench_row mt__bench_row_compute(const mt__bench_result *r, const mt__bench_result *base)
{
    mt__bench_row v;
    memset(&v, 0, sizeof v);
    v.r = r;
    v.ok = measured(r);
    v.faces = r->bench_case ? (double)r->bench_case->list.num_faces : NAN;
    if (!v.ok) return v;
    double built =
        r->kind == MT__BENCH_LIBRARY && r->topology.faces ? (double)r->topology.faces : v.faces;
    v.build_ms = mt__bench_median(r, MT__BENCH_BUILD);
    v.build_min = v.build_max = r->samples[0].build_ms;
    for (uint32_t i = 1; i < r->num_samples; i++) {
        v.build_min = fmin(v.build_min, r->samples[i].build_ms);
        v.build_max = fmax(v.build_max, r->samples[i].build_ms);
    }
    v.ns_per_face = v.build_ms * 1e6 / v.faces;
    bool base_ok = measured(base);
    v.build_ratio = base_ok ? v.build_ms / mt__bench_median(base, MT__BENCH_BUILD) : NAN;
    if (r->kind != MT__BENCH_LIBRARY) {
        v.ring_ms = v.ring_ratio = v.ring_per_s = NAN;
        v.adj_ms = v.adj_ratio = v.adj_per_s = NAN;
        v.loops_ms = v.components_ms = v.heap_per_face = v.structure_per_face = NAN;
        return v;
    }
    v.ring_ms = mt__bench_median(r, MT__BENCH_RING);
    v.adj_ms = mt__bench_median(r, MT__BENCH_ADJ);
    v.ring_ratio = base_ok ? v.ring_ms / mt__bench_median(base, MT__BENCH_RING) : NAN;
    v.adj_ratio = base_ok ? v.adj_ms / mt__bench_median(base, MT__BENCH_ADJ) : NAN;
    v.ring_per_s = (double)r->topology.ring_neighbours / (v.ring_ms * 1e-3);
    v.adj_per_s = (double)r->topology.adj_neighbours / (v.adj_ms * 1e-3);
    v.loops_ms = mt__bench_median(r, MT__BENCH_LOOPS);
    v.components_ms = mt__bench_median(r, MT__BENCH_COMPONENTS);
    v.heap_per_face = median_heap(r) / built;
    v.structure_per_face = r->structure_bytes ? (double)r->structure_bytes / built : NAN;
    return v;
}

const char *mt__bench_threads_text(const mt__bench_result *r, char *buf, size_t size)
{
    if (r->kind != MT__BENCH_LIBRARY) return "1";
    if (r->threads == 0) return "auto";
    snprintf(buf, size, "%u", r->threads);
    return buf;
}

const char *mt__bench_num(char *buf, size_t size, double x, int decimals)
{
    if (isnan(x) || isinf(x)) return "-";
    snprintf(buf, size, "%.*f", decimals, x);
    return buf;
}

/* Milliseconds: three decimals below 1 ms, two below 10 ms, one above. */
const char *mt__bench_ms(char *buf, size_t size, double x)
{
    return mt__bench_num(buf, size, x, x < 1 ? 3 : x < 10 ? 2 : 1);
}

/* Engineering notation for rates: 123.4 M. */
const char *mt__bench_rate(char *buf, size_t size, double x)
{
    if (isnan(x) || isinf(x)) return "-";
    if (x >= 1e9)
        snprintf(buf, size, "%.2f G", x * 1e-9);
    else if (x >= 1e6)
        snprintf(buf, size, "%.1f M", x * 1e-6);
    else
        snprintf(buf, size, "%.1f k", x * 1e-3);
    return buf;
}

void mt__bench_table_print(FILE *out, const mt__bench_options *options,
                           const mt__bench_result *results, uint32_t num_cases,
                           uint32_t num_runners)
{
    fprintf(out,
            "median of %u repetitions after one warm-up; OpenMesh and CGAL %s; ratio: the "
            "row's median time over the fastest meshtopo row's (above 1: meshtopo is "
            "faster)\n",
            options->reps,
            options->peer_no_reserve ? "do not reserve()"
                                     : "reserve() the V, E, F of their warm-up build");
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *row = &results[(size_t)c * num_runners];
        const mt__bench_result *base = mt__bench_base(row, num_runners);
        const mt_face_list *l = &row->bench_case->list;
        fprintf(out, "\n%s, %s: %u vertices, %u faces\n", row->bench_case->mesh,
                row->bench_case->order, l->num_verts, l->num_faces);
        fprintf(out, "  %-15s %-7s %3s %9s %6s %7s %9s %9s %6s %8s %8s\n", "library", "version",
                "thr", "build ms", "ratio", "ns/face", "ring/s", "adj/s", "B/face", "loops ms",
                "comp ms");
        for (uint32_t k = 0; k < num_runners; k++) {
            const mt__bench_result *r = &row[k];
            mt__bench_row v = mt__bench_row_compute(r, base);
            if (!v.ok) {
                fprintf(out, "  %-15s %s: %s\n", r->library,
                        r->state == MT__BENCH_SKIPPED ? "skipped" : "FAILED", r->message);
                continue;
            }
            char b[10][32];
            fprintf(out, "  %-15s %-7.7s %3s %9s %6s %7s %9s %9s %6s %8s %8s\n", r->library,
                    r->version, mt__bench_threads_text(r, b[0], 32),
                    mt__bench_ms(b[1], 32, v.build_ms), mt__bench_num(b[2], 32, v.build_ratio, 2),
                    mt__bench_num(b[3], 32, v.ns_per_face, 1),
                    mt__bench_rate(b[4], 32, v.ring_per_s), mt__bench_rate(b[5], 32, v.adj_per_s),
                    mt__bench_num(b[6], 32, v.heap_per_face, 1), mt__bench_ms(b[7], 32, v.loops_ms),
                    mt__bench_ms(b[8], 32, v.components_ms));
        }
        if (base && base->topology.faces) {
            fprintf(out,
                    "  meshtopo structure %.1f bytes/face (mt_mesh_memory_bytes), report %.2f "
                    "bytes/face\n",
                    (double)base->structure_bytes / (double)base->topology.faces,
                    (double)base->report_bytes / (double)base->topology.faces);
        }
    }
    fprintf(out,
            "\nring/s, adj/s: neighbours visited per second by the one-ring and the "
            "face-adjacency sweep.\nB/face: heap growth over the build (mallinfo2), positions "
            "included (- when unknown), for meshtopo less what its workspace holds.\n"
            "meshtopo-Nt: each mesh recycled into the build workspace for the next build;\n"
            "meshtopo-Nt-new: each mesh built into new memory.\nmemcpy rows: the bandwidth "
            "floor (input bytes read, meshtopo's structure bytes written).\n");
}

/* The benchmark issue's build targets, by library and order. */
typedef struct target {
    const char *library;
    const char *order;
    double min_build_ratio;
} target;

static const target targets[] = {
    {"OpenMesh", "ordered", 4.0},
    {"CGAL", "ordered", 3.0},
    {"OpenMesh", "permuted", 6.0},
    {"CGAL", "permuted", 4.0},
};

#define MT__BENCH_MAX_BYTES_PER_FACE 56.0
#define MT__BENCH_MAX_FLOOR_RATIO 3.0
#define MT__BENCH_TARGET_MIN_FACES 100000u

static bool verdict(FILE *out, bool met, const mt__bench_case *c, const char *text)
{
    fprintf(out, "  %-4s %-22s %-8s %s\n", met ? "met" : "MISS", c->mesh, c->order, text);
    return met;
}

bool mt__bench_targets_print(FILE *out, const mt__bench_result *results, uint32_t num_cases,
                             uint32_t num_runners)
{
    bool all_met = true;
    uint32_t checked = 0;
    fprintf(out, "\ntargets (meshes of %u faces or more; fastest meshtopo row):\n",
            MT__BENCH_TARGET_MIN_FACES);
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *row = &results[(size_t)c * num_runners];
        const mt__bench_case *bc = row->bench_case;
        if (bc->list.num_faces < MT__BENCH_TARGET_MIN_FACES) continue;
        const mt__bench_result *base = mt__bench_base(row, num_runners);
        if (!base) {
            fprintf(out, "  not checked on %s, %s: meshtopo has no measurement\n", bc->mesh,
                    bc->order);
            continue;
        }
        checked++;
        mt__bench_row mv = mt__bench_row_compute(base, base);
        char text[160];
        double bytes = isnan(mv.heap_per_face)
                           ? (double)(base->structure_bytes + base->report_bytes) /
                                 (double)base->topology.faces
                           : mv.heap_per_face;
        snprintf(text, sizeof text, "memory %.1f bytes/face (at most %.0f)", bytes,
                 MT__BENCH_MAX_BYTES_PER_FACE);
        all_met &= verdict(out, bytes <= MT__BENCH_MAX_BYTES_PER_FACE, bc, text);
        double best_ring = 0, best_adj = 0;
        const char *ring_lib = NULL, *adj_lib = NULL;
        for (uint32_t k = 0; k < num_runners; k++) {
            const mt__bench_result *r = &row[k];
            if (r->is_meshtopo) continue;
            mt__bench_row v = mt__bench_row_compute(r, base);
            if (!v.ok) continue;
            if (r->kind == MT__BENCH_FLOOR) {
                if (strcmp(r->library, "memcpy-fresh") != 0) continue;
                double f = 1.0 / v.build_ratio;
                snprintf(text, sizeof text, "build %.2fx the fresh-memory floor (at most %.0fx)", f,
                         MT__BENCH_MAX_FLOOR_RATIO);
                all_met &= verdict(out, f <= MT__BENCH_MAX_FLOOR_RATIO, bc, text);
                continue;
            }
            if (v.ring_per_s > best_ring) {
                best_ring = v.ring_per_s;
                ring_lib = r->library;
            }
            if (v.adj_per_s > best_adj) {
                best_adj = v.adj_per_s;
                adj_lib = r->library;
            }
            for (size_t t = 0; t < sizeof targets / sizeof targets[0]; t++) {
                if (strcmp(targets[t].library, r->library) != 0 ||
                    strcmp(targets[t].order, bc->order) != 0) {
                    continue;
                }
                snprintf(text, sizeof text, "build %.2fx the speed of %s (at least %.0fx)",
                         v.build_ratio, r->library, targets[t].min_build_ratio);
                all_met &= verdict(out, v.build_ratio >= targets[t].min_build_ratio, bc, text);
            }
        }
        if (ring_lib) {
            snprintf(text, sizeof text, "one-ring sweep %.2fx the speed of %s, the fastest peer",
                     mv.ring_per_s / best_ring, ring_lib);
            all_met &= verdict(out, mv.ring_per_s >= best_ring, bc, text);
        }
        if (adj_lib) {
            snprintf(text, sizeof text, "adjacency sweep %.2fx the speed of %s, the fastest peer",
                     mv.adj_per_s / best_adj, adj_lib);
            all_met &= verdict(out, mv.adj_per_s >= best_adj, bc, text);
        }
    }
    if (checked == 0) fprintf(out, "  none checked: no mesh in this run is that large\n");
    return checked > 0 && all_met;
}
