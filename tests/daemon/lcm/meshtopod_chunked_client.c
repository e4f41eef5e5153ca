/* The client side of daemon.netns_chunked_*: waits for meshtopod, submits a
 * 2M-triangle grid (~56 MB of mesh_t content) through meshtopo::client, which
 * sends it as mesh_chunk_t pieces, and checks that it arrived bit-identical
 * (ack content hash = sender's) with the report built in-process
 * (mtd_topology_fill, encoded byte for byte). Prints the send time and the
 * client's counters. usage: CLIENT NAME */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "meshtopo/client.h"
#include "meshtopo/core.h"
#include "topology.h"

#define HEARTBEAT_WAIT_MS 10000

static double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Encodes a topology_t into a new buffer; NULL on failure. */
static void *encode_topology(const meshtopo_topology_t *t, int *out_size)
{
    int size = meshtopo_topology_t_encoded_size(t);
    void *buf = size > 0 ? malloc((size_t)size) : NULL;
    if (!buf || meshtopo_topology_t_encode(buf, 0, size, t) != size) {
        free(buf);
        return NULL;
    }
    *out_size = size;
    return buf;
}

int main(int argc, char **argv)
{
    const char *name = argc > 1 ? argv[1] : "chunked";
    mt_diag diag;
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.source = "chunked-test";
    opts.timeout_ms = 2000;
    opts.retries = 5;
    mt_client *client = NULL;
    if (mt_client_create(&opts, &client, &diag) != MT_OK) {
        fprintf(stderr, "%s: mt_client_create: %s\n", name, diag.message);
        return 1;
    }
    if (mt_client_wait_daemon(client, HEARTBEAT_WAIT_MS, NULL, &diag) != MT_OK) {
        fprintf(stderr, "%s: %s\n", name, diag.message);
        mt_client_destroy(client);
        return 1;
    }
    mt_face_list list;
    if (mt_gen_grid(1000, 1000, true, &list) != MT_OK) {
        fprintf(stderr, "%s: mt_gen_grid failed\n", name);
        mt_client_destroy(client);
        return 1;
    }
    mt_client_ack ack;
    double t0 = seconds_now();
    mt_status st = mt_client_submit(client, "grid2m", &list, 0, &ack, &diag);
    double elapsed = seconds_now() - t0;
    mt_client_stats stats;
    mt_client_get_stats(client, &stats);
    int failed = 0;
    if (st != MT_OK) {
        fprintf(stderr, "%s: submit failed after %.2f s: %s\n", name, elapsed, diag.message);
        failed = 1;
    } else if ((uint64_t)ack.msg.content_hash != ack.sent_content_hash) {
        fprintf(stderr, "%s: content hash %016" PRIx64 " in the ack, %016" PRIx64 " sent\n", name,
                (uint64_t)ack.msg.content_hash, ack.sent_content_hash);
        failed = 1;
    }
    const meshtopo_topology_t *got = failed ? NULL : mt_client_ack_report(&ack);
    if (!failed && !got) {
        fprintf(stderr, "%s: the ack carries no report\n", name);
        failed = 1;
    }
    if (got) {
        /* The same report built here, with the daemon's bookkeeping fields. */
        mt_mesh *mesh = NULL;
        mt_build_options bo = {.strict = false, .threads = 1};
        if (mt_mesh_build(&list, &bo, &mesh, &diag) != MT_OK ||
            mt_mesh_validate(mesh, &diag) != MT_OK) {
            fprintf(stderr, "%s: in-process build or validate failed: %s\n", name, diag.message);
            failed = 1;
        } else {
            mtd_mesh_info info = {.id = got->mesh_id,
                                  .version = (uint32_t)got->version,
                                  .source = got->source,
                                  .utime = got->mesh_utime,
                                  .content_hash = ack.sent_content_hash};
            meshtopo_topology_t mine;
            if (mtd_topology_fill(mesh, &info, got->build_duration_us, MTD_TOPOLOGY_LIST_MAX,
                                  &mine) != 0) {
                fprintf(stderr, "%s: mtd_topology_fill failed\n", name);
                failed = 1;
            } else {
                mine.utime = got->utime;
                int size_a = 0, size_b = 0;
                void *a = encode_topology(&mine, &size_a), *b = encode_topology(got, &size_b);
                if (!a || !b || size_a != size_b || memcmp(a, b, (size_t)size_a) != 0) {
                    fprintf(stderr,
                            "%s: the daemon's report differs from the in-process one "
                            "(%d vs %d bytes; faces %d vs %d, edges %" PRId64 " vs %" PRId64 ")\n",
                            name, size_b, size_a, got->num_faces, mine.num_faces, got->num_edges,
                            mine.num_edges);
                    failed = 1;
                }
                free(a);
                free(b);
                mtd_topology_free(&mine);
            }
        }
        mt_mesh_destroy(mesh);
    }
    printf("%s: %u triangles, %u vertices: %s in %.3f s (content hash %016" PRIx64 "; %" PRIu64
           " messages published, %" PRIu64 " replies)\n",
           name, list.num_faces, list.num_verts, failed ? "FAILED" : "acked, report equal", elapsed,
           ack.sent_content_hash, stats.attempts, stats.replies);
    mt_client_ack_free(&ack);
    mt_client_destroy(client);
    mt_face_list_free(&list);
    return failed;
}
