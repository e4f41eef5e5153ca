/* Writing one mesh version: the VTKHDF 1.0 UnstructuredGrid a viewer reads
 * (/VTKHDF, with the topology arrays of archive_topology.c), the face list
 * exactly as submitted with provenance and the topology report
 * (/meshtopo), all into a temporary file that is flushed, closed, fsynced
 * and then linked into place (see write_durably for why each step is
 * needed, and for why nothing planted in the directory can redirect the
 * write), and (format 2) the half-edge arrays with (format 4) their digest
 * (archive_halfedge.c). Layout: contiguous datasets by default, or chunked
 * with shuffle + deflate or Blosc LZ4 (mt_archive_write_options). */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "archive_internal.h"

/* Random temporary names tried before giving up: a collision of 64 random
 * bits is never expected, so running out means something keeps taking the
 * names, which is worth an error. */
#define TMP_ATTEMPTS 16

/* The VTKHDF cells are the faces the build kept (rejected faces would make
 * a viewer read out of bounds), in VTKHDF's types. They are converted and
 * written in blocks through one small buffer rather than made whole in
 * memory: a large mesh's cells would be tens of megabytes of fresh memory
 * to fault in, fill and free on every write. */
typedef enum cells_column {
    COLUMN_CONNECTIVITY,
    COLUMN_OFFSETS,
    COLUMN_TYPES,
    COLUMN_FACE_IDS
} cells_column;

/* Rows per block: 4 MiB of int64, a whole number of 1 MiB chunks for each
 * column's element size. */
#define BLOCK_ROWS (1u << 19)

typedef struct vtk_cells {
    uint64_t cells, ids;
    const uint32_t *face_he; /* the mesh's: MT_NONE for a rejected face */
    const mt_face_list *list;
    void *buffer; /* BLOCK_ROWS * 8 bytes */
} vtk_cells;

static void vtk_cells_count(const mt_face_list *list, const mt_mesh *mesh, vtk_cells *out)
{
    memset(out, 0, sizeof *out);
    mt_mesh_view view;
    mt_mesh_get_view(mesh, &view);
    out->face_he = view.face_he;
    out->list = list;
    for (uint32_t f = 0; f < list->num_faces; f++)
        if (view.face_he[f] != MT_NONE) {
            out->cells++;
            out->ids += list->face_sizes[f];
        }
}

/* Values of one column gathered in the block buffer and written a block at
 * a time. */
typedef struct column_writer {
    hid_t dset, mtype;
    bool bytes; /* uint8 values, else int64 */
    void *buffer;
    size_t fill, block;
    uint64_t written;
    const char *file, *dname;
    mt_status st;
} column_writer;

static void column_flush(column_writer *w, mt_diag *diag)
{
    if (w->st == MT_OK)
        w->st = mt__h5_write_rows(w->dset, w->mtype, w->written, w->fill, w->buffer, w->file,
                                  w->dname, diag);
    w->written += w->fill;
    w->fill = 0;
}

static void column_push(column_writer *w, int64_t value, mt_diag *diag)
{
    if (w->bytes)
        ((uint8_t *)w->buffer)[w->fill++] = (uint8_t)value;
    else
        ((int64_t *)w->buffer)[w->fill++] = value;
    if (w->fill == w->block) column_flush(w, diag);
}

/* Writes one column of the cells: Connectivity (ids rows), Offsets (cells
 * + 1), Types (cells, VTK_TRIANGLE 5, VTK_QUAD 9, VTK_POLYGON 7) or the
 * original face ids (cells). */
static mt_status write_cells_column(hid_t loc, const char *dname, cells_column column,
                                    const vtk_cells *v, const mt__h5_layout *layout,
                                    const char *name, mt_diag *diag)
{
    column_writer w;
    memset(&w, 0, sizeof w);
    w.bytes = column == COLUMN_TYPES;
    w.mtype = w.bytes ? H5T_NATIVE_UINT8 : H5T_NATIVE_INT64;
    w.buffer = v->buffer;
    w.block = w.bytes ? 8 * (size_t)BLOCK_ROWS : BLOCK_ROWS;
    w.file = name;
    w.dname = dname;
    const uint64_t rows = column == COLUMN_CONNECTIVITY ? v->ids
                          : column == COLUMN_OFFSETS    ? v->cells + 1
                                                        : v->cells;
    w.dset = mt__h5_create_dataset(loc, dname, w.bytes ? H5T_STD_U8LE : H5T_STD_I64LE, rows, layout,
                                   name, diag);
    if (w.dset < 0) return MT_ERR_IO;
    const mt_face_list *list = v->list;
    const uint32_t *sizes = list->face_sizes, *indices = list->face_indices;
    /* Every face kept (the usual case): the connectivity is the face list's
     * indices, widened to int64 by HDF5's own conversion in one write. */
    if (column == COLUMN_CONNECTIVITY && v->cells == list->num_faces) {
        w.st = mt__h5_write_rows(w.dset, H5T_NATIVE_UINT32, 0, rows, indices, name, dname, diag);
        H5Dclose(w.dset);
        return w.st;
    }
    int64_t *out64 = v->buffer;
    uint8_t *out8 = v->buffer;
    uint64_t start = 0, pos = 0;
    if (column == COLUMN_OFFSETS) column_push(&w, 0, diag);
    /* One face's values go straight into the block (flushed first when they
     * would not fit): this loop runs once per face side of the mesh, so it
     * stays free of calls. Only a face with more sides than a block holds
     * goes value by value. */
    for (uint32_t f = 0; w.st == MT_OK && f < list->num_faces; start += sizes[f], f++) {
        if (v->face_he[f] == MT_NONE) continue;
        const uint32_t n = sizes[f];
        const size_t count = column == COLUMN_CONNECTIVITY ? n : 1;
        if (w.fill + count > w.block) column_flush(&w, diag);
        switch (column) {
            case COLUMN_CONNECTIVITY:
                if (n > w.block) {
                    for (uint32_t k = 0; k < n; k++) column_push(&w, indices[start + k], diag);
                    break;
                }
                for (uint32_t k = 0; k < n; k++) out64[w.fill + k] = indices[start + k];
                w.fill += n;
                break;
            case COLUMN_OFFSETS:
                pos += n;
                out64[w.fill++] = (int64_t)pos;
                break;
            case COLUMN_TYPES:
                out8[w.fill++] = n == 3 ? 5 : n == 4 ? 9 : 7;
                break;
            case COLUMN_FACE_IDS:
                out64[w.fill++] = f;
                break;
        }
    }
    column_flush(&w, diag);
    H5Dclose(w.dset);
    return w.st;
}

static hid_t group_create(hid_t loc, const char *name, const char *file, mt_diag *diag)
{
    hid_t g = H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot create group %s", file, name);
    return g;
}

static mt_status write_vtkhdf(hid_t file, const vtk_cells *v, uint32_t num_verts,
                              const mt__topology *topology, const mt__h5_layout *layout,
                              const char *name, mt_diag *diag)
{
    hid_t g = group_create(file, "VTKHDF", name, diag);
    if (g < 0) return MT_ERR_IO;
    static const int64_t version[2] = {1, 0};
    int64_t counts[3] = {num_verts, (int64_t)v->cells, (int64_t)v->ids};
    hsize_t one[1] = {1}, pts[2] = {num_verts, 3};
    mt_status st = mt__h5_write_attr_ints(g, "Version", H5T_STD_I64LE, version, 2, name, diag);
    if (st == MT_OK) st = mt__h5_write_attr_string(g, "Type", "UnstructuredGrid", name, diag);
    const char *count_names[3] = {"NumberOfPoints", "NumberOfCells", "NumberOfConnectivityIds"};
    for (int i = 0; st == MT_OK && i < 3; i++)
        st = mt__h5_write_dataset(g, count_names[i], H5T_STD_I64LE, H5T_NATIVE_INT64, 1, one,
                                  &counts[i], name, diag);
    /* Points are the positions (zeros for a mesh without geometry). */
    double *zeros = NULL;
    if (st == MT_OK && !v->list->positions &&
        !(zeros = calloc(3 * (size_t)num_verts + 1, sizeof(double))))
        st = mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    if (st == MT_OK)
        st = mt__h5_write_dataset_layout(g, "Points", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, pts,
                                         zeros ? zeros : v->list->positions, layout, name, diag);
    free(zeros);
    if (st == MT_OK)
        st = write_cells_column(g, "Connectivity", COLUMN_CONNECTIVITY, v, layout, name, diag);
    if (st == MT_OK) st = write_cells_column(g, "Offsets", COLUMN_OFFSETS, v, layout, name, diag);
    if (st == MT_OK) st = write_cells_column(g, "Types", COLUMN_TYPES, v, layout, name, diag);
    hid_t cd = st == MT_OK ? group_create(g, "CellData", name, diag) : -1;
    if (st == MT_OK && cd < 0) st = MT_ERR_IO;
    if (st == MT_OK)
        st = write_cells_column(cd, "original_face_id", COLUMN_FACE_IDS, v, layout, name, diag);
    hid_t pd = st == MT_OK ? group_create(g, "PointData", name, diag) : -1;
    if (st == MT_OK && pd < 0) st = MT_ERR_IO;
    if (st == MT_OK) st = mt__topology_write(cd, pd, topology, layout, name, diag);
    if (pd >= 0) H5Gclose(pd);
    if (cd >= 0) H5Gclose(cd);
    H5Gclose(g);
    return st;
}

static mt_status write_meshtopo(hid_t file, const mt_archive_meta *meta, const mt_face_list *list,
                                const mt_mesh *mesh, const mt__h5_layout *layout, const char *name,
                                mt_diag *diag)
{
    hid_t g = group_create(file, "meshtopo", name, diag);
    if (g < 0) return MT_ERR_IO;
    uint32_t format_version = MT_ARCHIVE_FORMAT_VERSION;
    int64_t num_verts = list->num_verts, num_faces = list->num_faces,
            num_indices = (int64_t)list->num_indices;
    mt_status st = mt__h5_write_attr_string(
        g, "description",
        "meshtopo archive of one mesh version: the face list exactly as submitted "
        "(positions, face_vertex_counts, face_vertex_indices; rejected faces included), "
        "provenance attributes, the build's topology report (group report) and the "
        "half-edge arrays (group halfedge) that a reload restores without a rebuild, and the "
        "elements' user attributes (group attributes) when there are any. /VTKHDF "
        "holds the faces the build kept; its CellData/original_face_id maps cells back, and "
        "its CellData and PointData hold the topology (components, defects, boundary, "
        "orientation), each dataset described by its attribute description.",
        name, diag);
    if (st == MT_OK)
        st = mt__h5_write_attr_int(g, "format_version", H5T_NATIVE_UINT32, &format_version, name,
                                   diag);
    if (st == MT_OK) st = mt__h5_write_attr_string(g, "mesh_id", meta->mesh_id, name, diag);
    if (st == MT_OK)
        st = mt__h5_write_attr_int(g, "version", H5T_NATIVE_UINT32, &meta->version, name, diag);
    if (st == MT_OK)
        st = mt__h5_write_attr_int(g, "utime", H5T_NATIVE_INT64, &meta->utime, name, diag);
    if (st == MT_OK)
        st = mt__h5_write_attr_string(g, "source", meta->source ? meta->source : "", name, diag);
    if (st == MT_OK)
        st = mt__h5_write_attr_int(g, "content_hash", H5T_NATIVE_UINT64, &meta->content_hash, name,
                                   diag);
    if (st == MT_OK)
        st = mt__h5_write_attr_int(g, "num_verts", H5T_NATIVE_INT64, &num_verts, name, diag);
    if (st == MT_OK)
        st = mt__h5_write_attr_int(g, "num_faces", H5T_NATIVE_INT64, &num_faces, name, diag);
    if (st == MT_OK)
        st = mt__h5_write_attr_int(g, "num_indices", H5T_NATIVE_INT64, &num_indices, name, diag);
    /* A mesh without geometry has a positions dataset of shape (0, 3). */
    hsize_t pos[2] = {list->positions ? list->num_verts : 0, 3};
    hsize_t counts[1] = {list->num_faces}, indices[1] = {list->num_indices};
    /* With geometry, positions is a second name (an HDF5 hard link) of
     * /VTKHDF/Points: the same N x 3 float64 values, stored once. */
    if (st == MT_OK && list->positions) {
        if (H5Lcreate_hard(file, "/VTKHDF/Points", g, "positions", H5P_DEFAULT, H5P_DEFAULT) < 0)
            st = mt__h5_fail(diag, MT_ERR_IO, name, "%s: cannot link /meshtopo/positions", name);
    } else if (st == MT_OK) {
        st = mt__h5_write_dataset(g, "positions", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, pos,
                                  list->positions, name, diag);
    }
    /* int32 as in mesh_t: the uint32 entries are written with an int32 memory
     * type (same bits, no conversion), so an index read as -1 shows as -1. */
    if (st == MT_OK)
        st = mt__h5_write_dataset_layout(g, "face_vertex_counts", H5T_STD_I32LE, H5T_NATIVE_INT32,
                                         1, counts, list->face_sizes, layout, name, diag);
    if (st == MT_OK)
        st = mt__h5_write_dataset_layout(g, "face_vertex_indices", H5T_STD_I32LE, H5T_NATIVE_INT32,
                                         1, indices, list->face_indices, layout, name, diag);
    hid_t rg = st == MT_OK ? group_create(g, "report", name, diag) : -1;
    if (st == MT_OK && rg < 0) st = MT_ERR_IO;
    if (st == MT_OK) st = mt__report_write(rg, mt_mesh_report(mesh), name, diag);
    if (rg >= 0) H5Gclose(rg);
    if (st == MT_OK) st = mt__halfedge_write(g, mesh, meta->content_hash, layout, name, diag);
    if (st == MT_OK) st = mt__attributes_write(g, mesh, layout, name, diag);
    H5Gclose(g);
    return st;
}

/* The temporary file: ".mt-tmp-<pid>-<16 random hex digits>.<host>.part"
 * (the host, so that a writer on another machine sharing the directory
 * never takes it for a leftover of a dead local process) created with
 * O_CREAT | O_EXCL | O_NOFOLLOW, so that nothing already there (a
 * symbolic link planted at a guessed name included) is opened, followed or
 * truncated; a taken name means another draw. On MT_OK *out_fd is the new
 * empty file and *out_path its path (malloc'ed). */
static mt_status tmp_create(const mt_archive *archive, int *out_fd, char **out_path, mt_diag *diag)
{
    *out_fd = -1;
    *out_path = NULL;
    for (int attempt = 0; attempt < TMP_ATTEMPTS; attempt++) {
        char hex[17], name[160], host[MT__ARCHIVE_HOST_MAX + 1];
        mt__archive_random_hex(hex);
        mt__archive_host(host, sizeof host);
        snprintf(name, sizeof name, MT__ARCHIVE_TMP_PREFIX "%ld-%s.%s.part", (long)getpid(), hex,
                 host);
        char *path = mt__archive_path(archive, name);
        if (!path) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
        int fd = open(path, O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd >= 0) {
            *out_fd = fd;
            *out_path = path;
            return MT_OK;
        }
        int err = errno;
        if (err != EEXIST) {
            mt_status st = mt__archive_fail_os(diag, MT_ERR_IO, err, archive->dir,
                                               "%s: cannot create the temporary file", path);
            free(path);
            return st;
        }
        free(path);
    }
    return mt__archive_fail(diag, MT_ERR_IO,
                            "%s: %d random temporary names were all taken: something keeps "
                            "creating " MT__ARCHIVE_TMP_PREFIX "* files there",
                            archive->dir, TMP_ATTEMPTS);
}

/* What is at a final name that is not a regular file, for the messages. */
static const char *in_the_way(mode_t mode)
{
    return S_ISLNK(mode) ? "a symbolic link" : S_ISDIR(mode) ? "a directory" : "a non-regular file";
}

/* Links the written file (fd, named tmp) to final_path, never replacing
 * anything there. With /proc, linkat links the open file itself, whatever
 * became of its temporary name; without, link(tmp) and a check that the
 * final name is our file (a swapped-in temporary name is unlinked again). */
static mt_status link_final(const mt_archive *archive, int fd, const char *tmp,
                            const char *final_path, const mt_archive_meta *meta, mt_diag *diag)
{
    char proc[32];
    const bool by_fd = mt__fd_proc_path(fd, proc, sizeof proc);
    int rc = by_fd ? linkat(AT_FDCWD, proc, AT_FDCWD, final_path, AT_SYMLINK_FOLLOW)
                   : link(tmp, final_path);
    if (rc != 0) {
        int err = errno;
        struct stat there;
        if (err == EEXIST && lstat(final_path, &there) == 0 && !S_ISREG(there.st_mode))
            return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                    "%s: version %u of mesh '%s' cannot be archived: %s is in "
                                    "the way (nothing was written through it)",
                                    final_path, meta->version, meta->mesh_id,
                                    in_the_way(there.st_mode));
        if (err == EEXIST)
            return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                    "%s: version %u of mesh '%s' is already archived", final_path,
                                    meta->version, meta->mesh_id);
        return mt__archive_fail_os(diag, MT_ERR_IO, err, archive->dir,
                                   "%s: cannot link the new file into place", final_path);
    }
    /* linkat of the open file links nothing else; link by name might have. */
    struct stat ours, linked;
    if (!by_fd && (fstat(fd, &ours) != 0 || lstat(final_path, &linked) != 0 ||
                   ours.st_dev != linked.st_dev || ours.st_ino != linked.st_ino)) {
        unlink(final_path);
        return mt__archive_fail(diag, MT_ERR_IO,
                                "%s: the temporary file %s was replaced while being written; "
                                "nothing was archived",
                                final_path, tmp);
    }
    return MT_OK;
}

/* Crash safety, step by step (HDF5 1.10 files are not crash-safe while
 * open for writing: a file killed before it is closed cannot be opened
 * again, so nothing is ever written under the final name):
 *  1. Create the temporary file in the same directory (same file system,
 *     so step 4 is atomic) exclusively and without following links
 *     (tmp_create), then let HDF5 create its file in it through
 *     /proc/self/fd: HDF5 opens files by name, and that name leads to the
 *     file just created whatever its directory entry has become.
 *     H5F_CLOSE_STRONG makes H5Fclose close every object and really
 *     release the file.
 *  2. H5Fflush(H5F_SCOPE_GLOBAL) writes HDF5's metadata cache and raw data
 *     out of its buffers; H5Fclose then writes the superblock's final
 *     end-of-file address. Only after both is the file complete.
 *  3. fsync the file: complete in the page cache is not on disk.
 *  4. link the final name to it (fails with EEXIST instead of replacing
 *     an existing version or a symbolic link planted there, unlike rename),
 *     then unlink the temporary name.
 *  5. fsync the directory so the new name itself survives a power loss.
 * A crash before 4 leaves only a temporary file (removed at the next open);
 * between 4 and the unlink, both names of one complete file. Without /proc
 * (a chroot) step 1 hands HDF5 the temporary name after removing the empty
 * file, for HDF5 to create it exclusively itself (H5F_ACC_EXCL is O_CREAT |
 * O_EXCL: never through a link), and step 4 checks the linked file is ours.
 * Every failure the system causes is reported with its errno text. */
static mt_status write_durably(const mt_archive *archive, const char *final_name,
                               const mt_archive_meta *meta, const mt_face_list *list,
                               const mt_mesh *mesh, const mt__h5_layout *layout,
                               const mt_archive_write_options *options,
                               mt_archive_write_stats *stats, mt_diag *diag)
{
    char *final_path = mt__archive_path(archive, final_name);
    if (!final_path) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    vtk_cells cells;
    double t0 = mt__archive_now_ms();
    /* The topology arrays first: what fails there (out of memory, bad
     * self-intersection pairs) fails before any file is made. */
    mt__topology topology;
    mt_status st = mt__topology_compute(
        list, mesh, options ? options->self_intersections : MT_ARCHIVE_SELF_INTERSECTIONS_SKIP,
        options ? options->self_intersection_pairs : NULL,
        options ? options->num_self_intersection_pairs : 0, &topology, diag);
    double topology_ms = mt__archive_now_ms() - t0;
    if (st != MT_OK) {
        free(final_path);
        return st;
    }
    vtk_cells_count(list, mesh, &cells);
    cells.buffer = malloc((size_t)BLOCK_ROWS * 8);
    if (!cells.buffer) st = mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    int fd = -1;
    char *tmp = NULL;
    if (st == MT_OK) st = tmp_create(archive, &fd, &tmp, diag);
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    hid_t file = -1;
    if (st == MT_OK) {
        char proc[32];
        bool by_fd = mt__fd_proc_path(fd, proc, sizeof proc);
        if (!by_fd) {
            unlink(tmp);
            close(fd);
            fd = -1;
        }
        if (fapl >= 0) H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
        file = fapl < 0 ? -1
                        : H5Fcreate(by_fd ? proc : tmp, by_fd ? H5F_ACC_TRUNC : H5F_ACC_EXCL,
                                    H5P_DEFAULT, fapl);
        if (file < 0) st = mt__h5_fail(diag, MT_ERR_IO, tmp, "%s: cannot create the file", tmp);
        /* Without /proc: our own descriptor of what HDF5 created, for the
         * fsync and the identity check of step 4. */
        void *handle = NULL;
        if (st == MT_OK && !by_fd &&
            (H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) < 0 || !handle ||
             (fd = fcntl(*(int *)handle, F_DUPFD_CLOEXEC, 0)) < 0))
            st = mt__archive_fail(diag, MT_ERR_IO, "%s: cannot get the file's descriptor", tmp);
    }
    if (st == MT_OK) st = write_vtkhdf(file, &cells, list->num_verts, &topology, layout, tmp, diag);
    if (st == MT_OK) st = write_meshtopo(file, meta, list, mesh, layout, tmp, diag);
    if (st == MT_OK && H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
        st = mt__h5_fail(diag, MT_ERR_IO, tmp, "%s: cannot flush the file", tmp);
    if (file >= 0 && H5Fclose(file) < 0 && st == MT_OK)
        st = mt__h5_fail(diag, MT_ERR_IO, tmp, "%s: cannot close the file", tmp);
    if (fapl >= 0) H5Pclose(fapl);
    free(cells.buffer);
    mt__topology_free(&topology);
    double t1 = mt__archive_now_ms();
    if (st == MT_OK && fsync(fd) != 0)
        st = mt__archive_fail_os(diag, MT_ERR_IO, errno, tmp, "%s: fsync failed", tmp);
    if (st == MT_OK) st = link_final(archive, fd, tmp, final_path, meta, diag);
    /* After a successful link: the second name; after a failure: the
     * leftover. Unlinking never follows a link. */
    if (tmp) unlink(tmp);
    if (st == MT_OK) st = mt__archive_fsync_dir(archive, diag);
    double t2 = mt__archive_now_ms();
    if (st == MT_OK && stats) {
        struct stat sb;
        stats->write_ms = t1 - t0;
        stats->fsync_ms = t2 - t1;
        stats->file_bytes = fstat(fd, &sb) == 0 ? (uint64_t)sb.st_size : 0;
        stats->topology_ms = topology_ms;
    }
    if (fd >= 0) close(fd);
    free(tmp);
    free(final_path);
    return st;
}

mt_status mt_archive_write(mt_archive *archive, const mt_archive_meta *meta,
                           const mt_face_list *list, const mt_mesh *mesh,
                           mt_archive_write_stats *out_stats, mt_diag *diag)
{
    return mt_archive_write_with(archive, meta, list, mesh, NULL, out_stats, diag);
}

mt_status mt_archive_write_with(mt_archive *archive, const mt_archive_meta *meta,
                                const mt_face_list *list, const mt_mesh *mesh,
                                const mt_archive_write_options *options,
                                mt_archive_write_stats *out_stats, mt_diag *diag)
{
    mt_diag_clear(diag);
    mt__h5_quiet();
    if (out_stats) memset(out_stats, 0, sizeof *out_stats);
    if (!archive || !meta || !list || !mesh)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_write: NULL argument");
    mt__h5_layout layout = {MT_ARCHIVE_COMPRESSION_NONE, 1};
    if (options) {
        if ((unsigned)options->compression > (unsigned)MT_ARCHIVE_COMPRESSION_LZ4 ||
            options->deflate_level > 9)
            return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                    "mt_archive_write: unknown compression %d or deflate level %u",
                                    (int)options->compression, options->deflate_level);
        if ((unsigned)options->self_intersections > (unsigned)MT_ARCHIVE_SELF_INTERSECTIONS_GIVEN)
            return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                    "mt_archive_write: unknown self_intersections %d",
                                    (int)options->self_intersections);
        layout.compression = options->compression;
        layout.level = options->deflate_level ? options->deflate_level : 1;
        if (layout.compression == MT_ARCHIVE_COMPRESSION_LZ4 && !mt_archive_lz4_available())
            return mt__archive_fail(diag, MT_ERR_UNSUPPORTED,
                                    "mt_archive_write: LZ4 compression needs HDF5's Blosc filter "
                                    "plugin (filter %d; Debian: hdf5-filter-plugin-blosc-serial), "
                                    "not found in HDF5's plugin path (HDF5_PLUGIN_PATH)",
                                    MT__H5_FILTER_BLOSC);
    }
    if (archive->read_only)
        return mt__archive_fail(diag, MT_ERR_UNSUPPORTED, "%s: archive opened read-only",
                                archive->dir);
    mt_status st = mt_mesh_id_check(meta->mesh_id, diag);
    if (st != MT_OK) return st;
    if (meta->version == 0)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mesh '%s': version 0 is not a version",
                                meta->mesh_id);
    st = mt_face_list_check(list, diag);
    if (st != MT_OK) return st;
    if (mt_mesh_num_verts(mesh) != list->num_verts || mt_mesh_num_faces(mesh) != list->num_faces)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                "mesh '%s': the built mesh (%u vertices, %u faces) is not the "
                                "face list's (%u, %u)",
                                meta->mesh_id, mt_mesh_num_verts(mesh), mt_mesh_num_faces(mesh),
                                list->num_verts, list->num_faces);
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(meta->mesh_id, meta->version, name, sizeof name);
    /* A quick refusal; the link of write_durably is what guarantees it. */
    char *final_path = mt__archive_path(archive, name);
    struct stat there;
    bool taken = final_path && lstat(final_path, &there) == 0;
    free(final_path);
    if (taken && !S_ISREG(there.st_mode))
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                "%s/%s: version %u of mesh '%s' cannot be archived: %s is in the "
                                "way (nothing was written through it)",
                                archive->dir, name, meta->version, meta->mesh_id,
                                in_the_way(there.st_mode));
    /* A file an earlier meshtopo wrote holds the version too. */
    char existing[MT_ARCHIVE_FILE_NAME_MAX + 1];
    if (!taken && mt_archive_file_find(archive, meta->mesh_id, meta->version, existing,
                                       sizeof existing, NULL) == MT_OK) {
        taken = true;
        memcpy(name, existing, sizeof name);
    }
    if (taken)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                "%s/%s: version %u of mesh '%s' is already archived", archive->dir,
                                name, meta->version, meta->mesh_id);
    return write_durably(archive, name, meta, list, mesh, &layout, options, out_stats, diag);
}
