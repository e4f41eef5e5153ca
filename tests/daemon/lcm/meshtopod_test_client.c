/* meshtopod_test_client: the integration test's client, talking to a real
 * meshtopod over LCM (run inside netns-run). It waits for the daemon's first
 * heartbeat, submits a mesh file (resending on silence: requests are
 * idempotent), asks for the one-rings of its first vertices and compares the
 * reply with the core library's answer computed here. Exits 0 when all agree.
 *
 * usage: meshtopod_test_client MESH_FILE */
#include <inttypes.h>
#include <lcm/lcm.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "meshtopo/core.h"
#include "meshtopo/io.h"
#include "meshtopo/msgs.h"

#define RING_VERTS 16

typedef struct client {
    int heartbeats;
    int32_t daemon_pid;
    void *reply; /* the last message on the reply channel */
    size_t reply_size;
} client;

static void on_status(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    client *c = user;
    meshtopo_status_t st;
    if (mt_msgs_decode(&mt_msgs_type_status, rbuf->data, rbuf->data_size, &st, NULL, 0) != 0)
        return;
    c->heartbeats++;
    c->daemon_pid = st.pid;
    meshtopo_status_t_decode_cleanup(&st);
}

static void on_reply(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    client *c = user;
    free(c->reply);
    c->reply = malloc(rbuf->data_size);
    memcpy(c->reply, rbuf->data, rbuf->data_size);
    c->reply_size = rbuf->data_size;
}

static int fail(const char *fmt, const char *detail)
{
    fprintf(stderr, "meshtopod_test_client: ");
    fprintf(stderr, fmt, detail);
    fprintf(stderr, "\n");
    return 1;
}

/* Publishes msg every second until a reply of `type` with request_id arrives
 * (decoded into out) or 10 tries pass. */
static int request(lcm_t *lcm, client *c, const char *channel, const mt_msgs_type *send_type,
                   const void *msg, const mt_msgs_type *type, int64_t request_id, void *out)
{
    int size = send_type->encoded_size(msg);
    void *buf = malloc((size_t)size);
    send_type->encode(buf, 0, size, msg);
    for (int attempt = 0; attempt < 10; attempt++) {
        lcm_publish(lcm, channel, buf, (unsigned)size);
        for (int wait = 0; wait < 20; wait++) {
            lcm_handle_timeout(lcm, 50);
            if (!c->reply) continue;
            if (mt_msgs_decode(type, c->reply, c->reply_size, out, NULL, 0) == 0) {
                int64_t id = type == &mt_msgs_type_ack ? ((meshtopo_ack_t *)out)->request_id
                                                       : ((meshtopo_reply_t *)out)->request_id;
                if (id == request_id) {
                    free(buf);
                    return 0;
                }
                type->decode_cleanup(out);
            }
            free(c->reply);
            c->reply = NULL;
        }
    }
    free(buf);
    return -1;
}

int main(int argc, char **argv)
{
    if (argc != 2) return fail("%s", "usage: meshtopod_test_client MESH_FILE");
    mt_face_list list;
    mt_diag diag;
    if (mt_read_file(argv[1], MT_FORMAT_AUTO, &list, &diag) != MT_OK)
        return fail("cannot read the mesh: %s", diag.message);
    mt_mesh *mesh = NULL;
    if (mt_mesh_build(&list, NULL, &mesh, &diag) != MT_OK)
        return fail("local build failed: %s", diag.message);

    lcm_t *lcm = lcm_create(NULL);
    if (!lcm) return fail("%s", "lcm_create failed");
    client c = {0};
    char reply_channel[64];
    snprintf(reply_channel, sizeof reply_channel, "MESHTOPO_TEST_CLIENT_%d", (int)getpid());
    lcm_subscribe(lcm, "MESHTOPO_STATUS", on_status, &c);
    char answers[80];
    snprintf(answers, sizeof answers, "%s_(ACK|REPLY)", reply_channel);
    lcm_subscribe(lcm, answers, on_reply, &c);
    for (int i = 0; i < 200 && c.heartbeats == 0; i++) lcm_handle_timeout(lcm, 50);
    if (!c.heartbeats) return fail("%s", "no heartbeat from meshtopod within 10 s");
    printf("heartbeat from meshtopod pid %d\n", (int)c.daemon_pid);

    meshtopo_mesh_t m;
    memset(&m, 0, sizeof m);
    m.request_id = 1;
    m.reply_channel = reply_channel;
    m.mesh_id = "teapot";
    m.source = "meshtopod_test_client";
    m.num_verts = (int32_t)list.num_verts;
    m.num_position_values = list.positions ? 3 * (int32_t)list.num_verts : 0;
    m.positions = list.positions;
    m.num_faces = (int32_t)list.num_faces;
    m.face_vertex_counts = (int32_t *)list.face_sizes;
    m.num_indices = (int32_t)list.num_indices;
    m.face_vertex_indices = (int32_t *)list.face_indices;
    meshtopo_ack_t ack;
    if (request(lcm, &c, "MESHTOPO_SUBMIT", &mt_msgs_type_mesh, &m, &mt_msgs_type_ack, 1, &ack))
        return fail("%s", "no ack for the submission");
    if (ack.status != 0) return fail("submission refused: %s", ack.error);
    printf("ack: version %d, %d faces\n", (int)ack.version, (int)ack.reports[0].num_faces);
    meshtopo_ack_t_decode_cleanup(&ack);

    int32_t ids[RING_VERTS];
    int32_t n = list.num_verts < RING_VERTS ? (int32_t)list.num_verts : RING_VERTS;
    for (int32_t i = 0; i < n; i++) ids[i] = i;
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.request_id = 2;
    q.reply_channel = reply_channel;
    q.mesh_id = "teapot";
    q.kind = MESHTOPO_QUERY_T_VERTEX_RING;
    q.num_ids = n;
    q.ids = ids;
    meshtopo_reply_t r;
    if (request(lcm, &c, "MESHTOPO_QUERY", &mt_msgs_type_query, &q, &mt_msgs_type_reply, 2, &r))
        return fail("%s", "no reply to the one-ring query");
    if (r.status != 0) return fail("query failed: %s", r.error);
    int bad = r.num_items != n;
    uint32_t nb[256], faces[256];
    mt_fan fans[16];
    for (int32_t i = 0; i < n && !bad; i++) {
        mt_ring ring = {nb, 256, faces, 256, fans, 16, 0, 0, 0};
        if (mt_vert_ring(mesh, (uint32_t)i, &ring) != MT_OK) return fail("%s", "local ring");
        int32_t g0 = r.item_offsets[i], g1 = r.item_offsets[i + 1];
        if ((size_t)(g1 - g0) != ring.num_fans) bad = 1;
        for (size_t f = 0; f < ring.num_fans && !bad; f++) {
            int32_t g = g0 + (int32_t)f;
            int32_t v0 = r.value_offsets[g], v1 = r.value_offsets[g + 1];
            int32_t w0 = r.value2_offsets[g], w1 = r.value2_offsets[g + 1];
            if ((uint32_t)(v1 - v0) != fans[f].neighbor_count ||
                (uint32_t)(w1 - w0) != fans[f].face_count ||
                (bool)r.group_boundary[g] != fans[f].boundary)
                bad = 1;
            for (int32_t k = 0; !bad && k < v1 - v0; k++)
                bad = r.values[v0 + k] != (int32_t)nb[fans[f].neighbor_begin + k];
            for (int32_t k = 0; !bad && k < w1 - w0; k++)
                bad = r.values2[w0 + k] != (int32_t)faces[fans[f].face_begin + k];
        }
    }
    meshtopo_reply_t_decode_cleanup(&r);
    if (bad) return fail("%s", "the one-rings differ from the core library's");
    printf("one-rings of %d vertices agree with the core library\n", (int)n);
    free(c.reply);
    lcm_destroy(lcm);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    return 0;
}
