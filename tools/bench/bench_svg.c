/* build-time.svg: median build time against mesh size (faces), log-log, one
 * polyline per library and order (solid ordered, dashed permuted), with
 * decade ticks, grid lines and a legend. Plain SVG 1.1 written by hand, so
 * the benchmark needs no plotting library. */
#include <math.h>
#include <string.h>

#include "bench.h"

#define W 860.0
#define H 520.0
#define LEFT 80.0
#define RIGHT 640.0 /* plot area ends here; the legend is on the right */
#define TOP 40.0
#define BOTTOM 460.0

static const char *const colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                      "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

static double map(double value, double lo, double hi, double out_lo, double out_hi)
{
    return out_lo + (log10(value) - lo) / (hi - lo) * (out_hi - out_lo);
}

/* Writes text with &, < and > escaped. */
static void text_escaped(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '&')
            fputs("&amp;", f);
        else if (*s == '<')
            fputs("&lt;", f);
        else if (*s == '>')
            fputs("&gt;", f);
        else
            fputc(*s, f);
    }
}

/* 10^e as a label: 1k, 10k, 100k, 1M, 10M, else 1e-3 style. */
static void decade_label(char *buf, size_t size, int e)
{
    static const char *const names[] = {"1",    "10", "100", "1k",   "10k",
                                        "100k", "1M", "10M", "100M", "1G"};
    if (e >= 0 && e <= 9) {
        snprintf(buf, size, "%s", names[e]);
    } else {
        snprintf(buf, size, "1e%d", e);
    }
}

bool mt__bench_svg_write(const char *path, const mt__bench_result *results, uint32_t num_cases,
                         uint32_t num_runners)
{
    double f_lo = INFINITY, f_hi = 0, t_lo = INFINITY, t_hi = 0;
    for (size_t i = 0; i < (size_t)num_cases * num_runners; i++) {
        const mt__bench_result *r = &results[i];
        if (r->state != MT__BENCH_OK || r->num_samples == 0) continue;
        double faces = r->bench_case->list.num_faces;
        double ms = mt__bench_median(r, MT__BENCH_BUILD);
        if (!(faces > 0) || !(ms > 0)) continue;
        f_lo = f_lo < faces ? f_lo : faces;
        f_hi = f_hi > faces ? f_hi : faces;
        t_lo = t_lo < ms ? t_lo : ms;
        t_hi = t_hi > ms ? t_hi : ms;
    }
    if (!(f_hi > 0)) { /* nothing measured: an empty chart */
        f_lo = t_lo = 1;
        f_hi = t_hi = 10;
    }
    double x_lo = floor(log10(f_lo)), x_hi = ceil(log10(f_hi));
    double y_lo = floor(log10(t_lo)), y_hi = ceil(log10(t_hi));
    if (x_hi <= x_lo) x_hi = x_lo + 1;
    if (y_hi <= y_lo) y_hi = y_lo + 1;

    FILE *f = fopen(path, "w");
    if (!f) return false;
    fprintf(f,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"%.0f\" "
            "height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" "
            "font-size=\"12\">\n"
            "<rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"white\"/>\n"
            "<text x=\"%.0f\" y=\"24\" font-size=\"15\" text-anchor=\"middle\">Build time "
            "(median) against mesh size</text>\n",
            W, H, W, H, W, H, (LEFT + RIGHT) / 2);

    /* Grid, ticks and labels at every decade. */
    char label[16];
    for (int e = (int)x_lo; e <= (int)x_hi; e++) {
        double x = LEFT + (e - x_lo) / (x_hi - x_lo) * (RIGHT - LEFT);
        decade_label(label, sizeof label, e);
        fprintf(f,
                "<line x1=\"%.1f\" y1=\"%.0f\" x2=\"%.1f\" y2=\"%.0f\" stroke=\"#ddd\"/>\n"
                "<line x1=\"%.1f\" y1=\"%.0f\" x2=\"%.1f\" y2=\"%.0f\" stroke=\"black\"/>\n"
                "<text x=\"%.1f\" y=\"%.0f\" text-anchor=\"middle\">%s</text>\n",
                x, TOP, x, BOTTOM, x, BOTTOM, x, BOTTOM + 6, x, BOTTOM + 20, label);
    }
    for (int e = (int)y_lo; e <= (int)y_hi; e++) {
        double y = BOTTOM - (e - y_lo) / (y_hi - y_lo) * (BOTTOM - TOP);
        if (e >= 0) {
            snprintf(label, sizeof label, "%.0f", pow(10, e));
        } else {
            snprintf(label, sizeof label, "%.*f", -e, pow(10, e));
        }
        fprintf(f,
                "<line x1=\"%.0f\" y1=\"%.1f\" x2=\"%.0f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n"
                "<line x1=\"%.0f\" y1=\"%.1f\" x2=\"%.0f\" y2=\"%.1f\" stroke=\"black\"/>\n"
                "<text x=\"%.0f\" y=\"%.1f\" text-anchor=\"end\">%s</text>\n",
                LEFT, y, RIGHT, y, LEFT - 6, y, LEFT, y, LEFT - 9, y + 4, label);
    }
    fprintf(f,
            "<rect x=\"%.0f\" y=\"%.0f\" width=\"%.0f\" height=\"%.0f\" fill=\"none\" "
            "stroke=\"black\"/>\n"
            "<text x=\"%.0f\" y=\"%.0f\" text-anchor=\"middle\">faces (log scale)</text>\n"
            "<text x=\"18\" y=\"%.0f\" text-anchor=\"middle\" transform=\"rotate(-90 18 "
            "%.0f)\">build ms (log scale)</text>\n",
            LEFT, TOP, RIGHT - LEFT, BOTTOM - TOP, (LEFT + RIGHT) / 2, BOTTOM + 40,
            (TOP + BOTTOM) / 2, (TOP + BOTTOM) / 2);

    /* One polyline per library and order, cases in size order. */
    static const char *const orders[] = {"ordered", "permuted"};
    double legend_y = TOP + 10;
    for (uint32_t k = 0; k < num_runners; k++) {
        const char *colour = colours[k % (sizeof colours / sizeof colours[0])];
        for (int o = 0; o < 2; o++) {
            double xs[MT__BENCH_MAX_CASES], ys[MT__BENCH_MAX_CASES];
            uint32_t n = 0;
            for (uint32_t c = 0; c < num_cases; c++) {
                const mt__bench_result *r = &results[(size_t)c * num_runners + k];
                if (strcmp(r->bench_case->order, orders[o]) != 0) continue;
                if (r->state != MT__BENCH_OK || r->num_samples == 0) continue;
                double faces = r->bench_case->list.num_faces;
                double ms = mt__bench_median(r, MT__BENCH_BUILD);
                if (!(faces > 0) || !(ms > 0)) continue;
                /* Insert in order of faces. */
                uint32_t at = n;
                while (at > 0 && xs[at - 1] > faces) {
                    xs[at] = xs[at - 1];
                    ys[at] = ys[at - 1];
                    at--;
                }
                xs[at] = faces;
                ys[at] = ms;
                n++;
            }
            if (n == 0) continue;
            const char *dash = o ? " stroke-dasharray=\"6 4\"" : "";
            fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\"%s points=\"",
                    colour, dash);
            for (uint32_t i = 0; i < n; i++) {
                fprintf(f, "%s%.1f,%.1f", i ? " " : "", map(xs[i], x_lo, x_hi, LEFT, RIGHT),
                        map(ys[i], y_lo, y_hi, BOTTOM, TOP));
            }
            fprintf(f, "\"/>\n");
            for (uint32_t i = 0; i < n; i++) {
                fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"%s\"/>\n",
                        map(xs[i], x_lo, x_hi, LEFT, RIGHT), map(ys[i], y_lo, y_hi, BOTTOM, TOP),
                        colour);
            }
            fprintf(f,
                    "<line x1=\"%.0f\" y1=\"%.0f\" x2=\"%.0f\" y2=\"%.0f\" stroke=\"%s\" "
                    "stroke-width=\"2\"%s/>\n<text x=\"%.0f\" y=\"%.0f\">",
                    RIGHT + 15, legend_y, RIGHT + 45, legend_y, colour, dash, RIGHT + 52,
                    legend_y + 4);
            text_escaped(f, results[k].library);
            fprintf(f, " %s</text>\n", orders[o]);
            legend_y += 18;
        }
    }
    fprintf(f, "</svg>\n");
    return fclose(f) == 0;
}
