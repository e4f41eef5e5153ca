/* mt_mesh_build: checks the input, plans the parts, allocates the mesh's
 * arrays and runs the phases in order (faces, edges, links, fans, then the
 * report; see build/build_state.h); a mesh is freed by mesh/mesh_lifetime.c.
 * A build makes a fixed number of allocations whatever the mesh size (plus
 * O(log n) for defect and bundle lists, which grow geometrically). */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "build/build_phases.h"
#include "meshtopo/report.h"
#include "report/report_internal.h"

/* A mesh array of count * elem bytes, every byte 0xff if asked: an array
 * the workspace kept from a recycled mesh when one fits, else new memory. */
static void *mesh_array(mt__build *b, size_t count, size_t elem, int fill_none)
{
    size_t bytes;
    if (!mt__mul_size(count, elem, &bytes)) return NULL;
    void *p = mt__kept_array_take(b->workspace, bytes);
    if (!p) p = mt__malloc(bytes);
    if (p && fill_none) memset(p, 0xff, bytes);
    return p;
}

/* The half-edge block (see MT__HE_STAGGER). */
static mt_status alloc_half_edges(mt__build *b)
{
    mt_mesh *m = b->m;
    const size_t n = m->num_half_edges, stagger = MT__HE_STAGGER / sizeof(uint32_t);
    uint32_t *block = mesh_array(b, 3 * n + 2 * stagger, sizeof(uint32_t), 0);
    if (!block) return MT_ERR_NOMEM;
    m->he_head = block;
    m->he_next = block + n + stagger;
    m->he_face = m->he_next + n + stagger;
    return MT_OK;
}

static void build_free_temporaries(mt__build *b)
{
    mt__free(b->block_start);
    mt__scratch_put(b, b->sides);
    mt__free(b->block_half_edges);
    mt__scratch_put(b, b->c2h);
    mt__scratch_put(b, (void *)b->fan_start);
    for (uint32_t t = 0; t < MT__MAX_PARTS; t++) {
        mt__part *p = &b->part[t];
        mt__scratch_put(b, p->degree);
        mt__free(p->block_sides);
        mt__vec_free(&p->large_sizes);
        mt__vec_free(&p->invalid_refs);
        mt__vec_free(&p->defects);
        mt__vec_free(&p->scratch);
        mt__vec_free(&p->large_uses);
        mt__vec_free(&p->bundle_offsets);
        mt__vec_free(&p->bundle_edges);
        mt__vec_free(&p->split_verts);
        mt__vec_free(&p->boundary_halves);
        mt__vec_free(&p->dup_candidates);
    }
    mt__vec_free(&b->large_sizes);
    mt__vec_free(&b->invalid_refs);
    mt__vec_free(&b->defects);
    mt__vec_free(&b->large_uses);
    mt__vec_free(&b->bundle_offsets);
    mt__vec_free(&b->bundle_edges);
    mt__vec_free(&b->copy_original);
    mt__vec_free(&b->split_verts);
    mt__vec_free(&b->boundary_halves);
    mt__vec_free(&b->dup_candidates);
}

static mt_status check_input(const mt_face_list *in, mt_mesh **out_mesh, mt_diag *diag)
{
    if (!out_mesh) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "build: out_mesh is NULL");
    *out_mesh = NULL;
    if (!in) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "build: input face list is NULL");
    mt_status s = mt_face_list_check(in, diag);
    if (s != MT_OK) return s;
    if (in->num_indices > 0x7fffffffu)
        return mt__fail(diag, MT_ERR_TOO_LARGE, MT_NONE,
                        "build: %llu face indices; at most 2^31 - 1 are supported",
                        (unsigned long long)in->num_indices);
    if (in->num_verts > 0x7fffffffu)
        return mt__fail(diag, MT_ERR_TOO_LARGE, MT_NONE,
                        "build: %u vertices; at most 2^31 - 1 are supported", in->num_verts);
    return MT_OK;
}

static mt_status strict_refusal(mt__build *b)
{
    const mt_report *r = &b->m->report;
    if (r->num_defects == 0) return MT_OK;
    char text[400];
    mt_defect_describe(&r->defects[0], text, sizeof text);
    return mt__fail(b->diag, MT_ERR_DEFECT, r->defects[0].a,
                    "strict build refused: %s (%zu defect%s in all)", text, r->num_defects,
                    r->num_defects == 1 ? "" : "s");
}

/* Online processor cores (at least 1). */
static uint32_t online_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (uint32_t)n : 1u;
}

/* Splits faces (by corner count) and vertices into parts for the parallel
 * phases; one part for small meshes or when asked for one thread. */
static void plan_parts(mt__build *b, uint32_t threads)
{
    const mt_face_list *in = b->in;
    uint32_t parts = threads;
    if (threads == 0) parts = in->num_indices < MT__PARALLEL_MIN_CORNERS ? 1 : online_cores();
    if (parts > MT__MAX_PARTS) parts = MT__MAX_PARTS;
    b->parts = parts;
    uint32_t f = 0;
    uint64_t offset = 0;
    for (uint32_t t = 0; t < parts; t++) {
        mt__part *p = &b->part[t];
        const uint64_t goal = in->num_indices * (t + 1) / parts;
        p->face_begin = f;
        p->index_begin = (uint32_t)offset;
        while (f < in->num_faces && (t + 1 == parts || offset < goal))
            offset += in->face_sizes[f++];
        p->face_end = f;
        p->vert_begin = (uint32_t)((uint64_t)in->num_verts * t / parts);
        p->vert_end = (uint32_t)((uint64_t)in->num_verts * (t + 1) / parts);
        p->status = MT_OK;
        p->large_sizes.elem_size = p->invalid_refs.elem_size = sizeof(uint32_t);
        p->scratch.elem_size = p->large_uses.elem_size = sizeof(uint32_t);
        p->bundle_offsets.elem_size = p->bundle_edges.elem_size = sizeof(uint32_t);
        p->split_verts.elem_size = p->dup_candidates.elem_size = sizeof(uint32_t);
        p->boundary_halves.elem_size = sizeof(uint32_t);
        p->defects.elem_size = sizeof(mt_defect);
    }
}

static mt_status build(mt__build *b)
{
    const mt_face_list *in = b->in;
    mt_mesh *m = b->m;
    m->num_verts = m->num_verts_internal = in->num_verts;
    m->num_faces = in->num_faces;
    m->face_he = mesh_array(b, in->num_faces, sizeof(uint32_t), 0);
    if (in->positions)
        m->positions = b->positions_taken ? in->positions
                                          : mesh_array(b, in->num_verts, 3 * sizeof(double), 0);
    if (!m->face_he || (in->positions && !m->positions)) return MT_ERR_NOMEM;
    b->block_shift = MT__BLOCK_MIN_SHIFT;
    while ((in->num_verts >> b->block_shift) >= MT__MAX_BLOCKS) b->block_shift++;
    b->num_blocks = (in->num_verts >> b->block_shift) + 1;
    for (uint32_t t = 0; t < b->parts; t++) {
        b->part[t].degree = mt__scratch_get(b, MT__SCRATCH_DEGREE + t, (size_t)in->num_verts + 1,
                                            sizeof(uint32_t), 1);
        b->part[t].block_sides = mt__calloc(b->num_blocks, sizeof(uint32_t));
        if (!b->part[t].degree || !b->part[t].block_sides) return MT_ERR_NOMEM;
    }

    mt_status s = mt__build_faces(b);
    if (s != MT_OK) return s;

    b->sides = mt__scratch_get(b, MT__SCRATCH_SIDES, b->num_corners, sizeof(mt__side), 0);
    b->block_start = mt__malloc(((size_t)b->num_blocks + 1) * sizeof(uint32_t));
    b->block_half_edges = mt__malloc((size_t)b->num_blocks * sizeof(uint32_t));
    b->c2h = mt__scratch_get(b, MT__SCRATCH_C2H, in->num_indices, sizeof(uint32_t), 0);
    if (!b->sides || !b->block_start || !b->block_half_edges || !b->c2h) return MT_ERR_NOMEM;
    s = mt__build_edges(b);
    if (s != MT_OK) return s;

    m->num_half_edges = 2 * b->num_internal_edges;
    if (alloc_half_edges(b) != MT_OK) return MT_ERR_NOMEM;
    mt__build_edges_publish(b);
    mt__scratch_put(b, b->sides);
    b->sides = NULL;

    m->vert_he = mesh_array(b, in->num_verts, sizeof(uint32_t), 1);
    b->vert_capacity = in->num_verts;
    b->fan_start = mt__scratch_get(b, MT__SCRATCH_FAN_START, in->num_verts, sizeof(uint32_t), 0);
    if (!m->vert_he || !b->fan_start) return MT_ERR_NOMEM;
    mt__build_links(b);
    mt__scratch_put(b, b->c2h);
    b->c2h = NULL;

    s = mt__build_fans(b);
    if (s != MT_OK) return s;
    for (uint32_t t = 0; t < b->parts; t++) {
        mt__scratch_put(b, b->part[t].degree);
        b->part[t].degree = NULL;
    }
    return mt__build_report(b);
}

/* mt_mesh_build, with the mesh taking in->positions instead of a copy when
 * `take_positions`. */
static mt_status build_mesh(const mt_face_list *in, bool take_positions,
                            const mt_build_options *options, mt_mesh **out_mesh, mt_diag *diag)
{
    mt_diag_clear(diag);
    mt_status s = check_input(in, out_mesh, diag);
    if (s != MT_OK) return s;
    mt__build b;
    memset(&b, 0, sizeof b);
    b.in = in;
    b.diag = diag;
    b.workspace = options ? options->workspace : NULL;
    b.positions_taken = take_positions;
    plan_parts(&b, options ? options->threads : 0);
    b.large_sizes.elem_size = b.invalid_refs.elem_size = sizeof(uint32_t);
    b.large_uses.elem_size = sizeof(uint32_t);
    b.bundle_offsets.elem_size = b.bundle_edges.elem_size = sizeof(uint32_t);
    b.copy_original.elem_size = b.split_verts.elem_size = sizeof(uint32_t);
    b.boundary_halves.elem_size = sizeof(uint32_t);
    b.dup_candidates.elem_size = sizeof(uint32_t);
    b.defects.elem_size = sizeof(mt_defect);
    b.m = mt__calloc(1, sizeof(mt_mesh));
    if (!b.m) return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "build: out of memory");
    s = build(&b);
    if (s == MT_OK && options && options->strict) s = strict_refusal(&b);
    build_free_temporaries(&b);
    if (s != MT_OK) {
        if (s == MT_ERR_NOMEM && (!diag || diag->status == MT_OK))
            mt__fail(diag, MT_ERR_NOMEM, MT_NONE,
                     "build: out of memory (%u vertices, %u faces, %llu indices)", in->num_verts,
                     in->num_faces, (unsigned long long)in->num_indices);
        if (b.positions_taken) b.m->positions = NULL; /* still the caller's */
        mt_mesh_destroy(b.m);
        return s;
    }
    *out_mesh = b.m;
    return MT_OK;
}

mt_status mt_mesh_build(const mt_face_list *in, const mt_build_options *options, mt_mesh **out_mesh,
                        mt_diag *diag)
{
    return build_mesh(in, false, options, out_mesh, diag);
}

mt_status mt_mesh_build_taking_positions(mt_face_list *in, const mt_build_options *options,
                                         mt_mesh **out_mesh, mt_diag *diag)
{
    mt_status s = build_mesh(in, true, options, out_mesh, diag);
    if (s == MT_OK) in->positions = NULL;
    return s;
}
