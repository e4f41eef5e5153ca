/* The two hashes a load checks. The content hash of a stored face list is
 * the daemon's (meshtopo/mesh_ident.h: XXH3-64 over the bytes LCM encodes
 * for mesh_t's content fields), so the face list a file holds can be matched
 * with the hash its submission was acknowledged with; it is computed a block
 * at a time straight from the file. The digest of the half-edge arrays
 * (format 4) covers everything a restored mesh serves: arrays, positions and
 * report, tied to the content hash; a load compares it instead of
 * rebuilding the mesh to compare (XXH3 runs at memory speed, a rebuild does
 * not). */
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"

/* Values per block of mt__content_hash_stored: 1 MiB of int32, a whole
 * chunk of a deflated dataset (MT__H5_CHUNK_BYTES). */
#define HASH_BLOCK_VALUES (MT__H5_CHUNK_BYTES / 4)

mt_status mt_archive_content_hash(void *ctx, const mt_face_list *faces, uint64_t *out_hash,
                                  mt_diag *diag)
{
    (void)ctx;
    mt_diag_clear(diag);
    if (!faces || !out_hash)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_content_hash: NULL argument");
    return mt_face_list_content_hash(faces, out_hash, diag);
}

/* mt__h5_read_blocks' callback: a block of int32 values. */
static void hash_block(void *ctx, void *rows, size_t n)
{
    mt_content_hasher_int32s(ctx, rows, n);
}

mt_status mt__content_hash_stored(hid_t g, const char *file, uint32_t num_verts,
                                  const double *positions, uint64_t *out, mt_diag *diag)
{
    /* The content in mesh_ident.h's order: num_verts, num_position_values,
     * the positions, num_faces, the face counts, num_indices, the indices.
     * The two counts that follow an array are the datasets' lengths, known
     * only once read. */
    uint64_t num_faces = 0, num_indices = 0;
    mt_status st = mt__h5_dataset_rows(g, "/meshtopo/face_vertex_counts", file, 1, 0, MT__H5_INT, 4,
                                       &num_faces, diag);
    if (st == MT_OK)
        st = mt__h5_dataset_rows(g, "/meshtopo/face_vertex_indices", file, 1, 0, MT__H5_INT, 4,
                                 &num_indices, diag);
    if (st != MT_OK) return st;
    if (num_verts > INT32_MAX / 3 || num_faces > INT32_MAX || num_indices > INT32_MAX)
        return mt__archive_fail(diag, MT_ERR_TOO_LARGE,
                                "%s: a face list of %u vertices, %llu faces and %llu indices does "
                                "not fit mesh_t: its content hash is not defined",
                                file, num_verts, (unsigned long long)num_faces,
                                (unsigned long long)num_indices);
    uint32_t *buf = malloc((size_t)HASH_BLOCK_VALUES * 4);
    mt_content_hasher *hasher = mt_content_hasher_new();
    if (!buf || !hasher) {
        free(buf);
        mt_content_hasher_free(hasher);
        return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory hashing %s", file);
    }
    const uint32_t npos = positions ? 3 * num_verts : 0;
    mt_content_hasher_count(hasher, num_verts);
    mt_content_hasher_count(hasher, npos);
    mt_content_hasher_doubles(hasher, positions, npos);
    mt_content_hasher_count(hasher, (uint32_t)num_faces);
    uint64_t rows = 0;
    st =
        mt__h5_read_blocks(g, "/meshtopo/face_vertex_counts", file, MT__H5_INT, 4, H5T_NATIVE_INT32,
                           buf, HASH_BLOCK_VALUES, hash_block, hasher, &rows, diag);
    if (st == MT_OK) mt_content_hasher_count(hasher, (uint32_t)num_indices);
    if (st == MT_OK)
        st = mt__h5_read_blocks(g, "/meshtopo/face_vertex_indices", file, MT__H5_INT, 4,
                                H5T_NATIVE_INT32, buf, HASH_BLOCK_VALUES, hash_block, hasher, &rows,
                                diag);
    if (st == MT_OK) *out = mt_content_hasher_digest(hasher);
    mt_content_hasher_free(hasher);
    free(buf);
    return st;
}

/* XXH3-64 of n values of elem bytes each (uint32 or float64), as
 * little-endian bytes. */
static mt_status hash_array(const void *data, uint64_t n, size_t elem, uint64_t *out, mt_diag *diag)
{
    if (n == 0 || !data) {
        *out = mt_content_hash_bytes("", 0);
        return MT_OK;
    }
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    /* The arrays are in host order: hash a little-endian copy. */
    if (n > SIZE_MAX / elem) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    uint8_t *copy = malloc((size_t)n * elem);
    if (!copy) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory hashing an array");
    const uint8_t *src = data;
    for (uint64_t i = 0; i < n; i++)
        for (size_t b = 0; b < elem; b++) copy[i * elem + b] = src[i * elem + elem - 1 - b];
    *out = mt_content_hash_bytes(copy, (size_t)n * elem);
    free(copy);
#else
    (void)diag;
    *out = mt_content_hash_bytes(data, (size_t)n * elem);
#endif
    return MT_OK;
}

mt_status mt__halfedge_digest(const mt_mesh_parts *p, const mt_report *report,
                              uint64_t content_hash, uint64_t *out, mt_diag *diag)
{
    /* The arrays in the order /meshtopo/halfedge's description gives. */
    const uint64_t he = p->num_half_edges, bundled = p->num_bundled,
                   offsets = p->num_bundles ? (uint64_t)p->num_bundles + 1 : 0,
                   components = p->vert_component ? p->num_verts_internal : 0;
    const struct {
        const uint32_t *data;
        uint64_t n;
    } arrays[] = {
        {p->he_head, he},
        {p->he_next, he},
        {p->he_face, he},
        {p->face_he, p->num_faces},
        {p->vert_he, p->num_verts_internal},
        {p->copy_original, p->num_copies},
        {p->copies_sorted, p->num_copies},
        {p->bundle_offsets, offsets},
        {p->bundle_edges, bundled},
        {p->bundled_sorted, bundled},
        {p->bundled_bundle, bundled},
        {p->vert_component, components},
    };
    enum { NUM_COUNTS = 10, NUM_ARRAYS = sizeof arrays / sizeof arrays[0] };
    uint64_t words[NUM_COUNTS + NUM_ARRAYS + 2] = {
        content_hash,          p->num_verts,      p->num_faces,
        p->num_verts_internal, p->num_half_edges, p->num_copies,
        p->num_bundles,        p->num_bundled,    p->vert_component != NULL,
        p->positions != NULL};
    mt_status st = MT_OK;
    for (size_t i = 0; st == MT_OK && i < NUM_ARRAYS; i++)
        st =
            hash_array(arrays[i].data, arrays[i].n, sizeof(uint32_t), &words[NUM_COUNTS + i], diag);
    if (st == MT_OK)
        st = hash_array(p->positions, p->positions ? 3 * (uint64_t)p->num_verts : 0, sizeof(double),
                        &words[NUM_COUNTS + NUM_ARRAYS], diag);
    if (st == MT_OK) st = mt__report_hash(report, &words[NUM_COUNTS + NUM_ARRAYS + 1], diag);
    if (st != MT_OK) return st;
    uint8_t bytes[sizeof words];
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        for (int b = 0; b < 8; b++) bytes[8 * i + (size_t)b] = (uint8_t)(words[i] >> (8 * b));
    *out = mt_content_hash_bytes(bytes, sizeof bytes);
    return MT_OK;
}
