/* What a load (mt_archive_load_mesh*) and a verification
 * (mt_archive_verify_file*) check in a file, in one place so that the two
 * agree on every file: provenance and report, the face list's content hash,
 * the stored half-edge arrays (validated by mt_mesh_restore and matched
 * against their digest; formats 2 and 3, which have none, against a
 * rebuild), and the rebuild from the face list when they fail. The steps
 * are listed at mt_archive_load_mesh_file in archive.h.
 *
 * Why a digest and not a comparison with a rebuild: validation proves the
 * arrays are a consistent mesh, not that they are the face list's; only a
 * rebuild or a hash tells that, and hashing the arrays costs a small part of
 * a restore where a rebuild with its checks costs several restores
 * (docs/performance/archive.md, "What a reload's checks cost"). The content
 * hash is computed a block at a time from the file (check_hash_stored)
 * rather than from the whole face list read first, which would mean fresh
 * memory to fault in. Validation stays: the digest is no signature, and the
 * arrays come from a file. */
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"
#include "meshtopo/validate.h"

/* Fails the check with st (diag already filled): the fault the status
 * stands for, unless the caller has set one. */
static mt_status failed(mt__check *c, mt_status st)
{
    if (c->fault == MT_ARCHIVE_FAULT_NONE || c->fault == MT_ARCHIVE_FAULT_DERIVED)
        c->fault = mt__archive_read_fault(st);
    return st;
}

/* A failure of the stored arrays that is the system's (memory, an I/O
 * error), not the file's: no rebuild is tried. */
static bool system_failure(mt_status st)
{
    return st == MT_ERR_NOMEM || mt__archive_last_errno != 0;
}

/* The face list of /meshtopo (group g), checked against the report's counts. */
static mt_status read_faces(hid_t g, const char *file_name, mt_archive_record *r, mt_diag *diag)
{
    mt_status st = mt__archive_read_faces(g, file_name, &r->faces, diag);
    if (st == MT_OK &&
        (r->report.num_verts != r->faces.num_verts || r->report.num_faces != r->faces.num_faces))
        st = mt__archive_fail(diag, MT_ERR_PARSE,
                              "%s: the report counts %u vertices and %u faces, the face list %u "
                              "and %u",
                              file_name, r->report.num_verts, r->report.num_faces,
                              r->faces.num_verts, r->faces.num_faces);
    return st;
}

/* A computed content hash h against the file's: a mismatch is the fault
 * CONTENT. */
static mt_status compare_hash(mt__check *c, uint64_t h, const char *file_name, mt_diag *diag)
{
    if (h != c->record.content_hash) {
        c->fault = MT_ARCHIVE_FAULT_CONTENT;
        return mt__archive_fail(diag, MT_ERR_CORRUPT,
                                "%s: content hash mismatch: the file says %016llx, the face list "
                                "hashes to %016llx",
                                file_name, (unsigned long long)c->record.content_hash,
                                (unsigned long long)h);
    }
    c->hash_checked = true;
    return MT_OK;
}

/* The content hash of `faces` must be the file's content_hash. */
static mt_status check_hash(mt__check *c, const mt_face_list *faces, const char *file_name,
                            mt_diag *diag)
{
    double t = mt__archive_now_ms();
    uint64_t h = 0;
    mt_diag why;
    mt_diag_clear(&why);
    mt_status st = c->hash(c->hash_ctx, faces, &h, &why);
    c->check_ms += mt__archive_now_ms() - t;
    if (st != MT_OK)
        return mt__archive_fail(diag, st, "%s: the content hash cannot be computed: %s", file_name,
                                why.message);
    return compare_hash(c, h, file_name, diag);
}

/* The content hash check of a restored mesh's file without decoding the
 * face list into a copy: face_vertex_counts and face_vertex_indices are
 * read as they are stored and hashed with the mesh's positions (the same
 * dataset as the face list's). Reading and copying the whole face list
 * would cost 3 times as much on a large mesh. */
static mt_status check_hash_stored(mt__check *c, hid_t g, const char *file_name,
                                   const mt_mesh *mesh, mt_diag *diag)
{
    mt_mesh_parts parts;
    mt_mesh_get_parts(mesh, &parts);
    double t = mt__archive_now_ms();
    if (c->hash == mt_archive_content_hash) {
        /* The daemon's hash, computed a block at a time from the file. */
        uint64_t h = 0;
        mt_status st =
            mt__content_hash_stored(g, file_name, parts.num_verts, parts.positions, &h, diag);
        c->check_ms += mt__archive_now_ms() - t;
        if (st != MT_OK) return st;
        return compare_hash(c, h, file_name, diag);
    }
    void *counts = NULL, *indices = NULL;
    uint64_t num_counts = 0, num_indices = 0;
    mt_status st = mt__h5_read_dataset(g, "/meshtopo/face_vertex_counts", file_name, 1, 0,
                                       MT__H5_INT, 4, H5T_NATIVE_INT32, &counts, &num_counts, diag);
    if (st == MT_OK)
        st = mt__h5_read_dataset(g, "/meshtopo/face_vertex_indices", file_name, 1, 0, MT__H5_INT, 4,
                                 H5T_NATIVE_INT32, &indices, &num_indices, diag);
    c->read_ms += mt__archive_now_ms() - t;
    if (st == MT_OK) {
        /* Not owned, never written (the hash function takes it const). */
        mt_face_list view = {parts.num_verts, (uint32_t)num_counts,
                             num_indices,     (double *)parts.positions,
                             counts,          indices};
        st = check_hash(c, &view, file_name, diag);
    }
    free(counts);
    free(indices);
    return st;
}

/* The format 4 check of a restored mesh: the digest of its arrays,
 * positions and report equals the stored one. Problems go to c->fallback. */
static mt_status check_digest(hid_t g, const char *file_name, const mt_mesh *mesh,
                              uint64_t content_hash, mt__check *c)
{
    uint64_t stored = 0, computed = 0;
    mt_status st = mt__halfedge_read_digest(g, file_name, &stored, &c->fallback);
    mt_mesh_parts parts;
    mt_mesh_get_parts(mesh, &parts);
    if (st == MT_OK)
        st = mt__halfedge_digest(&parts, mt_mesh_report(mesh), content_hash, &computed,
                                 &c->fallback);
    if (st == MT_OK && computed != stored)
        st = mt__archive_fail(&c->fallback, MT_ERR_CORRUPT,
                              "%s: the half-edge arrays, positions and report hash to %016llx, "
                              "not to the digest stored with them (%016llx): they are not what "
                              "was archived",
                              file_name, (unsigned long long)computed, (unsigned long long)stored);
    return st;
}

/* Rebuilds the mesh from r's face list and validates it; *out_differs gets
 * the first difference between the rebuild's report and the stored one
 * (empty when equal). */
static mt_status rebuild(const mt_archive_record *r, mt_mesh **out_mesh, char *out_differs,
                         size_t size, mt_diag *diag)
{
    *out_mesh = NULL;
    out_differs[0] = '\0';
    mt_mesh *mesh = NULL;
    mt_diag why;
    mt_status st = mt_mesh_build(&r->faces, NULL, &mesh, &why);
    if (st != MT_OK)
        return mt__archive_fail(diag, st, "%s: rebuilding the stored face list failed: %s",
                                r->file_name, why.message);
    st = mt_mesh_validate(mesh, &why);
    if (st != MT_OK) {
        mt_mesh_destroy(mesh);
        return mt__archive_fail(diag, MT_ERR_CORRUPT, "%s: the rebuilt mesh is invalid: %s",
                                r->file_name, why.message);
    }
    if (mt_archive_report_equal(&r->report, mt_mesh_report(mesh), out_differs, size))
        out_differs[0] = '\0';
    *out_mesh = mesh;
    return MT_OK;
}

/* Fills diag with `problem` after the arrays' problem (c->fallback) when
 * there was one, so a failed fallback names both. */
static mt_status fail_after_fallback(const mt__check *c, mt_status st, const char *what,
                                     const mt_diag *problem, mt_diag *diag)
{
    if (c->fallback.status != MT_OK)
        return mt__archive_fail(diag, st, "%s; %s: %s", c->fallback.message, what,
                                problem->message);
    if (diag) *diag = *problem;
    return st;
}

mt_status mt__archive_check(hid_t file, const char *file_name, mt__check *c, mt_diag *diag)
{
    mt_archive_record *r = &c->record;
    memset(r, 0, sizeof *r);
    c->mesh = NULL;
    c->fault = MT_ARCHIVE_FAULT_NONE;
    c->restored = c->hash_checked = false;
    mt_diag_clear(&c->fallback);
    c->read_ms = c->mesh_ms = c->check_ms = 0;
    mt__archive_last_errno = 0;
    mt_mesh *legacy = NULL; /* formats 2 and 3: the stored arrays, pending */
    mt_mesh_parts legacy_parts;
    memset(&legacy_parts, 0, sizeof legacy_parts);

    double t0 = mt__archive_now_ms();
    mt_status st = MT_OK;
    if (!(r->file_name = mt__archive_strdup(file_name)))
        st = mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    hid_t g = st == MT_OK ? mt__archive_group_open(file, "meshtopo", file_name, diag) : -1;
    if (st == MT_OK && g < 0) st = MT_ERR_PARSE;
    if (st == MT_OK) st = mt__archive_read_provenance(g, file_name, r, diag);
    hid_t rg = st == MT_OK ? mt__archive_group_open(g, "report", file_name, diag) : -1;
    if (st == MT_OK && rg < 0) st = MT_ERR_PARSE;
    if (st == MT_OK) st = mt__report_read(rg, r->format_version, file_name, &r->report, diag);
    if (rg >= 0) H5Gclose(rg);
    /* The face list, decoded: for the caller, or for the comparison with a
     * rebuild that files without a digest need. Its content hash is checked
     * as soon as it is read, or (a restored mesh's) from the stored arrays. */
    const bool hashed = c->hash && r->format_version >= MT_ARCHIVE_FORMAT_VERSION_HASHED;
    bool faces_read = false;
    if (st == MT_OK && (c->keep_faces || r->format_version < MT_ARCHIVE_FORMAT_VERSION_DIGEST)) {
        st = read_faces(g, file_name, r, diag);
        faces_read = true;
    }
    c->read_ms = mt__archive_now_ms() - t0;
    if (st == MT_OK && faces_read && hashed) st = check_hash(c, &r->faces, file_name, diag);
    if (st != MT_OK) goto fail;

    /* The stored arrays: restored, validated and matched with their digest
     * (format 4), or read for the comparison with the rebuild (2 and 3). */
    if (r->format_version >= 2) {
        double t = mt__archive_now_ms();
        const double *positions = faces_read ? r->faces.positions : NULL;
        mt_status rs;
        if (r->format_version >= MT_ARCHIVE_FORMAT_VERSION_DIGEST) {
            rs = mt__halfedge_restore(g, file_name, &r->report, positions, &c->mesh, &c->fallback);
            c->mesh_ms += mt__archive_now_ms() - t;
            if (rs == MT_OK) {
                t = mt__archive_now_ms();
                rs = check_digest(g, file_name, c->mesh, r->content_hash, c);
                c->check_ms += mt__archive_now_ms() - t;
            }
            if (rs != MT_OK) {
                mt_mesh_destroy(c->mesh);
                c->mesh = NULL;
            }
            if (rs == MT_OK && hashed && !c->hash_checked) {
                st = check_hash_stored(c, g, file_name, c->mesh, diag);
                if (st != MT_OK) goto fail;
            }
        } else {
            rs = mt__halfedge_read(g, file_name, positions, &legacy, &legacy_parts, &c->fallback);
            c->mesh_ms += mt__archive_now_ms() - t;
        }
        if (rs != MT_OK && system_failure(rs)) {
            st = mt__archive_fail(diag, rs, "%s", c->fallback.message);
            goto fail;
        }
    }

    if (!c->mesh) {
        /* A rebuild from the face list: format 1, formats 2 and 3 (to
         * compare), or stored arrays that failed. */
        mt_diag why;
        if (!faces_read) {
            double t = mt__archive_now_ms();
            st = read_faces(g, file_name, r, &why);
            c->read_ms += mt__archive_now_ms() - t;
            if (st != MT_OK) {
                fail_after_fallback(c, st, "the face list for a rebuild cannot be read either",
                                    &why, diag);
                goto fail;
            }
        }
        if (hashed && !c->hash_checked) {
            st = check_hash(c, &r->faces, file_name, diag);
            if (st != MT_OK) goto fail;
        }
        double t = mt__archive_now_ms();
        char differs[256];
        st = rebuild(r, &c->mesh, differs, sizeof differs, &why);
        c->mesh_ms += mt__archive_now_ms() - t;
        if (st != MT_OK) {
            fail_after_fallback(c, st, "the rebuild from the face list failed too", &why, diag);
            goto fail;
        }
        if (differs[0] && !c->hash_checked) {
            /* Nothing tells whether the face list or the report is damaged. */
            if (c->fallback.status != MT_OK)
                st = mt__archive_fail(diag, MT_ERR_CORRUPT,
                                      "%s; the rebuild from the face list differs from the stored "
                                      "one too (report %s: stored != rebuilt)",
                                      c->fallback.message, differs);
            else
                st = mt__archive_fail(diag, MT_ERR_CORRUPT,
                                      "%s: the rebuild's report differs from the stored one (%s: "
                                      "stored != rebuilt)",
                                      file_name, differs);
            c->fault = MT_ARCHIVE_FAULT_CONTENT;
            goto fail;
        }
        if (differs[0] && c->fallback.status == MT_OK)
            /* The face list is vouched for by its content hash: the stored
             * report is what is damaged; the rebuild's is served. */
            mt__archive_fail(&c->fallback, MT_ERR_CORRUPT,
                             "%s: the stored report differs from the rebuild of the intact face "
                             "list (%s: stored != rebuilt)",
                             file_name, differs);
        if (legacy && c->fallback.status == MT_OK) {
            t = mt__archive_now_ms();
            mt_mesh_parts built;
            mt_mesh_get_parts(c->mesh, &built);
            char difference[256];
            if (!mt__parts_equal(&legacy_parts, &built, difference, sizeof difference))
                mt__archive_fail(&c->fallback, MT_ERR_CORRUPT,
                                 "%s: the stored half-edge arrays differ from the rebuild's "
                                 "(meshtopo/halfedge/%s: stored != rebuilt)",
                                 file_name, difference);
            c->check_ms += mt__archive_now_ms() - t;
        }
        if (c->fallback.status != MT_OK) c->fault = MT_ARCHIVE_FAULT_DERIVED;
    } else {
        c->restored = true;
    }
    /* Damaged attributes leave the mesh servable without them (the rest of
     * the file vouches for it): a derived fault, which verification reports. */
    {
        mt_diag why;
        mt_status as = mt__attributes_read(g, file_name, c->mesh, c->restored, &why);
        if (as != MT_OK && system_failure(as)) {
            st = mt__archive_fail(diag, as, "%s", why.message);
            goto fail;
        }
        if (as != MT_OK) {
            if (c->fallback.status == MT_OK) c->fallback = why;
            c->fault = MT_ARCHIVE_FAULT_DERIVED;
        }
    }
    mt_mesh_destroy(legacy);
    if (g >= 0) H5Gclose(g);
    if (!c->keep_faces) {
        mt_face_list_free(&r->faces);
        memset(&r->faces, 0, sizeof r->faces);
    }
    return MT_OK;

fail:
    failed(c, st);
    mt_mesh_destroy(legacy);
    mt_mesh_destroy(c->mesh);
    c->mesh = NULL;
    c->restored = false;
    if (g >= 0) H5Gclose(g);
    mt_archive_record_free(r);
    return st;
}
