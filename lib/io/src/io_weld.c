/* Welding a face list: vertices merged by position, exactly (equal
 * coordinates) or within a distance eps, in linear expected time with a
 * hash table of the survivors keyed by their coordinates or by their cell
 * in a grid of side eps. Survivors are pairwise more than eps apart, so a
 * cell holds a bounded number of them and a vertex looks at the 27 cells
 * around it. Vertices are taken in id order and merge into the
 * lowest-numbered survivor within eps: the result never depends on the
 * hash. Everything is allocated before the list is touched. */
#include <math.h>
#include <stdlib.h>

#include "io_internal.h"

#define EMPTY UINT32_MAX

/* Cells past this many cell sides from the origin are clamped: points that
 * far are either in the same clamped cell or in neighbouring ones, so no
 * pair within eps is missed (the cell just holds more points). */
#define CELL_LIMIT 4611686018427387904.0 /* 2^62 */

typedef struct weld_table {
    uint32_t *slots; /* survivor ids, EMPTY when free */
    size_t mask;
    const double *positions;
    double eps;
} weld_table;

static uint64_t mix(uint64_t h)
{
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
}

static uint64_t hash3(uint64_t a, uint64_t b, uint64_t c)
{
    return mix(a * 0x9e3779b97f4a7c15ull ^ mix(b + 0x632be59bd9b4e019ull) ^ mix(c) * 3);
}

/* The bits of a coordinate compared by value: -0.0 as 0.0. */
static uint64_t value_bits(double x)
{
    if (x == 0) x = 0;
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

static int64_t cell_of(double x, double eps)
{
    double c = floor(x / eps);
    if (c > CELL_LIMIT) c = CELL_LIMIT;
    if (c < -CELL_LIMIT) c = -CELL_LIMIT;
    return (int64_t)c;
}

static void cell3(const weld_table *t, uint32_t v, int64_t *c)
{
    const double *p = t->positions + 3 * (size_t)v;
    for (int k = 0; k < 3; k++) c[k] = cell_of(p[k], t->eps);
}

static uint64_t cell_hash(const int64_t *c)
{
    return hash3((uint64_t)c[0], (uint64_t)c[1], (uint64_t)c[2]);
}

/* 1 when p and q are within eps (scaled, so that neither overflow nor
 * underflow of the squares decides). */
static int within(const double *p, const double *q, double eps)
{
    double d[3], m = 0;
    for (int k = 0; k < 3; k++) {
        d[k] = fabs(p[k] - q[k]);
        if (d[k] > m) m = d[k];
    }
    if (m > eps) return 0;
    if (m == 0) return 1;
    double s = 0;
    for (int k = 0; k < 3; k++) s += (d[k] / m) * (d[k] / m);
    return m * sqrt(s) <= eps;
}

static int finite3(const double *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* Exact: the survivor with v's coordinates, else EMPTY; *slot is where v
 * goes when it survives. */
static uint32_t find_exact(const weld_table *t, uint32_t v, size_t *slot)
{
    const double *p = t->positions + 3 * (size_t)v;
    size_t s = (size_t)hash3(value_bits(p[0]), value_bits(p[1]), value_bits(p[2])) & t->mask;
    for (;; s = (s + 1) & t->mask) {
        uint32_t r = t->slots[s];
        if (r == EMPTY) break;
        const double *q = t->positions + 3 * (size_t)r;
        if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) return r;
    }
    *slot = s;
    return EMPTY;
}

/* Within eps: the lowest-numbered survivor within eps of v, else EMPTY. */
static uint32_t find_near(const weld_table *t, uint32_t v)
{
    const double *p = t->positions + 3 * (size_t)v;
    int64_t c[3];
    cell3(t, v, c);
    uint32_t best = EMPTY;
    for (int dx = -1; dx <= 1; dx++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dz = -1; dz <= 1; dz++) {
                int64_t n[3] = {c[0] + dx, c[1] + dy, c[2] + dz};
                /* a clamped cell has no neighbour past the limit */
                if (n[0] > (int64_t)CELL_LIMIT || n[0] < -(int64_t)CELL_LIMIT ||
                    n[1] > (int64_t)CELL_LIMIT || n[1] < -(int64_t)CELL_LIMIT ||
                    n[2] > (int64_t)CELL_LIMIT || n[2] < -(int64_t)CELL_LIMIT)
                    continue;
                for (size_t s = (size_t)cell_hash(n) & t->mask;; s = (s + 1) & t->mask) {
                    uint32_t r = t->slots[s];
                    if (r == EMPTY) break;
                    if (r >= best) continue;
                    int64_t rc[3];
                    cell3(t, r, rc);
                    if (rc[0] == n[0] && rc[1] == n[1] && rc[2] == n[2] &&
                        within(p, t->positions + 3 * (size_t)r, t->eps))
                        best = r;
                }
            }
    return best;
}

static void insert_near(weld_table *t, uint32_t v)
{
    int64_t c[3];
    cell3(t, v, c);
    size_t s = (size_t)cell_hash(c) & t->mask;
    while (t->slots[s] != EMPTY) s = (s + 1) & t->mask;
    t->slots[s] = v;
}

mt_status mt_face_list_weld(mt_face_list *list, double eps, uint32_t *out_map,
                            mt_weld_stats *out_stats, mt_diag *diag)
{
    mt_diag_clear(diag);
    mt__io_src none = {.name = "weld"};
    if (!list)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "NULL face list");
    if (!(eps >= 0) || !isfinite(eps))
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "distance %g: expected 0 (exact) or a positive finite distance", eps);
    mt_status status = mt_face_list_check(list, diag);
    if (status != MT_OK) return status;
    uint32_t n = list->num_verts;
    if (n && !list->positions)
        return mt__io_fail(diag, MT_ERR_INVALID_ARG, &none, MT__POS_NONE, 0, MT_NONE,
                           "%u vertices without positions: nothing to weld by", n);
    if (out_stats) {
        out_stats->vertices_before = n;
        out_stats->vertices_after = n;
        out_stats->merged = 0;
    }
    if (n == 0) return MT_OK;

    /* A table of at least twice as many slots as vertices (a power of two). */
    size_t cap = 1;
    while (cap < 2 * (size_t)n) cap *= 2;
    weld_table t = {malloc(cap * sizeof(uint32_t)), cap - 1, list->positions, eps};
    uint32_t *map = out_map ? out_map : malloc((size_t)n * sizeof(uint32_t));
    if (!t.slots || !map) {
        free(t.slots);
        if (map != out_map) free(map);
        return mt__io_fail_nomem(diag, &none);
    }
    memset(t.slots, 0xff, cap * sizeof(uint32_t));

    /* map[v]: v's survivor (an old id) first, then the survivor's new id. */
    uint32_t kept = 0;
    for (uint32_t v = 0; v < n; v++) {
        uint32_t r = EMPTY;
        if (finite3(list->positions + 3 * (size_t)v)) {
            if (eps == 0) {
                size_t slot = 0;
                r = find_exact(&t, v, &slot);
                if (r == EMPTY) t.slots[slot] = v;
            } else {
                r = find_near(&t, v);
                if (r == EMPTY) insert_near(&t, v);
            }
        }
        map[v] = r == EMPTY ? kept++ : map[r];
    }
    free(t.slots);

    /* Survivors move down to their new ids (never up: new <= old). */
    double *pos = list->positions;
    for (uint32_t v = 0, next = 0; v < n; v++) {
        if (map[v] != next) continue;
        if (next != v) memcpy(pos + 3 * (size_t)next, pos + 3 * (size_t)v, 3 * sizeof(double));
        next++;
    }
    for (uint64_t k = 0; k < list->num_indices; k++) {
        uint32_t i = list->face_indices[k];
        if (i < n) list->face_indices[k] = map[i];
    }
    list->num_verts = kept; /* the arrays keep their size: they may be the caller's */
    if (map != out_map) free(map);
    if (out_stats) {
        out_stats->vertices_after = kept;
        out_stats->merged = n - kept;
    }
    return MT_OK;
}
