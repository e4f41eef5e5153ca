/* meshtopod's dispatch over in-process LCM (memq://): submissions are built,
 * stored and acknowledged; every query kind answers what the core library
 * answers, computed here with the core API independently of the daemon's
 * answerers (daemon/answer_*.c; geometry kinds included);
 * every kind of bad message gets an error reply naming the problem while the
 * daemon keeps serving; a retried request id is answered from the cache. */
#include <dirent.h>
#include <inttypes.h>
#include <lcm/lcm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <xxhash.h>

#include "clock.h"
#include "daemon.h"
#include "harness.h"
#include "meshtopo/archive.h"
#include "meshtopo/core.h"
#include "meshtopo/io.h"
#include "meshtopo/msgs.h"
#include "meshtopo/query_kinds.h"
#include "query_route.h"

#define REPLY_CHANNEL "TEST_REPLY"
#define MAX_RECEIVED 64

typedef struct received {
    void *data;
    size_t size;
} received;

typedef struct fixture {
    lcm_t *lcm;
    mtd_daemon *daemon;
    received inbox[MAX_RECEIVED];
    size_t num_inbox;
    int topology_messages;
    int status_messages;
    meshtopo_status_t last_status;
    bool have_status;
    int64_t next_request_id;
} fixture;

/* Keeps an answer; each answer channel carries its one type (R_ACK ack_t,
 * R_REPLY reply_t, R_PART reply_part_t). */
static void on_reply(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    fixture *fx = user;
    char expected[MT_MSGS_CHANNEL_NAME_MAX + 1];
    const mt_msgs_type *type = mt_msgs_type_of(rbuf->data, rbuf->data_size);
    if (!type || mt_msgs_reply_channel_name(REPLY_CHANNEL, type, expected) != MT_OK ||
        strcmp(channel, expected) != 0)
        mt_test_fail(__FILE__, __LINE__, "a %s on channel %s", type ? type->name : "non-message",
                     channel);
    if (fx->num_inbox == MAX_RECEIVED) return;
    void *copy = malloc(rbuf->data_size);
    memcpy(copy, rbuf->data, rbuf->data_size);
    fx->inbox[fx->num_inbox++] = (received){copy, rbuf->data_size};
}

static void on_topology(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    fixture *fx = user;
    meshtopo_topology_t t;
    if (mt_msgs_decode(&mt_msgs_type_topology, rbuf->data, rbuf->data_size, &t, NULL, 0) == 0) {
        fx->topology_messages++;
        meshtopo_topology_t_decode_cleanup(&t);
    }
}

static void on_status(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    fixture *fx = user;
    if (fx->have_status) meshtopo_status_t_decode_cleanup(&fx->last_status);
    fx->have_status = mt_msgs_decode(&mt_msgs_type_status, rbuf->data, rbuf->data_size,
                                     &fx->last_status, NULL, 0) == 0;
    fx->status_messages++;
}

/* A daemon with meshtopod's flags argv[1 .. argc - 1]. */
static void fixture_init_with(fixture *fx, int argc, char **argv)
{
    memset(fx, 0, sizeof *fx);
    fx->next_request_id = 1;
    mtd_config config;
    mtd_config_action action;
    mt_diag diag;
    CHECK_OK(mtd_config_parse(argc, argv, &config, &action, &diag));
    mtd_log_set_level(config.log_level);
    fx->lcm = lcm_create("memq://");
    CHECK(fx->lcm != NULL);
    CHECK_OK(mtd_daemon_create(&config, fx->lcm, NULL, &fx->daemon, &diag));
    lcm_subscribe(fx->lcm, REPLY_CHANNEL "_(ACK|REPLY|PART)", on_reply, fx);
    lcm_subscribe(fx->lcm, "MESHTOPO_TOPOLOGY", on_topology, fx);
    lcm_subscribe(fx->lcm, "MESHTOPO_STATUS", on_status, fx);
}

static void fixture_init(fixture *fx)
{
    char *argv[] = {"meshtopod", "--max-verts", "100000",      "--max-faces", "200000",
                    "--workers", "2",           "--log-level", "error"};
    fixture_init_with(fx, 9, argv);
}

static void fixture_free(fixture *fx)
{
    mtd_daemon_destroy(fx->daemon);
    lcm_destroy(fx->lcm);
    for (size_t i = 0; i < fx->num_inbox; i++) free(fx->inbox[i].data);
    if (fx->have_status) meshtopo_status_t_decode_cleanup(&fx->last_status);
}

static void publish(fixture *fx, const char *channel, const mt_msgs_type *type, const void *msg)
{
    int size = type->encoded_size(msg);
    void *buf = malloc((size_t)size);
    CHECK_EQ(type->encode(buf, 0, size, msg), size);
    CHECK_EQ(lcm_publish(fx->lcm, channel, buf, (unsigned)size), 0);
    free(buf);
}

static void publish_bytes(fixture *fx, const char *channel, const void *data, size_t size)
{
    CHECK_EQ(lcm_publish(fx->lcm, channel, data, (unsigned)size), 0);
}

/* A large reply_t arriving as reply_part_t pieces (msgs/reply_part_t.lcm). */
typedef struct parts_buf {
    int64_t total, hash;
    int32_t part_size;
    size_t num_parts, num_have;
    uint8_t *data, *have;
} parts_buf;

/* Moves the parts of request_id from the inbox into pb; once every part is
 * in, the reassembled reply_t goes back into the inbox (pb is emptied). */
static void take_parts(fixture *fx, int64_t request_id, parts_buf *pb)
{
    for (size_t i = fx->num_inbox; i-- > 0;) {
        received *r = &fx->inbox[i];
        meshtopo_reply_part_t part;
        if (mt_msgs_type_of(r->data, r->size) != &mt_msgs_type_reply_part ||
            mt_msgs_decode(&mt_msgs_type_reply_part, r->data, r->size, &part, NULL, 0) != 0)
            continue;
        if (part.request_id == request_id && part.part_size > 0 && part.total_size > 0) {
            if (!pb->data) {
                pb->total = part.total_size;
                pb->hash = part.answer_hash;
                pb->part_size = part.part_size;
                pb->num_parts = (size_t)((part.total_size + part.part_size - 1) / part.part_size);
                pb->data = malloc((size_t)part.total_size);
                pb->have = calloc(pb->num_parts, 1);
            }
            size_t k = (size_t)(part.offset / pb->part_size);
            CHECK(part.total_size == pb->total && part.answer_hash == pb->hash);
            CHECK(part.offset % pb->part_size == 0 && k < pb->num_parts);
            if (k < pb->num_parts && !pb->have[k] && part.offset + part.length <= pb->total) {
                memcpy(pb->data + part.offset, part.data, (size_t)part.length);
                pb->have[k] = 1;
                pb->num_have++;
            }
            free(r->data);
            fx->inbox[i] = fx->inbox[--fx->num_inbox];
        }
        meshtopo_reply_part_t_decode_cleanup(&part);
    }
    if (pb->data && pb->num_have == pb->num_parts && fx->num_inbox < MAX_RECEIVED) {
        fx->inbox[fx->num_inbox++] = (received){pb->data, (size_t)pb->total};
        free(pb->have);
        memset(pb, 0, sizeof *pb);
    }
}

/* Asks the daemon for the next parts pb lacks (reply_pull_t, 16 at most). */
static void pull_parts(fixture *fx, int64_t request_id, const parts_buf *pb)
{
    int64_t offsets[16], lengths[16];
    meshtopo_reply_pull_t pull;
    memset(&pull, 0, sizeof pull);
    pull.request_id = request_id;
    pull.reply_channel = REPLY_CHANNEL;
    pull.total_size = pb->total;
    pull.answer_hash = pb->hash;
    pull.offsets = offsets;
    pull.lengths = lengths;
    for (size_t k = 0; k < pb->num_parts && pull.num_ranges < 16; k++) {
        if (pb->have[k]) continue;
        offsets[pull.num_ranges] = (int64_t)k * pb->part_size;
        lengths[pull.num_ranges++] = pb->part_size;
    }
    publish(fx, "MESHTOPO_QUERY_PULL", &mt_msgs_type_reply_pull, &pull);
}

/* Handles LCM until a message of `type` with request_id arrives (decoded into
 * out; release with type->decode_cleanup) or 20 s pass. Returns 0 when found.
 * A reply_t or ack_t sent in parts is reassembled (pulling the parts after
 * the first). */
static int wait_for(fixture *fx, const mt_msgs_type *type, int64_t request_id, void *out)
{
    parts_buf pb;
    memset(&pb, 0, sizeof pb);
    bool idle = false;
    for (int round = 0; round < 4000; round++) {
        if (type == &mt_msgs_type_reply || type == &mt_msgs_type_ack) {
            take_parts(fx, request_id, &pb);
            if (pb.data && idle) pull_parts(fx, request_id, &pb);
        }
        for (size_t i = 0; i < fx->num_inbox; i++) {
            received *r = &fx->inbox[i];
            if (mt_msgs_type_of(r->data, r->size) != type) continue;
            char error[MT_MSGS_ERROR_SIZE];
            if (mt_msgs_decode(type, r->data, r->size, out, error, sizeof error) != 0) {
                mt_test_fail(__FILE__, __LINE__, "reply does not decode: %s", error);
                continue;
            }
            /* ack_t and reply_t both start with utime, request_id. */
            int64_t id = type == &mt_msgs_type_ack ? ((meshtopo_ack_t *)out)->request_id
                                                   : ((meshtopo_reply_t *)out)->request_id;
            if (id == request_id) {
                free(r->data);
                fx->inbox[i] = fx->inbox[--fx->num_inbox];
                free(pb.data);
                free(pb.have);
                return 0;
            }
            type->decode_cleanup(out);
        }
        idle = lcm_handle_timeout(fx->lcm, 5) <= 0;
    }
    free(pb.data);
    free(pb.have);
    mt_test_fail(__FILE__, __LINE__, "no %s for request %" PRId64 " within 20 s", type->name,
                 request_id);
    return -1;
}

/* ---- requests ---- */

static meshtopo_mesh_t mesh_msg(fixture *fx, const char *id, const mt_face_list *list)
{
    meshtopo_mesh_t m;
    memset(&m, 0, sizeof m);
    m.utime = 1700000000000000;
    m.request_id = fx->next_request_id++;
    m.reply_channel = REPLY_CHANNEL;
    m.mesh_id = (char *)id;
    m.source = "test_dispatch";
    m.num_verts = (int32_t)list->num_verts;
    m.num_position_values = list->positions ? 3 * (int32_t)list->num_verts : 0;
    m.positions = list->positions;
    m.num_faces = (int32_t)list->num_faces;
    m.face_vertex_counts = (int32_t *)list->face_sizes;
    m.num_indices = (int32_t)list->num_indices;
    m.face_vertex_indices = (int32_t *)list->face_indices;
    return m;
}

/* Submits and waits for the ack (out; decode_cleanup it). */
static int submit(fixture *fx, const meshtopo_mesh_t *m, meshtopo_ack_t *out)
{
    publish(fx, "MESHTOPO_SUBMIT", &mt_msgs_type_mesh, m);
    return wait_for(fx, &mt_msgs_type_ack, m->request_id, out);
}

/* Submits a face list that must be accepted; returns its version. */
static int32_t submit_ok(fixture *fx, const char *id, const mt_face_list *list)
{
    meshtopo_mesh_t m = mesh_msg(fx, id, list);
    meshtopo_ack_t ack;
    if (submit(fx, &m, &ack) != 0) return 0;
    if (ack.status != 0) mt_test_fail(__FILE__, __LINE__, "submit %s: %s", id, ack.error);
    CHECK_EQ(ack.num_reports, 1);
    int32_t version = ack.version;
    meshtopo_ack_t_decode_cleanup(&ack);
    return version;
}

static int query(fixture *fx, const char *id, int32_t version, int32_t kind, const int32_t *ids,
                 int32_t num_ids, meshtopo_reply_t *out)
{
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.request_id = fx->next_request_id++;
    q.reply_channel = REPLY_CHANNEL;
    q.instance = "";
    q.mesh_id = (char *)id;
    q.version = version;
    q.kind = kind;
    q.num_ids = num_ids;
    q.ids = (int32_t *)ids;
    publish(fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    return wait_for(fx, &mt_msgs_type_reply, q.request_id, out);
}

/* Checks that an error reply has `status` and an error containing `needle`. */
#define CHECK_ERROR(status_got, error_got, status_want, needle)                            \
    do {                                                                                   \
        CHECK_EQ(status_got, status_want);                                                 \
        if (!strstr((error_got), (needle)))                                                \
            mt_test_fail(__FILE__, __LINE__, "error '%s' does not name '%s'", (error_got), \
                         (needle));                                                        \
    } while (0)

static void check_query_error(fixture *fx, const char *id, int32_t version, int32_t kind,
                              const int32_t *ids, int32_t num_ids, int32_t status,
                              const char *needle, int line)
{
    meshtopo_reply_t r;
    if (query(fx, id, version, kind, ids, num_ids, &r) != 0) return;
    if (r.status != status || !strstr(r.error, needle))
        mt_test_fail(__FILE__, line, "query kind %d: status %d '%s', expected %d naming '%s'",
                     (int)kind, (int)r.status, r.error, (int)status, needle);
    CHECK_EQ(r.num_items, 0);
    CHECK_EQ(r.num_item_offsets, 1);
    meshtopo_reply_t_decode_cleanup(&r);
}

/* ---- the expected answers, from the core library ---- */

/* A growable int32_t array. */
typedef struct vec {
    int32_t *v;
    size_t n, cap;
} vec;

static void vec_push(vec *a, int32_t value)
{
    if (a->n == a->cap) {
        a->cap = a->cap ? 2 * a->cap : 16;
        a->v = realloc(a->v, a->cap * sizeof *a->v);
    }
    a->v[a->n++] = value;
}

typedef struct expected {
    vec item_status, item_offsets, group_boundary, value_offsets, value2_offsets, values, values2;
} expected;

static void exp_value(expected *e, uint32_t v)
{
    vec_push(&e->values, (int32_t)v);
}

static void exp_value2(expected *e, uint32_t v)
{
    vec_push(&e->values2, (int32_t)v);
}

static void exp_group(expected *e, bool boundary)
{
    vec_push(&e->group_boundary, boundary);
    vec_push(&e->value_offsets, (int32_t)e->values.n);
    vec_push(&e->value2_offsets, (int32_t)e->values2.n);
}

static void exp_item(expected *e, int32_t status)
{
    vec_push(&e->item_status, status);
    vec_push(&e->item_offsets, (int32_t)e->group_boundary.n);
}

static void exp_init(expected *e)
{
    memset(e, 0, sizeof *e);
    vec_push(&e->item_offsets, 0);
    vec_push(&e->value_offsets, 0);
    vec_push(&e->value2_offsets, 0);
}

static void exp_free(expected *e)
{
    vec *vecs[] = {&e->item_status,    &e->item_offsets, &e->group_boundary, &e->value_offsets,
                   &e->value2_offsets, &e->values,       &e->values2};
    for (size_t i = 0; i < sizeof vecs / sizeof vecs[0]; i++) free(vecs[i]->v);
}

/* The core's answer to one query, in reply_t's layout. */
static void expect_core(const mt_mesh *mesh, int32_t kind, const int32_t *ids, int32_t n,
                        expected *e)
{
    exp_init(e);
    static uint32_t buf[1 << 16], buf2[1 << 16], offsets[1 << 12];
    static mt_fan fans[1 << 10];
    size_t count = 0, count2 = 0;
    if (kind == MESHTOPO_QUERY_T_COMPONENTS && n == 0) n = (int32_t)mt_mesh_num_faces(mesh);
    if (kind == MESHTOPO_QUERY_T_DEFECTS && n == 0) n = MT_DEFECT_KIND_COUNT;
    if (kind == MESHTOPO_QUERY_T_BOUNDARY_LOOPS) {
        CHECK_OK(mt_boundary_loops(mesh, buf, 1 << 16, offsets, 1 << 12, &count, &count2));
        for (size_t l = 0; l < count2; l++) {
            for (uint32_t k = offsets[l]; k < offsets[l + 1]; k++) exp_value(e, buf[k]);
            exp_group(e, true);
            exp_item(e, 0);
        }
        return;
    }
    int32_t step = kind == MESHTOPO_QUERY_T_EDGE_FACES ? 2 : 1;
    for (int32_t i = 0; i < n; i += step) {
        uint32_t id = ids ? (uint32_t)ids[i] : (uint32_t)i;
        if (kind == MESHTOPO_QUERY_T_VERTEX_RING) {
            mt_ring ring = {buf, 1 << 16, buf2, 1 << 16, fans, 1 << 10, 0, 0, 0};
            CHECK_OK(mt_vert_ring(mesh, id, &ring));
            for (size_t f = 0; f < ring.num_fans; f++) {
                for (uint32_t k = 0; k < fans[f].neighbor_count; k++)
                    exp_value(e, buf[fans[f].neighbor_begin + k]);
                for (uint32_t k = 0; k < fans[f].face_count; k++)
                    exp_value2(e, buf2[fans[f].face_begin + k]);
                exp_group(e, fans[f].boundary);
            }
            exp_item(e, 0);
        } else if (kind == MESHTOPO_QUERY_T_VALENCE) {
            uint32_t valence = 0;
            CHECK_OK(mt_vert_valence(mesh, id, &valence));
            exp_value(e, valence);
            exp_group(e, false);
            exp_item(e, 0);
        } else if (kind == MESHTOPO_QUERY_T_FACE_NEIGHBORS) {
            size_t sides = 0;
            mt_status s =
                mt_face_neighbors(mesh, id, buf, 1 << 16, offsets, 1 << 12, &count, &sides);
            if (s == MT_ERR_NOT_FOUND) {
                exp_item(e, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
                continue;
            }
            CHECK_OK(s);
            CHECK_OK(mt_face_verts(mesh, id, buf2, 1 << 16, &count2));
            for (size_t k = 0; k < sides; k++) {
                for (uint32_t j = offsets[k]; j < offsets[k + 1]; j++) exp_value(e, buf[j]);
                exp_value2(e, buf2[k]);
                exp_value2(e, buf2[(k + 1) % sides]);
                exp_group(e, offsets[k] == offsets[k + 1]);
            }
            exp_item(e, 0);
        } else if (kind == MESHTOPO_QUERY_T_EDGE_FACES) {
            mt_status s = mt_edge_faces(mesh, id, (uint32_t)ids[i + 1], buf, 1 << 16, &count);
            if (s == MT_ERR_NOT_FOUND) {
                exp_item(e, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
                continue;
            }
            CHECK_OK(s);
            for (size_t k = 0; k < count; k++) exp_value(e, buf[k]);
            exp_group(e, false);
            exp_item(e, 0);
        } else if (kind == MESHTOPO_QUERY_T_COMPONENTS) {
            uint32_t component = 0;
            mt_status s = mt_face_component(mesh, id, &component);
            if (s == MT_ERR_NOT_FOUND) {
                exp_item(e, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
                continue;
            }
            CHECK_OK(s);
            exp_value(e, component);
            exp_group(e, false);
            exp_item(e, 0);
        } else if (kind == MESHTOPO_QUERY_T_DEFECTS) {
            const mt_report *r = mt_mesh_report(mesh);
            for (size_t k = 0; k < r->num_defects; k++) {
                if (r->defects[k].kind != id) continue;
                exp_value(e, r->defects[k].a);
                exp_value(e, r->defects[k].b);
                exp_value(e, r->defects[k].c);
            }
            exp_group(e, false);
            exp_item(e, 0);
        }
    }
}

static void check_array(const char *what, int kind, const int32_t *got, int32_t ngot,
                        const int32_t *want, size_t nwant, int line)
{
    if ((size_t)ngot != nwant) {
        mt_test_fail(__FILE__, line, "kind %d %s: %d entries, expected %zu", kind, what, (int)ngot,
                     nwant);
        return;
    }
    for (size_t i = 0; i < nwant; i++)
        if (got[i] != want[i]) {
            mt_test_fail(__FILE__, line, "kind %d %s[%zu]: %d, expected %d", kind, what, i,
                         (int)got[i], (int)want[i]);
            return;
        }
}

static void check_array8(const char *what, int kind, const int8_t *got, int32_t ngot,
                         const int32_t *want, size_t nwant, int line)
{
    int32_t *wide = malloc((size_t)(ngot > 0 ? ngot : 1) * sizeof *wide);
    for (int32_t i = 0; i < ngot; i++) wide[i] = got[i];
    check_array(what, kind, wide, ngot, want, nwant, line);
    free(wide);
}

/* Queries the daemon and compares with the core's answer on `mesh`. */
static void check_kind(fixture *fx, const char *id, const mt_mesh *mesh, int32_t kind,
                       const int32_t *ids, int32_t n, int line)
{
    meshtopo_reply_t r;
    if (query(fx, id, 0, kind, ids, n, &r) != 0) return;
    if (r.status != 0) {
        mt_test_fail(__FILE__, line, "kind %d: status %d: %s", (int)kind, (int)r.status, r.error);
        meshtopo_reply_t_decode_cleanup(&r);
        return;
    }
    expected e;
    expect_core(mesh, kind, ids, n, &e);
    check_array8("item_status", kind, r.item_status, r.num_items, e.item_status.v, e.item_status.n,
                 line);
    check_array("item_offsets", kind, r.item_offsets, r.num_item_offsets, e.item_offsets.v,
                e.item_offsets.n, line);
    check_array8("group_boundary", kind, r.group_boundary, r.num_groups, e.group_boundary.v,
                 e.group_boundary.n, line);
    check_array("value_offsets", kind, r.value_offsets, r.num_value_offsets, e.value_offsets.v,
                e.value_offsets.n, line);
    check_array("value2_offsets", kind, r.value2_offsets, r.num_value_offsets, e.value2_offsets.v,
                e.value2_offsets.n, line);
    check_array("values", kind, r.values, r.num_values, e.values.v, e.values.n, line);
    check_array("values2", kind, r.values2, r.num_values2, e.values2.v, e.values2.n, line);
    CHECK_EQ(r.num_reports, 0);
    exp_free(&e);
    meshtopo_reply_t_decode_cleanup(&r);
}

/* The REPORT reply against the core's report. */
static void check_report(fixture *fx, const char *id, const mt_mesh *mesh)
{
    meshtopo_reply_t r;
    if (query(fx, id, 0, MESHTOPO_QUERY_T_REPORT, NULL, 0, &r) != 0) return;
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.num_reports, 1);
    if (r.num_reports == 1) {
        const mt_report *want = mt_mesh_report(mesh);
        const meshtopo_topology_t *t = &r.reports[0];
        CHECK_EQ(t->num_verts, want->num_verts);
        CHECK_EQ(t->num_faces, want->num_faces);
        CHECK_EQ(t->num_faces_valid, want->num_faces_valid);
        CHECK_EQ(t->num_edges, want->num_edges);
        CHECK_EQ(t->boundary_edges, want->boundary_edges);
        CHECK_EQ(t->boundary_loops, want->boundary_loops);
        CHECK_EQ(t->nonmanifold_edges, want->nonmanifold_edges);
        CHECK_EQ(t->nonmanifold_vertices, want->nonmanifold_vertices);
        CHECK_EQ(t->connected_components, want->connected_components);
        CHECK_EQ(t->euler_characteristic, want->euler_characteristic);
        CHECK_EQ(t->closed, want->closed);
        CHECK_EQ(t->manifold, want->manifold);
        CHECK_EQ(t->orientable, want->orientable);
        CHECK_EQ(t->genus, want->genus);
        CHECK_EQ(t->num_components_listed, want->connected_components);
        CHECK_EQ(t->num_defects, want->num_defects);
        CHECK_EQ(t->num_defects_listed, want->num_defects);
        for (size_t i = 0; i < want->num_defects && (int64_t)i < t->num_defects_listed; i++) {
            CHECK_EQ(t->defect_kind[i], want->defects[i].kind);
            CHECK_EQ(t->defect_a[i], (int32_t)want->defects[i].a);
            CHECK_EQ(t->defect_b[i], (int32_t)want->defects[i].b);
            CHECK_EQ(t->defect_c[i], (int32_t)want->defects[i].c);
        }
        CHECK_EQ(t->version, r.version);
        CHECK(strcmp(t->mesh_id, id) == 0);
    }
    meshtopo_reply_t_decode_cleanup(&r);
}

/* Submits list as `id` and checks every query kind against the core. */
static void check_every_kind(fixture *fx, const char *id, const mt_face_list *list)
{
    int32_t version = submit_ok(fx, id, list);
    CHECK(version >= 1);
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(list, NULL, &mesh, NULL));
    if (!mesh) return;
    CHECK_OK(mt_mesh_validate(mesh, NULL));
    uint32_t nv = mt_mesh_num_verts(mesh), nf = mt_mesh_num_faces(mesh);
    int32_t *verts = malloc(nv * sizeof *verts);
    int32_t *faces = malloc(nf * sizeof *faces);
    for (uint32_t v = 0; v < nv; v++) verts[v] = (int32_t)v;
    for (uint32_t f = 0; f < nf; f++) faces[f] = (int32_t)f;
    /* Edge pairs: every side of the first faces (both directions), plus a
     * pair that is no edge. */
    int32_t pairs[2 * 64 + 2];
    int32_t npairs = 0;
    uint64_t at = 0;
    for (uint32_t f = 0; f < nf && npairs < 2 * 60; f++) {
        uint32_t size = list->face_sizes[f];
        for (uint32_t k = 0; k < size && npairs < 2 * 60; k++) {
            uint32_t a = list->face_indices[at + k], b = list->face_indices[at + (k + 1) % size];
            if (a >= nv || b >= nv) continue;
            pairs[npairs++] = (int32_t)(k % 2 ? b : a);
            pairs[npairs++] = (int32_t)(k % 2 ? a : b);
        }
        at += size;
    }
    pairs[npairs++] = 0;
    pairs[npairs++] = 0;
    check_kind(fx, id, mesh, MESHTOPO_QUERY_T_VERTEX_RING, verts, (int32_t)nv, __LINE__);
    check_kind(fx, id, mesh, MESHTOPO_QUERY_T_VALENCE, verts, (int32_t)nv, __LINE__);
    check_kind(fx, id, mesh, MESHTOPO_QUERY_T_FACE_NEIGHBORS, faces, (int32_t)nf, __LINE__);
    check_kind(fx, id, mesh, MESHTOPO_QUERY_T_EDGE_FACES, pairs, npairs, __LINE__);
    check_kind(fx, id, mesh, MESHTOPO_QUERY_T_BOUNDARY_LOOPS, NULL, 0, __LINE__);
    check_kind(fx, id, mesh, MESHTOPO_QUERY_T_COMPONENTS, NULL, 0, __LINE__);
    check_kind(fx, id, mesh, MESHTOPO_QUERY_T_COMPONENTS, faces, (int32_t)nf, __LINE__);
    check_kind(fx, id, mesh, MESHTOPO_QUERY_T_DEFECTS, NULL, 0, __LINE__);
    int32_t kinds[] = {MT_DEFECT_NONMANIFOLD_EDGE, MT_DEFECT_DEGENERATE_FACE};
    check_kind(fx, id, mesh, MESHTOPO_QUERY_T_DEFECTS, kinds, 2, __LINE__);
    check_report(fx, id, mesh);
    free(verts);
    free(faces);
    mt_mesh_destroy(mesh);
}

static void load_corpus(const char *name, mt_face_list *out)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", mt_test_corpus_dir(), name);
    mt_diag diag;
    mt_status s = mt_read_file(path, MT_FORMAT_AUTO, out, &diag);
    if (s != MT_OK) mt_test_fail(__FILE__, __LINE__, "reading %s: %s", path, diag.message);
}

/* The daemon still answers: a valence query on a held mesh succeeds. */
static void check_still_serving(fixture *fx, const char *id)
{
    int32_t v = 0;
    meshtopo_reply_t r;
    if (query(fx, id, 0, MESHTOPO_QUERY_T_VALENCE, &v, 1, &r) != 0) return;
    if (r.status != 0) mt_test_fail(__FILE__, __LINE__, "no longer serving %s: %s", id, r.error);
    CHECK_EQ(r.num_items, 1);
    meshtopo_reply_t_decode_cleanup(&r);
}

/* A fixture holding a cube as "cube". */
static void fixture_with_cube(fixture *fx)
{
    fixture_init(fx);
    mt_face_list cube;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &cube));
    CHECK_EQ(submit_ok(fx, "cube", &cube), 1);
    mt_face_list_free(&cube);
}

/* ---- tests ---- */

/* Every kind of the query-kind table has an answerer in the daemon. */
static void test_every_kind_has_an_answerer(void)
{
    for (size_t i = 0; i < mt_msgs_query_kind_count(); i++)
        CHECK(mtd_query_answerer(mt_msgs_query_kind_at(i)->kind) != NULL);
    CHECK(mtd_query_answerer(mt_msgs_query_kind_last() + 1) == NULL);
}

static void test_generated_every_kind(void)
{
    fixture fx;
    fixture_init(&fx);
    mt_face_list grid, fin;
    CHECK_OK(mt_gen_grid(4, 3, true, &grid));
    check_every_kind(&fx, "grid", &grid);
    CHECK_OK(mt_gen_fin(&fin));
    check_every_kind(&fx, "fin", &fin);
    /* The report goes out on TOPOLOGY from the build's worker, next to the
     * ack: it may still be queued when the last answer has arrived. */
    for (int i = 0; i < 100 && fx.topology_messages < 2; i++) lcm_handle_timeout(fx.lcm, 50);
    CHECK_EQ(fx.topology_messages, 2);
    mt_face_list_free(&grid);
    mt_face_list_free(&fin);
    fixture_free(&fx);
}

static void test_corpus_every_kind(void)
{
    fixture fx;
    fixture_init(&fx);
    const char *names[] = {"npm_teapot.off", "cgal_many_umbrellas.off", "vcg_nonmanifold.off",
                           "assimp_malformed.off"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        mt_face_list list;
        memset(&list, 0, sizeof list);
        load_corpus(names[i], &list);
        if (list.num_verts) check_every_kind(&fx, names[i], &list);
        mt_face_list_free(&list);
    }
    fixture_free(&fx);
}

static void test_versions_and_list(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    mt_face_list tet;
    CHECK_OK(mt_gen_platonic(MT_TETRAHEDRON, &tet));
    CHECK_EQ(submit_ok(&fx, "cube", &tet), 2);
    int32_t v7 = 7;
    meshtopo_reply_t r;
    /* version 1 is still the cube: vertex 7 exists there only. */
    if (query(&fx, "cube", 1, MESHTOPO_QUERY_T_VALENCE, &v7, 1, &r) == 0) {
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.version, 1);
        CHECK_EQ(r.num_values, 1);
        if (r.num_values == 1) CHECK_EQ(r.values[0], 3);
        meshtopo_reply_t_decode_cleanup(&r);
    }
    check_query_error(&fx, "cube", 0, MESHTOPO_QUERY_T_VALENCE, &v7, 1,
                      MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE, "ids[0] = 7", __LINE__);
    if (query(&fx, "", 0, MESHTOPO_QUERY_T_LIST_MESHES, NULL, 0, &r) == 0) {
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.num_meshes, 2);
        if (r.num_meshes == 2) {
            CHECK_EQ(r.list_versions[0], 1);
            CHECK_EQ(r.list_num_verts[0], 8);
            CHECK_EQ(r.list_versions[1], 2);
            CHECK_EQ(r.list_num_verts[1], 4);
            CHECK(strcmp(r.list_sources[1], "test_dispatch") == 0);
        }
        meshtopo_reply_t_decode_cleanup(&r);
    }
    /* A query naming another daemon's instance is left to that daemon; one
     * naming this daemon's is answered. Queries run in order on the LCM
     * thread: once the second is answered, the first would have been. */
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.reply_channel = REPLY_CHANNEL;
    q.mesh_id = "";
    q.kind = MESHTOPO_QUERY_T_LIST_MESHES;
    q.request_id = 9001;
    q.instance = "elsewhere:1:1700000000000000";
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    q.request_id = 9002;
    q.instance = (char *)mtd_daemon_instance(fx.daemon);
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    if (wait_for(&fx, &mt_msgs_type_reply, 9002, &r) == 0) {
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.num_meshes, 2);
        meshtopo_reply_t_decode_cleanup(&r);
    }
    for (size_t i = 0; i < fx.num_inbox; i++) {
        meshtopo_reply_t other;
        if (mt_msgs_type_of(fx.inbox[i].data, fx.inbox[i].size) != &mt_msgs_type_reply ||
            mt_msgs_decode(&mt_msgs_type_reply, fx.inbox[i].data, fx.inbox[i].size, &other, NULL,
                           0) != 0)
            continue;
        CHECK(other.request_id != 9001);
        meshtopo_reply_t_decode_cleanup(&other);
    }
    mt_face_list_free(&tet);
    fixture_free(&fx);
}

static void test_content_hash(void)
{
    fixture fx;
    fixture_init(&fx);
    mt_face_list cube;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &cube));
    meshtopo_mesh_t m = mesh_msg(&fx, "cube", &cube);
    int size = meshtopo_mesh_t_encoded_size(&m);
    unsigned char *buf = malloc((size_t)size);
    meshtopo_mesh_t_encode(buf, 0, size, &m);
    /* The content starts at num_verts: after fingerprint, utime, request_id,
     * three strings and the strict flag. */
    size_t start = 8 + 8 + 8 + (4 + strlen(m.reply_channel) + 1) + (4 + strlen(m.mesh_id) + 1) +
                   (4 + strlen(m.source) + 1) + 1;
    /* XXH3-64 of those bytes (msgs/mesh_t.lcm), from libxxhash itself. */
    uint64_t want = XXH3_64bits(buf + start, (size_t)size - start);
    meshtopo_ack_t ack;
    if (submit(&fx, &m, &ack) == 0) {
        CHECK_EQ(ack.status, 0);
        CHECK(ack.content_hash == (int64_t)want);
        CHECK(ack.num_reports == 1 && ack.reports[0].content_hash == (int64_t)want);
        meshtopo_ack_t_decode_cleanup(&ack);
    }
    free(buf);
    mt_face_list_free(&cube);
    fixture_free(&fx);
}

static void test_bad_undecodable(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    mt_face_list cube;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &cube));
    meshtopo_mesh_t m = mesh_msg(&fx, "cut", &cube);
    int size = meshtopo_mesh_t_encoded_size(&m);
    unsigned char *buf = malloc((size_t)size);
    meshtopo_mesh_t_encode(buf, 0, size, &m);
    publish_bytes(&fx, "MESHTOPO_SUBMIT", buf, (size_t)size - 5); /* cut short */
    meshtopo_ack_t ack;
    if (wait_for(&fx, &mt_msgs_type_ack, m.request_id, &ack) == 0) {
        CHECK_ERROR(ack.status, ack.error, MESHTOPO_STATUS_CODE_T_UNDECODABLE, "undecodable");
        CHECK_EQ(ack.version, 0);
        meshtopo_ack_t_decode_cleanup(&ack);
    }
    /* A negative array length on the wire: num_indices, the last int32
     * before the (empty) index array of a mesh without faces. */
    meshtopo_mesh_t empty = m;
    empty.request_id = fx.next_request_id++;
    empty.num_faces = 0;
    empty.num_indices = 0;
    size = meshtopo_mesh_t_encoded_size(&empty);
    meshtopo_mesh_t_encode(buf, 0, size, &empty);
    memset(buf + size - 4, 0xff, 4);
    publish_bytes(&fx, "MESHTOPO_SUBMIT", buf, (size_t)size);
    if (wait_for(&fx, &mt_msgs_type_ack, empty.request_id, &ack) == 0) {
        CHECK_ERROR(ack.status, ack.error, MESHTOPO_STATUS_CODE_T_UNDECODABLE, "negative");
        meshtopo_ack_t_decode_cleanup(&ack);
    }
    /* Garbage without a readable header gets no reply but is counted. */
    publish_bytes(&fx, "MESHTOPO_QUERY", "abc", 3);
    check_still_serving(&fx, "cube");
    free(buf);
    mt_face_list_free(&cube);
    fixture_free(&fx);
}

/* Counts what arrives on one channel. */
static void count_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)rbuf;
    (void)channel;
    (*(int *)user)++;
}

/* Each request channel takes its one type: a chunk on SUBMIT or a pull on
 * QUERY is answered UNDECODABLE and starts nothing; a query on QUERY_PULL is
 * dropped. A reply channel too long for its answers' suffixes (55 bytes) is
 * never answered but counted as an error, while 54 bytes are answered; the
 * daemon keeps serving. */
static void test_bad_channels(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    uint8_t data[4] = {1, 2, 3, 4};
    meshtopo_mesh_chunk_t c;
    memset(&c, 0, sizeof c);
    c.request_id = 5100;
    c.reply_channel = REPLY_CHANNEL;
    c.mesh_id = "piece";
    c.source = "";
    c.total_size = 4;
    c.length = 4;
    c.data = data;
    c.want_status = true;
    publish(&fx, "MESHTOPO_SUBMIT", &mt_msgs_type_mesh_chunk, &c);
    meshtopo_ack_t ack;
    if (wait_for(&fx, &mt_msgs_type_ack, 5100, &ack) == 0) {
        CHECK_ERROR(ack.status, ack.error, MESHTOPO_STATUS_CODE_T_UNDECODABLE,
                    "not a meshtopo.mesh_t");
        meshtopo_ack_t_decode_cleanup(&ack);
    }
    meshtopo_reply_pull_t pull;
    memset(&pull, 0, sizeof pull);
    pull.request_id = 5101;
    pull.reply_channel = REPLY_CHANNEL;
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_reply_pull, &pull);
    meshtopo_reply_t r;
    if (wait_for(&fx, &mt_msgs_type_reply, 5101, &r) == 0) {
        CHECK_ERROR(r.status, r.error, MESHTOPO_STATUS_CODE_T_UNDECODABLE,
                    "not a meshtopo.query_t");
        meshtopo_reply_t_decode_cleanup(&r);
    }
    int32_t vertex = 0;
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.request_id = 5102;
    q.reply_channel = REPLY_CHANNEL;
    q.instance = "";
    q.mesh_id = "cube";
    q.kind = MESHTOPO_QUERY_T_VALENCE;
    q.num_ids = 1;
    q.ids = &vertex;
    publish(&fx, "MESHTOPO_QUERY_PULL", &mt_msgs_type_query, &q);
    /* The chunk counts as a (refused) message on SUBMIT and started no
     * transfer. */
    mtd_daemon_heartbeat(fx.daemon);
    for (int i = 0; i < 100 && !fx.have_status; i++) lcm_handle_timeout(fx.lcm, 50);
    CHECK(fx.have_status);
    CHECK_EQ(fx.last_status.submissions, 2);
    CHECK_EQ(fx.last_status.chunks, 0);
    CHECK_EQ(fx.last_status.transfers_active, 0);
    mtd_counters counts;
    mtd_daemon_get_counts(fx.daemon, &counts);

    char too_long[MESHTOPO_MESH_T_REPLY_CHANNEL_MAX + 2],
        longest[MESHTOPO_MESH_T_REPLY_CHANNEL_MAX + 1];
    memset(too_long, 'L', sizeof too_long - 1);
    too_long[sizeof too_long - 1] = '\0';
    memset(longest, 'M', sizeof longest - 1);
    longest[sizeof longest - 1] = '\0';
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    int on_too_long = 0, on_longest = 0;
    CHECK(snprintf(channel, sizeof channel, "%s_REPLY", too_long) < (int)sizeof channel);
    lcm_subscription_t *sub_too_long = lcm_subscribe(fx.lcm, channel, count_message, &on_too_long);
    CHECK_OK(mt_msgs_reply_channel_name(longest, &mt_msgs_type_reply, channel));
    lcm_subscription_t *sub_longest = lcm_subscribe(fx.lcm, channel, count_message, &on_longest);
    int64_t errors_before = counts.errors;
    q.reply_channel = too_long;
    q.request_id = 5103;
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    q.reply_channel = longest;
    q.request_id = 5104;
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    for (int i = 0; i < 400 && on_longest == 0; i++) lcm_handle_timeout(fx.lcm, 5);
    CHECK_EQ(on_longest, 1);
    CHECK_EQ(on_too_long, 0);
    mtd_daemon_get_counts(fx.daemon, &counts);
    CHECK_EQ(counts.errors, errors_before + 1);
    lcm_unsubscribe(fx.lcm, sub_too_long);
    lcm_unsubscribe(fx.lcm, sub_longest);

    /* A reply channel naming a daemon channel: refused, noted, never
     * published on (nor beside it). */
    int on_daemon_channels = 0;
    lcm_subscription_t *sub_daemon =
        lcm_subscribe(fx.lcm, "MESHTOPO_(SUBMIT|QUERY|TOPOLOGY|STATUS).*_(ACK|REPLY|PART|TRANSFER)",
                      count_message, &on_daemon_channels);
    const char *daemon_channels[] = {"MESHTOPO_QUERY", "MESHTOPO_SUBMIT", "MESHTOPO_STATUS",
                                     "MESHTOPO_TOPOLOGY_X"};
    for (size_t i = 0; i < 4; i++) {
        q.reply_channel = (char *)daemon_channels[i];
        q.request_id = 5110 + (int64_t)i;
        publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    }
    mt_face_list cube;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &cube));
    meshtopo_mesh_t m = mesh_msg(&fx, "cube", &cube);
    m.reply_channel = "MESHTOPO_SUBMIT";
    publish(&fx, "MESHTOPO_SUBMIT", &mt_msgs_type_mesh, &m);
    mt_face_list_free(&cube);
    c.reply_channel = "MESHTOPO_STATUS";
    c.request_id = 5120;
    publish(&fx, "MESHTOPO_SUBMIT_CHUNK", &mt_msgs_type_mesh_chunk, &c);
    for (int i = 0; i < 100; i++) lcm_handle_timeout(fx.lcm, 2);
    CHECK_EQ(on_daemon_channels, 0);
    mtd_daemon_get_counts(fx.daemon, &counts);
    CHECK_EQ(counts.errors, errors_before + 1 + 6);
    mtd_daemon_heartbeat(fx.daemon);
    int beats = fx.status_messages;
    for (int i = 0; i < 100 && fx.status_messages == beats; i++) lcm_handle_timeout(fx.lcm, 20);
    CHECK(fx.have_status && strstr(fx.last_status.last_error, "names a daemon channel"));
    CHECK_EQ(fx.last_status.transfers_active, 0);
    lcm_unsubscribe(fx.lcm, sub_daemon);
    check_still_serving(&fx, "cube");
    fixture_free(&fx);
}

static void test_bad_fingerprint(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.request_id = 4242;
    q.reply_channel = REPLY_CHANNEL;
    q.instance = "";
    q.mesh_id = "cube";
    q.kind = MESHTOPO_QUERY_T_REPORT;
    int size = meshtopo_query_t_encoded_size(&q);
    unsigned char *buf = malloc((size_t)size);
    meshtopo_query_t_encode(buf, 0, size, &q);
    buf[3] ^= 0x5a;
    publish_bytes(&fx, "MESHTOPO_QUERY", buf, (size_t)size);
    meshtopo_reply_t r;
    if (wait_for(&fx, &mt_msgs_type_reply, 4242, &r) == 0) {
        CHECK_ERROR(r.status, r.error, MESHTOPO_STATUS_CODE_T_UNDECODABLE, "fingerprint");
        meshtopo_reply_t_decode_cleanup(&r);
    }
    /* A query_t sent to the submission channel. */
    buf[3] ^= 0x5a;
    q.request_id = 4243;
    meshtopo_query_t_encode(buf, 0, size, &q);
    publish_bytes(&fx, "MESHTOPO_SUBMIT", buf, (size_t)size);
    meshtopo_ack_t ack;
    if (wait_for(&fx, &mt_msgs_type_ack, 4243, &ack) == 0) {
        CHECK_ERROR(ack.status, ack.error, MESHTOPO_STATUS_CODE_T_UNDECODABLE, "mesh_t");
        meshtopo_ack_t_decode_cleanup(&ack);
    }
    check_still_serving(&fx, "cube");
    free(buf);
    fixture_free(&fx);
}

/* Submits m (changed by the caller) and checks the error ack. */
static void check_submit_error(fixture *fx, meshtopo_mesh_t *m, int32_t status, const char *needle,
                               int line)
{
    m->request_id = fx->next_request_id++;
    meshtopo_ack_t ack;
    if (submit(fx, m, &ack) != 0) return;
    if (ack.status != status || !strstr(ack.error, needle))
        mt_test_fail(__FILE__, line, "submit: status %d '%s', expected %d naming '%s'",
                     (int)ack.status, ack.error, (int)status, needle);
    CHECK_EQ(ack.version, 0);
    meshtopo_ack_t_decode_cleanup(&ack);
}

static void test_bad_counts(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    mt_face_list cube;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &cube));
    meshtopo_mesh_t m = mesh_msg(&fx, "bad", &cube);
    m.num_verts = -8;
    m.num_position_values = 0;
    check_submit_error(&fx, &m, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "num_verts", __LINE__);
    m = mesh_msg(&fx, "bad", &cube);
    m.num_verts = 9; /* positions hold 8 */
    check_submit_error(&fx, &m, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "num_position_values",
                       __LINE__);
    int32_t counts[6] = {4, 4, 4, 4, 8, -4};
    m = mesh_msg(&fx, "bad", &cube);
    m.face_vertex_counts = counts;
    check_submit_error(&fx, &m, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "face_vertex_counts[5]",
                       __LINE__);
    int32_t counts2[6] = {4, 4, 4, 4, 4, 3};
    m.face_vertex_counts = counts2;
    check_submit_error(&fx, &m, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "num_indices", __LINE__);
    check_still_serving(&fx, "cube");
    mt_face_list_free(&cube);
    fixture_free(&fx);
}

static void test_bad_too_large(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    mt_face_list empty;
    memset(&empty, 0, sizeof empty);
    meshtopo_mesh_t m = mesh_msg(&fx, "huge", &empty);
    m.num_verts = 100001; /* the fixture's --max-verts is 100000 */
    check_submit_error(&fx, &m, MESHTOPO_STATUS_CODE_T_TOO_LARGE, "--max-verts", __LINE__);
    m.num_verts = 2000000000;
    check_submit_error(&fx, &m, MESHTOPO_STATUS_CODE_T_TOO_LARGE, "num_verts", __LINE__);
    /* 200,001 triangles on 3 vertices: over the fixture's --max-faces 200000. */
    mt_face_list many;
    CHECK_OK(mt_face_list_alloc(&many, 3, 200001, 3 * 200001, NULL));
    for (uint32_t f = 0; f < many.num_faces; f++) {
        many.face_sizes[f] = 3;
        for (uint32_t k = 0; k < 3; k++) many.face_indices[3 * f + k] = k;
    }
    m = mesh_msg(&fx, "huge", &many);
    check_submit_error(&fx, &m, MESHTOPO_STATUS_CODE_T_TOO_LARGE, "--max-faces", __LINE__);
    check_still_serving(&fx, "cube");
    mt_face_list_free(&many);
    fixture_free(&fx);
}

/* A mesh_t of six triangles on the last 18 of num_verts vertices, without
 * positions: about a hundred bytes whatever num_verts claims. `sizes` and
 * `indices` (6 and 18 entries) are filled here and must outlive it. */
static meshtopo_mesh_t sparse_msg(fixture *fx, const char *id, int32_t num_verts, int32_t *sizes,
                                  int32_t *indices)
{
    for (int i = 0; i < 6; i++) sizes[i] = 3;
    for (int i = 0; i < 18; i++) indices[i] = num_verts - 1 - i;
    meshtopo_mesh_t m;
    memset(&m, 0, sizeof m);
    m.request_id = fx->next_request_id++;
    m.reply_channel = REPLY_CHANNEL;
    m.mesh_id = (char *)id;
    m.source = "sparse";
    m.num_verts = num_verts;
    m.num_faces = 6;
    m.face_vertex_counts = sizes;
    m.num_indices = 18;
    m.face_vertex_indices = indices;
    return m;
}

/* Tiny mesh_t claiming the most vertices the default limits allow (no
 * positions, six faces), across many ids: each refused by its claim before
 * any build, with both figures named; nothing built, memory flat. */
static void test_hostile_claims(void)
{
    fixture fx;
    char *argv[] = {"meshtopod", "--log-level", "error"}; /* the default limits */
    fixture_init_with(&fx, 3, argv);
    long rss_before = mt_test_rss_kb();
    int32_t sizes[6], indices[18];
    mtd_counters before;
    mtd_daemon_get_counts(fx.daemon, &before);
    for (int k = 0; k < 40; k++) {
        char id[32];
        snprintf(id, sizeof id, "claim-%d", k);
        meshtopo_mesh_t m = sparse_msg(&fx, id, 16 << 20, sizes, indices);
        CHECK(meshtopo_mesh_t_encoded_size(&m) < 200);
        check_submit_error(&fx, &m, MESHTOPO_STATUS_CODE_T_TOO_LARGE, "--max-claim-ratio",
                           __LINE__);
    }
    mtd_counters after;
    mtd_daemon_get_counts(fx.daemon, &after);
    CHECK_EQ(after.builds, before.builds);
    long rss_after = mt_test_rss_kb();
    CHECK(rss_before > 0 && rss_after - rss_before < 32 * 1024);
    /* --max-claim-ratio 0: the user who really sends such meshes. */
    fixture_free(&fx);
    char *lenient[] = {"meshtopod", "--log-level", "error", "--max-claim-ratio", "0"};
    fixture_init_with(&fx, 5, lenient);
    meshtopo_mesh_t m = sparse_msg(&fx, "sparse", 1 << 20, sizes, indices);
    meshtopo_ack_t ack;
    CHECK_EQ(submit(&fx, &m, &ack), 0);
    CHECK_EQ(ack.status, MESHTOPO_STATUS_CODE_T_OK);
    meshtopo_ack_t_decode_cleanup(&ack);
    fixture_free(&fx);
}

/* Two daemons started together on one prefix (both past their start-up
 * listening): each notes the other in its error log (the heartbeat's
 * last_error) and goes on serving, since a heartbeat can be forged; the one
 * that started later knows the other is older. */
static void test_second_daemon_noted(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    mtd_config config;
    mtd_config_action action;
    mt_diag diag;
    char *argv[] = {"meshtopod", "--name", "younger", "--log-level", "error"};
    CHECK_OK(mtd_config_parse(5, argv, &config, &action, &diag));
    struct timespec pause = {0, 2000000L};
    nanosleep(&pause, NULL); /* a later start time */
    mtd_daemon *younger = NULL;
    CHECK_OK(mtd_daemon_create(&config, fx.lcm, NULL, &younger, &diag));
    char who[256] = "";
    CHECK(!mtd_daemon_other_seen(younger, who, sizeof who));
    mtd_counters before;
    mtd_daemon_get_counts(fx.daemon, &before);
    mtd_daemon_heartbeat(fx.daemon);
    mtd_daemon_heartbeat(younger);
    for (int i = 0; i < 50; i++) lcm_handle_timeout(fx.lcm, 5);
    CHECK(mtd_daemon_other_seen(younger, who, sizeof who));
    CHECK(strstr(who, mtd_daemon_instance(fx.daemon)) != NULL);
    CHECK(strstr(who, "'meshtopod'") != NULL);
    CHECK(!mtd_daemon_other_seen(fx.daemon, who, sizeof who));
    mtd_counters after;
    mtd_daemon_get_counts(fx.daemon, &after);
    CHECK_EQ(after.errors, before.errors + 1); /* the younger one, noted once */
    mtd_daemon_heartbeat(younger);
    for (int i = 0; i < 20; i++) lcm_handle_timeout(fx.lcm, 5);
    mtd_daemon_get_counts(fx.daemon, &after);
    CHECK_EQ(after.errors, before.errors + 1);
    mtd_daemon_heartbeat(fx.daemon);
    int beats = fx.status_messages;
    for (int i = 0; i < 50 && fx.status_messages == beats; i++) lcm_handle_timeout(fx.lcm, 5);
    CHECK(fx.have_status && strstr(fx.last_status.last_error, "another meshtopod") &&
          strstr(fx.last_status.last_error, mtd_daemon_instance(younger)));
    mtd_daemon_destroy(younger);
    check_still_serving(&fx, "cube");
    fixture_free(&fx);
}

/* Counts the flooder's answers: BUSY replies whole, served ones in parts. */
typedef struct flood_count {
    int busy, other_replies, parts;
} flood_count;

static void on_flood_answer(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    flood_count *n = user;
    if (strstr(channel, "_PART")) {
        n->parts++;
        return;
    }
    meshtopo_reply_t r;
    if (mt_msgs_decode(&mt_msgs_type_reply, rbuf->data, rbuf->data_size, &r, NULL, 0) != 0) return;
    if (r.status == MESHTOPO_STATUS_CODE_T_BUSY && strstr(r.error, "'FLOOD' used"))
        n->busy++;
    else
        n->other_replies++;
    meshtopo_reply_t_decode_cleanup(&r);
}

/* One sender floods one-rings of every vertex without waiting for answers;
 * another asks small queries in between: the flooder is answered BUSY once
 * over its share of the LCM thread, the other is always served. */
static void test_query_flood_shared(void)
{
    fixture fx;
    fixture_init(&fx);
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(120, 120, true, &grid));
    CHECK_EQ(submit_ok(&fx, "grid", &grid), 1);
    int32_t n = (int32_t)grid.num_verts;
    int32_t *all = malloc((size_t)n * sizeof *all);
    for (int32_t i = 0; i < n; i++) all[i] = i;
    flood_count count = {0, 0, 0};
    lcm_subscription_t *sub = lcm_subscribe(fx.lcm, "FLOOD_(REPLY|PART)", on_flood_answer, &count);
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.reply_channel = "FLOOD";
    q.instance = "";
    q.mesh_id = "grid";
    q.kind = MESHTOPO_QUERY_T_VERTEX_RING;
    q.num_ids = n;
    q.ids = all;
    int served = 0;
    int64_t deadline = mtd_monotonic_us() + 15 * 1000000LL;
    for (int round = 0; round < 400 && count.busy == 0 && mtd_monotonic_us() < deadline; round++) {
        for (int k = 0; k < 10; k++) {
            q.request_id = 100000 + round * 10 + k;
            publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
        }
        int32_t vertex = round % n;
        meshtopo_reply_t r;
        if (query(&fx, "grid", 0, MESHTOPO_QUERY_T_VALENCE, &vertex, 1, &r) == 0) {
            CHECK_EQ(r.status, MESHTOPO_STATUS_CODE_T_OK);
            served += r.status == MESHTOPO_STATUS_CODE_T_OK;
            meshtopo_reply_t_decode_cleanup(&r);
        }
    }
    CHECK(count.busy > 0);
    CHECK(count.parts > 0); /* served while under its share */
    CHECK(served > 0);
    lcm_unsubscribe(fx.lcm, sub);
    free(all);
    mt_face_list_free(&grid);
    fixture_free(&fx);
}

static void test_bad_mesh_ids(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    mt_face_list tet;
    CHECK_OK(mt_gen_platonic(MT_TETRAHEDRON, &tet));
    char *long_id = malloc(10 * 1024 + 1);
    memset(long_id, 'a', 10 * 1024);
    long_id[10 * 1024] = 0;
    const char *ids[] = {"../x", "a/b", "", long_id, "tab\there"};
    for (size_t i = 0; i < sizeof ids / sizeof ids[0]; i++) {
        meshtopo_mesh_t m = mesh_msg(&fx, ids[i], &tet);
        check_submit_error(&fx, &m, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "mesh_id", __LINE__);
        int32_t v = 0;
        check_query_error(&fx, ids[i], 0, MESHTOPO_QUERY_T_VALENCE, &v, 1,
                          MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "mesh_id", __LINE__);
    }
    meshtopo_reply_t r;
    if (query(&fx, "", 0, MESHTOPO_QUERY_T_LIST_MESHES, NULL, 0, &r) == 0) {
        CHECK_EQ(r.num_meshes, 1); /* only the cube was stored */
        meshtopo_reply_t_decode_cleanup(&r);
    }
    check_still_serving(&fx, "cube");
    free(long_id);
    mt_face_list_free(&tet);
    fixture_free(&fx);
}

static void test_bad_queries(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    int32_t ids[] = {0, 1, 2};
    check_query_error(&fx, "nosuch", 0, MESHTOPO_QUERY_T_VALENCE, ids, 1,
                      MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH, "nosuch", __LINE__);
    check_query_error(&fx, "cube", 9, MESHTOPO_QUERY_T_VALENCE, ids, 1,
                      MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH, "version 9", __LINE__);
    check_query_error(&fx, "cube", 0, 42, ids, 1, MESHTOPO_STATUS_CODE_T_UNKNOWN_KIND, "kind: 42",
                      __LINE__);
    check_query_error(&fx, "cube", 0, 0, ids, 1, MESHTOPO_STATUS_CODE_T_UNKNOWN_KIND, "kind: 0",
                      __LINE__);
    int32_t out_of_range[] = {0, 8};
    check_query_error(&fx, "cube", 0, MESHTOPO_QUERY_T_VERTEX_RING, out_of_range, 2,
                      MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE, "ids[1] = 8", __LINE__);
    int32_t negative[] = {-1};
    check_query_error(&fx, "cube", 0, MESHTOPO_QUERY_T_FACE_NEIGHBORS, negative, 1,
                      MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE, "ids[0] = -1", __LINE__);
    int32_t faces[] = {6};
    check_query_error(&fx, "cube", 0, MESHTOPO_QUERY_T_COMPONENTS, faces, 1,
                      MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE, "face", __LINE__);
    check_query_error(&fx, "cube", 0, MESHTOPO_QUERY_T_EDGE_FACES, ids, 3,
                      MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "odd", __LINE__);
    check_query_error(&fx, "cube", 0, MESHTOPO_QUERY_T_VERTEX_RING, NULL, 0,
                      MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "needs ids", __LINE__);
    check_query_error(&fx, "cube", 0, MESHTOPO_QUERY_T_REPORT, ids, 1,
                      MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "takes no ids", __LINE__);
    int32_t bad_kind[] = {8};
    check_query_error(&fx, "cube", 0, MESHTOPO_QUERY_T_DEFECTS, bad_kind, 1,
                      MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "DEFECT_", __LINE__);
    check_query_error(&fx, "cube", -1, MESHTOPO_QUERY_T_VALENCE, ids, 1,
                      MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "version", __LINE__);
    check_still_serving(&fx, "cube");
    fixture_free(&fx);
}

/* ---- geometry kinds ---- */

/* The daemon's DIHEDRAL_ANGLES, ANGLE_DEFICITS and CONVEXITY answers for
 * `list` equal what meshtopo/geometry.h answers on the same mesh built here:
 * every side of every face as an edge (plus one pair that is no edge), every
 * vertex, and the whole mesh. Doubles must be equal bit for bit: the same
 * code computes them on the same input. */
static void check_geometry(fixture *fx, const char *id, const mt_face_list *list, bool convex)
{
    const double tol = MESHTOPO_QUERY_T_GEOMETRY_TOLERANCE;
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(list, NULL, &mesh, NULL));
    CHECK_OK(mt_mesh_validate(mesh, NULL));
    if (submit_ok(fx, id, list) == 0) {
        mt_mesh_destroy(mesh);
        return;
    }
    /* Edges: the sides of every face, then a pair no face joins. */
    int32_t *pairs = malloc((2 * list->num_indices + 2) * sizeof *pairs);
    int32_t n = 0;
    uint64_t offset = 0;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        uint32_t size = list->face_sizes[f];
        for (uint32_t k = 0; k < size; k++) {
            pairs[n++] = (int32_t)list->face_indices[offset + k];
            pairs[n++] = (int32_t)list->face_indices[offset + (k + 1) % size];
        }
        offset += size;
    }
    int32_t lonely_a = -1, lonely_b = -1;
    for (uint32_t a = 0; a < list->num_verts && lonely_a < 0; a++)
        for (uint32_t b = a + 1; b < list->num_verts && lonely_a < 0; b++) {
            size_t count = 0;
            if (mt_edge_faces(mesh, a, b, NULL, 0, &count) == MT_ERR_NOT_FOUND)
                lonely_a = (int32_t)a, lonely_b = (int32_t)b;
        }
    CHECK(lonely_a >= 0);
    pairs[n++] = lonely_a;
    pairs[n++] = lonely_b;

    meshtopo_reply_t r;
    if (query(fx, id, 0, MESHTOPO_QUERY_T_DIHEDRAL_ANGLES, pairs, n, &r) == 0) {
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.num_items, n / 2);
        CHECK_EQ(r.num_reals, n / 2);
        for (int32_t i = 0; i < r.num_items && r.num_reals == r.num_items; i++) {
            uint32_t a = (uint32_t)pairs[2 * i], b = (uint32_t)pairs[2 * i + 1];
            mt_edge_shape shape;
            mt_status s = mt_edge_convexity(mesh, a, b, tol, &shape, NULL);
            if (s == MT_ERR_NOT_FOUND) {
                CHECK_EQ(r.item_status[i], MESHTOPO_STATUS_CODE_T_NOT_FOUND);
                CHECK(isnan(r.reals[i]));
                continue;
            }
            CHECK_OK(s);
            CHECK_EQ(r.item_status[i], MESHTOPO_STATUS_CODE_T_OK);
            int32_t g = r.item_offsets[i];
            CHECK_EQ(r.item_offsets[i + 1], g + 1);
            CHECK_EQ(r.value_offsets[g + 1] - r.value_offsets[g], 1);
            CHECK_EQ(r.values[r.value_offsets[g]], (int32_t)shape);
            if (shape <= MT_EDGE_REFLEX) {
                double angle = 0.0;
                CHECK_OK(mt_edge_dihedral_angle(mesh, a, b, &angle, NULL));
                if (memcmp(&angle, &r.reals[i], sizeof angle) != 0)
                    mt_test_fail(__FILE__, __LINE__,
                                 "edge %u-%u: angle %.17g over the wire, %.17g here", a, b,
                                 r.reals[i], angle);
            } else {
                CHECK(isnan(r.reals[i]));
            }
        }
        meshtopo_reply_t_decode_cleanup(&r);
    }
    free(pairs);

    int32_t *verts = malloc(list->num_verts * sizeof *verts);
    for (uint32_t v = 0; v < list->num_verts; v++) verts[v] = (int32_t)v;
    if (query(fx, id, 0, MESHTOPO_QUERY_T_ANGLE_DEFICITS, verts, (int32_t)list->num_verts, &r) ==
        0) {
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.num_items, (int32_t)list->num_verts);
        CHECK_EQ(r.num_reals, (int32_t)list->num_verts);
        for (int32_t i = 0; i < r.num_items && r.num_reals == r.num_items; i++) {
            double deficit = 0.0;
            bool boundary = false;
            CHECK_OK(mt_vert_angle_deficit(mesh, (uint32_t)i, &deficit, &boundary, NULL));
            CHECK(memcmp(&deficit, &r.reals[i], sizeof deficit) == 0);
            CHECK_EQ(r.group_boundary[r.item_offsets[i]] != 0, boundary);
        }
        meshtopo_reply_t_decode_cleanup(&r);
    }
    free(verts);

    mt_convexity c;
    uint32_t reflex[256];
    CHECK_OK(mt_mesh_convexity(mesh, tol, &c, reflex, 128, NULL));
    CHECK_EQ(c.convex, convex);
    if (query(fx, id, 0, MESHTOPO_QUERY_T_CONVEXITY, NULL, 0, &r) == 0) {
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.num_items, 1);
        CHECK_EQ(r.num_groups, 2);
        CHECK_EQ(r.num_reals, 1);
        if (r.num_groups == 2 && r.num_reals == 1) {
            CHECK_EQ(r.value_offsets[1], 4);
            CHECK_EQ(r.values[0], c.convex ? 1 : 0);
            CHECK_EQ(r.values[1], (int32_t)c.reasons);
            CHECK_EQ(r.values[2], (int32_t)c.num_reflex);
            CHECK_EQ(r.values[3], (int32_t)c.num_degenerate);
            CHECK_EQ(r.value_offsets[2] - r.value_offsets[1], 2 * (int32_t)c.num_reflex);
            for (size_t k = 0; k < 2 * c.num_reflex && r.value_offsets[2] == r.num_values; k++)
                CHECK_EQ(r.values[4 + k], (int32_t)reflex[k]);
            CHECK(memcmp(&c.volume, &r.reals[0], sizeof c.volume) == 0);
        }
        meshtopo_reply_t_decode_cleanup(&r);
    }
    mt_mesh_destroy(mesh);
}

static void test_geometry_kinds(void)
{
    fixture fx;
    fixture_init(&fx);
    mt_face_list ico, grid;
    CHECK_OK(mt_gen_platonic(MT_ICOSAHEDRON, &ico));
    check_geometry(&fx, "icosahedron", &ico, true);
    /* Vertex 0 pushed towards the centre: its edges turn reflex. */
    for (int k = 0; k < 3; k++) ico.positions[k] *= 0.2;
    check_geometry(&fx, "dented", &ico, false);
    CHECK_OK(mt_gen_grid(3, 2, true, &grid));
    check_geometry(&fx, "grid", &grid, false); /* open: boundary edges have no angle */

    /* A mesh without positions: NO_GEOMETRY for every geometry kind. */
    free(grid.positions);
    grid.positions = NULL;
    CHECK_EQ(submit_ok(&fx, "bare", &grid), 1);
    int32_t ids[] = {0, 1, 2};
    check_query_error(&fx, "bare", 0, MESHTOPO_QUERY_T_DIHEDRAL_ANGLES, ids, 2,
                      MESHTOPO_STATUS_CODE_T_NO_GEOMETRY, "positions", __LINE__);
    check_query_error(&fx, "bare", 0, MESHTOPO_QUERY_T_ANGLE_DEFICITS, ids, 3,
                      MESHTOPO_STATUS_CODE_T_NO_GEOMETRY, "positions", __LINE__);
    check_query_error(&fx, "bare", 0, MESHTOPO_QUERY_T_CONVEXITY, NULL, 0,
                      MESHTOPO_STATUS_CODE_T_NO_GEOMETRY, "positions", __LINE__);
    /* Bad requests. */
    check_query_error(&fx, "grid", 0, MESHTOPO_QUERY_T_DIHEDRAL_ANGLES, ids, 3,
                      MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "odd", __LINE__);
    check_query_error(&fx, "grid", 0, MESHTOPO_QUERY_T_CONVEXITY, ids, 1,
                      MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "takes no ids", __LINE__);
    int32_t far[] = {0, 1000};
    check_query_error(&fx, "grid", 0, MESHTOPO_QUERY_T_ANGLE_DEFICITS, far, 2,
                      MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE,
                      "ids[1] = 1000: no such vertex (mesh 'grid' has 12 vertices)", __LINE__);
    check_query_error(&fx, "grid", 0, MESHTOPO_QUERY_T_DIHEDRAL_ANGLES, far, 2,
                      MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE, "ids[1] = 1000", __LINE__);
    check_still_serving(&fx, "grid");
    mt_face_list_free(&ico);
    mt_face_list_free(&grid);
    fixture_free(&fx);
}

/* SELF_INTERSECTIONS over the wire equals the three geometry.h lists on
 * the same mesh: an octahedron with its top apex pushed out through a
 * bottom face (three face pairs) next to a pentagram face (crossing itself,
 * and so does its boundary loop). Answered by a worker; bad requests and a
 * mesh without positions refused. */
static void test_self_intersections_kind(void)
{
    fixture fx;
    fixture_init(&fx);
    double pos[33] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0.5, 0.5, -0.5, 0, 0, -1};
    for (int i = 0; i < 5; i++) { /* the pentagram, at z = 5 */
        double angle = 2 * 3.14159265358979323846 * (2 * i % 5) / 5;
        pos[18 + 3 * i] = cos(angle), pos[19 + 3 * i] = sin(angle), pos[20 + 3 * i] = 5;
    }
    uint32_t indices[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5,
                          1, 2, 5, 3, 1, 5, 0, 3, 5, 6, 7, 8, 9, 10};
    uint32_t sizes[] = {3, 3, 3, 3, 3, 3, 3, 3, 5};
    mt_face_list list = {11, 9, 29, pos, sizes, indices};
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(&list, NULL, &mesh, NULL));
    mt_face_pair pairs[8];
    mt_face_shape faces[4];
    mt_loop_crossing loops[4];
    size_t num_pairs = 0, num_faces = 0, num_loops = 0;
    CHECK_OK(mt_mesh_self_intersections(mesh, pairs, 8, &num_pairs, NULL));
    CHECK_OK(mt_mesh_nonsimple_faces(mesh, faces, 4, &num_faces, NULL));
    CHECK_OK(mt_mesh_boundary_loop_crossings(mesh, loops, 4, &num_loops, NULL));
    CHECK(num_pairs == 3 && num_faces == 1 && num_loops == 1);
    meshtopo_reply_t r;
    if (submit_ok(&fx, "pushed", &list) &&
        query(&fx, "pushed", 0, MESHTOPO_QUERY_T_SELF_INTERSECTIONS, NULL, 0, &r) == 0) {
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.num_items, 1);
        CHECK_EQ(r.num_groups, 3);
        CHECK_EQ(r.num_reals, 1);
        CHECK_EQ(r.num_values, 2 * 3 + 4 + 5);
        if (r.num_groups == 3 && r.num_values == 15 && r.num_reals == 1) {
            CHECK(r.value_offsets[1] == 6 && r.value_offsets[2] == 10);
            for (size_t i = 0; i < num_pairs; i++) {
                CHECK_EQ(r.values[2 * i], (int32_t)pairs[i].a);
                CHECK_EQ(r.values[2 * i + 1], (int32_t)pairs[i].b);
            }
            const int32_t *f = r.values + 6, *l = r.values + 10;
            CHECK(f[0] == 8 && f[0] == (int32_t)faces[0].face);
            CHECK_EQ(f[1], MT_FACE_SELF_CROSSING);
            CHECK(f[2] == (int32_t)faces[0].side_a && f[3] == (int32_t)faces[0].side_b);
            CHECK(memcmp(&r.reals[0], &faces[0].warp, sizeof(double)) == 0);
            CHECK_EQ(l[0], (int32_t)loops[0].loop);
            CHECK(l[1] == (int32_t)loops[0].edge_a[0] && l[2] == (int32_t)loops[0].edge_a[1]);
            CHECK(l[3] == (int32_t)loops[0].edge_b[0] && l[4] == (int32_t)loops[0].edge_b[1]);
        }
        meshtopo_reply_t_decode_cleanup(&r);
    }
    mt_mesh_destroy(mesh);
    int32_t ids[] = {0};
    check_query_error(&fx, "pushed", 0, MESHTOPO_QUERY_T_SELF_INTERSECTIONS, ids, 1,
                      MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "takes no ids", __LINE__);
    list.positions = NULL;
    CHECK_EQ(submit_ok(&fx, "bare", &list), 1);
    check_query_error(&fx, "bare", 0, MESHTOPO_QUERY_T_SELF_INTERSECTIONS, NULL, 0,
                      MESHTOPO_STATUS_CODE_T_NO_GEOMETRY, "positions", __LINE__);
    check_query_error(&fx, "absent", 0, MESHTOPO_QUERY_T_SELF_INTERSECTIONS, NULL, 0,
                      MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH, "absent", __LINE__);
    check_still_serving(&fx, "pushed");
    fixture_free(&fx);
}

/* Any node may ask for self-intersection checks, each long on a large
 * mesh: one runs at a time (on a worker), a second asked meanwhile is
 * answered BUSY, the next one after it is served, and so are other
 * requests throughout. */
static void test_self_intersections_one_at_a_time(void)
{
    fixture fx;
    fixture_init(&fx);
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(300, 300, true, &grid)); /* 180,000 triangles: a check takes a while */
    CHECK_EQ(submit_ok(&fx, "big", &grid), 1);
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.reply_channel = REPLY_CHANNEL;
    q.instance = "";
    q.mesh_id = "big";
    q.kind = MESHTOPO_QUERY_T_SELF_INTERSECTIONS;
    const int64_t first = fx.next_request_id++, second = fx.next_request_id++;
    q.request_id = first;
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    q.request_id = second;
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    meshtopo_reply_t r;
    if (wait_for(&fx, &mt_msgs_type_reply, second, &r) == 0) {
        CHECK_ERROR(r.status, r.error, MESHTOPO_STATUS_CODE_T_BUSY, "self-intersection check");
        meshtopo_reply_t_decode_cleanup(&r);
    }
    if (wait_for(&fx, &mt_msgs_type_reply, first, &r) == 0) {
        CHECK_EQ(r.status, MESHTOPO_STATUS_CODE_T_OK);
        CHECK_EQ(r.num_items, 1);
        meshtopo_reply_t_decode_cleanup(&r);
    }
    /* The first one answered, the next is served. */
    if (query(&fx, "big", 0, MESHTOPO_QUERY_T_SELF_INTERSECTIONS, NULL, 0, &r) == 0) {
        CHECK_EQ(r.status, MESHTOPO_STATUS_CODE_T_OK);
        meshtopo_reply_t_decode_cleanup(&r);
    }
    check_still_serving(&fx, "big");
    mt_face_list_free(&grid);
    fixture_free(&fx);
}

/* A sender's mesh of 2000 triangles stacked in parallel planes, none
 * crossing another but every two to be tested exactly (1,999,000 tests):
 * the check stops at the daemon's bound on tests (32 per face and 2^20
 * besides) with TOO_LARGE naming it, instead of holding a worker for all
 * of them; the daemon serves on. */
static void test_self_intersections_of_a_stack(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    enum { N = 2000 };
    double *pos = malloc(9 * (size_t)N * sizeof *pos);
    uint32_t *indices = malloc(3 * (size_t)N * sizeof *indices);
    uint32_t *sizes = malloc(N * sizeof *sizes);
    CHECK(pos && indices && sizes);
    if (pos && indices && sizes) {
        for (uint32_t f = 0; f < N; f++) {
            const double c = 0.00001 * f;
            const double corners[9] = {0, 0, c, 1, 0, c + 0.5, 0, 1, c + 0.5};
            memcpy(pos + 9 * (size_t)f, corners, sizeof corners);
            for (uint32_t k = 0; k < 3; k++) indices[3 * f + k] = 3 * f + k;
            sizes[f] = 3;
        }
        mt_face_list stack = {3 * N, N, 3 * N, pos, sizes, indices};
        CHECK_EQ(submit_ok(&fx, "stack", &stack), 1);
        check_query_error(&fx, "stack", 0, MESHTOPO_QUERY_T_SELF_INTERSECTIONS, NULL, 0,
                          MESHTOPO_STATUS_CODE_T_TOO_LARGE,
                          "more than 1112576 pairs of triangles whose boxes overlap", __LINE__);
        check_still_serving(&fx, "cube");
    }
    free(pos);
    free(indices);
    free(sizes);
    fixture_free(&fx);
}

static void test_nan_positions(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    mt_face_list tet;
    CHECK_OK(mt_gen_platonic(MT_TETRAHEDRON, &tet));
    tet.positions[3 * 2 + 1] = NAN;
    /* Not strict: stored, and the report lists the non-finite coordinate. */
    meshtopo_mesh_t m = mesh_msg(&fx, "nan", &tet);
    meshtopo_ack_t ack;
    if (submit(&fx, &m, &ack) == 0) {
        CHECK_EQ(ack.status, 0);
        CHECK_EQ(ack.num_reports, 1);
        if (ack.num_reports == 1) {
            const meshtopo_topology_t *t = &ack.reports[0];
            CHECK_EQ(t->nonfinite_vertices, 1);
            CHECK_EQ(t->num_defects_listed, 1);
            if (t->num_defects_listed == 1) {
                CHECK_EQ(t->defect_kind[0], MESHTOPO_TOPOLOGY_T_DEFECT_NONFINITE_COORD);
                CHECK_EQ(t->defect_a[0], 2);
                CHECK_EQ(t->defect_b[0], 1);
            }
        }
        meshtopo_ack_t_decode_cleanup(&ack);
    }
    /* Strict: refused, with the report and an error naming the defect. */
    m = mesh_msg(&fx, "nan_strict", &tet);
    m.strict = 1;
    if (submit(&fx, &m, &ack) == 0) {
        CHECK_ERROR(ack.status, ack.error, MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED, "vertex 2");
        CHECK_EQ(ack.version, 0);
        CHECK_EQ(ack.num_reports, 1);
        meshtopo_ack_t_decode_cleanup(&ack);
    }
    check_query_error(&fx, "nan_strict", 0, MESHTOPO_QUERY_T_REPORT, NULL, 0,
                      MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH, "nan_strict", __LINE__);
    check_still_serving(&fx, "cube");
    mt_face_list_free(&tet);
    fixture_free(&fx);
}

/* A request is remembered under the channel of its answer: a query_t that
 * reuses the request id of an earlier mesh_t is a new request and gets a
 * reply_t, not the remembered ack; both stay remembered apart. */
static void test_request_id_shared_by_kinds(void)
{
    fixture fx;
    fixture_init(&fx);
    mt_face_list tet;
    CHECK_OK(mt_gen_platonic(MT_TETRAHEDRON, &tet));
    meshtopo_mesh_t m = mesh_msg(&fx, "tet", &tet);
    m.request_id = 4242;
    meshtopo_ack_t ack;
    if (submit(&fx, &m, &ack) == 0) {
        CHECK_EQ(ack.status, 0);
        meshtopo_ack_t_decode_cleanup(&ack);
    }
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.request_id = 4242;
    q.reply_channel = REPLY_CHANNEL;
    q.instance = "";
    q.mesh_id = "tet";
    q.kind = MESHTOPO_QUERY_T_VALENCE;
    int32_t v = 0;
    q.num_ids = 1;
    q.ids = &v;
    meshtopo_reply_t r;
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    if (wait_for(&fx, &mt_msgs_type_reply, 4242, &r) == 0) {
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.num_items, 1);
        CHECK_EQ(r.values[0], 3); /* a tetrahedron's vertex has three neighbours */
        meshtopo_reply_t_decode_cleanup(&r);
    }
    /* Each sent again: each answered from its own memory, nothing run twice. */
    mtd_counters before;
    mtd_daemon_get_counts(fx.daemon, &before);
    if (submit(&fx, &m, &ack) == 0) {
        CHECK_EQ(ack.version, 1);
        meshtopo_ack_t_decode_cleanup(&ack);
    }
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    if (wait_for(&fx, &mt_msgs_type_reply, 4242, &r) == 0) {
        CHECK_EQ(r.num_items, 1);
        meshtopo_reply_t_decode_cleanup(&r);
    }
    mtd_counters after;
    mtd_daemon_get_counts(fx.daemon, &after);
    CHECK_EQ(after.builds, before.builds);
    CHECK_EQ(after.duplicates, before.duplicates + 2);
    mt_face_list_free(&tet);
    fixture_free(&fx);
}

static void test_duplicate_request(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    mt_face_list tet;
    CHECK_OK(mt_gen_platonic(MT_TETRAHEDRON, &tet));
    meshtopo_mesh_t m = mesh_msg(&fx, "tet", &tet);
    meshtopo_ack_t first, again;
    if (submit(&fx, &m, &first) == 0) {
        if (submit(&fx, &m, &again) == 0) {
            CHECK_EQ(again.status, 0);
            CHECK_EQ(again.version, first.version);
            CHECK_EQ(again.utime, first.utime); /* the same bytes, not a new ack */
            meshtopo_ack_t_decode_cleanup(&again);
        }
        meshtopo_ack_t_decode_cleanup(&first);
    }
    mtd_counters counts;
    mtd_daemon_get_counts(fx.daemon, &counts);
    CHECK_EQ(counts.builds, 2); /* cube and tet, not tet twice */
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.request_id = 777;
    q.reply_channel = REPLY_CHANNEL;
    q.instance = "";
    q.mesh_id = "tet";
    q.kind = MESHTOPO_QUERY_T_REPORT;
    meshtopo_reply_t r1, r2;
    publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
    if (wait_for(&fx, &mt_msgs_type_reply, 777, &r1) == 0) {
        publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
        if (wait_for(&fx, &mt_msgs_type_reply, 777, &r2) == 0) {
            CHECK_EQ(r2.status, 0);
            CHECK_EQ(r2.utime, r1.utime);
            meshtopo_reply_t_decode_cleanup(&r2);
        }
        meshtopo_reply_t_decode_cleanup(&r1);
    }
    mtd_daemon_get_counts(fx.daemon, &counts);
    CHECK_EQ(counts.duplicates, 2);
    mt_face_list_free(&tet);
    fixture_free(&fx);
}

static void test_heartbeat(void)
{
    fixture fx;
    fixture_with_cube(&fx);
    int32_t v = 100;
    check_query_error(&fx, "cube", 0, MESHTOPO_QUERY_T_VALENCE, &v, 1,
                      MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE, "ids[0]", __LINE__);
    mtd_daemon_heartbeat(fx.daemon);
    for (int i = 0; i < 100 && !fx.have_status; i++) lcm_handle_timeout(fx.lcm, 50);
    CHECK(fx.have_status);
    if (fx.have_status) {
        const meshtopo_status_t *s = &fx.last_status;
        CHECK(strcmp(s->name, "meshtopod") == 0);
        CHECK(strcmp(s->channel_prefix, "MESHTOPO_") == 0);
        CHECK_EQ(s->meshes_held, 1);
        CHECK_EQ(s->versions_held, 1);
        CHECK(s->memory_bytes > 0);
        CHECK_EQ(s->submissions, 1);
        CHECK_EQ(s->builds, 1);
        CHECK_EQ(s->queries, 1);
        CHECK_EQ(s->errors, 1);
        CHECK_EQ(s->worker_threads, 2);
        CHECK(strstr(s->last_error, "ids[0] = 100") != NULL);
        CHECK(s->last_error_utime > 0);
    }
    fixture_free(&fx);
}

/* Removes a flat directory (an archive) and what it holds. */
static void remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        unlink(path);
    }
    if (d) closedir(d);
    rmdir(dir);
}

/* Lets every daemon on fx's LCM hear the others' heartbeats and act on it. */
static void let_members_meet(fixture *fx, mtd_daemon *const *daemons, int n)
{
    for (int i = 0; i < n; i++) mtd_daemon_heartbeat(daemons[i]);
    for (int i = 0; i < 50; i++) lcm_handle_timeout(fx->lcm, 2);
    for (int i = 0; i < n; i++) mtd_daemon_watch_cluster(daemons[i]);
}

/* Two members of a cluster in one process, on one in-process LCM and one
 * archive directory, their builds on two workers each: every id built and
 * acknowledged once, the listings of the two members split the ids; then
 * one member gone silent: the other takes its ids over and serves them from
 * the archive; then two members whose views disagree both build the same
 * ids, and the archive numbers the versions (the builds race on the same
 * names). */
static void test_cluster_in_process(void)
{
    char dir[] = "/tmp/meshtopo-cluster-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char *argv_a[] = {"meshtopod", "--cluster", "t", "--archive",   dir,     "--workers",
                      "2",         "--name",    "a", "--log-level", "error", "--heartbeat-ms",
                      "200"};
    fixture fx;
    fixture_init_with(&fx, 13, argv_a);
    char *argv_b[13];
    memcpy(argv_b, argv_a, sizeof argv_b);
    argv_b[8] = "b";
    mtd_config config_b;
    mtd_config_action action;
    mt_diag diag;
    CHECK_OK(mtd_config_parse(13, argv_b, &config_b, &action, &diag));
    mtd_daemon *b = NULL;
    CHECK_OK(mtd_daemon_create(&config_b, fx.lcm, NULL, &b, &diag));
    if (!b) return;
    mtd_daemon *both[2] = {fx.daemon, b};
    let_members_meet(&fx, both, 2);

    mt_face_list tet;
    CHECK_OK(mt_gen_platonic(MT_TETRAHEDRON, &tet));
    enum { IDS = 40 };
    char ids[IDS][16];
    for (int k = 0; k < IDS; k++) {
        snprintf(ids[k], sizeof ids[k], "part-%d", k);
        CHECK_EQ(submit_ok(&fx, ids[k], &tet), 1);
    }
    for (int i = 0; i < 50; i++) lcm_handle_timeout(fx.lcm, 2);
    CHECK_EQ(fx.num_inbox, 0); /* no second ack */
    mtd_counters ca, cb;
    mtd_daemon_get_counts(fx.daemon, &ca);
    mtd_daemon_get_counts(b, &cb);
    CHECK_EQ(ca.builds + cb.builds, IDS);
    CHECK(ca.builds >= 8 && cb.builds >= 8);

    /* Each member lists the ids it owns. */
    int listed = 0;
    for (int i = 0; i < 2; i++) {
        meshtopo_query_t q;
        memset(&q, 0, sizeof q);
        q.reply_channel = REPLY_CHANNEL;
        q.mesh_id = "";
        q.kind = MESHTOPO_QUERY_T_LIST_MESHES;
        q.request_id = 7000 + i;
        q.instance = (char *)mtd_daemon_instance(both[i]);
        publish(&fx, "MESHTOPO_QUERY", &mt_msgs_type_query, &q);
        meshtopo_reply_t r;
        if (wait_for(&fx, &mt_msgs_type_reply, q.request_id, &r) != 0) continue;
        CHECK_EQ(r.num_meshes, i == 0 ? ca.builds : cb.builds);
        listed += r.num_meshes;
        meshtopo_reply_t_decode_cleanup(&r);
    }
    CHECK_EQ(listed, IDS);

    /* b goes silent: once the expiry passes, a owns every id and loads b's
     * meshes from the archive. */
    mtd_daemon_destroy(b);
    b = NULL;
    struct timespec pause = {0, 500 * 1000 * 1000}; /* beyond 2 heartbeat periods */
    nanosleep(&pause, NULL);
    mtd_daemon_watch_cluster(fx.daemon);
    for (int k = 0; k < IDS; k++) {
        meshtopo_reply_t r;
        if (query(&fx, ids[k], 0, MESHTOPO_QUERY_T_REPORT, NULL, 0, &r) != 0) continue;
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.version, 1);
        meshtopo_reply_t_decode_cleanup(&r);
    }

    /* c joins but ignores a's heartbeats: c believes it owns every id, a
     * owns about half of them (it hears c). A second submission of each id
     * is built by both for a's half: every build is archived under its own
     * number. */
    char *argv_c[15];
    memcpy(argv_c, argv_a, sizeof argv_a);
    argv_c[8] = "c";
    argv_c[13] = "--test-ignore-member";
    argv_c[14] = "a";
    mtd_config config_c;
    CHECK_OK(mtd_config_parse(15, argv_c, &config_c, &action, &diag));
    mtd_daemon *c = NULL;
    CHECK_OK(mtd_daemon_create(&config_c, fx.lcm, NULL, &c, &diag));
    if (c) {
        mtd_daemon *pair[2] = {fx.daemon, c};
        let_members_meet(&fx, pair, 2);
        for (int k = 0; k < IDS; k++) CHECK(submit_ok(&fx, ids[k], &tet) >= 2);
        for (int i = 0; i < 100; i++) lcm_handle_timeout(fx.lcm, 2);
        mtd_daemon_destroy(c);
    }
    /* Whoever built them, every version number of an id is used once. */
    mt_archive *archive = NULL;
    CHECK_OK(mt_archive_open(dir, &(mt_archive_options){.read_only = true}, &archive, &diag));
    mt_archive_listing l;
    if (archive && mt_archive_list(archive, &l, &diag) == MT_OK) {
        int second = 0;
        for (size_t i = 0; i < l.count; i++) {
            CHECK_OK(l.entries[i].status);
            second += l.entries[i].version >= 2;
            if (i > 0 && l.entries[i].status == MT_OK && l.entries[i - 1].status == MT_OK &&
                strcmp(l.entries[i].mesh_id, l.entries[i - 1].mesh_id) == 0)
                CHECK(l.entries[i].version != l.entries[i - 1].version);
        }
        CHECK(second >= IDS);          /* one second version at least per id */
        CHECK((int)l.count > 2 * IDS); /* and a third one for the ids c built too */
        mt_archive_listing_free(&l);
    }
    mt_archive_close(archive);
    mt_face_list_free(&tet);
    fixture_free(&fx);
    remove_dir(dir);
}

static const mt_test_case cases[] = {
    {"every_kind_has_an_answerer", test_every_kind_has_an_answerer},
    {"generated_every_kind", test_generated_every_kind},
    {"corpus_every_kind", test_corpus_every_kind},
    {"versions_and_list", test_versions_and_list},
    {"content_hash", test_content_hash},
    {"bad_undecodable", test_bad_undecodable},
    {"bad_fingerprint", test_bad_fingerprint},
    {"bad_channels", test_bad_channels},
    {"bad_counts", test_bad_counts},
    {"bad_too_large", test_bad_too_large},
    {"hostile_claims", test_hostile_claims},
    {"second_daemon_noted", test_second_daemon_noted},
    {"query_flood_shared", test_query_flood_shared},
    {"bad_mesh_ids", test_bad_mesh_ids},
    {"bad_queries", test_bad_queries},
    {"geometry_kinds", test_geometry_kinds},
    {"self_intersections_kind", test_self_intersections_kind},
    {"self_intersections_one_at_a_time", test_self_intersections_one_at_a_time},
    {"self_intersections_of_a_stack", test_self_intersections_of_a_stack},
    {"nan_positions", test_nan_positions},
    {"duplicate_request", test_duplicate_request},
    {"request_id_shared_by_kinds", test_request_id_shared_by_kinds},
    {"heartbeat", test_heartbeat},
    {"cluster_in_process", test_cluster_in_process},
};
const mt_test_table mt_tests_dispatch = {cases, sizeof cases / sizeof cases[0]};
