/* meshtopod's answer to LIST_MESHES (answer.h): the held mesh versions, by
 * mesh id then version, in the list_* arrays of reply_t; in a cluster, a
 * listing of every mesh shows the ids this member owns. */
#include <stdlib.h>
#include <string.h>

#include "answer.h"

/* Whether a listing shows `id`: the one asked for, or every id this
 * member owns. */
static bool listed(mtd_cluster *cluster, const char *mesh_id, const char *id)
{
    return mesh_id[0] ? strcmp(mesh_id, id) == 0 : mtd_cluster_owns(cluster, id);
}

/* LIST_MESHES: fills the list_* arrays of a->list (freed with a). */
void mtd_answer_list_meshes(mtd_answer *a, const mtd_answer_input *in)
{
    mtd_store *store = in->store;
    mtd_cluster *cluster = in->cluster;
    const char *mesh_id = in->query->mesh_id;
    meshtopo_reply_t *out = &a->list;
    a->have_list = true;
    mtd_store_listing *listing = NULL;
    if (mtd_store_list(store, &listing) != MT_OK) {
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory listing the meshes");
        return;
    }
    size_t n = 0;
    for (size_t i = 0; i < listing->num_ids; i++)
        if (listed(cluster, mesh_id, listing->ids[i].id)) n += listing->ids[i].num_versions;
    out->list_mesh_ids = calloc(n + 1, sizeof(char *));
    out->list_versions = calloc(n + 1, sizeof(int32_t));
    out->list_sources = calloc(n + 1, sizeof(char *));
    out->list_utimes = calloc(n + 1, sizeof(int64_t));
    out->list_num_verts = calloc(n + 1, sizeof(int32_t));
    out->list_num_faces = calloc(n + 1, sizeof(int32_t));
    out->list_num_defects = calloc(n + 1, sizeof(int64_t));
    out->list_content_hashes = calloc(n + 1, sizeof(int64_t));
    if (!out->list_mesh_ids || !out->list_versions || !out->list_sources || !out->list_utimes ||
        !out->list_num_verts || !out->list_num_faces || !out->list_num_defects ||
        !out->list_content_hashes) {
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory listing the meshes");
        mtd_store_listing_free(listing);
        return;
    }
    size_t k = 0;
    for (size_t i = 0; i < listing->num_ids && k < n; i++) {
        const mtd_listed_id *id = &listing->ids[i];
        if (!listed(cluster, mesh_id, id->id)) continue;
        for (uint32_t v = 0; v < id->num_versions && k < n; v++) {
            const mtd_mesh_info *info = &id->versions[v];
            out->list_mesh_ids[k] = strdup(info->id);
            out->list_sources[k] = strdup(info->source);
            out->list_versions[k] = (int32_t)info->version;
            out->list_utimes[k] = info->utime;
            out->list_content_hashes[k] = (int64_t)info->content_hash;
            out->list_num_verts[k] = (int32_t)info->num_verts;
            out->list_num_faces[k] = (int32_t)info->num_faces;
            out->list_num_defects[k] = (int64_t)info->num_defects;
            if (!out->list_mesh_ids[k] || !out->list_sources[k])
                mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL,
                                "out of memory listing the meshes");
            k++;
        }
    }
    out->num_meshes = (int32_t)k;
    mtd_store_listing_free(listing);
}
