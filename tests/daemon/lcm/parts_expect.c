/* Checks of large answers (VERTEX_RING, BOUNDARY_LOOPS replies) against the
 * core library, read through the reply accessors (meshtopo/client_reply.h),
 * and the grid with holes used to make many boundary loops. See
 * parts_expect.h. */
#include "parts_expect.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int differ(char *why, size_t why_size, const char *what, size_t at, long got, long want)
{
    snprintf(why, why_size, "%s %zu: reply has %ld, the core %ld", what, at, got, want);
    return -1;
}

/* The reply is OK and its CSR arrays describe it (the check the client runs
 * on what it hands out; a reply decoded by hand gets it here), so the
 * accessors below may index it. */
static int shape_ok(const meshtopo_reply_t *r, char *why, size_t why_size)
{
    if (r->status != 0) {
        snprintf(why, why_size, "status %d: %s", (int)r->status, r->error);
        return -1;
    }
    mt_diag diag;
    if (mt_client_reply_check(r, &diag) != MT_OK) {
        snprintf(why, why_size, "offsets: %s", diag.message);
        return -1;
    }
    return 0;
}

int mt_test_check_rings(const mt_mesh *mesh, const uint32_t *ids, size_t n,
                        const meshtopo_reply_t *r, char *why, size_t why_size)
{
    if (shape_ok(r, why, why_size) != 0) return -1;
    size_t num_items = mt_client_reply_num_items(r);
    if (num_items != n) return differ(why, why_size, "items", 0, (long)num_items, (long)n);
    enum { CAP = 4096 };
    uint32_t nb[CAP], fc[CAP];
    mt_fan fans[256];
    for (size_t i = 0; i < n; i++) {
        mt_ring ring = {nb, CAP, fc, CAP, fans, 256, 0, 0, 0};
        if (mt_vert_ring(mesh, ids[i], &ring) != MT_OK) {
            snprintf(why, why_size, "mt_vert_ring(%u) failed", ids[i]);
            return -1;
        }
        mt_client_item item = mt_client_reply_item(r, i);
        if (item.num_groups != ring.num_fans)
            return differ(why, why_size, "fans of item", i, (long)item.num_groups,
                          (long)ring.num_fans);
        for (size_t f = 0; f < ring.num_fans; f++) {
            mt_client_group g = mt_client_item_group(r, &item, f);
            if (g.num_values != fans[f].neighbor_count || g.num_values2 != fans[f].face_count)
                return differ(why, why_size, "fan size of item", i, (long)g.num_values,
                              (long)fans[f].neighbor_count);
            if (g.boundary != fans[f].boundary)
                return differ(why, why_size, "fan boundary flag of item", i, g.boundary,
                              fans[f].boundary);
            for (uint32_t k = 0; k < fans[f].neighbor_count; k++)
                if ((uint32_t)g.values[k] != nb[fans[f].neighbor_begin + k])
                    return differ(why, why_size, "neighbour of item", i, g.values[k],
                                  (long)nb[fans[f].neighbor_begin + k]);
            for (uint32_t k = 0; k < fans[f].face_count; k++)
                if ((uint32_t)g.values2[k] != fc[fans[f].face_begin + k])
                    return differ(why, why_size, "face of item", i, g.values2[k],
                                  (long)fc[fans[f].face_begin + k]);
        }
    }
    return 0;
}

int mt_test_check_loops(const mt_mesh *mesh, const meshtopo_reply_t *r, char *why, size_t why_size)
{
    if (shape_ok(r, why, why_size) != 0) return -1;
    size_t num_verts = 0, num_loops = 0;
    mt_status s = mt_boundary_loops(mesh, NULL, 0, NULL, 0, &num_verts, &num_loops);
    if (s != MT_OK && s != MT_ERR_BUFFER_TOO_SMALL) {
        snprintf(why, why_size, "mt_boundary_loops: %s", mt_strerror(s));
        return -1;
    }
    uint32_t *verts = malloc((num_verts + 1) * sizeof *verts);
    uint32_t *offsets = malloc((num_loops + 1) * sizeof *offsets);
    int rc = -1;
    size_t num_items = mt_client_reply_num_items(r);
    if (!verts || !offsets ||
        mt_boundary_loops(mesh, verts, num_verts + 1, offsets, num_loops + 1, &num_verts,
                          &num_loops) != MT_OK) {
        snprintf(why, why_size, "mt_boundary_loops failed");
    } else if (num_items != num_loops || (size_t)r->num_groups != num_loops) {
        differ(why, why_size, "loops", 0, (long)num_items, (long)num_loops);
    } else if ((size_t)r->num_values != num_verts) {
        differ(why, why_size, "loop vertices", 0, r->num_values, (long)num_verts);
    } else {
        /* One group per loop, in order: its start is the vertices before it. */
        rc = 0;
        size_t start = 0;
        for (size_t l = 0; l < num_loops && rc == 0; l++) {
            mt_client_group g = mt_client_reply_group(r, l);
            if (start != offsets[l])
                rc = differ(why, why_size, "start of loop", l, (long)start, (long)offsets[l]);
            for (size_t k = 0; k < g.num_values && rc == 0; k++)
                if ((uint32_t)g.values[k] != verts[start + k])
                    rc = differ(why, why_size, "loop vertex", start + k, g.values[k],
                                (long)verts[start + k]);
            start += g.num_values;
        }
    }
    free(verts);
    free(offsets);
    return rc;
}

mt_status mt_test_grid_with_holes(uint32_t nx, uint32_t ny, uint32_t every, mt_face_list *out)
{
    mt_status s = mt_gen_grid(nx, ny, true, out);
    if (s != MT_OK || every == 0) return s;
    /* mt_gen_grid(triangles): cell (i, j) (row j) is faces 2 * (j * nx + i) and
     * the next; every face has 3 indices. Remove holes by compacting. */
    uint32_t kept = 0;
    for (uint32_t f = 0; f < out->num_faces; f++) {
        uint32_t cell = f / 2, i = cell % nx, j = cell / nx;
        if (i % every == every / 2 && j % every == every / 2) continue;
        memmove(out->face_indices + 3 * (size_t)kept, out->face_indices + 3 * (size_t)f,
                3 * sizeof *out->face_indices);
        out->face_sizes[kept] = 3;
        kept++;
    }
    out->num_faces = kept;
    out->num_indices = 3 * (uint64_t)kept;
    return MT_OK;
}
