/* Splitting a face list into mapper-style blocks (block_split.h): faces
 * sorted by the grid cell of their centroid, each block with its own copies
 * of the vertices it uses (seams duplicated, as nvblox sends them), the
 * file's unreferenced vertices in the block of their cell. */
#include "block_split.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Cells further than this from the origin go to the outlier block. */
#define CELL_LIMIT 1073741824.0

typedef struct item {
    mt_map_key key;
    uint32_t kind; /* 0: a face, 1: an unreferenced vertex */
    uint32_t idx;
} item;

static int key_cmp(mt_map_key a, mt_map_key b)
{
    if (a.x != b.x) return a.x < b.x ? -1 : 1;
    if (a.y != b.y) return a.y < b.y ? -1 : 1;
    if (a.z != b.z) return a.z < b.z ? -1 : 1;
    return 0;
}

static int item_cmp(const void *pa, const void *pb)
{
    const item *a = pa, *b = pb;
    int c = key_cmp(a->key, b->key);
    if (c) return c;
    if (a->kind != b->kind) return a->kind < b->kind ? -1 : 1;
    return a->idx < b->idx ? -1 : a->idx > b->idx;
}

/* The cell of the mean of the in-range corners idx[0..n). */
static mt_map_key cell_of(const mt_face_list *list, const uint32_t *idx, uint32_t n, double size)
{
    double c[3] = {0, 0, 0};
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (idx[i] >= list->num_verts) continue;
        for (int a = 0; a < 3; a++) c[a] += list->positions[3 * (size_t)idx[i] + a];
        k++;
    }
    if (k == 0) return CLI_BLOCK_OUTLIER_KEY;
    int32_t q[3];
    for (int a = 0; a < 3; a++) {
        const double x = floor(c[a] / k / size);
        if (!isfinite(x) || x < -CELL_LIMIT || x > CELL_LIMIT) return CLI_BLOCK_OUTLIER_KEY;
        q[a] = (int32_t)x;
    }
    return (mt_map_key){q[0], q[1], q[2]};
}

void cli_block_set_free(cli_block_set *set)
{
    if (!set) return;
    for (size_t b = 0; b < set->count; b++) {
        mt_face_list_free(&set->blocks[b].list);
        free(set->blocks[b].source);
    }
    free(set->blocks);
    memset(set, 0, sizeof *set);
}

/* Fills block `out` from items[0..n) (one key). `stamp`/`local`: per file
 * vertex scratch; `mark` is unique to this block. */
static mt_status fill_block(const mt_face_list *list, const uint64_t *first, const item *items,
                            size_t n, uint32_t *stamp, uint32_t *local, uint32_t mark,
                            cli_block *out, mt_diag *diag)
{
    uint32_t nf = 0, nv = 0;
    uint64_t ni = 0;
    for (size_t i = 0; i < n; i++) {
        if (items[i].kind == 1) {
            nv++;
            continue;
        }
        const uint32_t f = items[i].idx, size = list->face_sizes[f];
        nf++;
        ni += size;
        for (uint32_t j = 0; j < size; j++) {
            const uint32_t v = list->face_indices[first[f] + j];
            if (v < list->num_verts && stamp[v] != mark) stamp[v] = mark, nv++;
        }
    }
    out->key = items[0].key;
    mt_status st = mt_face_list_alloc(&out->list, nv, nf, ni, diag);
    if (st != MT_OK) return st;
    out->source = malloc((nv ? nv : 1) * sizeof *out->source);
    if (!out->source) return mt_diag_set(diag, MT_ERR_NOMEM, "out of memory splitting into blocks");
    const uint32_t fill = mark + 1; /* a second mark: this block's vertices get local ids */
    uint32_t at_v = 0, at_f = 0;
    uint64_t at = 0;
    for (size_t i = 0; i < n; i++) {
        if (items[i].kind == 1) continue;
        const uint32_t f = items[i].idx, size = list->face_sizes[f];
        const uint32_t *in = list->face_indices + first[f];
        out->list.face_sizes[at_f++] = size;
        uint32_t rank = 0;
        for (uint32_t j = 0; j < size; j++) {
            const uint32_t v = in[j];
            if (v >= list->num_verts) {
                uint32_t k = 0;
                while (k < j && in[k] != v) k++;
                out->list.face_indices[at + j] =
                    k < j ? out->list.face_indices[at + k] : UINT32_MAX - rank++;
                continue;
            }
            if (stamp[v] != fill) {
                stamp[v] = fill;
                local[v] = at_v;
                memcpy(&out->list.positions[3 * (size_t)at_v], &list->positions[3 * (size_t)v],
                       3 * sizeof(double));
                out->source[at_v++] = v;
            }
            out->list.face_indices[at + j] = local[v];
        }
        at += size;
    }
    for (size_t i = 0; i < n; i++) {
        if (items[i].kind != 1) continue;
        const uint32_t v = items[i].idx;
        memcpy(&out->list.positions[3 * (size_t)at_v], &list->positions[3 * (size_t)v],
               3 * sizeof(double));
        out->source[at_v++] = v;
    }
    return MT_OK;
}

mt_status cli_blocks_split(const mt_face_list *list, double size, cli_block_set *out, mt_diag *diag)
{
    memset(out, 0, sizeof *out);
    if (!(size > 0) || !isfinite(size))
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "the block size must be finite and positive");
    if (list->num_verts > 0 && !list->positions)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "the vertices have no positions");
    const uint32_t nf = list->num_faces, nv = list->num_verts;
    uint64_t *first = malloc(((size_t)nf + 1) * sizeof *first);
    unsigned char *used = calloc(nv ? nv : 1, 1);
    uint32_t *stamp = calloc(nv ? nv : 1, sizeof *stamp);
    uint32_t *local = malloc((nv ? nv : 1) * sizeof *local);
    item *items = malloc(((size_t)nf + nv + 1) * sizeof *items);
    mt_status st = MT_OK;
    if (!first || !used || !stamp || !local || !items) {
        st = mt_diag_set(diag, MT_ERR_NOMEM, "out of memory splitting into blocks");
        goto done;
    }
    first[0] = 0;
    for (uint32_t f = 0; f < nf; f++) first[f + 1] = first[f] + list->face_sizes[f];
    size_t n = 0;
    for (uint32_t f = 0; f < nf; f++) {
        const uint32_t *in = list->face_indices + first[f];
        for (uint32_t j = 0; j < list->face_sizes[f]; j++)
            if (in[j] < nv) used[in[j]] = 1;
        items[n++] = (item){cell_of(list, in, list->face_sizes[f], size), 0, f};
    }
    for (uint32_t v = 0; v < nv; v++)
        if (!used[v]) items[n++] = (item){cell_of(list, &v, 1, size), 1, v};
    qsort(items, n, sizeof *items, item_cmp);
    size_t groups = 0;
    for (size_t i = 0; i < n; i++) groups += i == 0 || key_cmp(items[i].key, items[i - 1].key);
    out->blocks = calloc(groups ? groups : 1, sizeof *out->blocks);
    if (!out->blocks) {
        st = mt_diag_set(diag, MT_ERR_NOMEM, "out of memory splitting into blocks");
        goto done;
    }
    for (size_t a = 0; a < n && st == MT_OK;) {
        size_t b = a + 1;
        while (b < n && key_cmp(items[b].key, items[a].key) == 0) b++;
        /* Two marks per block: counting, then numbering. */
        st = fill_block(list, first, items + a, b - a, stamp, local, (uint32_t)(2 * out->count + 1),
                        &out->blocks[out->count], diag);
        out->count++;
        a = b;
    }
done:
    if (st != MT_OK) cli_block_set_free(out);
    free(first);
    free(used);
    free(stamp);
    free(local);
    free(items);
    return st;
}
