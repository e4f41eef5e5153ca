/* Client helpers of the Python package (python_api.h): a client from plain
 * options, submissions whose ack comes back as numbers and the report's
 * JSON summary, and replies read through the client's accessors
 * (meshtopo/client_reply.h) into flat arrays numpy can hold. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/client_report.h"
#include "meshtopo/report_json.h"
#include "python_api.h"

struct mt_py_reply {
    meshtopo_reply_t reply;
};

mt_status mt_py_client_create(const char *lcm_url, const char *channel_prefix, int timeout_ms,
                              int retries, const char *source, mt_client **out, mt_diag *diag)
{
    mt_client_options options;
    memset(&options, 0, sizeof options);
    options.lcm_url = lcm_url;
    options.channel_prefix = channel_prefix;
    options.timeout_ms = timeout_ms;
    options.retries = retries;
    options.source = source;
    return mt_client_create(&options, out, diag);
}

/* The ack's report as JSON: the summary with the daemon's keys and the
 * count of every defect found. NULL when out of memory or the report is
 * unusable (diag then says why). */
static char *report_json(const meshtopo_topology_t *t, mt_diag *diag)
{
    mt_client_report report;
    if (mt_client_report_from_topology(t, &report, diag) != MT_OK) return NULL;
    char *doc = NULL;
    size_t doc_size = 0;
    FILE *mem = open_memstream(&doc, &doc_size);
    bool ok = mem != NULL;
    if (ok) {
        mt_json j;
        mt_json_init(&j, mem);
        mt_json_object_begin(&j);
        ok = mt_report_json_write_summary(&j, &report.report, report.num_loop_lengths,
                                          report.num_components, MT_REPORT_JSON_KEYS_DAEMON);
        mt_json_key(&j, "num_defects");
        mt_json_uint(&j, report.num_defects_found);
        mt_json_object_end(&j);
        ok = mt_json_finish(&j) && ok;
        ok = fclose(mem) == 0 && ok;
    }
    mt_client_report_free(&report);
    if (!ok) {
        free(doc);
        mt_diag_set(diag, MT_ERR_NOMEM, "out of memory while writing the report");
        return NULL;
    }
    return doc;
}

mt_status mt_py_client_submit(mt_client *client, const char *mesh_id, const mt_face_list *list,
                              int strict, int32_t *out_version, int64_t *out_content_hash,
                              char **out_report_json, mt_diag *diag)
{
    *out_version = 0;
    *out_content_hash = 0;
    *out_report_json = NULL;
    mt_client_ack ack;
    mt_status st = mt_client_submit(client, mesh_id, list, strict, &ack, diag);
    *out_version = ack.msg.version;
    *out_content_hash = ack.msg.content_hash;
    const meshtopo_topology_t *t = mt_client_ack_report(&ack);
    if (t) {
        mt_diag report_diag;
        *out_report_json = report_json(t, &report_diag);
        if (!*out_report_json && st == MT_OK) {
            st = report_diag.status;
            if (diag) *diag = report_diag;
        }
    }
    mt_client_ack_free(&ack);
    return st;
}

mt_status mt_py_client_query(mt_client *client, const char *mesh_id, int32_t version, int32_t kind,
                             const uint32_t *ids, size_t num_ids, mt_py_reply **out_reply,
                             mt_diag *diag)
{
    *out_reply = NULL;
    mt_py_reply *r = calloc(1, sizeof *r);
    if (!r) return mt_diag_set(diag, MT_ERR_NOMEM, "out of memory");
    /* A listing (mesh_id "" or NULL: every mesh) through mt_client_list;
     * with ids it goes as asked, for the daemon to refuse. */
    const mt_msgs_query_kind *k = mt_msgs_query_kind_of(kind);
    mt_status st =
        k && k->reply == MT_MSGS_REPLY_LIST && num_ids == 0
            ? mt_client_list(client, mesh_id, &r->reply, diag)
            : mt_client_query(client, mesh_id, version, kind, ids, num_ids, &r->reply, diag);
    /* A reply that arrived, even with an error status, is handed out. */
    if (r->reply.mesh_id || r->reply.num_items > 0 || r->reply.num_meshes > 0)
        *out_reply = r;
    else
        mt_py_reply_free(r);
    return st;
}

void mt_py_reply_free(mt_py_reply *reply)
{
    if (!reply) return;
    mt_client_reply_free(&reply->reply);
    free(reply);
}

int32_t mt_py_reply_version(const mt_py_reply *reply)
{
    return reply->reply.version;
}

void mt_py_reply_sizes(const mt_py_reply *reply, size_t out_sizes[6])
{
    const meshtopo_reply_t *r = &reply->reply;
    size_t values = 0, values2 = 0;
    for (size_t g = 0; g < (size_t)r->num_groups; g++) {
        mt_client_group group = mt_client_reply_group(r, g);
        values += group.num_values;
        values2 += group.num_values2;
    }
    out_sizes[0] = mt_client_reply_num_items(r);
    out_sizes[1] = r->num_groups > 0 ? (size_t)r->num_groups : 0;
    out_sizes[2] = values;
    out_sizes[3] = values2;
    out_sizes[4] = r->num_reals > 0 ? (size_t)r->num_reals : 0;
    out_sizes[5] = r->num_meshes > 0 ? (size_t)r->num_meshes : 0;
}

void mt_py_reply_flatten(const mt_py_reply *reply, int32_t *item_status, uint64_t *item_groups,
                         uint8_t *group_boundary, uint64_t *group_values, int32_t *values,
                         uint64_t *group_values2, int32_t *values2, double *reals)
{
    const meshtopo_reply_t *r = &reply->reply;
    const size_t num_items = mt_client_reply_num_items(r);
    uint64_t groups = 0, nv = 0, nv2 = 0;
    item_groups[0] = 0;
    group_values[0] = 0;
    group_values2[0] = 0;
    for (size_t i = 0; i < num_items; i++) {
        mt_client_item item = mt_client_reply_item(r, i);
        item_status[i] = item.status;
        for (size_t k = 0; k < item.num_groups; k++) {
            mt_client_group group = mt_client_item_group(r, &item, k);
            group_boundary[groups] = group.boundary;
            if (group.num_values)
                memcpy(values + nv, group.values, group.num_values * sizeof *values);
            if (group.num_values2)
                memcpy(values2 + nv2, group.values2, group.num_values2 * sizeof *values2);
            nv += group.num_values;
            nv2 += group.num_values2;
            groups++;
            group_values[groups] = nv;
            group_values2[groups] = nv2;
        }
        item_groups[i + 1] = groups;
    }
    for (size_t k = 0; k < (size_t)(r->num_reals > 0 ? r->num_reals : 0); k++)
        reals[k] = r->reals[k];
}

void mt_py_reply_listed(const mt_py_reply *reply, size_t index, const char **out_mesh_id,
                        const char **out_source, int32_t *out_version, int64_t *out_utime,
                        int32_t *out_num_verts, int32_t *out_num_faces, int64_t *out_num_defects,
                        int64_t *out_content_hash)
{
    const meshtopo_reply_t *r = &reply->reply;
    *out_mesh_id = r->list_mesh_ids[index];
    *out_source = r->list_sources[index];
    *out_version = r->list_versions[index];
    *out_utime = r->list_utimes[index];
    *out_num_verts = r->list_num_verts[index];
    *out_num_faces = r->list_num_faces[index];
    *out_num_defects = r->list_num_defects[index];
    *out_content_hash = r->list_content_hashes[index];
}
