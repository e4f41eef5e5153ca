/* libFuzzer target for mt_mesh_restore (meshtopo/mesh_parts.h): arrays as
 * an archive file could hold them, either a real mesh's arrays with some
 * entries and counts rewritten or arrays made entirely of input bytes. The
 * restore must never read out of bounds (sanitizers watch); when it
 * accepts, mt_mesh_validate must pass and every query must run on every
 * element. Any broken rule calls abort() so the fuzzer keeps the input.
 *
 * Input layout (missing bytes read as 0):
 *   byte 0    bit 7 clear: base mesh (byte % 6: cube, bowtie, fin, 3x2 grid,
 *             moebius, bowtie + two fins); then triples (array, index, value)
 *             rewriting one entry: array byte % 14 (0..11 the uint32 arrays
 *             of mt_mesh_parts in declaration order, 12 a count, 13 the
 *             report's valid face count), index byte, value byte (0xFF =
 *             MT_NONE, 0xFE = 0x7fffffff, 0xFD = 0xffffffff - 1, else byte % 48)
 *             bit 7 set: arrays from bytes: V, copies, F, half-edges / 2,
 *             bundles, bundled (each byte % 16), then every entry one byte
 *             as above, in declaration order. */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/core.h"

static void require(bool ok, const char *what, int line)
{
    if (ok) return;
    fprintf(stderr, "fuzz_mesh_restore.c:%d: invariant violated: %s\n", line, what);
    abort();
}

#define REQUIRE(cond) require((cond), #cond, __LINE__)

typedef struct byte_reader {
    const uint8_t *data;
    size_t size, pos;
} byte_reader;

static uint8_t next_byte(byte_reader *r)
{
    return r->pos < r->size ? r->data[r->pos++] : 0;
}

static uint32_t value_of(uint8_t b)
{
    if (b == 0xFF) return MT_NONE;
    if (b == 0xFE) return 0x7fffffffu;
    if (b == 0xFD) return 0xfffffffeu;
    return b % 48u;
}

#define NUM_ARRAYS 12

/* Owned, exactly sized copies of the arrays (so ASan sees any overrun). */
typedef struct arrays {
    mt_mesh_parts parts;
    uint32_t *a[NUM_ARRAYS];
    size_t len[NUM_ARRAYS];
} arrays;

static const uint32_t **field(mt_mesh_parts *p, int i)
{
    const uint32_t **f[NUM_ARRAYS] = {&p->he_head,        &p->he_next,        &p->he_face,
                                      &p->face_he,        &p->vert_he,        &p->copy_original,
                                      &p->copies_sorted,  &p->bundle_offsets, &p->bundle_edges,
                                      &p->bundled_sorted, &p->bundled_bundle, &p->vert_component};
    return f[i];
}

static void lengths(const mt_mesh_parts *p, size_t *len)
{
    len[0] = len[1] = len[2] = p->num_half_edges;
    len[3] = p->num_faces;
    len[4] = p->num_verts_internal;
    len[5] = len[6] = p->num_copies;
    len[7] = p->num_bundles ? (size_t)p->num_bundles + 1 : 0;
    len[8] = len[9] = len[10] = p->num_bundled;
    len[11] = p->num_verts_internal;
}

static void arrays_take(arrays *x, const mt_mesh_parts *from)
{
    x->parts = *from;
    lengths(from, x->len);
    for (int i = 0; i < NUM_ARRAYS; i++) {
        const uint32_t *src = *field(&x->parts, i);
        if (i == 11 && !src) x->len[i] = 0;
        x->a[i] = x->len[i] ? malloc(x->len[i] * sizeof(uint32_t)) : NULL;
        REQUIRE(x->len[i] == 0 || x->a[i] != NULL);
        if (x->len[i]) memcpy(x->a[i], src, x->len[i] * sizeof(uint32_t));
        *field(&x->parts, i) = x->a[i];
    }
    x->parts.positions = NULL;
}

static void arrays_free(arrays *x)
{
    for (int i = 0; i < NUM_ARRAYS; i++) free(x->a[i]);
}

static mt_status base_list(int kind, mt_face_list *out)
{
    switch (kind) {
        case 0:
            return mt_gen_platonic(MT_CUBE, out);
        case 1:
            return mt_gen_bowtie(out);
        case 2:
            return mt_gen_fin(out);
        case 3:
            return mt_gen_grid(3, 2, true, out);
        case 4:
            return mt_gen_moebius(5, out);
        default: {
            mt_face_list p[3];
            REQUIRE(mt_gen_bowtie(&p[0]) == MT_OK && mt_gen_fin(&p[1]) == MT_OK &&
                    mt_gen_fin(&p[2]) == MT_OK);
            uint32_t nv = 0, nf = 0;
            uint64_t ni = 0;
            for (int i = 0; i < 3; i++) {
                nv += p[i].num_verts;
                nf += p[i].num_faces;
                ni += p[i].num_indices;
            }
            mt_status st = mt_face_list_alloc(out, nv, nf, ni, NULL);
            uint32_t v0 = 0, f0 = 0;
            uint64_t i0 = 0;
            for (int i = 0; i < 3; i++) {
                if (st == MT_OK) {
                    memcpy(out->face_sizes + f0, p[i].face_sizes,
                           p[i].num_faces * sizeof(uint32_t));
                    for (uint64_t k = 0; k < p[i].num_indices; k++)
                        out->face_indices[i0 + k] = p[i].face_indices[k] + v0;
                }
                v0 += p[i].num_verts;
                f0 += p[i].num_faces;
                i0 += p[i].num_indices;
                mt_face_list_free(&p[i]);
            }
            return st;
        }
    }
}

/* Every query on every element (and one past): must not crash. */
static void run_queries(const mt_mesh *m)
{
    const uint32_t nv = mt_mesh_num_verts(m), nf = mt_mesh_num_faces(m);
    for (uint32_t v = 0; v <= nv; v++) {
        mt_ring ring;
        memset(&ring, 0, sizeof ring);
        mt_status st = mt_vert_ring(m, v, &ring);
        if (st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL) {
            ring.neighbors = malloc((ring.num_neighbors + 1) * sizeof(uint32_t));
            ring.faces = malloc((ring.num_faces + 1) * sizeof(uint32_t));
            ring.fans = malloc((ring.num_fans + 1) * sizeof(mt_fan));
            ring.neighbors_capacity = ring.num_neighbors;
            ring.faces_capacity = ring.num_faces;
            ring.fans_capacity = ring.num_fans;
            REQUIRE(mt_vert_ring(m, v, &ring) == MT_OK);
            free(ring.neighbors);
            free(ring.faces);
            free(ring.fans);
        }
        uint32_t valence;
        mt_vert_valence(m, v, &valence);
    }
    for (uint32_t f = 0; f <= nf; f++) {
        size_t n = 0, nn = 0, ne = 0;
        uint32_t c, verts[64], offsets[65], faces[256];
        if (mt_face_verts(m, f, verts, 64, &n) == MT_OK && n >= 2) {
            size_t k = 0;
            mt_edge_faces(m, verts[0], verts[1], faces, 256, &k);
        }
        mt_face_neighbors(m, f, faces, 256, offsets, 65, &nn, &ne);
        mt_face_component(m, f, &c);
    }
    size_t lv = 0, ll = 0;
    mt_status st = mt_boundary_loops(m, NULL, 0, NULL, 0, &lv, &ll);
    if (st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL) {
        uint32_t *verts = malloc((lv + 1) * sizeof(uint32_t));
        uint32_t *offs = malloc((ll + 2) * sizeof(uint32_t));
        REQUIRE(mt_boundary_loops(m, verts, lv, offs, ll + 1, &lv, &ll) == MT_OK);
        free(verts);
        free(offs);
    }
}

static void try_restore(const mt_mesh_parts *parts, const mt_report *report)
{
    mt_mesh *m = NULL;
    mt_diag diag;
    mt_status st = mt_mesh_restore(parts, report, &m, &diag);
    if (st != MT_OK) {
        REQUIRE(m == NULL);
        REQUIRE(diag.message[0] != '\0');
        return;
    }
    REQUIRE(mt_mesh_validate(m, NULL) == MT_OK);
    run_queries(m);
    mt_mesh_destroy(m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    byte_reader r = {data, size, 0};
    const uint8_t mode = next_byte(&r);
    if (!(mode & 0x80)) {
        mt_face_list list;
        REQUIRE(base_list(mode % 6, &list) == MT_OK);
        mt_mesh *built = NULL;
        REQUIRE(mt_mesh_build(&list, NULL, &built, NULL) == MT_OK);
        mt_face_list_free(&list);
        mt_mesh_parts parts;
        mt_mesh_get_parts(built, &parts);
        arrays x;
        arrays_take(&x, &parts);
        mt_report report = *mt_mesh_report(built);
        while (r.pos < r.size) {
            const uint8_t which = next_byte(&r) % 14, index = next_byte(&r);
            const uint32_t value = value_of(next_byte(&r));
            if (which < NUM_ARRAYS) {
                if (x.len[which]) x.a[which][index % x.len[which]] = value;
            } else if (which == 12) {
                /* A count: the arrays stay as long as they were, so only a
                 * count smaller than the real one keeps reads in bounds for
                 * the caller's side; restore must cope with the rest. */
                uint32_t *counts[] = {&x.parts.num_half_edges,     &x.parts.num_faces,
                                      &x.parts.num_verts_internal, &x.parts.num_copies,
                                      &x.parts.num_bundles,        &x.parts.num_bundled};
                uint32_t *c = counts[index % 6];
                if (value < *c) *c = value;
            } else {
                report.num_faces_valid = value;
            }
        }
        try_restore(&x.parts, &report);
        arrays_free(&x);
        mt_mesh_destroy(built);
        return 0;
    }
    /* Arrays made of bytes, with a report that agrees on the counts. */
    mt_mesh_parts p;
    memset(&p, 0, sizeof p);
    p.num_verts = next_byte(&r) % 16;
    p.num_copies = next_byte(&r) % 16;
    p.num_verts_internal = p.num_verts + p.num_copies;
    p.num_faces = next_byte(&r) % 16;
    p.num_half_edges = 2 * (next_byte(&r) % 16);
    p.num_bundles = next_byte(&r) % 16;
    p.num_bundled = p.num_bundles ? next_byte(&r) % 16 : 0;
    const bool components = next_byte(&r) & 1;
    arrays x;
    memset(&x, 0, sizeof x);
    x.parts = p;
    lengths(&p, x.len);
    if (!components) x.len[11] = 0;
    uint32_t faces_valid = 0;
    for (int i = 0; i < NUM_ARRAYS; i++) {
        x.a[i] = x.len[i] ? malloc(x.len[i] * sizeof(uint32_t)) : NULL;
        for (size_t k = 0; k < x.len[i]; k++) x.a[i][k] = value_of(next_byte(&r));
        *field(&x.parts, i) = x.a[i];
    }
    if (p.num_bundles) x.a[7][p.num_bundles] = p.num_bundled; /* else refused at once */
    for (uint32_t f = 0; f < p.num_faces; f++) faces_valid += x.a[3][f] != MT_NONE;
    mt_report report;
    memset(&report, 0, sizeof report);
    report.num_verts = p.num_verts;
    report.num_faces = p.num_faces;
    report.num_faces_valid = faces_valid;
    report.connected_components = next_byte(&r) % 4;
    mt_component_info comps[4];
    memset(comps, 0, sizeof comps);
    report.components = comps;
    try_restore(&x.parts, &report);
    arrays_free(&x);
    return 0;
}
