/* meshtopod_test_client: the integration test's client, talking to a real
 * meshtopod through meshtopo::client (run inside netns-run). It waits for the
 * daemon's first heartbeat, submits a mesh file (resent on silence: requests
 * are idempotent), asks for the one-rings of its first vertices and compares
 * the reply, read with the reply accessors, with the core library's answer
 * computed here. Exits 0 when all agree. usage: meshtopod_test_client MESH_FILE */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/client.h"
#include "meshtopo/core.h"
#include "meshtopo/io.h"

#define RING_VERTS 16
#define HEARTBEAT_WAIT_MS 10000
/* Ten attempts a second apart for each request. */
#define ATTEMPT_MS 1000
#define RETRIES 9

static int fail(const char *fmt, const char *detail)
{
    fprintf(stderr, "meshtopod_test_client: ");
    fprintf(stderr, fmt, detail);
    fprintf(stderr, "\n");
    return 1;
}

/* 1 when item i of r holds exactly the one-ring of vertex i of mesh, fan by
 * fan; 0 when it differs, -1 when the core cannot give the ring. */
static int ring_equal(const mt_mesh *mesh, const meshtopo_reply_t *r, size_t i)
{
    uint32_t nb[256], faces[256];
    mt_fan fans[16];
    mt_ring ring = {nb, 256, faces, 256, fans, 16, 0, 0, 0};
    if (mt_vert_ring(mesh, (uint32_t)i, &ring) != MT_OK) return -1;
    mt_client_item item = mt_client_reply_item(r, i);
    if (item.num_groups != ring.num_fans) return 0;
    for (size_t f = 0; f < ring.num_fans; f++) {
        mt_client_group g = mt_client_item_group(r, &item, f);
        if (g.num_values != fans[f].neighbor_count || g.num_values2 != fans[f].face_count ||
            g.boundary != fans[f].boundary)
            return 0;
        for (size_t k = 0; k < g.num_values; k++)
            if (g.values[k] != (int32_t)nb[fans[f].neighbor_begin + k]) return 0;
        for (size_t k = 0; k < g.num_values2; k++)
            if (g.values2[k] != (int32_t)faces[fans[f].face_begin + k]) return 0;
    }
    return 1;
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

    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.source = "meshtopod_test_client";
    opts.timeout_ms = ATTEMPT_MS;
    opts.retries = RETRIES;
    mt_client *client = NULL;
    if (mt_client_create(&opts, &client, &diag) != MT_OK)
        return fail("mt_client_create: %s", diag.message);
    meshtopo_status_t *heartbeat = NULL;
    if (mt_client_wait_daemon(client, HEARTBEAT_WAIT_MS, &heartbeat, &diag) != MT_OK)
        return fail("no heartbeat from meshtopod: %s", diag.message);
    printf("heartbeat from meshtopod pid %d\n", (int)heartbeat->pid);
    meshtopo_status_t_destroy(heartbeat);

    mt_client_ack ack;
    mt_status st = mt_client_submit(client, "teapot", &list, 0, &ack, &diag);
    if (st != MT_OK)
        return fail(ack.msg.error ? "submission refused: %s" : "no ack for the submission: %s",
                    diag.message);
    const meshtopo_topology_t *report = mt_client_ack_report(&ack);
    if (!report) return fail("%s", "the ack carries no report");
    printf("ack: version %d, %d faces\n", (int)ack.msg.version, (int)report->num_faces);
    mt_client_ack_free(&ack);

    uint32_t ids[RING_VERTS];
    size_t n = list.num_verts < RING_VERTS ? list.num_verts : RING_VERTS;
    for (size_t i = 0; i < n; i++) ids[i] = (uint32_t)i;
    meshtopo_reply_t r;
    st = mt_client_query(client, "teapot", 0, MESHTOPO_QUERY_T_VERTEX_RING, ids, n, &r, &diag);
    if (st != MT_OK)
        return fail(r.error ? "query failed: %s" : "no reply to the one-ring query: %s",
                    diag.message);
    int bad = mt_client_reply_num_items(&r) != n;
    for (size_t i = 0; i < n && !bad; i++) {
        int eq = ring_equal(mesh, &r, i);
        if (eq < 0) return fail("%s", "local ring");
        bad = !eq;
    }
    mt_client_reply_free(&r);
    if (bad) return fail("%s", "the one-rings differ from the core library's");
    printf("one-rings of %d vertices agree with the core library\n", (int)n);
    mt_client_destroy(client);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    return 0;
}
