/* The numbers meshtopo-bench prints: medians of the repetitions, ratios to
 * meshtopo (runner 0 of each case), the console table, the targets of the
 * benchmark issue, and the same rows as CSV and Markdown. Every printer
 * reads its figures from one row_values so the three outputs cannot drift. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median_of(double *values, uint32_t n)
{
    if (n == 0) return NAN;
    qsort(values, n, sizeof *values, compare_double);
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double mt__bench_median(const mt__bench_result *result, bool sweep)
{
    double values[MT__BENCH_MAX_REPS];
    for (uint32_t i = 0; i < result->num_samples; i++) {
        values[i] = sweep ? result->samples[i].sweep_ms : result->samples[i].build_ms;
    }
    return median_of(values, result->num_samples);
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
    return median_of(values, n);
}

typedef struct row_values {
    const mt__bench_result *r;
    bool ok;
    double build_ms, build_min, build_max, build_ratio, ns_per_face;
    double sweep_ms, sweep_ratio, neighbours_per_s;
    double heap_per_face;      /* mallinfo2 growth / F */
    double structure_per_face; /* meshtopo only: mt_mesh_memory_bytes / F */
} row_values;

static row_values row_compute(const mt__bench_result *r, const mt__bench_result *base)
{
    row_values v;
    memset(&v, 0, sizeof v);
    v.r = r;
    v.ok = r->state == MT__BENCH_OK && r->num_samples > 0;
    if (!v.ok) return v;
    double faces = r->topology.faces ? (double)r->topology.faces : NAN;
    v.build_ms = mt__bench_median(r, false);
    v.sweep_ms = mt__bench_median(r, true);
    v.build_min = v.build_max = r->samples[0].build_ms;
    for (uint32_t i = 1; i < r->num_samples; i++) {
        v.build_min = fmin(v.build_min, r->samples[i].build_ms);
        v.build_max = fmax(v.build_max, r->samples[i].build_ms);
    }
    bool base_ok = base->state == MT__BENCH_OK && base->num_samples > 0;
    v.build_ratio = base_ok ? v.build_ms / mt__bench_median(base, false) : NAN;
    v.sweep_ratio = base_ok ? v.sweep_ms / mt__bench_median(base, true) : NAN;
    v.ns_per_face = v.build_ms * 1e6 / faces;
    v.neighbours_per_s = (double)r->samples[0].neighbours / (v.sweep_ms * 1e-3);
    v.heap_per_face = median_heap(r) / faces;
    v.structure_per_face = r->structure_bytes ? (double)r->structure_bytes / faces : NAN;
    return v;
}

static const char *threads_text(const mt__bench_options *o, const mt__bench_result *r, char *buf,
                                size_t size)
{
    if (strcmp(r->library, "meshtopo") != 0) return "1";
    if (o->threads == 0) return "auto";
    snprintf(buf, size, "%u", o->threads);
    return buf;
}

/* "%.*f" of x, or "-" when x is not a number. */
static const char *num(char *buf, size_t size, double x, int decimals)
{
    if (isnan(x) || isinf(x)) return "-";
    snprintf(buf, size, "%.*f", decimals, x);
    return buf;
}

/* Milliseconds: two decimals below 10 ms, one above. */
static const char *ms(char *buf, size_t size, double x)
{
    return num(buf, size, x, x < 10 ? 2 : 1);
}

/* Engineering notation for rates: 123.4 M. */
static const char *rate(char *buf, size_t size, double x)
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

static void mesh_line(FILE *out, const mt__bench_options *o, const mt__bench_result *results,
                      uint32_t num_cases, uint32_t num_runners, const char *prefix)
{
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *r = &results[(size_t)c * num_runners];
        const mt_face_list *l = &r->bench_case->list;
        fprintf(out, "%s%s, %s: %u vertices, %u faces, %llu indices\n", prefix, r->bench_case->mesh,
                r->bench_case->order, l->num_verts, l->num_faces,
                (unsigned long long)l->num_indices);
    }
    char buf[16];
    fprintf(out, "%smedian of %u repetitions after one warm-up; meshtopo threads: %s\n", prefix,
            o->reps, o->threads ? (snprintf(buf, sizeof buf, "%u", o->threads), buf) : "auto");
    fprintf(out, "%sOpenMesh and CGAL %s before each timed build\n", prefix,
            o->peer_no_reserve ? "do not reserve()"
                               : "reserve() the exact V, E, F of their warm-up build");
}

void mt__bench_table_print(FILE *out, const mt__bench_options *options,
                           const mt__bench_result *results, uint32_t num_cases,
                           uint32_t num_runners)
{
    mesh_line(out, options, results, num_cases, num_runners, "");
    fprintf(out, "\n%-9s %-8s %-9s %9s %6s %8s %9s %6s %13s %10s\n", "library", "version", "order",
            "build ms", "ratio", "ns/face", "sweep ms", "ratio", "neighbours/s", "bytes/face");
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *base = &results[(size_t)c * num_runners];
        for (uint32_t k = 0; k < num_runners; k++) {
            const mt__bench_result *r = &base[k];
            row_values v = row_compute(r, base);
            if (!v.ok) {
                fprintf(out, "%-9s %-8s %-9s %s: %s\n", r->library,
                        r->version[0] ? r->version : "-", r->bench_case->order,
                        r->state == MT__BENCH_SKIPPED ? "skipped" : "FAILED", r->message);
                continue;
            }
            char b[8][32];
            fprintf(out, "%-9s %-8s %-9s %9s %6s %8s %9s %6s %13s %10s\n", r->library, r->version,
                    r->bench_case->order, ms(b[0], 32, v.build_ms), num(b[1], 32, v.build_ratio, 2),
                    num(b[2], 32, v.ns_per_face, 1), ms(b[3], 32, v.sweep_ms),
                    num(b[4], 32, v.sweep_ratio, 2), rate(b[5], 32, v.neighbours_per_s),
                    num(b[6], 32, v.heap_per_face, 1));
        }
    }
    fprintf(out,
            "\nratio: the library's median time over meshtopo's (above 1: meshtopo is faster).\n"
            "bytes/face: heap growth over the build (mallinfo2), positions included\n"
            "(- when the heap cannot be measured, as under AddressSanitizer).\n");
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *r = &results[(size_t)c * num_runners];
        if (r->state != MT__BENCH_OK || !r->topology.faces) continue;
        fprintf(out,
                "meshtopo %s: structure %.1f bytes/face (mt_mesh_memory_bytes), report %.2f "
                "bytes/face\n",
                r->bench_case->order, (double)r->structure_bytes / (double)r->topology.faces,
                (double)r->report_bytes / (double)r->topology.faces);
    }
}

/* The benchmark issue's targets, by library and order. */
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

bool mt__bench_targets_print(FILE *out, const mt__bench_result *results, uint32_t num_cases,
                             uint32_t num_runners)
{
    bool all_met = true;
    bool any = false;
    fprintf(out, "\ntargets:\n");
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *base = &results[(size_t)c * num_runners];
        row_values mv = row_compute(base, base);
        if (!mv.ok) continue;
        double bytes = isnan(mv.heap_per_face)
                           ? (double)(base->structure_bytes + base->report_bytes) /
                                 (double)base->topology.faces
                           : mv.heap_per_face;
        bool met = bytes <= MT__BENCH_MAX_BYTES_PER_FACE;
        all_met = all_met && met;
        any = true;
        fprintf(out, "  %-4s %-8s memory %5.1f bytes/face (at most %.0f)\n", met ? "met" : "MISS",
                base->bench_case->order, bytes, MT__BENCH_MAX_BYTES_PER_FACE);
        for (uint32_t k = 1; k < num_runners; k++) {
            row_values v = row_compute(&base[k], base);
            if (!v.ok) continue;
            for (size_t t = 0; t < sizeof targets / sizeof targets[0]; t++) {
                if (strcmp(targets[t].library, base[k].library) != 0 ||
                    strcmp(targets[t].order, base->bench_case->order) != 0) {
                    continue;
                }
                met = v.build_ratio >= targets[t].min_build_ratio;
                all_met = all_met && met;
                fprintf(out, "  %-4s %-8s build  %5.2fx the speed of %s (at least %.0fx)\n",
                        met ? "met" : "MISS", base->bench_case->order, v.build_ratio,
                        base[k].library, targets[t].min_build_ratio);
            }
            met = v.sweep_ratio >= 1.0;
            all_met = all_met && met;
            fprintf(out, "  %-4s %-8s sweep  %5.2fx the speed of %s (at least 1x)\n",
                    met ? "met" : "MISS", base->bench_case->order, v.sweep_ratio, base[k].library);
        }
    }
    if (!any) fprintf(out, "  not checked: meshtopo has no measurement\n");
    return any && all_met;
}

bool mt__bench_csv_write(const char *path, const mt__bench_options *options,
                         const mt__bench_result *results, uint32_t num_cases, uint32_t num_runners)
{
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fprintf(f,
            "mesh,order,library,version,state,threads,reps,verts,edges,faces,boundary_loops,"
            "build_ms_median,build_ms_min,build_ms_max,build_ratio,ns_per_face,sweep_ms_median,"
            "sweep_ratio,neighbours,neighbours_per_s,heap_bytes_per_face,"
            "structure_bytes_per_face\n");
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *base = &results[(size_t)c * num_runners];
        for (uint32_t k = 0; k < num_runners; k++) {
            const mt__bench_result *r = &base[k];
            row_values v = row_compute(r, base);
            char t[16], b[10][32];
            const char *state = r->state == MT__BENCH_OK        ? "ok"
                                : r->state == MT__BENCH_SKIPPED ? "skipped"
                                                                : "failed";
            fprintf(f, "%s,%s,%s,%s,%s,%s,%u,%llu,%llu,%llu,%llu,", r->bench_case->mesh,
                    r->bench_case->order, r->library, r->version, state,
                    threads_text(options, r, t, sizeof t), r->num_samples,
                    (unsigned long long)r->topology.verts, (unsigned long long)r->topology.edges,
                    (unsigned long long)r->topology.faces,
                    (unsigned long long)r->topology.boundary_loops);
            if (!v.ok) {
                fprintf(f, ",,,,,,,,,,\n");
                continue;
            }
            fprintf(f, "%s,%s,%s,%s,%s,%s,%s,%llu,%s,%s,%s\n", num(b[0], 32, v.build_ms, 3),
                    num(b[1], 32, v.build_min, 3), num(b[2], 32, v.build_max, 3),
                    num(b[3], 32, v.build_ratio, 3), num(b[4], 32, v.ns_per_face, 2),
                    num(b[5], 32, v.sweep_ms, 3), num(b[6], 32, v.sweep_ratio, 3),
                    (unsigned long long)r->samples[0].neighbours,
                    num(b[7], 32, v.neighbours_per_s, 0), num(b[8], 32, v.heap_per_face, 2),
                    num(b[9], 32, v.structure_per_face, 2));
        }
    }
    return fclose(f) == 0;
}

bool mt__bench_markdown_write(const char *path, const mt__bench_options *options,
                              const mt__bench_result *results, uint32_t num_cases,
                              uint32_t num_runners)
{
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fprintf(f, "# meshtopo build benchmark\n\n");
    mesh_line(f, options, results, num_cases, num_runners, "- ");
    fprintf(f,
            "\n| library | version | order | threads | build ms | ratio | ns/face | sweep ms | "
            "ratio | neighbours/s | bytes/face |\n"
            "|---|---|---|---|--:|--:|--:|--:|--:|--:|--:|\n");
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *base = &results[(size_t)c * num_runners];
        for (uint32_t k = 0; k < num_runners; k++) {
            const mt__bench_result *r = &base[k];
            row_values v = row_compute(r, base);
            char t[16], b[8][32];
            fprintf(f, "| %s | %s | %s | %s |", r->library, r->version[0] ? r->version : "-",
                    r->bench_case->order, threads_text(options, r, t, sizeof t));
            if (!v.ok) {
                fprintf(f, " %s | | | | | | |\n",
                        r->state == MT__BENCH_SKIPPED ? "skipped" : "failed");
                continue;
            }
            fprintf(f, " %s | %s | %s | %s | %s | %s | %s |\n", ms(b[0], 32, v.build_ms),
                    num(b[1], 32, v.build_ratio, 2), num(b[2], 32, v.ns_per_face, 1),
                    ms(b[3], 32, v.sweep_ms), num(b[4], 32, v.sweep_ratio, 2),
                    rate(b[5], 32, v.neighbours_per_s), num(b[6], 32, v.heap_per_face, 1));
        }
    }
    fprintf(f,
            "\nratio: the library's median time over meshtopo's (above 1: meshtopo is "
            "faster). bytes/face: heap growth over the build (mallinfo2), positions "
            "included.\n");
    return fclose(f) == 0;
}
