/* The result files of meshtopo-bench: one CSV row and one Markdown table row
 * per case and library (figures from mt__bench_row_compute, as the console
 * table), the Markdown headed by the machine and the command that made it
 * and closed by the targets. Columns are listed in tools/bench/README.md. */
#include <math.h>
#include <time.h>

#include "bench.h"

static const char *state_text(const mt__bench_result *r)
{
    return r->state == MT__BENCH_OK ? "ok" : r->state == MT__BENCH_SKIPPED ? "skipped" : "failed";
}

bool mt__bench_csv_write(const char *path, const mt__bench_options *options,
                         const mt__bench_result *results, uint32_t num_cases, uint32_t num_runners)
{
    (void)options;
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fprintf(f,
            "mesh,order,faces,library,version,state,threads,reps,verts,edges,faces_built,"
            "boundary_loops,components,build_ms_median,build_ms_min,build_ms_max,build_ratio,"
            "ns_per_face,ring_ms_median,ring_ratio,ring_neighbours,ring_neighbours_per_s,"
            "adj_ms_median,adj_ratio,adj_neighbours,adj_neighbours_per_s,loops_ms_median,"
            "components_ms_median,heap_bytes_per_face,structure_bytes_per_face\n");
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *row = &results[(size_t)c * num_runners];
        const mt__bench_result *base = mt__bench_base(row, num_runners);
        for (uint32_t k = 0; k < num_runners; k++) {
            const mt__bench_result *r = &row[k];
            mt__bench_row v = mt__bench_row_compute(r, base);
            const mt__bench_topology *t = &r->topology;
            bool lib = r->kind == MT__BENCH_LIBRARY && r->state == MT__BENCH_OK;
            char th[16], b[20][32];
            fprintf(f, "%s,%s,%u,%s,%s,%s,%s,%u,", r->bench_case->mesh, r->bench_case->order,
                    r->bench_case->list.num_faces, r->library, r->version, state_text(r),
                    mt__bench_threads_text(r, th, sizeof th), r->num_samples);
            if (lib) {
                fprintf(f, "%llu,%llu,%llu,%llu,%s,", (unsigned long long)t->verts,
                        (unsigned long long)t->edges, (unsigned long long)t->faces,
                        (unsigned long long)t->boundary_loops,
                        t->components == MT__BENCH_UNKNOWN
                            ? ""
                            : mt__bench_num(b[0], 32, (double)t->components, 0));
            } else {
                fprintf(f, ",,,,,");
            }
            if (!v.ok) {
                fprintf(f, ",,,,,,,,,,,,,,,,\n");
                continue;
            }
            /* "-" (not a number) becomes an empty field. */
            const char *fields[17] = {
                mt__bench_num(b[1], 32, v.build_ms, 4),
                mt__bench_num(b[2], 32, v.build_min, 4),
                mt__bench_num(b[3], 32, v.build_max, 4),
                mt__bench_num(b[4], 32, v.build_ratio, 4),
                mt__bench_num(b[5], 32, v.ns_per_face, 2),
                mt__bench_num(b[6], 32, v.ring_ms, 4),
                mt__bench_num(b[7], 32, v.ring_ratio, 4),
                lib ? mt__bench_num(b[8], 32, (double)t->ring_neighbours, 0) : "-",
                mt__bench_num(b[9], 32, v.ring_per_s, 0),
                mt__bench_num(b[10], 32, v.adj_ms, 4),
                mt__bench_num(b[11], 32, v.adj_ratio, 4),
                lib ? mt__bench_num(b[12], 32, (double)t->adj_neighbours, 0) : "-",
                mt__bench_num(b[13], 32, v.adj_per_s, 0),
                mt__bench_num(b[14], 32, v.loops_ms, 4),
                mt__bench_num(b[15], 32, v.components_ms, 4),
                mt__bench_num(b[16], 32, v.heap_per_face, 2),
                mt__bench_num(b[17], 32, v.structure_per_face, 2),
            };
            for (int i = 0; i < 17; i++) {
                fprintf(f, "%s%s", fields[i][0] == '-' && !fields[i][1] ? "" : fields[i],
                        i < 16 ? "," : "\n");
            }
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
    char date[32] = "?";
    time_t now = time(NULL);
    struct tm tm;
    if (gmtime_r(&now, &tm)) strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", &tm);
    fprintf(f, "# meshtopo benchmark\n\n");
    fprintf(f, "- command: `%s`\n- machine: %s\n- date: %s\n", options->command, options->machine,
            date);
    fprintf(f,
            "- medians of %u repetitions after one warm-up; OpenMesh and CGAL %s\n"
            "- ratio: the row's median time over the fastest meshtopo row's (above 1: "
            "meshtopo is faster); one-ring/s and face-adj/s: neighbours visited per second; "
            "bytes/face: heap growth over the build (mallinfo2), positions included (for "
            "meshtopo, less what its workspace holds); memcpy rows: the bandwidth floor (input "
            "bytes read, meshtopo's structure bytes written)\n"
            "- meshtopo rows keep a build workspace across the repetitions; meshtopo-1t and -2t "
            "hand each mesh back to it (mt_build_workspace_recycle), so the next build reuses "
            "its arrays, while meshtopo-1t-new and -2t-new build every mesh into new memory\n",
            options->reps,
            options->peer_no_reserve ? "do not reserve()"
                                     : "reserve() the V, E, F of their warm-up build");
    fprintf(f,
            "\n| mesh | faces | order | library | threads | build ms | ratio | ns/face | "
            "one-ring/s | face-adj/s | bytes/face | loops ms | components ms |\n"
            "|---|--:|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
    for (uint32_t c = 0; c < num_cases; c++) {
        const mt__bench_result *row = &results[(size_t)c * num_runners];
        const mt__bench_result *base = mt__bench_base(row, num_runners);
        for (uint32_t k = 0; k < num_runners; k++) {
            const mt__bench_result *r = &row[k];
            mt__bench_row v = mt__bench_row_compute(r, base);
            char th[16], b[10][32];
            fprintf(f, "| %s | %u | %s | %s | %s |", r->bench_case->mesh,
                    r->bench_case->list.num_faces, r->bench_case->order, r->library,
                    mt__bench_threads_text(r, th, sizeof th));
            if (!v.ok) {
                fprintf(f, " %s | | | | | | | |\n", state_text(r));
                continue;
            }
            fprintf(f, " %s | %s | %s | %s | %s | %s | %s | %s |\n",
                    mt__bench_ms(b[0], 32, v.build_ms), mt__bench_num(b[1], 32, v.build_ratio, 2),
                    mt__bench_num(b[2], 32, v.ns_per_face, 1),
                    mt__bench_rate(b[3], 32, v.ring_per_s), mt__bench_rate(b[4], 32, v.adj_per_s),
                    mt__bench_num(b[5], 32, v.heap_per_face, 1), mt__bench_ms(b[6], 32, v.loops_ms),
                    mt__bench_ms(b[7], 32, v.components_ms));
        }
    }
    fprintf(f, "\n```\n");
    mt__bench_targets_print(f, results, num_cases, num_runners);
    fprintf(f, "```\n");
    return fclose(f) == 0;
}
