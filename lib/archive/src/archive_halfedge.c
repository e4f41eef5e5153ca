/* The half-edge arrays in an archive file (format 2): group
 * /meshtopo/halfedge holds every array of the built mesh (meshtopo/
 * mesh_parts.h) as a 1-D uint32 dataset named for what it holds, with the
 * counts as attributes, so that a reload restores the mesh instead of
 * rebuilding it, and (format 4) their digest (archive_hash.c). Reading
 * checks every length; the values are left to mt_mesh_restore, which
 * validates them, and to the digest, which tells whether they are the ones
 * archived. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"

/* Which count gives a dataset's length. */
typedef enum count_kind {
    COUNT_HALF_EDGES,
    COUNT_FACES,
    COUNT_VERTS_INTERNAL,
    COUNT_COPIES,
    COUNT_BUNDLE_OFFSETS, /* num_bundles + 1, or 0 without bundles */
    COUNT_BUNDLED,
    COUNT_COMPONENTS /* num_verts_internal, or 0 when the mesh keeps none */
} count_kind;

typedef struct array_desc {
    const char *name;
    count_kind count;
    size_t offset;        /* of the const uint32_t * in mt_mesh_parts */
    size_t buffer_offset; /* of the uint32_t * in mt_mesh_parts_buffers */
} array_desc;

#define ARRAY(name, count, field)                                                           \
    {                                                                                       \
        name, count, offsetof(mt_mesh_parts, field), offsetof(mt_mesh_parts_buffers, field) \
    }

static const array_desc arrays[] = {
    ARRAY("head", COUNT_HALF_EDGES, he_head),
    ARRAY("next", COUNT_HALF_EDGES, he_next),
    ARRAY("face", COUNT_HALF_EDGES, he_face),
    ARRAY("face_halfedge", COUNT_FACES, face_he),
    ARRAY("vertex_halfedge", COUNT_VERTS_INTERNAL, vert_he),
    ARRAY("copy_original", COUNT_COPIES, copy_original),
    ARRAY("copies_sorted", COUNT_COPIES, copies_sorted),
    ARRAY("bundle_offsets", COUNT_BUNDLE_OFFSETS, bundle_offsets),
    ARRAY("bundle_edges", COUNT_BUNDLED, bundle_edges),
    ARRAY("bundled_sorted", COUNT_BUNDLED, bundled_sorted),
    ARRAY("bundled_bundle", COUNT_BUNDLED, bundled_bundle),
    ARRAY("vertex_component", COUNT_COMPONENTS, vert_component),
};
#define NUM_ARRAYS (sizeof arrays / sizeof arrays[0])

static const uint32_t **array_field(mt_mesh_parts *p, const array_desc *d)
{
    return (const uint32_t **)((char *)p + d->offset);
}

static uint64_t array_length(const mt_mesh_parts *p, count_kind kind)
{
    switch (kind) {
        case COUNT_HALF_EDGES:
            return p->num_half_edges;
        case COUNT_FACES:
            return p->num_faces;
        case COUNT_VERTS_INTERNAL:
            return p->num_verts_internal;
        case COUNT_COPIES:
            return p->num_copies;
        case COUNT_BUNDLE_OFFSETS:
            return p->num_bundles ? (uint64_t)p->num_bundles + 1 : 0;
        case COUNT_BUNDLED:
            return p->num_bundled;
        case COUNT_COMPONENTS:
            return p->vert_component ? p->num_verts_internal : 0;
    }
    return 0;
}

/* The count attributes of the group, named like mt_mesh_parts' fields. */
typedef struct count_attr {
    const char *name;
    size_t offset; /* of the uint32_t in mt_mesh_parts */
} count_attr;

static const count_attr count_attrs[] = {
    {"num_verts_internal", offsetof(mt_mesh_parts, num_verts_internal)},
    {"num_half_edges", offsetof(mt_mesh_parts, num_half_edges)},
    {"num_copies", offsetof(mt_mesh_parts, num_copies)},
    {"num_bundles", offsetof(mt_mesh_parts, num_bundles)},
    {"num_bundled", offsetof(mt_mesh_parts, num_bundled)},
};
#define NUM_COUNT_ATTRS (sizeof count_attrs / sizeof count_attrs[0])

static const char description[] =
    "half-edge structure of the built mesh (meshtopo/mesh_parts.h), so that a reload "
    "skips the rebuild. Half-edges come in twins h and h^1 (edge h>>1); 4294967295 means "
    "none. head/next/face [num_half_edges]: vertex each half-edge points to, next "
    "half-edge of its face or boundary ring, its face (none on a boundary). "
    "face_halfedge [faces]: half-edge from a face's first vertex to its second (none for a "
    "rejected face). vertex_halfedge [num_verts_internal]: an outgoing half-edge (the "
    "boundary one on a boundary). Internal vertices past num_verts are copies of caller "
    "vertex copy_original[i], one per extra fan; copies_sorted orders them by original. "
    "bundle_offsets/bundle_edges: internal edges holding one caller edge (non-manifold or "
    "same-direction edges); bundled_sorted/bundled_bundle index them. vertex_component: "
    "edge-connected component of each internal vertex (empty for one component). "
    "digest: XXH3-64 over 64-bit little-endian words: the mesh's content_hash, the counts "
    "(num_verts, num_faces, num_verts_internal, num_half_edges, num_copies, num_bundles, "
    "num_bundled, 1 if vertex_component is stored, 1 if positions are), the XXH3-64 of each "
    "array above in this order, of /meshtopo/positions and of the report's values, so that a "
    "reload can check them without a rebuild.";

mt_status mt__halfedge_write(hid_t g, const mt_mesh *mesh, uint64_t content_hash,
                             const mt__h5_layout *layout, const char *file, mt_diag *diag)
{
    mt_mesh_parts p;
    mt_mesh_get_parts(mesh, &p);
    uint64_t digest = 0;
    mt_status st = mt__halfedge_digest(&p, mt_mesh_report(mesh), content_hash, &digest, diag);
    if (st != MT_OK) return st;
    hid_t hg = H5Gcreate2(g, "halfedge", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (hg < 0) return mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot create group halfedge", file);
    st = mt__h5_write_attr_string(hg, "description", description, file, diag);
    const uint32_t none = MT_NONE;
    if (st == MT_OK)
        st = mt__h5_write_attr_int(hg, "none_value", H5T_NATIVE_UINT32, &none, file, diag);
    if (st == MT_OK)
        st = mt__h5_write_attr_int(hg, "digest", H5T_NATIVE_UINT64, &digest, file, diag);
    for (size_t i = 0; st == MT_OK && i < NUM_COUNT_ATTRS; i++) {
        const uint32_t *value = (const uint32_t *)((const char *)&p + count_attrs[i].offset);
        int64_t v = *value;
        st = mt__h5_write_attr_int(hg, count_attrs[i].name, H5T_NATIVE_INT64, &v, file, diag);
    }
    for (size_t i = 0; st == MT_OK && i < NUM_ARRAYS; i++) {
        hsize_t dims[1] = {array_length(&p, arrays[i].count)};
        st = mt__h5_write_dataset_layout(hg, arrays[i].name, H5T_STD_U32LE, H5T_NATIVE_UINT32, 1,
                                         dims, *array_field(&p, &arrays[i]), layout, file, diag);
    }
    H5Gclose(hg);
    return st;
}

/* A count attribute: 0 .. 2^31 - 1. */
static mt_status read_count(hid_t g, const char *group, const char *name, const char *file,
                            uint32_t *out, mt_diag *diag)
{
    int64_t v = 0;
    mt_status st = mt__h5_read_attr_i64(g, name, file, &v, diag);
    if (st == MT_OK && (v < 0 || (uint64_t)v > MT__ARCHIVE_MAX_ELEMENTS))
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: attribute %s/%s is %lld (0 to 2^31 - 1)",
                              file, group, name, (long long)v);
    if (st == MT_OK) *out = (uint32_t)v;
    return st;
}

/* The shape of the stored mesh: counts from the attributes, and whether
 * positions and vertex components are stored (their datasets' lengths). */
static mt_status read_shape(hid_t g, hid_t hg, const char *file, mt_mesh_parts *p,
                            mt_mesh_shape *shape, mt_diag *diag)
{
    mt_status st = read_count(g, "meshtopo", "num_verts", file, &p->num_verts, diag);
    if (st == MT_OK) st = read_count(g, "meshtopo", "num_faces", file, &p->num_faces, diag);
    for (size_t i = 0; st == MT_OK && i < NUM_COUNT_ATTRS; i++)
        st = read_count(hg, "meshtopo/halfedge", count_attrs[i].name, file,
                        (uint32_t *)((char *)p + count_attrs[i].offset), diag);
    uint64_t component_rows = 0, position_rows = 0;
    if (st == MT_OK)
        st = mt__h5_dataset_rows(hg, "/meshtopo/halfedge/vertex_component", file, 1, 0, MT__H5_UINT,
                                 4, &component_rows, diag);
    if (st == MT_OK && component_rows != 0 && component_rows != p->num_verts_internal)
        st = mt__archive_fail(diag, MT_ERR_PARSE,
                              "%s: dataset meshtopo/halfedge/vertex_component has %llu entries, "
                              "not num_verts_internal (%u) or 0",
                              file, (unsigned long long)component_rows, p->num_verts_internal);
    if (st == MT_OK)
        st = mt__h5_dataset_rows(g, "/meshtopo/positions", file, 2, 3, MT__H5_FLOAT, 8,
                                 &position_rows, diag);
    if (st == MT_OK && position_rows != 0 && position_rows != p->num_verts)
        st = mt__archive_fail(diag, MT_ERR_PARSE,
                              "%s: dataset meshtopo/positions has %llu rows but num_verts is %u",
                              file, (unsigned long long)position_rows, p->num_verts);
    if (st != MT_OK) return st;
    shape->num_verts = p->num_verts;
    shape->num_verts_internal = p->num_verts_internal;
    shape->num_faces = p->num_faces;
    shape->num_half_edges = p->num_half_edges;
    shape->num_copies = p->num_copies;
    shape->num_bundles = p->num_bundles;
    shape->num_bundled = p->num_bundled;
    shape->has_positions = position_rows != 0;
    shape->has_vert_component = component_rows != 0;
    return MT_OK;
}

mt_status mt__halfedge_read(hid_t g, const char *file, const double *positions,
                            mt_mesh **out_pending, mt_mesh_parts *out_parts, mt_diag *diag)
{
    *out_pending = NULL;
    memset(out_parts, 0, sizeof *out_parts);
    hid_t hg = mt__archive_group_open(g, "/meshtopo/halfedge", file, diag);
    if (hg < 0) return MT_ERR_PARSE;
    mt_mesh_parts p;
    memset(&p, 0, sizeof p);
    mt_mesh_shape shape;
    mt_status st = read_shape(g, hg, file, &p, &shape, diag);
    mt_mesh *pending = NULL;
    mt_mesh_parts_buffers b;
    mt_diag why;
    if (st == MT_OK) {
        st = mt_mesh_restore_begin(&shape, &pending, &b, &why);
        if (st != MT_OK) mt__archive_fail(diag, st, "%s: meshtopo/halfedge: %s", file, why.message);
    }
    if (st == MT_OK) p.vert_component = shape.has_vert_component ? b.vert_component : NULL;
    for (size_t i = 0; st == MT_OK && i < NUM_ARRAYS; i++) {
        uint32_t *buf = *(uint32_t **)((char *)&b + arrays[i].buffer_offset);
        char path[64];
        snprintf(path, sizeof path, "/meshtopo/halfedge/%s", arrays[i].name);
        st = mt__h5_read_dataset_into(hg, path, file, 1, 0, MT__H5_UINT, 4, H5T_NATIVE_UINT32, buf,
                                      array_length(&p, arrays[i].count), diag);
        *array_field(&p, &arrays[i]) = buf;
    }
    /* The positions are the face list's (the same dataset): a copy of
     * those already read costs less than reading them again. */
    if (st == MT_OK && shape.has_positions && positions)
        memcpy(b.positions, positions, 3 * sizeof(double) * (size_t)shape.num_verts);
    else if (st == MT_OK && shape.has_positions)
        st = mt__h5_read_dataset_into(g, "/meshtopo/positions", file, 2, 3, MT__H5_FLOAT, 8,
                                      H5T_NATIVE_DOUBLE, b.positions, shape.num_verts, diag);
    H5Gclose(hg);
    if (st != MT_OK) {
        mt_mesh_destroy(pending);
        return st;
    }
    p.positions = b.positions;
    if (p.num_bundles == 0) p.bundle_offsets = NULL;
    *out_pending = pending;
    *out_parts = p;
    return MT_OK;
}

mt_status mt__halfedge_restore(hid_t g, const char *file, const mt_report *report,
                               const double *positions, mt_mesh **out_mesh, mt_diag *diag)
{
    *out_mesh = NULL;
    mt_mesh *pending = NULL;
    mt_mesh_parts parts;
    mt_status st = mt__halfedge_read(g, file, positions, &pending, &parts, diag);
    if (st != MT_OK) return st;
    mt_diag why;
    st = mt_mesh_restore_finish(pending, report, out_mesh, &why);
    if (st != MT_OK)
        mt__archive_fail(diag, st, "%s: the arrays of meshtopo/halfedge %s: %s", file,
                         st == MT_ERR_CORRUPT ? "fail validation" : "cannot be restored",
                         why.message);
    return st;
}

mt_status mt__halfedge_read_digest(hid_t g, const char *file, uint64_t *out, mt_diag *diag)
{
    *out = 0;
    hid_t hg = mt__archive_group_open(g, "/meshtopo/halfedge", file, diag);
    if (hg < 0) return MT_ERR_PARSE;
    mt_status st = mt__h5_read_attr_u64(hg, "digest", file, out, diag);
    H5Gclose(hg);
    return st;
}

/* First index where two arrays of n entries differ, n when none does. */
static uint64_t first_difference(const uint32_t *a, const uint32_t *b, uint64_t n)
{
    if (n == 0 || memcmp(a, b, (size_t)n * sizeof *a) == 0) return n;
    uint64_t i = 0;
    while (a[i] == b[i]) i++;
    return i;
}

bool mt__parts_equal(const mt_mesh_parts *a, const mt_mesh_parts *b, char *buf, size_t size)
{
    const uint32_t ac[] = {a->num_verts,  a->num_faces,   a->num_verts_internal, a->num_half_edges,
                           a->num_copies, a->num_bundles, a->num_bundled};
    const uint32_t bc[] = {b->num_verts,  b->num_faces,   b->num_verts_internal, b->num_half_edges,
                           b->num_copies, b->num_bundles, b->num_bundled};
    static const char *const count_names[] = {"num_verts",      "num_faces",  "num_verts_internal",
                                              "num_half_edges", "num_copies", "num_bundles",
                                              "num_bundled"};
    for (size_t i = 0; i < sizeof ac / sizeof ac[0]; i++)
        if (ac[i] != bc[i]) {
            snprintf(buf, size, "%s: %u != %u", count_names[i], ac[i], bc[i]);
            return false;
        }
    if ((a->vert_component == NULL) != (b->vert_component == NULL)) {
        snprintf(buf, size, "vertex_component: %s != %s", a->vert_component ? "present" : "absent",
                 b->vert_component ? "present" : "absent");
        return false;
    }
    for (size_t i = 0; i < NUM_ARRAYS; i++) {
        mt_mesh_parts pa = *a, pb = *b;
        const uint32_t *x = *array_field(&pa, &arrays[i]), *y = *array_field(&pb, &arrays[i]);
        uint64_t n = array_length(a, arrays[i].count);
        uint64_t k = first_difference(x, y, n);
        if (k < n) {
            snprintf(buf, size, "%s[%llu]: %u != %u", arrays[i].name, (unsigned long long)k, x[k],
                     y[k]);
            return false;
        }
    }
    if ((a->positions == NULL) != (b->positions == NULL) ||
        (a->positions &&
         memcmp(a->positions, b->positions, 3 * (size_t)a->num_verts * sizeof(double)) != 0)) {
        snprintf(buf, size, "positions differ");
        return false;
    }
    return true;
}
