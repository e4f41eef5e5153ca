/* The client side of daemon.netns_parts_*: waits for meshtopod and submits a
 * 2M-triangle grid with 10,000 holes through meshtopo::client, then asks in
 * one call each for the one-rings of 100,000 vertices (about 6 MB of reply_t)
 * and all 10,001 boundary loops, both arriving as reply_part_t pieces; every
 * answer must equal the core's on the same mesh built in-process
 * (parts_expect.c). Prints times and part counters. usage: CLIENT NAME */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "meshtopo/client.h"
#include "meshtopo/core.h"
#include "parts_expect.h"

#define NUM_RING_IDS 100000
#define HEARTBEAT_WAIT_MS 10000

static double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    const char *name = argc > 1 ? argv[1] : "parts";
    mt_diag diag;
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.source = "parts-test";
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
    if (mt_test_grid_with_holes(1000, 1000, 10, &list) != MT_OK) {
        fprintf(stderr, "%s: mt_test_grid_with_holes failed\n", name);
        mt_client_destroy(client);
        return 1;
    }
    mt_mesh *mesh = NULL;
    if (mt_mesh_build(&list, NULL, &mesh, &diag) != MT_OK ||
        mt_mesh_validate(mesh, &diag) != MT_OK) {
        fprintf(stderr, "%s: in-process build or validate failed: %s\n", name, diag.message);
        mt_client_destroy(client);
        return 1;
    }
    int failed = 0;
    mt_client_ack ack;
    double t0 = seconds_now();
    if (mt_client_submit(client, "holes2m", &list, 0, &ack, &diag) != MT_OK) {
        fprintf(stderr, "%s: submit failed: %s\n", name, diag.message);
        failed = 1;
    }
    double t_submit = seconds_now() - t0;
    mt_client_ack_free(&ack);

    /* 100,000 vertices spread over the whole grid, boundary ones included. */
    uint32_t *ids = malloc(NUM_RING_IDS * sizeof *ids);
    for (uint32_t i = 0; i < NUM_RING_IDS; i++)
        ids[i] = (uint32_t)((uint64_t)i * list.num_verts / NUM_RING_IDS);
    char why[256] = "";
    meshtopo_reply_t r;
    double t_rings = 0, t_loops = 0;
    size_t ring_bytes = 0;
    if (!failed) {
        t0 = seconds_now();
        mt_status st = mt_client_query(client, "holes2m", 0, MESHTOPO_QUERY_T_VERTEX_RING, ids,
                                       NUM_RING_IDS, &r, &diag);
        t_rings = seconds_now() - t0;
        if (st != MT_OK) {
            fprintf(stderr, "%s: VERTEX_RING of %d vertices: %s\n", name, NUM_RING_IDS,
                    diag.message);
            failed = 1;
        } else if (mt_test_check_rings(mesh, ids, NUM_RING_IDS, &r, why, sizeof why) != 0) {
            fprintf(stderr, "%s: one-rings differ from the core's: %s\n", name, why);
            failed = 1;
        }
        ring_bytes = (size_t)meshtopo_reply_t_encoded_size(&r);
        mt_client_reply_free(&r);
    }
    mt_client_stats after_rings;
    mt_client_get_stats(client, &after_rings);
    if (!failed) {
        t0 = seconds_now();
        mt_status st = mt_client_query(client, "holes2m", 0, MESHTOPO_QUERY_T_BOUNDARY_LOOPS, NULL,
                                       0, &r, &diag);
        t_loops = seconds_now() - t0;
        if (st != MT_OK) {
            fprintf(stderr, "%s: BOUNDARY_LOOPS: %s\n", name, diag.message);
            failed = 1;
        } else if (mt_client_reply_num_items(&r) != 10001) {
            fprintf(stderr, "%s: %zu boundary loops, expected 10001\n", name,
                    mt_client_reply_num_items(&r));
            failed = 1;
        } else if (mt_test_check_loops(mesh, &r, why, sizeof why) != 0) {
            fprintf(stderr, "%s: boundary loops differ from the core's: %s\n", name, why);
            failed = 1;
        }
        mt_client_reply_free(&r);
    }
    mt_client_stats stats;
    mt_client_get_stats(client, &stats);
    if (!failed && after_rings.reply_parts < 100) {
        fprintf(stderr, "%s: the one-rings came in %" PRIu64 " parts; expected over 100\n", name,
                after_rings.reply_parts);
        failed = 1;
    }
    printf(
        "%s: %u triangles submitted in %.3f s; one-rings of %d vertices (%zu bytes) in "
        "%.3f s; %d boundary loops in %.3f s: %s (%" PRIu64 " parts, %" PRIu64 " pulls, %" PRIu64
        " refused parts, %" PRIu64 " messages published)\n",
        name, list.num_faces, t_submit, NUM_RING_IDS, ring_bytes, t_rings, 10001, t_loops,
        failed ? "FAILED" : "equal to the core's", stats.reply_parts, stats.reply_pulls,
        stats.bad_parts, stats.attempts);
    free(ids);
    mt_client_destroy(client);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    return failed;
}
