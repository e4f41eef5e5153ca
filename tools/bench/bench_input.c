/* The benchmark inputs, each in its natural order and with vertex ids and
 * face order shuffled (mt_face_list_permute, fixed seed): a triangulated
 * grid with boundary; for `all` also the bunny and a closed genus-4 mesh of
 * the corpus (read with meshtopo::io; left out, saying so, when the corpus
 * lacks one) and a closed torus. Each case is also
 * written to a raw file so the peer programs read byte-identical input.
 *
 * Raw file layout (native byte order, read back only on the same machine):
 *   0  char[8]  "MTBENCH1"
 *   8  uint32   num_verts
 *   12 uint32   num_faces
 *   16 uint64   num_indices
 *   24 uint32   1 if positions follow, else 0
 *   28 uint32   0 (reserved)
 *   32 double   positions[3 * num_verts] (x, y, z), when present
 *      uint32   face_sizes[num_faces]
 *      uint32   face_indices[num_indices]
 * peer_common.hpp reads it and checks the file size matches exactly. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "meshtopo/generate.h"
#include "meshtopo/io.h"

static bool write_all(FILE *f, const void *data, size_t elem_size, size_t count)
{
    if (count == 0) return true;
    return fwrite(data, elem_size, count, f) == count;
}

bool mt__bench_input_write(const mt_face_list *list, const char *path, char *err, size_t err_size)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        snprintf(err, err_size, "cannot create %s: %s", path, strerror(errno));
        return false;
    }
    uint32_t has_positions = list->positions != NULL;
    uint32_t reserved = 0;
    bool ok = write_all(f, "MTBENCH1", 1, 8) && write_all(f, &list->num_verts, 4, 1) &&
              write_all(f, &list->num_faces, 4, 1) && write_all(f, &list->num_indices, 8, 1) &&
              write_all(f, &has_positions, 4, 1) && write_all(f, &reserved, 4, 1);
    if (ok && has_positions)
        ok = write_all(f, list->positions, sizeof(double), 3 * (size_t)list->num_verts);
    ok = ok && write_all(f, list->face_sizes, 4, list->num_faces) &&
         write_all(f, list->face_indices, 4, (size_t)list->num_indices);
    int saved = errno;
    if (fclose(f) != 0 && ok) {
        saved = errno;
        ok = false;
    }
    if (!ok) {
        snprintf(err, err_size, "cannot write %s: %s", path, strerror(saved));
        remove(path);
    }
    return ok;
}

static bool face_list_copy(const mt_face_list *in, mt_face_list *out, char *err, size_t err_size)
{
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_face_list_alloc(out, in->num_verts, in->num_faces, in->num_indices, &diag);
    if (st != MT_OK) {
        snprintf(err, err_size, "cannot copy the face list: %s", diag.message);
        return false;
    }
    if (in->positions) {
        memcpy(out->positions, in->positions, 3 * sizeof(double) * (size_t)in->num_verts);
    }
    memcpy(out->face_sizes, in->face_sizes, sizeof(uint32_t) * (size_t)in->num_faces);
    memcpy(out->face_indices, in->face_indices, sizeof(uint32_t) * (size_t)in->num_indices);
    return true;
}

/* nx by ny cells, two triangles each, as square as the face count allows. */
static void grid_size(uint64_t faces, uint32_t *nx, uint32_t *ny)
{
    double cells = (double)(faces < 2 ? 2 : faces) / 2.0;
    double x = floor(sqrt(cells));
    if (x < 1) x = 1;
    double y = floor(cells / x + 0.5);
    if (y < 1) y = 1;
    *nx = (uint32_t)x;
    *ny = (uint32_t)y;
}

/* nu by nv cells of a torus with nu (around the hole) about 4 nv. */
static void torus_size(uint64_t faces, uint32_t *nu, uint32_t *nv)
{
    double cells = (double)(faces < 18 ? 18 : faces) / 2.0;
    double v = floor(sqrt(cells / 4.0));
    if (v < 3) v = 3;
    double u = floor(cells / v + 0.5);
    if (u < 3) u = 3;
    *nu = (uint32_t)u;
    *nv = (uint32_t)v;
}

uint64_t mt__bench_case_input_bytes(const mt__bench_case *bench_case)
{
    const mt_face_list *l = &bench_case->list;
    return (l->positions ? 24ull * l->num_verts : 0) + 4ull * l->num_faces + 4ull * l->num_indices;
}

/* The corpus file (without .off) of mesh 2 (the bunny) or 3 (fertility). */
static const char *corpus_mesh_name(uint32_t which)
{
    return which == 2 ? "npm_bunny" : "igl_fertility";
}

/* Makes the ordered case of one mesh into *ordered (mesh name set). */
static bool mesh_make(const mt__bench_options *options, uint32_t which, mt__bench_case *ordered,
                      char *err, size_t err_size)
{
    mt_status st;
    uint32_t a, b;
    const char *corpus_name = NULL;
    switch (which) {
        case 0:
            grid_size(options->faces, &a, &b);
            st = mt_gen_grid(a, b, true, &ordered->list);
            if (st != MT_OK) {
                snprintf(err, err_size, "mt_gen_grid(%u, %u) failed: %s", a, b, mt_strerror(st));
                return false;
            }
            snprintf(ordered->mesh, sizeof ordered->mesh, "grid %ux%u", a, b);
            return true;
        case 1:
            torus_size(options->torus_faces, &a, &b);
            st = mt_gen_torus(a, b, &ordered->list);
            if (st != MT_OK) {
                snprintf(err, err_size, "mt_gen_torus(%u, %u) failed: %s", a, b, mt_strerror(st));
                return false;
            }
            snprintf(ordered->mesh, sizeof ordered->mesh, "torus %ux%u", a, b);
            return true;
        default:
            corpus_name = corpus_mesh_name(which);
            break;
    }
    char path[PATH_MAX];
    int n = snprintf(path, sizeof path, "%s/%s.off", options->corpus_dir, corpus_name);
    if (n < 0 || (size_t)n >= sizeof path) {
        snprintf(err, err_size, "corpus path too long: %s", options->corpus_dir);
        return false;
    }
    mt_diag diag;
    mt_diag_clear(&diag);
    st = mt_read_file(path, MT_FORMAT_AUTO, &ordered->list, &diag);
    if (st != MT_OK) {
        snprintf(err, err_size, "cannot read %s (--corpus DIR): %s", path, diag.message);
        return false;
    }
    snprintf(ordered->mesh, sizeof ordered->mesh, "%s", corpus_name);
    return true;
}

/* Meshes by size: bunny, fertility, grid, torus for all; else the grid. */
static const uint32_t all_meshes[] = {2, 3, 0, 1};

/* Whether mesh `which` can be made: the generated ones always, a corpus
 * mesh when its file is in the corpus directory. */
static bool mesh_available(const mt__bench_options *options, uint32_t which)
{
    if (which < 2) return true;
    char path[PATH_MAX];
    int n = snprintf(path, sizeof path, "%s/%s.off", options->corpus_dir, corpus_mesh_name(which));
    return n >= 0 && (size_t)n < sizeof path && access(path, R_OK) == 0;
}

/* The m-th mesh of `all` that can be made. */
static uint32_t available_mesh(const mt__bench_options *options, uint32_t m)
{
    for (size_t i = 0; i < sizeof all_meshes / sizeof all_meshes[0]; i++) {
        if (!mesh_available(options, all_meshes[i])) continue;
        if (m-- == 0) return all_meshes[i];
    }
    return 0;
}

uint32_t mt__bench_num_meshes(const mt__bench_options *options)
{
    if (!options->all) return 1;
    uint32_t count = 0;
    for (size_t i = 0; i < sizeof all_meshes / sizeof all_meshes[0]; i++) {
        if (mesh_available(options, all_meshes[i])) {
            count++;
        } else {
            fprintf(stderr,
                    "meshtopo-bench: %s.off is not in the corpus %s: its rows are left out "
                    "(--corpus DIR names a corpus that has it)\n",
                    corpus_mesh_name(all_meshes[i]), options->corpus_dir);
        }
    }
    return count;
}

bool mt__bench_mesh_cases_make(const mt__bench_options *options, const char *dir, uint32_t m,
                               mt__bench_case *cases, char *err, size_t err_size)
{
    mt__bench_case *ordered = &cases[0];
    mt__bench_case *permuted = &cases[1];
    memset(cases, 0, 2 * sizeof *cases);
    if (!mesh_make(options, options->all ? available_mesh(options, m) : 0, ordered, err, err_size))
        return false;
    snprintf(ordered->order, sizeof ordered->order, "ordered");
    if (!face_list_copy(&ordered->list, &permuted->list, err, err_size)) return false;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_face_list_permute(&permuted->list, options->seed, &diag);
    if (st != MT_OK) {
        snprintf(err, err_size, "mt_face_list_permute failed: %s", diag.message);
        return false;
    }
    snprintf(permuted->mesh, sizeof permuted->mesh, "%s", ordered->mesh);
    snprintf(permuted->order, sizeof permuted->order, "permuted");

    for (uint32_t i = 0; i < 2; i++) {
        int n = snprintf(cases[i].path, sizeof cases[i].path, "%s/case%u-%s.mtbench", dir,
                         2 * m + i, cases[i].order);
        if (n < 0 || (size_t)n >= sizeof cases[i].path) {
            snprintf(err, err_size, "temporary directory path too long: %s", dir);
            cases[i].path[0] = '\0';
            return false;
        }
        if (!mt__bench_input_write(&cases[i].list, cases[i].path, err, err_size)) {
            cases[i].path[0] = '\0';
            return false;
        }
    }
    return true;
}

void mt__bench_case_release(mt__bench_case *bench_case)
{
    mt__bench_case_remove_file(bench_case);
    mt_face_list *l = &bench_case->list;
    free(l->positions);
    free(l->face_sizes);
    free(l->face_indices);
    l->positions = NULL;
    l->face_sizes = NULL;
    l->face_indices = NULL;
}

void mt__bench_case_remove_file(mt__bench_case *bench_case)
{
    if (bench_case->path[0]) remove(bench_case->path);
    bench_case->path[0] = '\0';
}
