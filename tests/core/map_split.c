/* Test helpers for the block map: splitting a mesh into mapper-style blocks,
 * the reference welded union, and comparing a map's counts with the report
 * of a full mt_mesh_build (see map_split.h). */
#include "map_split.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "meshtopo/io.h"
#include "meshtopo/validate.h"

static void *xalloc(size_t bytes)
{
    void *p = calloc(bytes ? bytes : 1, 1);
    if (!p) {
        fprintf(stderr, "map_split: out of memory\n");
        abort();
    }
    return p;
}

void map_list_copy(const mt_face_list *src, mt_face_list *dst)
{
    memset(dst, 0, sizeof *dst);
    dst->num_verts = src->num_verts;
    dst->num_faces = src->num_faces;
    dst->num_indices = src->num_indices;
    dst->positions = xalloc((size_t)src->num_verts * 3 * sizeof(double));
    dst->face_sizes = xalloc((size_t)src->num_faces * sizeof(uint32_t));
    dst->face_indices = xalloc((size_t)src->num_indices * sizeof(uint32_t));
    if (src->positions)
        memcpy(dst->positions, src->positions, (size_t)src->num_verts * 3 * sizeof(double));
    if (src->num_faces)
        memcpy(dst->face_sizes, src->face_sizes, (size_t)src->num_faces * sizeof(uint32_t));
    if (src->num_indices)
        memcpy(dst->face_indices, src->face_indices, (size_t)src->num_indices * sizeof(uint32_t));
}

static mt_map_key key_of(const mt_face_list *list, const uint32_t *idx, uint32_t n, double size)
{
    double c[3] = {0, 0, 0};
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (idx[i] >= list->num_verts) continue;
        for (int a = 0; a < 3; a++) c[a] += list->positions[3 * (size_t)idx[i] + a];
        k++;
    }
    mt_map_key key = {-999, 0, 0};
    if (k == 0) return key;
    int32_t q[3];
    for (int a = 0; a < 3; a++) {
        double x = floor(c[a] / k / size);
        if (!isfinite(x) || x < -1e6 || x > 1e6) return key;
        q[a] = (int32_t)x;
    }
    key.x = q[0];
    key.y = q[1];
    key.z = q[2];
    return key;
}

static bool same_key(mt_map_key a, mt_map_key b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

void map_split(const mt_face_list *list, double size, bool soup, map_block_set *out)
{
    memset(out, 0, sizeof *out);
    const uint32_t nf = list->num_faces;
    mt_map_key *keys = xalloc((size_t)nf * sizeof *keys);
    uint64_t *first = xalloc(((size_t)nf + 1) * sizeof *first);
    for (uint32_t f = 0; f < nf; f++) first[f + 1] = first[f] + list->face_sizes[f];
    for (uint32_t f = 0; f < nf; f++)
        keys[f] = key_of(list, list->face_indices + first[f], list->face_sizes[f], size);
    /* Distinct keys in first-use order. */
    mt_map_key *distinct = xalloc((size_t)(nf ? nf : 1) * sizeof *distinct);
    uint32_t *block_of = xalloc((size_t)nf * sizeof *block_of);
    size_t nb = 0;
    for (uint32_t f = 0; f < nf; f++) {
        size_t b = 0;
        while (b < nb && !same_key(distinct[b], keys[f])) b++;
        if (b == nb) distinct[nb++] = keys[f];
        block_of[f] = (uint32_t)b;
    }
    out->blocks = xalloc(nb * sizeof *out->blocks);
    out->count = nb;
    uint32_t *local = xalloc((size_t)(list->num_verts ? list->num_verts : 1) * sizeof *local);
    for (size_t b = 0; b < nb; b++) {
        map_block_src *src = &out->blocks[b];
        src->key = distinct[b];
        uint32_t faces = 0;
        uint64_t indices = 0;
        for (uint32_t f = 0; f < nf; f++)
            if (block_of[f] == b) faces++, indices += list->face_sizes[f];
        /* At most one vertex per index. */
        double *pos = xalloc((size_t)(indices ? indices : 1) * 3 * sizeof(double));
        uint32_t *ids = xalloc((size_t)(indices ? indices : 1) * sizeof(uint32_t));
        uint32_t *sizes = xalloc((size_t)faces * sizeof(uint32_t));
        uint32_t *idx = xalloc((size_t)indices * sizeof(uint32_t));
        for (uint32_t v = 0; v < list->num_verts; v++) local[v] = MT_NONE;
        uint32_t nv = 0, fi = 0;
        uint64_t at = 0;
        for (uint32_t f = 0; f < nf; f++) {
            if (block_of[f] != b) continue;
            const uint32_t n = list->face_sizes[f];
            const uint32_t *in = list->face_indices + first[f];
            sizes[fi++] = n;
            for (uint32_t i = 0; i < n; i++) {
                const uint32_t v = in[i];
                if (v >= list->num_verts) {
                    idx[at + i] = MT_NONE; /* fixed below */
                    continue;
                }
                if (soup) {
                    /* A face's own copy; a vertex repeated in the face stays one. */
                    uint32_t j = 0;
                    while (j < i && in[j] != v) j++;
                    if (j < i) {
                        idx[at + i] = idx[at + j];
                        continue;
                    }
                } else if (local[v] != MT_NONE) {
                    idx[at + i] = local[v];
                    continue;
                }
                memcpy(&pos[3 * (size_t)nv], &list->positions[3 * (size_t)v], 3 * sizeof(double));
                ids[nv] = v;
                local[v] = nv;
                idx[at + i] = nv++;
            }
            at += n;
        }
        /* Out-of-range entries: past the block's vertices, equal values kept equal. */
        at = 0;
        for (uint32_t f = 0; f < nf; f++) {
            if (block_of[f] != b) continue;
            const uint32_t n = list->face_sizes[f];
            const uint32_t *in = list->face_indices + first[f];
            uint32_t rank = 0;
            for (uint32_t i = 0; i < n; i++) {
                if (in[i] < list->num_verts) continue;
                uint32_t j = 0;
                while (j < i && in[j] != in[i]) j++;
                idx[at + i] = j < i ? idx[at + j] : nv + 7 + rank++;
            }
            at += n;
        }
        src->list.num_verts = nv;
        src->list.num_faces = faces;
        src->list.num_indices = indices;
        src->list.positions = pos;
        src->list.face_sizes = sizes;
        src->list.face_indices = idx;
        src->ids = ids;
    }
    free(local);
    free(keys);
    free(first);
    free(distinct);
    free(block_of);
}

void map_block_set_free(map_block_set *set)
{
    for (size_t b = 0; b < set->count; b++) {
        mt_face_list_free(&set->blocks[b].list);
        free(set->blocks[b].ids);
    }
    free(set->blocks);
    memset(set, 0, sizeof *set);
}

void map_union_welded(const mt_face_list *const *lists, size_t n, mt_face_list *out)
{
    uint64_t nv = 0, nf = 0, ni = 0;
    for (size_t b = 0; b < n; b++)
        nv += lists[b]->num_verts, nf += lists[b]->num_faces, ni += lists[b]->num_indices;
    mt_diag d;
    if (mt_face_list_alloc(out, (uint32_t)nv, (uint32_t)nf, ni, &d) != MT_OK) abort();
    uint32_t voff = 0, foff = 0;
    uint64_t at = 0;
    for (size_t b = 0; b < n; b++) {
        const mt_face_list *l = lists[b];
        if (l->num_verts)
            memcpy(&out->positions[3 * (size_t)voff], l->positions,
                   (size_t)l->num_verts * 3 * sizeof(double));
        uint64_t in_at = 0;
        for (uint32_t f = 0; f < l->num_faces; f++) {
            const uint32_t size = l->face_sizes[f];
            const uint32_t *in = l->face_indices + in_at;
            out->face_sizes[foff + f] = size;
            uint32_t rank = 0;
            for (uint32_t i = 0; i < size; i++) {
                if (in[i] < l->num_verts) {
                    out->face_indices[at + i] = voff + in[i];
                    continue;
                }
                uint32_t j = 0;
                while (j < i && in[j] != in[i]) j++;
                out->face_indices[at + i] = j < i ? out->face_indices[at + j] : MT_NONE - rank++;
            }
            at += size;
            in_at += size;
        }
        voff += l->num_verts;
        foff += l->num_faces;
    }
    if (mt_face_list_weld(out, 0, NULL, NULL, &d) != MT_OK) {
        fprintf(stderr, "map_union_welded: %s\n", d.message);
        abort();
    }
}

/* Records a failure with mt_map_compare_report's message when the map
 * differs from the report; returns 1 then, else 0. */
static int map_check_report(const mt_map *map, const mt_report *r, const char *what)
{
    mt_diag d;
    if (mt_map_compare_report(map, r, &d) == MT_OK) return 0;
    mt_test_fail(__FILE__, __LINE__, "%s: map differs from the full build: %s", what, d.message);
    return 1;
}

int map_check_against_list(const mt_map *map, const mt_face_list *list, const char *what)
{
    mt_mesh *mesh = NULL;
    mt_diag d;
    mt_build_options opts = {0};
    opts.threads = 1;
    if (mt_mesh_build(list, &opts, &mesh, &d) != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: build failed: %s", what, d.message);
        return 1;
    }
    int bad = 0;
    if (mt_mesh_validate(mesh, &d) != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: validate: %s", what, d.message);
        bad++;
    }
    bad += map_check_report(map, mt_mesh_report(mesh), what);
    mt_mesh_destroy(mesh);
    return bad;
}

int map_check_full(const mt_map *map, const char *what)
{
    mt_map_counts c;
    mt_map_get_counts(map, &c);
    uint32_t *vids = xalloc((size_t)c.num_verts * sizeof *vids);
    uint32_t *fids = xalloc((size_t)c.num_faces * sizeof *fids);
    mt_face_list list;
    mt_diag d;
    int bad = 0;
    if (mt_map_face_list(map, &list, vids, c.num_verts, fids, c.num_faces, &d) != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: mt_map_face_list: %s", what, d.message);
        free(vids);
        free(fids);
        return 1;
    }
    bad += map_check_against_list(map, &list, what);
    /* The ids: every list face is the map face it names, corner by corner. */
    uint64_t at = 0;
    uint32_t corners[64];
    for (uint32_t f = 0; f < list.num_faces && bad == 0; f++) {
        size_t n = 0;
        mt_status s = mt_map_face_verts(map, fids[f], corners, 64, &n);
        if (s == MT_ERR_BUFFER_TOO_SMALL) {
            at += list.face_sizes[f];
            continue;
        }
        if (s != MT_OK || n != list.face_sizes[f]) {
            mt_test_fail(__FILE__, __LINE__, "%s: face %u (map %u): %s", what, f, fids[f],
                         mt_strerror(s));
            bad++;
            break;
        }
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t x = list.face_indices[at + i];
            const uint32_t want = x < list.num_verts ? vids[x] : MT_NONE;
            if (corners[i] != want) {
                mt_test_fail(__FILE__, __LINE__, "%s: face %u corner %u: map %u, list %u", what,
                             fids[f], i, corners[i], want);
                bad++;
                break;
            }
        }
        at += list.face_sizes[f];
    }
    mt_face_list_free(&list);
    free(vids);
    free(fids);
    return bad;
}
