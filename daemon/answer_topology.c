/* meshtopod's answers to the topology kinds of query_t (answer.h): one-rings,
 * valences, face neighbours, edge faces, boundary loops, components, defects
 * and the report, exactly what the core library's queries (meshtopo/query.h)
 * answer; msgs/reply_t.lcm says what each kind puts where. The ids were
 * checked against the mesh before (query_check.h). */
#include <stdlib.h>
#include <string.h>

#include "answer.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"
#include "topology.h"

void mtd_answer_rings(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    const int32_t *ids = in->query->ids;
    const int32_t n = in->query->num_ids;
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    for (int32_t i = 0; i < n && mtd_answer_ok(a); i++) {
        mt_status s = mt_vert_ring(mesh, (uint32_t)ids[i], &ring);
        /* NULL buffers only learn the sizes, even when the call says MT_OK. */
        if (s == MT_ERR_BUFFER_TOO_SMALL ||
            (s == MT_OK &&
             (ring.num_fans > ring.fans_capacity || ring.num_neighbors > ring.neighbors_capacity ||
              ring.num_faces > ring.faces_capacity))) {
            mt_fan *fans = realloc(ring.fans, ring.num_fans * sizeof *fans);
            if (!fans && ring.num_fans) {
                mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL,
                                "out of memory building the answer");
                break;
            }
            if (fans) ring.fans = fans, ring.fans_capacity = ring.num_fans;
            if (!mtd_answer_reserve_u32(a, &ring.neighbors, &ring.neighbors_capacity,
                                        ring.num_neighbors) ||
                !mtd_answer_reserve_u32(a, &ring.faces, &ring.faces_capacity, ring.num_faces))
                break;
            s = mt_vert_ring(mesh, (uint32_t)ids[i], &ring);
        }
        if (s != MT_OK) {
            mtd_answer_fail_status(a, s, "one-ring", ids[i]);
            break;
        }
        for (size_t f = 0; f < ring.num_fans; f++) {
            const mt_fan *fan = &ring.fans[f];
            for (uint32_t k = 0; k < fan->neighbor_count; k++)
                mtd_answer_value(a, (int32_t)ring.neighbors[fan->neighbor_begin + k]);
            for (uint32_t k = 0; k < fan->face_count; k++)
                mtd_answer_value2(a, (int32_t)ring.faces[fan->face_begin + k]);
            mtd_answer_group_end(a, fan->boundary);
        }
        mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
    free(ring.neighbors);
    free(ring.faces);
    free(ring.fans);
}

void mtd_answer_valences(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    const int32_t *ids = in->query->ids;
    const int32_t n = in->query->num_ids;
    for (int32_t i = 0; i < n && mtd_answer_ok(a); i++) {
        uint32_t valence = 0;
        mt_status s = mt_vert_valence(mesh, (uint32_t)ids[i], &valence);
        if (s != MT_OK) {
            mtd_answer_fail_status(a, s, "valence", ids[i]);
            break;
        }
        mtd_answer_value(a, (int32_t)valence);
        mtd_answer_group_end(a, false);
        mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
}

void mtd_answer_face_neighbors(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    const int32_t *ids = in->query->ids;
    const int32_t n = in->query->num_ids;
    uint32_t *faces = NULL, *offsets = NULL, *verts = NULL;
    size_t faces_cap = 0, offsets_cap = 0, verts_cap = 0;
    for (int32_t i = 0; i < n && mtd_answer_ok(a); i++) {
        uint32_t face = (uint32_t)ids[i];
        size_t num_faces = 0, num_sides = 0, num_verts = 0;
        mt_status s = mt_face_neighbors(mesh, face, faces, faces_cap, offsets, offsets_cap,
                                        &num_faces, &num_sides);
        if (s == MT_ERR_BUFFER_TOO_SMALL ||
            (s == MT_OK && (num_faces > faces_cap || num_sides + 1 > offsets_cap))) {
            if (!mtd_answer_reserve_u32(a, &faces, &faces_cap, num_faces) ||
                !mtd_answer_reserve_u32(a, &offsets, &offsets_cap, num_sides + 1))
                break;
            s = mt_face_neighbors(mesh, face, faces, faces_cap, offsets, offsets_cap, &num_faces,
                                  &num_sides);
        }
        if (s == MT_ERR_NOT_FOUND) {
            mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
            continue;
        }
        if (s == MT_OK) {
            s = mt_face_verts(mesh, face, verts, verts_cap, &num_verts);
            if (s == MT_ERR_BUFFER_TOO_SMALL || (s == MT_OK && num_verts > verts_cap)) {
                if (!mtd_answer_reserve_u32(a, &verts, &verts_cap, num_verts)) break;
                s = mt_face_verts(mesh, face, verts, verts_cap, &num_verts);
            }
        }
        if (s != MT_OK || num_verts != num_sides) {
            mtd_answer_fail_status(a, s == MT_OK ? MT_ERR_CORRUPT : s, "face neighbours", ids[i]);
            break;
        }
        for (size_t k = 0; k < num_sides; k++) {
            for (uint32_t j = offsets[k]; j < offsets[k + 1]; j++)
                mtd_answer_value(a, (int32_t)faces[j]);
            mtd_answer_value2(a, (int32_t)verts[k]);
            mtd_answer_value2(a, (int32_t)verts[(k + 1) % num_sides]);
            mtd_answer_group_end(a, offsets[k] == offsets[k + 1]);
        }
        mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
    free(faces);
    free(offsets);
    free(verts);
}

void mtd_answer_edge_faces(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    const int32_t *ids = in->query->ids;
    const int32_t n = in->query->num_ids;
    uint32_t *faces = NULL;
    size_t cap = 0;
    for (int32_t i = 0; i + 1 < n && mtd_answer_ok(a); i += 2) {
        size_t count = 0;
        mt_status s =
            mt_edge_faces(mesh, (uint32_t)ids[i], (uint32_t)ids[i + 1], faces, cap, &count);
        if (s == MT_ERR_BUFFER_TOO_SMALL || (s == MT_OK && count > cap)) {
            if (!mtd_answer_reserve_u32(a, &faces, &cap, count)) break;
            s = mt_edge_faces(mesh, (uint32_t)ids[i], (uint32_t)ids[i + 1], faces, cap, &count);
        }
        if (s == MT_ERR_NOT_FOUND) {
            mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
            continue;
        }
        if (s != MT_OK) {
            mtd_answer_fail_status(a, s, "edge faces at vertex", ids[i]);
            break;
        }
        for (size_t k = 0; k < count; k++) mtd_answer_value(a, (int32_t)faces[k]);
        mtd_answer_group_end(a, false);
        mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
    free(faces);
}

void mtd_answer_boundary_loops(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    size_t num_verts = 0, num_loops = 0;
    mt_status s = mt_boundary_loops(mesh, NULL, 0, NULL, 0, &num_verts, &num_loops);
    uint32_t *verts = NULL, *offsets = NULL;
    size_t verts_cap = 0, offsets_cap = 0;
    if (s == MT_ERR_BUFFER_TOO_SMALL || s == MT_OK) {
        if (!mtd_answer_reserve_u32(a, &verts, &verts_cap, num_verts ? num_verts : 1) ||
            !mtd_answer_reserve_u32(a, &offsets, &offsets_cap, num_loops + 1))
            goto done;
        s = mt_boundary_loops(mesh, verts, verts_cap, offsets, offsets_cap, &num_verts, &num_loops);
    }
    if (s != MT_OK) {
        mtd_answer_fail_status(a, s, "boundary loops", 0);
        goto done;
    }
    for (size_t l = 0; l < num_loops; l++) {
        for (uint32_t k = offsets[l]; k < offsets[l + 1]; k++)
            mtd_answer_value(a, (int32_t)verts[k]);
        mtd_answer_group_end(a, true);
        mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
done:
    free(verts);
    free(offsets);
}

static void component_of(mtd_answer *a, const mt_mesh *mesh, uint32_t face)
{
    uint32_t component = 0;
    mt_status s = mt_face_component(mesh, face, &component);
    if (s == MT_ERR_NOT_FOUND) {
        mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
        return;
    }
    if (s != MT_OK) {
        mtd_answer_fail_status(a, s, "component", (int32_t)face);
        return;
    }
    mtd_answer_value(a, (int32_t)component);
    mtd_answer_group_end(a, false);
    mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
}

void mtd_answer_components(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    const int32_t *ids = in->query->ids;
    const int32_t n = in->query->num_ids;
    if (n == 0) {
        uint32_t faces = mt_mesh_num_faces(mesh);
        for (uint32_t f = 0; f < faces && mtd_answer_ok(a); f++) component_of(a, mesh, f);
    }
    for (int32_t i = 0; i < n && mtd_answer_ok(a); i++) component_of(a, mesh, (uint32_t)ids[i]);
}

static void defects_of_kind(mtd_answer *a, const mt_report *report, uint32_t kind)
{
    for (size_t i = 0; i < report->num_defects; i++) {
        const mt_defect *d = &report->defects[i];
        if (d->kind != kind) continue;
        mtd_answer_value(a, (int32_t)d->a);
        mtd_answer_value(a, (int32_t)d->b);
        mtd_answer_value(a, (int32_t)d->c);
    }
    mtd_answer_group_end(a, false);
    mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
}

void mtd_answer_defects(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    const int32_t *ids = in->query->ids;
    const int32_t n = in->query->num_ids;
    const mt_report *report = mt_mesh_report(mesh);
    if (n == 0)
        for (uint32_t k = 0; k < MT_DEFECT_KIND_COUNT; k++) defects_of_kind(a, report, k);
    for (int32_t i = 0; i < n; i++) defects_of_kind(a, report, (uint32_t)ids[i]);
}

void mtd_answer_report(mtd_answer *a, const mtd_answer_input *in)
{
    if (mtd_topology_fill(in->mesh, in->info, 0, SIZE_MAX, &a->report) == 0)
        a->have_report = true;
    else
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory copying the report");
}
