/* The topology arrays of /VTKHDF (format 6), read back with the HDF5 C API
 * as a viewer reads them: values worked out by hand on small meshes (a
 * grid with a hole, a fin, two components and an isolated vertex, a
 * flipped face, a bowtie, rejected and duplicate faces, a NaN corner, an
 * octahedron pushed through itself with and without self-intersections
 * asked for), the corpus against the report's counts and against the
 * public queries, the attributes that document them, and damaged arrays
 * (verification fails with a VTK fault, loads are not affected). */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archive_legacy.h"
#include "archive_test_util.h"
#include "harness.h"
#include "meshtopo/core.h"

/* ---- reading the file ------------------------------------------------- */

/* One array of /VTKHDF/<group> as int64 values (malloc'ed, NULL when it is
 * missing); its stored type ("int32", "uint32", "uint8", "int64", "other")
 * into type. */
static int64_t *read_array(const char *path, const char *group, const char *name, size_t *out_n,
                           char type[8])
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    char link[128];
    snprintf(link, sizeof link, "/VTKHDF/%s/%s", group, name);
    *out_n = 0;
    strcpy(type, "none");
    int64_t *values = NULL;
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f >= 0 && H5Lexists(f, link, H5P_DEFAULT) > 0 ? H5Dopen2(f, link, H5P_DEFAULT) : -1;
    if (d >= 0) {
        hid_t t = H5Dget_type(d), s = H5Dget_space(d);
        size_t size = H5Tget_size(t);
        bool is_int = H5Tget_class(t) == H5T_INTEGER, sign = H5Tget_sign(t) == H5T_SGN_2;
        strcpy(type, !is_int              ? "other"
                     : size == 4 && sign  ? "int32"
                     : size == 4          ? "uint32"
                     : size == 1 && !sign ? "uint8"
                     : size == 8 && sign  ? "int64"
                                          : "other");
        hssize_t n = H5Sget_simple_extent_npoints(s);
        values = malloc(((size_t)(n > 0 ? n : 0) + 1) * sizeof *values);
        if (values && n > 0 &&
            H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, values) < 0)
            n = -1;
        *out_n = n > 0 ? (size_t)n : 0;
        H5Sclose(s);
        H5Tclose(t);
        H5Dclose(d);
    }
    if (f >= 0) H5Fclose(f);
    return values;
}

/* A string attribute of object obj (fixed-length, or entry `index` of a
 * string array) into buf; false when missing. */
static bool read_text(const char *path, const char *obj, const char *name, size_t index, char *buf,
                      size_t size)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    buf[0] = '\0';
    bool ok = false;
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t o = f < 0 ? -1 : H5Oopen(f, obj, H5P_DEFAULT);
    hid_t a = o >= 0 && H5Aexists(o, name) > 0 ? H5Aopen(o, name, H5P_DEFAULT) : -1;
    if (a >= 0) {
        hid_t t = H5Aget_type(a), s = H5Aget_space(a);
        size_t width = H5Tget_size(t);
        hssize_t n = H5Sget_simple_extent_npoints(s);
        char *all = H5Tget_class(t) == H5T_STRING && !H5Tis_variable_str(t) && n > 0
                        ? calloc((size_t)n * width + 1, 1)
                        : NULL;
        if (all && H5Aread(a, t, all) >= 0 && index < (size_t)n) {
            size_t len = width < size - 1 ? width : size - 1;
            memcpy(buf, all + index * width, len);
            buf[len] = '\0';
            ok = true;
        }
        free(all);
        H5Sclose(s);
        H5Tclose(t);
        H5Aclose(a);
    }
    if (o >= 0) H5Oclose(o);
    if (f >= 0) H5Fclose(f);
    return ok;
}

/* Storage HDF5 allocated for a dataset (0 for one never written). */
static uint64_t storage_bytes(const char *path, const char *link)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f < 0 ? -1 : H5Dopen2(f, link, H5P_DEFAULT);
    uint64_t bytes = d >= 0 ? H5Dget_storage_size(d) : UINT64_MAX;
    if (d >= 0) H5Dclose(d);
    if (f >= 0) H5Fclose(f);
    return bytes;
}

/* Checks array group/name of the file against want[0 .. n) and its type. */
#define CHECK_ARRAY(path, group, name, want_type, want, n) \
    check_array(__FILE__, __LINE__, path, group, name, want_type, want, n)

static void check_array(const char *file, int line, const char *path, const char *group,
                        const char *name, const char *want_type, const int64_t *want, size_t n)
{
    size_t got_n = 0;
    char type[8];
    int64_t *got = read_array(path, group, name, &got_n, type);
    if (!got) {
        mt_test_fail(file, line, "%s/%s is missing", group, name);
        return;
    }
    if (strcmp(type, want_type) != 0)
        mt_test_fail(file, line, "%s/%s is %s, expected %s", group, name, type, want_type);
    if (got_n != n)
        mt_test_fail(file, line, "%s/%s has %zu rows, expected %zu", group, name, got_n, n);
    for (size_t i = 0; i < n && i < got_n; i++)
        if (got[i] != want[i]) {
            mt_test_fail(file, line, "%s/%s[%zu] is %lld, expected %lld", group, name, i,
                         (long long)got[i], (long long)want[i]);
            break;
        }
    free(got);
}

/* An integer attribute of object obj as int64 (-1 when missing). */
static int64_t read_int_attr(const char *path, const char *obj, const char *name)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    int64_t value = -1;
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t o = f < 0 ? -1 : H5Oopen(f, obj, H5P_DEFAULT);
    hid_t a = o >= 0 && H5Aexists(o, name) > 0 ? H5Aopen(o, name, H5P_DEFAULT) : -1;
    if (a >= 0 && H5Aread(a, H5T_NATIVE_INT64, &value) < 0) value = -1;
    if (a >= 0) H5Aclose(a);
    if (o >= 0) H5Oclose(o);
    if (f >= 0) H5Fclose(f);
    return value;
}

/* Format 8: every per-kind array of group (defect_<key>, uint8) holds bit
 * k of the bitmask `defects` (n rows). */
#define CHECK_KIND_ARRAYS(path, group, defects, n) \
    check_kind_arrays(__FILE__, __LINE__, path, group, defects, n)

static void check_kind_arrays(const char *file, int line, const char *path, const char *group,
                              const int64_t *defects, size_t n)
{
    int64_t *want = malloc((n + 1) * sizeof *want);
    if (!want) {
        mt_test_fail(file, line, "out of memory");
        return;
    }
    for (int k = 0; k < MT_DEFECT_KIND_COUNT; k++) {
        char name[64];
        snprintf(name, sizeof name, "defect_%s", mt_defect_key((mt_defect_kind)k));
        for (size_t i = 0; i < n; i++) want[i] = (defects[i] >> k) & 1;
        check_array(file, line, path, group, name, "uint8", want, n);
    }
    free(want);
}

/* ---- writing ---------------------------------------------------------- */

typedef struct fixture {
    char dir[512];
    char path[1024]; /* of the last file written */
    mt_archive *archive;
} fixture;

static bool fixture_open(fixture *fx)
{
    memset(fx, 0, sizeof *fx);
    mt_diag diag;
    CHECK(at_tmpdir(fx->dir, sizeof fx->dir));
    CHECK_OK(mt_archive_open(fx->dir, NULL, &fx->archive, &diag));
    return fx->archive != NULL;
}

static void fixture_close(fixture *fx)
{
    mt_archive_close(fx->archive);
    at_rmdir(fx->dir);
}

/* Builds (and validates) the face list, archives it as id v1 with options
 * (NULL: defaults) and checks the file verifies. Returns the write's
 * status; fx->path names the file. */
static mt_status archive_with(fixture *fx, const char *id, const mt_face_list *list,
                              const mt_archive_write_options *options)
{
    mt_mesh *mesh = NULL;
    mt_diag diag;
    mt_status st = mt_mesh_build(list, NULL, &mesh, &diag);
    CHECK_OK(st);
    if (st != MT_OK) return st;
    CHECK_OK(mt_mesh_validate(mesh, &diag));
    uint64_t hash = 0;
    at_hash(NULL, list, &hash, NULL);
    mt_archive_meta meta = {id, 1, 1700000000000001, "test-node", hash};
    st = mt_archive_write_with(fx->archive, &meta, list, mesh, options, NULL, &diag);
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(id, 1, name, sizeof name);
    snprintf(fx->path, sizeof fx->path, "%s/%s", fx->dir, name);
    if (st == MT_OK) {
        mt_status vs = mt_archive_verify_file(fx->archive, name, at_hash, NULL, &diag);
        CHECK_OK(vs);
        if (vs != MT_OK) printf("verify %s: %s\n", id, diag.message);
    }
    mt_mesh_destroy(mesh);
    return st;
}

/* A face list of `nf` faces (sizes NULL: triangles) over nv vertices. */
static void make_list(mt_face_list *list, uint32_t nv, const double *pos, uint32_t nf,
                      const uint32_t *sizes, const uint32_t *indices)
{
    uint64_t ni = 0;
    for (uint32_t f = 0; f < nf; f++) ni += sizes ? sizes[f] : 3;
    CHECK_OK(mt_face_list_alloc(list, pos ? nv : 0, nf, ni, NULL));
    list->num_verts = nv;
    for (uint32_t f = 0; f < nf; f++) list->face_sizes[f] = sizes ? sizes[f] : 3;
    memcpy(list->face_indices, indices, ni * sizeof *indices);
    if (pos) memcpy(list->positions, pos, 3 * (size_t)nv * sizeof *pos);
}

/* Bits of the defects arrays. */
#define BIT(kind) ((int64_t)1 << (kind))

/* ---- hand-built meshes ------------------------------------------------- */

/* A 4 x 4 grid of quads over vertices (i, j) = j * 5 + i with quad (2, 2)
 * left out: a hole inside. The boundary is the outer square and the hole's
 * four corners (12, 13, 17, 18); only vertices 6, 7, 8, 11 and 16 are
 * inside. Every quad but (1, 1), which meets the hole only at vertex 12,
 * touches a boundary edge. Nothing else is set: the other arrays hold
 * their fill values, and HDF5 stores nothing for them. */
static void test_topology_grid_with_hole(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    double pos[25 * 3];
    for (int v = 0; v < 25; v++) pos[3 * v] = v % 5, pos[3 * v + 1] = v / 5, pos[3 * v + 2] = 0;
    uint32_t sizes[15], idx[60];
    int64_t touches[15];
    uint32_t nf = 0;
    for (uint32_t j = 0; j < 4; j++)
        for (uint32_t i = 0; i < 4; i++) {
            if (i == 2 && j == 2) continue;
            const uint32_t v = j * 5 + i;
            const uint32_t quad[4] = {v, v + 1, v + 6, v + 5};
            memcpy(idx + 4 * nf, quad, sizeof quad);
            sizes[nf] = 4;
            touches[nf] = !(i == 1 && j == 1);
            nf++;
        }
    mt_face_list list;
    make_list(&list, 25, pos, nf, sizes, idx);
    CHECK_OK(archive_with(&fx, "hole", &list, NULL));
    int64_t boundary[25], zeros[25], ones[25];
    for (int v = 0; v < 25; v++) {
        boundary[v] = !(v == 6 || v == 7 || v == 8 || v == 11 || v == 16);
        zeros[v] = 0;
        ones[v] = 1;
    }
    CHECK_ARRAY(fx.path, "CellData", "touches_boundary", "uint8", touches, 15);
    CHECK_ARRAY(fx.path, "PointData", "boundary", "uint8", boundary, 25);
    CHECK_ARRAY(fx.path, "CellData", "component", "int32", zeros, 15);
    CHECK_ARRAY(fx.path, "CellData", "defects", "uint32", zeros, 15);
    CHECK_ARRAY(fx.path, "CellData", "orientation_consistent", "uint8", ones, 15);
    CHECK_ARRAY(fx.path, "PointData", "non_manifold", "uint8", zeros, 25);
    CHECK_ARRAY(fx.path, "PointData", "defects", "uint32", zeros, 25);
    /* Constant arrays are never written: HDF5 gives their fill value. */
    CHECK_EQ(storage_bytes(fx.path, "/VTKHDF/CellData/component"), 0);
    CHECK_EQ(storage_bytes(fx.path, "/VTKHDF/CellData/orientation_consistent"), 0);
    CHECK_EQ(storage_bytes(fx.path, "/VTKHDF/PointData/defects"), 0);
    CHECK_EQ(storage_bytes(fx.path, "/VTKHDF/CellData/touches_boundary"), 15);
    mt_face_list_free(&list);
    fixture_close(&fx);
}

/* Three triangles on edge 0-1, two of them running 0 -> 1: (0, 1, 2),
 * (1, 0, 3), (0, 1, 4). The edge is non-manifold (all three faces, both
 * ends), 0 -> 1 is a same-direction edge (faces 0 and 2 only, both ends),
 * and vertices 0 and 1 are non-manifold (their links have a vertex of
 * degree 3: every face has them as corners). Orientation: the edge has
 * three faces, so it does not count; every other edge is a boundary. */
static void test_topology_fin(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    const double pos[] = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1};
    const uint32_t idx[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    mt_face_list list;
    make_list(&list, 5, pos, 3, NULL, idx);
    CHECK_OK(archive_with(&fx, "fin", &list, NULL));
    const int64_t nme = BIT(MT_DEFECT_NONMANIFOLD_EDGE), sde = BIT(MT_DEFECT_SAME_DIRECTION_EDGE),
                  nmv = BIT(MT_DEFECT_NONMANIFOLD_VERTEX);
    const int64_t cell_defects[] = {nme | sde | nmv, nme | nmv, nme | sde | nmv};
    const int64_t point_defects[] = {nme | sde | nmv, nme | sde | nmv, 0, 0, 0};
    const int64_t non_manifold[] = {1, 1, 0, 0, 0}, ones[] = {1, 1, 1, 1, 1}, zeros[] = {0, 0, 0};
    CHECK_ARRAY(fx.path, "CellData", "defects", "uint32", cell_defects, 3);
    CHECK_ARRAY(fx.path, "PointData", "defects", "uint32", point_defects, 5);
    CHECK_ARRAY(fx.path, "PointData", "non_manifold", "uint8", non_manifold, 5);
    CHECK_ARRAY(fx.path, "PointData", "boundary", "uint8", ones, 5);
    CHECK_ARRAY(fx.path, "CellData", "touches_boundary", "uint8", ones, 3);
    CHECK_ARRAY(fx.path, "CellData", "orientation_consistent", "uint8", ones, 3);
    CHECK_ARRAY(fx.path, "CellData", "component", "int32", zeros, 3);
    /* The per-kind arrays (format 8): the bits again, by name; a kind the
     * mesh lacks is never written. */
    CHECK_KIND_ARRAYS(fx.path, "CellData", cell_defects, 3);
    CHECK_KIND_ARRAYS(fx.path, "PointData", point_defects, 5);
    const int64_t nme_cells[] = {1, 1, 1}, sde_cells[] = {1, 0, 1};
    CHECK_ARRAY(fx.path, "CellData", "defect_nonmanifold_edge", "uint8", nme_cells, 3);
    CHECK_ARRAY(fx.path, "CellData", "defect_same_direction_edge", "uint8", sde_cells, 3);
    CHECK(storage_bytes(fx.path, "/VTKHDF/CellData/defect_same_direction_edge") > 0);
    CHECK_EQ(storage_bytes(fx.path, "/VTKHDF/CellData/defect_duplicate_face"), 0);
    CHECK_EQ(storage_bytes(fx.path, "/VTKHDF/PointData/defect_isolated_vertex"), 0);
    mt_face_list_free(&list);
    fixture_close(&fx);
}

/* Face 0 a triangle (4, 5, 6) on its own, faces 1-4 a closed tetrahedron
 * on 0-3, vertex 7 in no face: components are numbered by their smallest
 * face, so the triangle is 0 and the tetrahedron 1. The triangle's corners
 * are on the boundary, the tetrahedron's are not; vertex 7 is isolated. */
static void test_topology_components(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 0, 0, 6, 0, 0, 5, 1, 0, 9, 9, 9};
    const uint32_t idx[] = {4, 5, 6, 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    mt_face_list list;
    make_list(&list, 8, pos, 5, NULL, idx);
    CHECK_OK(archive_with(&fx, "two parts", &list, NULL));
    const int64_t component[] = {0, 1, 1, 1, 1}, touches[] = {1, 0, 0, 0, 0};
    const int64_t boundary[] = {0, 0, 0, 0, 1, 1, 1, 0};
    const int64_t point_defects[] = {0, 0, 0, 0, 0, 0, 0, BIT(MT_DEFECT_ISOLATED_VERTEX)};
    const int64_t zeros[] = {0, 0, 0, 0, 0, 0, 0, 0};
    CHECK_ARRAY(fx.path, "CellData", "component", "int32", component, 5);
    CHECK_ARRAY(fx.path, "CellData", "touches_boundary", "uint8", touches, 5);
    CHECK_ARRAY(fx.path, "PointData", "boundary", "uint8", boundary, 8);
    CHECK_ARRAY(fx.path, "PointData", "defects", "uint32", point_defects, 8);
    CHECK_ARRAY(fx.path, "PointData", "non_manifold", "uint8", zeros, 8);
    CHECK_ARRAY(fx.path, "CellData", "defects", "uint32", zeros, 5);
    mt_face_list_free(&list);
    fixture_close(&fx);
}

/* The octahedron with vertices +-x (0, 1), +-y (2, 3), +-z (4, 5); faces 0-3
 * around the top apex, 4-7 around the bottom one, all outward. */
static const uint32_t octahedron_faces[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                            2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
static const double octahedron_pos[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};

/* Face 0 of the octahedron flipped to (4, 2, 0): it runs each of its edges
 * the way its neighbour across does (face 4 on 2-0, face 1 on 4-2, face 3
 * on 0-4). Those four faces are not consistently oriented, and they and
 * the vertices 0, 2, 4 carry same_direction_edge; the seams the half-edge
 * structure opens there are not boundary, and no vertex is non-manifold. */
static void test_topology_flipped_face(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    uint32_t idx[24];
    memcpy(idx, octahedron_faces, sizeof idx);
    idx[0] = 4, idx[2] = 0;
    mt_face_list list;
    make_list(&list, 6, octahedron_pos, 8, NULL, idx);
    CHECK_OK(archive_with(&fx, "flipped", &list, NULL));
    const int64_t sde = BIT(MT_DEFECT_SAME_DIRECTION_EDGE);
    const int64_t consistent[] = {0, 0, 1, 0, 0, 1, 1, 1};
    const int64_t cell_defects[] = {sde, sde, 0, sde, sde, 0, 0, 0};
    const int64_t point_defects[] = {sde, 0, sde, 0, sde, 0};
    const int64_t zeros[] = {0, 0, 0, 0, 0, 0, 0, 0};
    CHECK_ARRAY(fx.path, "CellData", "orientation_consistent", "uint8", consistent, 8);
    CHECK_ARRAY(fx.path, "CellData", "defects", "uint32", cell_defects, 8);
    CHECK_ARRAY(fx.path, "PointData", "defects", "uint32", point_defects, 6);
    CHECK_ARRAY(fx.path, "CellData", "touches_boundary", "uint8", zeros, 8);
    CHECK_ARRAY(fx.path, "PointData", "boundary", "uint8", zeros, 6);
    CHECK_ARRAY(fx.path, "PointData", "non_manifold", "uint8", zeros, 6);
    mt_face_list_free(&list);
    fixture_close(&fx);
}

/* Two triangles sharing only vertex 0 (mt_gen_bowtie): vertex 0 is a
 * non-manifold vertex, both faces have it as a corner; they share no edge,
 * so they are two components. */
static void test_topology_bowtie(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    mt_face_list list;
    CHECK_OK(mt_gen_bowtie(&list));
    CHECK_OK(archive_with(&fx, "bowtie", &list, NULL));
    const int64_t nmv = BIT(MT_DEFECT_NONMANIFOLD_VERTEX);
    const int64_t cell_defects[] = {nmv, nmv}, component[] = {0, 1};
    const int64_t point_defects[] = {nmv, 0, 0, 0, 0}, non_manifold[] = {1, 0, 0, 0, 0};
    CHECK_EQ(list.num_verts, 5);
    CHECK_ARRAY(fx.path, "CellData", "defects", "uint32", cell_defects, 2);
    CHECK_ARRAY(fx.path, "CellData", "component", "int32", component, 2);
    CHECK_ARRAY(fx.path, "PointData", "defects", "uint32", point_defects, 5);
    CHECK_ARRAY(fx.path, "PointData", "non_manifold", "uint8", non_manifold, 5);
    mt_face_list_free(&list);
    fixture_close(&fx);
}

/* Rejected faces are no cells, so the per-cell arrays follow
 * original_face_id: faces 0 (0, 1, 2) and 1 (0, 2, 3) are kept, 2 (1, -1,
 * 2) has an index out of range, 3 (0, 1) and 4 (0, 1, 1, 2) are degenerate,
 * 5 is empty, 6 (2, 1, 9) is out of range, 7 repeats face 0. Cells: faces
 * 0, 1, 7. Only face 7 is a duplicate; faces 0 and 7 run edges 0 -> 1 and
 * 1 -> 2 both, the only faces on them: both inconsistent. The corners of
 * the rejected faces carry their kinds; vertices 4, 5, 6 are isolated. */
static void test_topology_rejected_faces(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    const uint32_t sizes[] = {3, 3, 3, 2, 4, 0, 3, 3};
    const uint32_t idx[] = {0, 1, 2, 0, 2, 3, 1, 0xffffffffu, 2, 0, 1,
                            0, 1, 1, 2, 2, 1, 9, 0,           1, 2};
    double pos[21];
    for (int i = 0; i < 21; i++) pos[i] = (double)((i * 7) % 5) - 1.5;
    mt_face_list list;
    make_list(&list, 7, pos, 8, sizes, idx);
    CHECK_OK(archive_with(&fx, "rejected", &list, NULL));
    const int64_t oor = BIT(MT_DEFECT_OUT_OF_RANGE_INDEX), deg = BIT(MT_DEFECT_DEGENERATE_FACE),
                  dup = BIT(MT_DEFECT_DUPLICATE_FACE), iso = BIT(MT_DEFECT_ISOLATED_VERTEX);
    const int64_t face_ids[] = {0, 1, 7}, consistent[] = {0, 1, 0};
    CHECK_ARRAY(fx.path, "CellData", "original_face_id", "int64", face_ids, 3);
    CHECK_ARRAY(fx.path, "CellData", "orientation_consistent", "uint8", consistent, 3);
    size_t n = 0;
    char type[8];
    int64_t *cells = read_array(fx.path, "CellData", "defects", &n, type);
    CHECK_EQ(n, 3);
    const int64_t face_kinds = oor | deg | dup;
    if (cells && n == 3) {
        CHECK_EQ(cells[0] & face_kinds, 0);
        CHECK_EQ(cells[1] & face_kinds, 0);
        CHECK_EQ(cells[2] & face_kinds, dup);
    }
    free(cells);
    int64_t *points = read_array(fx.path, "PointData", "defects", &n, type);
    CHECK_EQ(n, 7);
    const int64_t mask = face_kinds | iso;
    const int64_t want[7] = {deg | dup, oor | deg | dup, oor | deg | dup, 0, iso, iso, iso};
    for (size_t v = 0; points && v < n && v < 7; v++) CHECK_EQ(points[v] & mask, want[v]);
    free(points);
    mt_face_list_free(&list);
    fixture_close(&fx);
}

/* A tetrahedron with vertex 3 at NaN: the vertex and its three faces carry
 * nonfinite_coordinate, face 0 (0, 2, 1) does not. */
static void test_topology_nonfinite(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, NAN, 0, 1};
    const uint32_t idx[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    mt_face_list list;
    make_list(&list, 4, pos, 4, NULL, idx);
    CHECK_OK(archive_with(&fx, "nan", &list, NULL));
    const int64_t nf = BIT(MT_DEFECT_NONFINITE_COORD);
    const int64_t cells[] = {0, nf, nf, nf}, points[] = {0, 0, 0, nf};
    CHECK_ARRAY(fx.path, "CellData", "defects", "uint32", cells, 4);
    CHECK_ARRAY(fx.path, "PointData", "defects", "uint32", points, 4);
    mt_face_list_free(&list);
    fixture_close(&fx);
}

/* ---- self-intersections ------------------------------------------------ */

/* The octahedron with its top apex pushed down to (0.5, 0.5, -0.5), through
 * face 4: faces 1, 2 and 3 pass through face 4 (pairs 1-4, 2-4, 3-4). By
 * default the array is left out and CellData says why; asked for, it is
 * computed, or taken from the caller's pairs. */
static void test_topology_self_intersections(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    double pos[18];
    memcpy(pos, octahedron_pos, sizeof pos);
    pos[12] = 0.5, pos[13] = 0.5, pos[14] = -0.5;
    mt_face_list list;
    make_list(&list, 6, pos, 8, NULL, octahedron_faces);
    const int64_t want[] = {0, 1, 1, 1, 1, 0, 0, 0};
    char text[256];

    CHECK_OK(archive_with(&fx, "skipped", &list, NULL));
    size_t n = 0;
    char type[8];
    int64_t *values = read_array(fx.path, "CellData", "self_intersecting", &n, type);
    CHECK(values == NULL);
    free(values);
    CHECK(read_text(fx.path, "/VTKHDF/CellData", "self_intersecting", 0, text, sizeof text));
    CHECK(strncmp(text, "not computed", 12) == 0);

    mt_archive_write_options options = {.self_intersections =
                                            MT_ARCHIVE_SELF_INTERSECTIONS_COMPUTE};
    CHECK_OK(archive_with(&fx, "computed", &list, &options));
    CHECK_ARRAY(fx.path, "CellData", "self_intersecting", "uint8", want, 8);
    CHECK(read_text(fx.path, "/VTKHDF/CellData/self_intersecting", "description", 0, text,
                    sizeof text));
    CHECK(strstr(text, "meets another face") != NULL);
    CHECK(!read_text(fx.path, "/VTKHDF/CellData", "self_intersecting", 0, text, sizeof text));

    const mt_face_pair pairs[] = {{1, 4}, {2, 4}, {3, 4}};
    options.self_intersections = MT_ARCHIVE_SELF_INTERSECTIONS_GIVEN;
    options.self_intersection_pairs = pairs;
    options.num_self_intersection_pairs = 3;
    CHECK_OK(archive_with(&fx, "given", &list, &options));
    CHECK_ARRAY(fx.path, "CellData", "self_intersecting", "uint8", want, 8);

    /* Given nothing: present, all zero. */
    options.num_self_intersection_pairs = 0;
    CHECK_OK(archive_with(&fx, "given none", &list, &options));
    const int64_t zeros[8] = {0};
    CHECK_ARRAY(fx.path, "CellData", "self_intersecting", "uint8", zeros, 8);

    /* A pair naming a face out of range is refused before anything is written. */
    const mt_face_pair bad[] = {{1, 8}};
    options.self_intersection_pairs = bad;
    options.num_self_intersection_pairs = 1;
    CHECK_STATUS(archive_with(&fx, "bad pair", &list, &options), MT_ERR_INVALID_ARG);
    CHECK(!mt_archive_contains(fx.archive, "bad pair", 1));
    options.self_intersection_pairs = NULL;
    CHECK_STATUS(archive_with(&fx, "no pairs", &list, &options), MT_ERR_INVALID_ARG);
    options.self_intersections = (mt_archive_self_intersections)9;
    CHECK_STATUS(archive_with(&fx, "bad mode", &list, &options), MT_ERR_INVALID_ARG);

    /* Without positions there is nothing to compute: left out, and said so. */
    free(list.positions);
    list.positions = NULL;
    options.self_intersections = MT_ARCHIVE_SELF_INTERSECTIONS_COMPUTE;
    CHECK_OK(archive_with(&fx, "no geometry", &list, &options));
    values = read_array(fx.path, "CellData", "self_intersecting", &n, type);
    CHECK(values == NULL);
    free(values);
    CHECK(read_text(fx.path, "/VTKHDF/CellData", "self_intersecting", 0, text, sizeof text));
    CHECK(strstr(text, "no positions") != NULL);
    mt_face_list_free(&list);
    fixture_close(&fx);
}

/* ---- documentation in the file ----------------------------------------- */

static void test_topology_attributes(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    mt_face_list list;
    CHECK_OK(mt_gen_fin(&list));
    CHECK_OK(archive_with(&fx, "fin", &list, NULL));
    const char *arrays[] = {"CellData/component",        "CellData/defects",
                            "CellData/touches_boundary", "CellData/orientation_consistent",
                            "PointData/boundary",        "PointData/non_manifold",
                            "PointData/defects"};
    char obj[128], text[512];
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) {
        snprintf(obj, sizeof obj, "/VTKHDF/%s", arrays[i]);
        bool described = read_text(fx.path, obj, "description", 0, text, sizeof text);
        CHECK(described && strlen(text) > 20);
        if (!described) printf("%s has no description\n", obj);
    }
    const char *bitmasks[] = {"/VTKHDF/CellData/defects", "/VTKHDF/PointData/defects"};
    for (int b = 0; b < 2; b++) {
        for (int k = 0; k < MT_DEFECT_KIND_COUNT; k++) {
            CHECK(read_text(fx.path, bitmasks[b], "bits", (size_t)k, text, sizeof text));
            CHECK(strcmp(text, mt_defect_key((mt_defect_kind)k)) == 0);
        }
        CHECK(!read_text(fx.path, bitmasks[b], "bits", MT_DEFECT_KIND_COUNT, text, sizeof text));
    }
    /* The per-kind arrays name their kind and bit. */
    for (int g = 0; g < 2; g++)
        for (int k = 0; k < MT_DEFECT_KIND_COUNT; k++) {
            const char *key = mt_defect_key((mt_defect_kind)k);
            snprintf(obj, sizeof obj, "/VTKHDF/%s/defect_%s", g ? "PointData" : "CellData", key);
            CHECK_EQ(read_int_attr(fx.path, obj, "bit"), k);
            CHECK(read_text(fx.path, obj, "description", 0, text, sizeof text));
            CHECK(strstr(text, key) != NULL && strstr(text, "defects") != NULL);
        }
    CHECK(read_text(fx.path, "/meshtopo", "description", 0, text, sizeof text));
    CHECK(strstr(text, "topology") != NULL);
    mt_face_list_free(&list);
    fixture_close(&fx);
}

/* ---- the corpus --------------------------------------------------------- */

static size_t count_where(const int64_t *v, size_t n, int64_t mask, int64_t value)
{
    size_t c = 0;
    for (size_t i = 0; i < n; i++) c += (v[i] & mask) == value;
    return c;
}

/* Whether the face has a side from a to b. */
static bool face_runs(const mt_mesh *mesh, uint32_t f, uint32_t a, uint32_t b)
{
    uint32_t verts[64];
    size_t n = 0;
    if (mt_face_verts(mesh, f, verts, 64, &n) != MT_OK) return false;
    for (size_t i = 0; i < n; i++)
        if (verts[i] == a && verts[(i + 1) % n] == b) return true;
    return false;
}

/* touches_boundary and orientation_consistent of every cell worked out
 * again with the public queries: a side with no face across is a boundary
 * edge; a side with one face across must be run the other way by it. */
static void check_with_queries(const char *name, const mt_mesh *mesh, const int64_t *face_ids,
                               const int64_t *touches, const int64_t *consistent, size_t cells)
{
    uint32_t across[256], offsets[65], verts[64];
    size_t wrong_touch = 0, wrong_orient = 0, checked = 0;
    for (size_t c = 0; c < cells; c++) {
        const uint32_t f = (uint32_t)face_ids[c];
        size_t nv = 0, nfaces = 0, nedges = 0;
        if (mt_face_verts(mesh, f, verts, 64, &nv) != MT_OK ||
            mt_face_neighbors(mesh, f, across, 256, offsets, 65, &nfaces, &nedges) != MT_OK)
            continue; /* a huge polygon or a crowded edge: not checked */
        checked++;
        bool boundary = false, orient = true;
        for (size_t e = 0; e < nedges; e++) {
            const uint32_t k = offsets[e + 1] - offsets[e];
            boundary |= k == 0;
            if (k == 1 && face_runs(mesh, across[offsets[e]], verts[e], verts[(e + 1) % nv]))
                orient = false;
        }
        wrong_touch += touches[c] != boundary;
        wrong_orient += consistent[c] != orient;
    }
    CHECK_EQ(wrong_touch, 0);
    CHECK_EQ(wrong_orient, 0);
    CHECK(checked + 16 >= cells);
    if (wrong_touch || wrong_orient) printf("%s: queries disagree\n", name);
}

static void check_corpus_mesh(const char *name, const mt_face_list *list, void *ctx)
{
    fixture *fx = ctx;
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(archive_with(fx, name, list, NULL));
    CHECK_OK(mt_mesh_build(list, NULL, &mesh, &diag));
    if (!mesh) return;
    const mt_report *r = mt_mesh_report(mesh);
    size_t n[9] = {0};
    char type[8];
    int64_t *ids = read_array(fx->path, "CellData", "original_face_id", &n[0], type);
    int64_t *comp = read_array(fx->path, "CellData", "component", &n[1], type);
    int64_t *cdef = read_array(fx->path, "CellData", "defects", &n[2], type);
    int64_t *touch = read_array(fx->path, "CellData", "touches_boundary", &n[3], type);
    int64_t *orient = read_array(fx->path, "CellData", "orientation_consistent", &n[4], type);
    int64_t *bnd = read_array(fx->path, "PointData", "boundary", &n[5], type);
    int64_t *nm = read_array(fx->path, "PointData", "non_manifold", &n[6], type);
    int64_t *pdef = read_array(fx->path, "PointData", "defects", &n[7], type);
    const size_t cells = r->num_faces_valid, points = list->num_verts;
    for (int i = 0; i < 5; i++) CHECK_EQ(n[i], cells);
    for (int i = 5; i < 8; i++) CHECK_EQ(n[i], points);
    bool complete = ids && comp && cdef && touch && orient && bnd && nm && pdef;
    CHECK(complete);
    for (int i = 0; complete && i < 8; i++) complete = n[i] == (i < 5 ? cells : points);
    if (complete) {
        /* The report's counts. */
        CHECK_EQ(count_where(nm, points, 1, 1), r->nonmanifold_vertices);
        CHECK_EQ(count_where(pdef, points, BIT(MT_DEFECT_NONMANIFOLD_VERTEX),
                             BIT(MT_DEFECT_NONMANIFOLD_VERTEX)),
                 r->nonmanifold_vertices);
        CHECK_EQ(count_where(pdef, points, BIT(MT_DEFECT_ISOLATED_VERTEX),
                             BIT(MT_DEFECT_ISOLATED_VERTEX)),
                 r->isolated_vertices);
        CHECK_EQ(count_where(pdef, points, BIT(MT_DEFECT_NONFINITE_COORD),
                             BIT(MT_DEFECT_NONFINITE_COORD)),
                 r->nonfinite_vertices);
        CHECK_EQ(
            count_where(cdef, cells, BIT(MT_DEFECT_DUPLICATE_FACE), BIT(MT_DEFECT_DUPLICATE_FACE)),
            r->duplicate_faces);
        CHECK_EQ(count_where(cdef, cells, BIT(MT_DEFECT_NONMANIFOLD_EDGE), 0) < cells,
                 r->nonmanifold_edges > 0);
        CHECK_EQ(count_where(touch, cells, 1, 1) > 0, r->boundary_edges > 0);
        CHECK_EQ(count_where(orient, cells, 1, 0) > 0, r->inconsistent_orientation_edges > 0);
        CHECK(count_where(orient, cells, 1, 0) <= 2 * r->inconsistent_orientation_edges);
        for (uint32_t k = 0; k < r->connected_components; k++)
            CHECK_EQ(count_where(comp, cells, -1, k), r->components[k].faces);
        /* Points on the boundary, as the geometry module finds them (an
         * edge at the vertex used by exactly one face). */
        bool *on_boundary = calloc(points + 1, sizeof *on_boundary);
        size_t count = 0, wrong = 0;
        if (on_boundary && list->positions &&
            mt_mesh_vert_curvature(mesh, NULL, NULL, on_boundary, points, &count, &diag) == MT_OK)
            for (size_t v = 0; v < points; v++) wrong += (bnd[v] != 0) != on_boundary[v];
        CHECK_EQ(wrong, 0);
        free(on_boundary);
        check_with_queries(name, mesh, ids, touch, orient, cells);
        CHECK_KIND_ARRAYS(fx->path, "CellData", cdef, cells);
        CHECK_KIND_ARRAYS(fx->path, "PointData", pdef, points);
    }
    free(ids);
    free(comp);
    free(cdef);
    free(touch);
    free(orient);
    free(bnd);
    free(nm);
    free(pdef);
    mt_mesh_destroy(mesh);
}

static void test_topology_corpus(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    CHECK(at_for_each_corpus_mesh(check_corpus_mesh, &fx) >= 20);
    fixture_close(&fx);
}

/* ---- damaged arrays ----------------------------------------------------- */

/* Verification reports damage to the arrays as a VTK fault; a load never
 * reads them. A file of format 5 (before the arrays) verifies without
 * them, one of format 7 without the per-kind arrays. */
static void expect_vtk_fault(fixture *fx, const char *name, const char *what)
{
    mt_diag diag;
    mt_archive_fault fault = MT_ARCHIVE_FAULT_NONE;
    CHECK_STATUS(mt_archive_verify_file_with(fx->archive, name, at_hash, NULL, &fault, &diag),
                 MT_ERR_PARSE);
    CHECK_EQ(fault, MT_ARCHIVE_FAULT_VTK);
    CHECK(strstr(diag.message, what) != NULL);
    if (!strstr(diag.message, what)) printf("verify: %s (expected %s)\n", diag.message, what);
    mt_mesh *mesh = NULL;
    mt_archive_load_info info;
    CHECK_OK(mt_archive_load_mesh_file(fx->archive, name, false, NULL, &mesh, &info, &diag));
    CHECK(mesh != NULL && info.restored);
    CHECK_EQ(info.fault, MT_ARCHIVE_FAULT_NONE);
    mt_mesh_destroy(mesh);
}

/* Replaces dataset link with a 1-D uint8 dataset of `rows` zeros. */
static bool replace_dataset(const char *path, const char *link, hsize_t rows)
{
    if (!at_delete(path, link)) return false;
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t s = H5Screate_simple(1, &rows, NULL);
    hid_t d =
        f < 0 ? -1 : H5Dcreate2(f, link, H5T_STD_U8LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    bool ok = d >= 0;
    if (d >= 0) H5Dclose(d);
    H5Sclose(s);
    return f >= 0 && H5Fclose(f) >= 0 && ok;
}

static void test_topology_damaged(void)
{
    fixture fx;
    if (!fixture_open(&fx)) return;
    mt_face_list list;
    CHECK_OK(mt_gen_fin(&list));
    const char *cases[] = {"value", "constant", "missing", "length",   "type", "self",
                           "old",   "kind",     "nokind",  "kindfill", "seven"};
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        mt_archive_write_options options = {.self_intersections =
                                                MT_ARCHIVE_SELF_INTERSECTIONS_COMPUTE};
        CHECK_OK(archive_with(&fx, cases[i], &list, &options));
        mt_archive_file_name(cases[i], 1, name, sizeof name);
        switch (i) {
            case 0: /* a written value changed */
                CHECK(at_poke_u32(fx.path, "/VTKHDF/CellData/defects", 1, 0));
                expect_vtk_fault(&fx, name, "CellData/defects[1]");
                break;
            case 1: /* a value of a never-written array */
                CHECK(at_poke_u32(fx.path, "/VTKHDF/CellData/orientation_consistent", 2, 0));
                expect_vtk_fault(&fx, name, "orientation_consistent[2] is 0");
                break;
            case 2:
                CHECK(at_delete(fx.path, "/VTKHDF/PointData/boundary"));
                expect_vtk_fault(&fx, name, "boundary is missing");
                break;
            case 3:
                CHECK(replace_dataset(fx.path, "/VTKHDF/CellData/touches_boundary", 2));
                expect_vtk_fault(&fx, name, "touches_boundary has 2 rows");
                break;
            case 4:
                CHECK(replace_dataset(fx.path, "/VTKHDF/CellData/component", 3));
                expect_vtk_fault(&fx, name, "component must hold int32");
                break;
            case 5:
                CHECK(at_poke_u32(fx.path, "/VTKHDF/CellData/self_intersecting", 0, 7));
                expect_vtk_fault(&fx, name, "self_intersecting[0] is 7");
                break;
            case 6: { /* format 5 had no arrays: none is looked for */
                CHECK(at_delete(fx.path, "/VTKHDF/CellData/defects"));
                CHECK(at_delete(fx.path, "/VTKHDF/PointData/boundary"));
                CHECK(al_set_format(fx.path, 5));
                mt_diag diag;
                CHECK_OK(mt_archive_verify_file(fx.archive, name, at_hash, NULL, &diag));
                break;
            }
            case 7: /* a per-kind value that disagrees with the bitmask */
                CHECK(at_poke_u32(fx.path, "/VTKHDF/CellData/defect_same_direction_edge", 1, 1));
                expect_vtk_fault(&fx, name, "defect_same_direction_edge[1] is 1");
                break;
            case 8:
                CHECK(at_delete(fx.path, "/VTKHDF/PointData/defect_nonmanifold_vertex"));
                expect_vtk_fault(&fx, name, "defect_nonmanifold_vertex is missing");
                break;
            case 9: /* a value of a never-written per-kind array */
                CHECK(at_poke_u32(fx.path, "/VTKHDF/PointData/defect_isolated_vertex", 4, 1));
                expect_vtk_fault(&fx, name, "defect_isolated_vertex[4] is 1");
                break;
            case 10: { /* format 7 had no per-kind arrays: none is looked for */
                CHECK(al_set_format(fx.path, 7));
                size_t n = 0;
                char type[8];
                CHECK(read_array(fx.path, "CellData", "defect_nonmanifold_edge", &n, type) == NULL);
                mt_diag diag;
                CHECK_OK(mt_archive_verify_file(fx.archive, name, at_hash, NULL, &diag));
                mt_mesh *mesh = NULL;
                CHECK_OK(
                    mt_archive_load_mesh_file(fx.archive, name, false, NULL, &mesh, NULL, &diag));
                CHECK(mesh != NULL);
                mt_mesh_destroy(mesh);
                break;
            }
        }
    }
    mt_face_list_free(&list);
    fixture_close(&fx);
}

static const mt_test_case cases[] = {
    {"topology_grid_with_hole", test_topology_grid_with_hole},
    {"topology_fin", test_topology_fin},
    {"topology_components", test_topology_components},
    {"topology_flipped_face", test_topology_flipped_face},
    {"topology_bowtie", test_topology_bowtie},
    {"topology_rejected_faces", test_topology_rejected_faces},
    {"topology_nonfinite", test_topology_nonfinite},
    {"topology_self_intersections", test_topology_self_intersections},
    {"topology_attributes", test_topology_attributes},
    {"topology_corpus", test_topology_corpus},
    {"topology_damaged", test_topology_damaged},
};
const mt_test_table mt_tests_archive_topology = {cases, sizeof cases / sizeof cases[0]};
