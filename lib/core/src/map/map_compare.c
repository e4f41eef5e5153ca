/* The block map against a full build (map.h, mt_map_compare_report): every
 * count the map keeps and both histograms compared with an mt_report, each
 * difference named with both values in the diag. Reads the map's own bins,
 * so it allocates nothing and is linear in the number of histogram bins. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "map/map_internal.h"

/* A message built piece by piece; once full it ends in "..." and takes no more. */
typedef struct diff_text {
    char buf[sizeof(((mt_diag *)0)->message)];
    size_t len;
    bool cut;
    int diffs;
} diff_text;

static void text_add(diff_text *t, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void text_add(diff_text *t, const char *fmt, ...)
{
    if (t->cut) return;
    const size_t room = sizeof t->buf - t->len;
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(t->buf + t->len, room, fmt, ap);
    va_end(ap);
    if (n >= 0 && (size_t)n < room) {
        t->len += (size_t)n;
        return;
    }
    t->cut = true;
    if (n < 0) { /* an encoding error: keep what came before */
        t->buf[t->len] = '\0';
        return;
    }
    t->len = sizeof t->buf - 1;
    memcpy(t->buf + sizeof t->buf - 4, "...", 4);
}

/* Starts a difference: "; " before every one but the first. */
static void text_next(diff_text *t)
{
    if (t->diffs++) text_add(t, "; ");
}

static void add_bins(diff_text *t, const mt_histogram_bin *bins, size_t n)
{
    text_add(t, "{");
    for (size_t i = 0; i < n && !t->cut; i++)
        text_add(t, "%s%u:%llu", i ? " " : "", bins[i].key, (unsigned long long)bins[i].count);
    text_add(t, "}");
}

static void compare_hist(diff_text *t, const char *name, const mt__hist *h,
                         const mt_histogram_bin *bins, size_t n)
{
    bool same = h->len == n;
    for (size_t i = 0; same && i < n; i++)
        same = h->bins[i].key == bins[i].key && h->bins[i].count == bins[i].count;
    if (same) return;
    text_next(t);
    text_add(t, "%s map ", name);
    add_bins(t, h->bins, h->len);
    text_add(t, ", build ");
    add_bins(t, bins, n);
}

mt_status mt_map_compare_report(const mt_map *map, const mt_report *report, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!map || !report)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "map compare: NULL %s",
                           map ? "report" : "map");
    mt_map_counts c;
    mt_map_get_counts(map, &c);
    diff_text t;
    t.len = 0;
    t.cut = false;
    t.diffs = 0;
    t.buf[0] = '\0';
    /* Unsigned counts and the flags (0 or 1), then the one signed count. */
#define MT__SAME_U(field)                                                             \
    do {                                                                              \
        if ((unsigned long long)c.field != (unsigned long long)report->field) {       \
            text_next(&t);                                                            \
            text_add(&t, #field " map %llu, build %llu", (unsigned long long)c.field, \
                     (unsigned long long)report->field);                              \
        }                                                                             \
    } while (0)
    MT__SAME_U(num_verts);
    MT__SAME_U(num_faces);
    MT__SAME_U(num_faces_valid);
    MT__SAME_U(num_edges);
    MT__SAME_U(num_half_edges);
    MT__SAME_U(boundary_edges);
    MT__SAME_U(nonmanifold_edges);
    MT__SAME_U(inconsistent_orientation_edges);
    MT__SAME_U(duplicate_directed_edges);
    MT__SAME_U(nonmanifold_vertices);
    MT__SAME_U(bowtie_vertices);
    MT__SAME_U(isolated_vertices);
    MT__SAME_U(unreferenced_vertices);
    MT__SAME_U(degenerate_faces);
    MT__SAME_U(duplicate_faces);
    MT__SAME_U(out_of_range_indices);
    MT__SAME_U(faces_with_out_of_range_indices);
    MT__SAME_U(nonfinite_vertices);
    MT__SAME_U(closed);
    MT__SAME_U(manifold);
    MT__SAME_U(consistently_oriented);
#undef MT__SAME_U
    if (c.euler_characteristic != report->euler_characteristic) {
        text_next(&t);
        text_add(&t, "euler_characteristic map %lld, build %lld", (long long)c.euler_characteristic,
                 (long long)report->euler_characteristic);
    }
    compare_hist(&t, "face_size_histogram", &map->face_sizes, report->face_size_histogram,
                 report->num_face_size_bins);
    compare_hist(&t, "edge_use_histogram", &map->edge_uses, report->edge_use_histogram,
                 report->num_edge_use_bins);
    if (t.diffs == 0) return MT_OK;
    return mt_diag_set(diag, MT_ERR_CORRUPT, "%s", t.buf);
}
