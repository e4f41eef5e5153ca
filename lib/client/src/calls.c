/* The client's calls: argument checks, encoding of mesh_t and query_t with a
 * fresh request id (kept for every retry), waiting or calling back. Nothing is sent for a call
 * whose arguments are wrong (a kind not in the query-kind table, meshtopo/query_kinds.h,
 * among them): it fails with MT_ERR_INVALID_ARG and a message. */
#include <stdlib.h>
#include <string.h>

#include "client_internal.h"
#include "meshtopo/content_hash.h"
#include "meshtopo/query_kinds.h"

/* ---- Freeing results ---------------------------------------------------- */

void mt_client_ack_free(mt_client_ack *ack)
{
    if (!ack) return;
    meshtopo_ack_t zero;
    memset(&zero, 0, sizeof zero);
    if (memcmp(&ack->msg, &zero, sizeof zero) != 0) meshtopo_ack_t_decode_cleanup(&ack->msg);
    memset(ack, 0, sizeof *ack);
}

void mt_client_reply_free(meshtopo_reply_t *reply)
{
    if (!reply) return;
    meshtopo_reply_t zero;
    memset(&zero, 0, sizeof zero);
    if (memcmp(reply, &zero, sizeof zero) != 0) meshtopo_reply_t_decode_cleanup(reply);
    memset(reply, 0, sizeof *reply);
}

/* ---- Argument checks ---------------------------------------------------- */

static mt_status check_client(mt_client *client, mt_diag *diag, const char *call)
{
    mt_diag_clear(diag);
    if (!client) return mt__client_fail(diag, MT_ERR_INVALID_ARG, "%s: client is NULL", call);
    return MT_OK;
}

static mt_status check_query(const char *mesh_id, int32_t version, int32_t kind,
                             const uint32_t *ids, size_t num_ids, mt_diag *diag)
{
    mt_status st = mt_msgs_mesh_id_check(mesh_id, diag);
    if (st != MT_OK) return st;
    if (version < 0)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "version %d is negative (0 = latest)",
                               (int)version);
    if (!mt_msgs_query_kind_of(kind))
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "query kind %d is not one of query_t's",
                               (int)kind);
    if (num_ids > 0 && !ids)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "ids is NULL but num_ids is %zu", num_ids);
    /* 4 bytes per id must fit one LCM message. */
    if (num_ids > (size_t)(LCM_MAX_MESSAGE_SIZE / 4 - 1024))
        return mt__client_fail(diag, MT_ERR_TOO_LARGE, "%zu ids do not fit one LCM message",
                               num_ids);
    return MT_OK;
}

/* ---- Encoding ----------------------------------------------------------- */

static mt_status encode_query(mt_client *client, int64_t request_id, const char *instance,
                              const char *mesh_id, int32_t version, int32_t kind,
                              const uint32_t *ids, size_t num_ids, mt__msgbuf **out_buf,
                              mt_diag *diag)
{
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.utime = mt__client_utime();
    q.request_id = request_id;
    q.reply_channel = client->reply_channel;
    q.instance = (char *)(uintptr_t)(instance ? instance : "");
    q.mesh_id = (char *)(uintptr_t)mesh_id;
    q.version = version;
    q.kind = kind;
    q.num_ids = (int32_t)num_ids;
    /* uint32_t and int32_t may alias: the ids go out as the same 32 bits. */
    q.ids = (int32_t *)(uintptr_t)ids;
    int size = meshtopo_query_t_encoded_size(&q);
    mt__msgbuf *buf = mt__msgbuf_new(size);
    if (!buf) return mt__client_fail(diag, MT_ERR_NOMEM, "no memory for a %d-byte query", size);
    if (meshtopo_query_t_encode(buf->data, 0, size, &q) != size) {
        mt__msgbuf_release(buf);
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "query_t did not encode");
    }
    *out_buf = buf;
    return MT_OK;
}

/* Publishes buf (taken) as request request_id on channel and waits for the
 * answer of answer_type, retrying as configured. p holds the answer
 * (p->has_answer) whatever the status. */
static mt_status call_sync(mt_client *client, int64_t request_id, const mt_msgs_type *answer_type,
                           const char *channel, mt__msgbuf *buf, mt__pending *p, mt_diag *diag)
{
    memset(p, 0, sizeof *p);
    p->request_id = request_id;
    p->answer_type = answer_type;
    p->channel = channel;
    p->buf = buf;
    pthread_cond_init(&p->cond, NULL);
    mt_status st = mt__client_start(client, p);
    if (st == MT_OK) {
        mt__client_wait(client, p);
        st = p->status;
    } else {
        mt__msgbuf_release(buf);
    }
    if (st != MT_OK && diag) *diag = p->diag;
    pthread_cond_destroy(&p->cond);
    return st;
}

mt_status mt_client_submit(mt_client *client, const char *mesh_id, const mt_face_list *list,
                           int strict, mt_client_ack *out_ack, mt_diag *diag)
{
    if (out_ack) memset(out_ack, 0, sizeof *out_ack);
    mt_status st = check_client(client, diag, "mt_client_submit");
    if (st != MT_OK) return st;
    if (!out_ack)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "mt_client_submit: out_ack is NULL");
    if ((st = mt_msgs_mesh_id_check(mesh_id, diag)) != MT_OK) return st;
    if (!list) return mt__client_fail(diag, MT_ERR_INVALID_ARG, "mt_client_submit: list is NULL");
    if ((st = mt_face_list_check(list, diag)) != MT_OK) return st;
    uint64_t tail = mt__content_size(list);
    if (tail == 0)
        return mt__client_fail(diag, MT_ERR_TOO_LARGE,
                               "mesh of %u vertices, %u faces, %llu indices does not fit "
                               "mesh_t's counts",
                               list->num_verts, list->num_faces,
                               (unsigned long long)list->num_indices);

    int64_t request_id = mt__client_next_id(client);
    meshtopo_mesh_t m;
    memset(&m, 0, sizeof m);
    m.utime = mt__client_utime();
    m.request_id = request_id;
    m.reply_channel = client->reply_channel;
    m.mesh_id = (char *)(uintptr_t)mesh_id;
    m.source = client->source;
    m.strict = strict ? 1 : 0;
    mt__mesh_content_of(list, &m);
    int size = meshtopo_mesh_t_encoded_size(&m);
    mt__pending p;
    if (size > MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX) {
        /* In chunks, each encoded when it is sent: no copy of the whole mesh. */
        out_ack->sent_content_hash = mt_msgs_mesh_content_hash_of(&m);
        st = mt__client_submit_chunked(client, &m, out_ack->sent_content_hash, &p, diag);
    } else {
        mt__msgbuf *buf = mt__msgbuf_new(size);
        if (!buf) return mt__client_fail(diag, MT_ERR_NOMEM, "no memory for a %d-byte mesh", size);
        if (meshtopo_mesh_t_encode(buf->data, 0, size, &m) != size || (uint64_t)size < tail) {
            mt__msgbuf_release(buf);
            return mt__client_fail(diag, MT_ERR_INVALID_ARG, "mesh_t did not encode");
        }
        /* The content fields are the tail of the encoded message. */
        out_ack->sent_content_hash = mt_msgs_mesh_content_hash(&m, buf->data, (size_t)size);
        st =
            call_sync(client, request_id, &mt_msgs_type_ack, client->submit_channel, buf, &p, diag);
    }
    if (p.has_answer) out_ack->msg = p.answer.ack;
    return st;
}

/* ---- Queries ------------------------------------------------------------ */

/* instance: the daemon that answers (NULL: any). */
static mt_status query_sync(mt_client *client, const char *instance, const char *mesh_id,
                            int32_t version, int32_t kind, const uint32_t *ids, size_t num_ids,
                            meshtopo_reply_t *out_reply, mt_diag *diag)
{
    int64_t request_id = mt__client_next_id(client);
    mt__msgbuf *buf = NULL;
    mt_status st = encode_query(client, request_id, instance, mesh_id, version, kind, ids, num_ids,
                                &buf, diag);
    if (st != MT_OK) return st;
    mt__pending p;
    st = call_sync(client, request_id, &mt_msgs_type_reply, client->query_channel, buf, &p, diag);
    if (p.has_answer) *out_reply = p.answer.reply;
    return st;
}

mt_status mt_client_query(mt_client *client, const char *mesh_id, int32_t version, int32_t kind,
                          const uint32_t *ids, size_t num_ids, meshtopo_reply_t *out_reply,
                          mt_diag *diag)
{
    if (out_reply) memset(out_reply, 0, sizeof *out_reply);
    mt_status st = check_client(client, diag, "mt_client_query");
    if (st != MT_OK) return st;
    if (!out_reply)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "mt_client_query: out_reply is NULL");
    if ((st = check_query(mesh_id, version, kind, ids, num_ids, diag)) != MT_OK) return st;
    return query_sync(client, NULL, mesh_id, version, kind, ids, num_ids, out_reply, diag);
}

mt_status mt_client_list(mt_client *client, const char *mesh_id, meshtopo_reply_t *out_reply,
                         mt_diag *diag)
{
    return mt_client_list_from(client, NULL, mesh_id, out_reply, diag);
}

mt_status mt_client_list_from(mt_client *client, const char *instance, const char *mesh_id,
                              meshtopo_reply_t *out_reply, mt_diag *diag)
{
    if (out_reply) memset(out_reply, 0, sizeof *out_reply);
    mt_status st = check_client(client, diag, "mt_client_list");
    if (st != MT_OK) return st;
    if (!out_reply)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "mt_client_list: out_reply is NULL");
    if (instance && strlen(instance) > MT_CLIENT_MAX_INSTANCE)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG,
                               "mt_client_list_from: instance longer than %d bytes",
                               MT_CLIENT_MAX_INSTANCE);
    if (!mesh_id) mesh_id = "";
    if (mesh_id[0] && (st = mt_msgs_mesh_id_check(mesh_id, diag)) != MT_OK) return st;
    return query_sync(client, instance, mesh_id, 0, MESHTOPO_QUERY_T_LIST_MESHES, NULL, 0,
                      out_reply, diag);
}

mt_status mt_client_query_async(mt_client *client, const char *mesh_id, int32_t version,
                                int32_t kind, const uint32_t *ids, size_t num_ids,
                                mt_client_reply_fn callback, void *user, mt_diag *diag)
{
    mt_status st = check_client(client, diag, "mt_client_query_async");
    if (st != MT_OK) return st;
    if (!callback)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "mt_client_query_async: callback is NULL");
    if ((st = check_query(mesh_id, version, kind, ids, num_ids, diag)) != MT_OK) return st;
    mt__pending *p = calloc(1, sizeof *p);
    if (!p) return mt__client_fail(diag, MT_ERR_NOMEM, "no memory for a pending query");
    p->request_id = mt__client_next_id(client);
    st = encode_query(client, p->request_id, NULL, mesh_id, version, kind, ids, num_ids, &p->buf,
                      diag);
    if (st != MT_OK) {
        free(p);
        return st;
    }
    p->answer_type = &mt_msgs_type_reply;
    p->channel = client->query_channel;
    p->callback = callback;
    p->user = user;
    /* Asynchronous requests cannot fail to start; from here on the callback owns p. */
    return mt__client_start(client, p);
}
