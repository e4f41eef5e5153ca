/* meshtopod_corpus_client: daemon.corpus.NAME's client, run inside netns-run
 * next to a real meshtopod. It waits for the daemon, submits the corpus mesh
 * NAME through meshtopo::client and checks that the ack's report, the REPORT
 * query's and the VERTEX_RING, VALENCE, FACE_NEIGHBORS, EDGE_FACES, COMPONENTS
 * and BOUNDARY_LOOPS answers equal NAME.expected.json (tests/corpus/
 * DEFINITIONS.md), key by key as test_core does (corpus_expect.c). */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "corpus_expect.h"
#include "harness.h"
#include "meshtopo/client.h"
#include "meshtopo/core.h"
#include "meshtopo/io.h"

/* usage: meshtopod_corpus_client NAME
 * Exit status: 0 all equal, 1 a difference or an error, SKIP_STATUS (ctest's
 * skip) when the mesh does not fit one LCM message or the receive buffer. */
#define SKIP_STATUS 77
/* Bytes of a mesh_t besides its content (header, strings), with room to spare. */
#define MESH_MSG_OVERHEAD 4096
#define HEARTBEAT_WAIT_MS 10000

/* ---- the mesh under test ------------------------------------------------ */

typedef struct run {
    const char *name;
    const cJSON *expected;
    mt_client *client;
    const mt_report *report; /* the checked report (for the query checks) */
} run;

#define fail_key(r, ...) mt_test_corpus_fail((r)->name, __VA_ARGS__)

/* The UDP receive buffer LCM's udpm gets for the URL's recv_buf_size: the
 * kernel caps the request at net.core.rmem_max and doubles it. 0 when the
 * URL asks for none or the cap is unknown. */
static uint64_t udp_receive_buffer(void)
{
    const char *url = getenv("LCM_DEFAULT_URL");
    const char *opt = url ? strstr(url, "recv_buf_size=") : NULL;
    if (!opt) return 0;
    uint64_t want = strtoull(opt + strlen("recv_buf_size="), NULL, 10), cap = 0;
    FILE *f = fopen("/proc/sys/net/core/rmem_max", "r");
    if (!f) return 0;
    if (fscanf(f, "%" SCNu64, &cap) != 1) cap = 0;
    fclose(f);
    return 2 * (want < cap ? want : cap);
}

/* ---- the report over the wire, as an mt_report -------------------------- */

static void wire_report_free(mt_report *r)
{
    free(r->boundary_loop_lengths);
    free(r->components);
    free(r->face_size_histogram);
    free(r->edge_use_histogram);
    free(r->defects);
    memset(r, 0, sizeof *r);
}

/* Fills *out from a topology_t (field for field, as topology_t.lcm mirrors
 * mt_report). Returns 0; 1 when a list is cut (*_listed below its count,
 * with what in why); -1 out of memory or a negative count. */
static int wire_report(const meshtopo_topology_t *t, mt_report *out, char *why, size_t why_size)
{
    memset(out, 0, sizeof *out);
    if (t->num_boundary_loop_lengths != t->boundary_loops) {
        snprintf(why, why_size, "%" PRId32 " of %" PRId32 " boundary loop lengths listed",
                 t->num_boundary_loop_lengths, t->boundary_loops);
        return 1;
    }
    if (t->num_components_listed != t->connected_components) {
        snprintf(why, why_size, "%" PRId32 " of %" PRId32 " components listed",
                 t->num_components_listed, t->connected_components);
        return 1;
    }
    if (t->num_defects_listed != t->num_defects) {
        snprintf(why, why_size, "%" PRId32 " of %" PRId64 " defects listed", t->num_defects_listed,
                 t->num_defects);
        return 1;
    }
    if (t->boundary_loops < 0 || t->connected_components < 0 || t->num_face_size_bins < 0 ||
        t->num_edge_use_bins < 0 || t->num_defects_listed < 0) {
        snprintf(why, why_size, "a negative count");
        return -1;
    }
    out->num_verts = (uint32_t)t->num_verts;
    out->num_faces = (uint32_t)t->num_faces;
    out->num_faces_valid = (uint32_t)t->num_faces_valid;
    out->num_edges = (uint64_t)t->num_edges;
    out->num_half_edges = (uint64_t)t->num_half_edges;
    out->boundary_edges = (uint64_t)t->boundary_edges;
    out->boundary_loops = (uint32_t)t->boundary_loops;
    out->boundary_loops_ambiguous = t->boundary_loops_ambiguous;
    out->nonmanifold_edges = (uint64_t)t->nonmanifold_edges;
    out->inconsistent_orientation_edges = (uint64_t)t->inconsistent_orientation_edges;
    out->duplicate_directed_edges = (uint64_t)t->duplicate_directed_edges;
    out->nonmanifold_vertices = (uint32_t)t->nonmanifold_vertices;
    out->bowtie_vertices = (uint32_t)t->bowtie_vertices;
    out->isolated_vertices = (uint32_t)t->isolated_vertices;
    out->unreferenced_vertices = (uint32_t)t->unreferenced_vertices;
    out->degenerate_faces = (uint32_t)t->degenerate_faces;
    out->duplicate_faces = (uint32_t)t->duplicate_faces;
    out->out_of_range_indices = (uint64_t)t->out_of_range_indices;
    out->faces_with_out_of_range_indices = (uint32_t)t->faces_with_out_of_range_indices;
    out->nonfinite_vertices = (uint32_t)t->nonfinite_vertices;
    out->connected_components = (uint32_t)t->connected_components;
    out->vertex_connected_components = (uint32_t)t->vertex_connected_components;
    out->euler_characteristic = t->euler_characteristic;
    out->closed = t->closed;
    out->manifold = t->manifold;
    out->orientable = t->orientable;
    out->consistently_oriented = t->consistently_oriented;
    out->genus = t->genus;

    size_t nl = (size_t)t->boundary_loops, nc = (size_t)t->connected_components;
    size_t nfs = (size_t)t->num_face_size_bins, neu = (size_t)t->num_edge_use_bins;
    size_t nd = (size_t)t->num_defects_listed;
    out->boundary_loop_lengths = calloc(nl + 1, sizeof *out->boundary_loop_lengths);
    out->components = calloc(nc + 1, sizeof *out->components);
    out->face_size_histogram = calloc(nfs + 1, sizeof *out->face_size_histogram);
    out->edge_use_histogram = calloc(neu + 1, sizeof *out->edge_use_histogram);
    out->defects = calloc(nd + 1, sizeof *out->defects);
    if (!out->boundary_loop_lengths || !out->components || !out->face_size_histogram ||
        !out->edge_use_histogram || !out->defects) {
        wire_report_free(out);
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    for (size_t i = 0; i < nl; i++)
        out->boundary_loop_lengths[i] = (uint32_t)t->boundary_loop_lengths[i];
    for (size_t i = 0; i < nc; i++) {
        mt_component_info *ci = &out->components[i];
        ci->min_face = (uint32_t)t->component_min_face[i];
        ci->faces = (uint32_t)t->component_faces[i];
        ci->vertices = (uint32_t)t->component_vertices[i];
        ci->edges = (uint64_t)t->component_edges[i];
        ci->euler_characteristic = t->component_euler_characteristic[i];
        ci->boundary_edges = (uint64_t)t->component_boundary_edges[i];
        ci->boundary_loops = (uint32_t)t->component_boundary_loops[i];
        ci->closed = t->component_closed[i];
        ci->manifold = t->component_manifold[i];
        ci->orientable = t->component_orientable[i];
        ci->genus = t->component_genus[i];
        ci->genus_with_boundary = t->component_genus_with_boundary[i];
    }
    out->num_face_size_bins = nfs;
    for (size_t i = 0; i < nfs; i++) {
        out->face_size_histogram[i].key = (uint32_t)t->face_size_keys[i];
        out->face_size_histogram[i].count = (uint64_t)t->face_size_counts[i];
    }
    out->num_edge_use_bins = neu;
    for (size_t i = 0; i < neu; i++) {
        out->edge_use_histogram[i].key = (uint32_t)t->edge_use_keys[i];
        out->edge_use_histogram[i].count = (uint64_t)t->edge_use_counts[i];
    }
    out->num_defects = nd;
    for (size_t i = 0; i < nd; i++) {
        out->defects[i].kind = (uint32_t)(uint8_t)t->defect_kind[i];
        out->defects[i].a = (uint32_t)t->defect_a[i];
        out->defects[i].b = (uint32_t)t->defect_b[i];
        out->defects[i].c = (uint32_t)t->defect_c[i];
    }
    return 0;
}

/* ---- replies ------------------------------------------------------------ */

/* Sends one query; 1 with a reply of num_items items, else 0 after recording
 * a failure (the client has checked the reply's offsets: a reply whose
 * offsets do not describe its arrays fails the call with MT_ERR_CORRUPT). */
static int query(const run *r, const char *what, int32_t kind, const uint32_t *ids, size_t num_ids,
                 size_t num_items, meshtopo_reply_t *out)
{
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_client_query(r->client, r->name, 0, kind, ids, num_ids, out, &diag);
    if (st != MT_OK) {
        fail_key(r, what, "query failed: %s (%s)", mt_strerror(st), diag.message);
        mt_client_reply_free(out);
        return 0;
    }
    if (mt_client_reply_num_items(out) != num_items) {
        fail_key(r, what, "reply of %zu items, %" PRId32 " groups; expected %zu items",
                 mt_client_reply_num_items(out), out->num_groups, num_items);
        mt_client_reply_free(out);
        return 0;
    }
    return 1;
}

/* Values (second = 0) or values2 (second = 1) in the groups of item i. */
static size_t item_num_values(const meshtopo_reply_t *rep, size_t i, int second)
{
    mt_client_item item = mt_client_reply_item(rep, i);
    size_t n = 0;
    for (size_t k = 0; k < item.num_groups; k++) {
        mt_client_group g = mt_client_item_group(rep, &item, k);
        n += second ? g.num_values2 : g.num_values;
    }
    return n;
}

/* Values (second = 0) or values2 (second = 1) of the groups of items
 * first .. first + count - 1, in order, appended to a fresh array; *out
 * (free it) and the count. */
static size_t items_values(const meshtopo_reply_t *rep, size_t first, size_t count, int second,
                           uint32_t **out)
{
    size_t n = 0;
    for (size_t i = first; i < first + count; i++) n += item_num_values(rep, i, second);
    *out = calloc(n + 1, sizeof **out);
    if (!*out) return 0;
    size_t at = 0;
    for (size_t i = first; i < first + count; i++) {
        mt_client_item item = mt_client_reply_item(rep, i);
        for (size_t k = 0; k < item.num_groups; k++) {
            mt_client_group g = mt_client_item_group(rep, &item, k);
            const int32_t *values = second ? g.values2 : g.values;
            size_t nv = second ? g.num_values2 : g.num_values;
            for (size_t v = 0; v < nv; v++) (*out)[at++] = (uint32_t)values[v];
        }
    }
    return n;
}

/* The one value of item i, when it has exactly one group of one value. */
static int item_single_value(const meshtopo_reply_t *rep, size_t i, int32_t *out)
{
    mt_client_item item = mt_client_reply_item(rep, i);
    if (item.num_groups != 1) return 0;
    mt_client_group g = mt_client_item_group(rep, &item, 0);
    if (g.num_values != 1) return 0;
    *out = g.values[0];
    return 1;
}

/* ---- the checks --------------------------------------------------------- */

/* The ids of an expected query list ("vertex_queries" / "face_queries", key
 * "vertex" / "face"); *out (free it) and the count. */
static size_t query_ids(const run *r, const char *list, const char *key, uint32_t **out)
{
    const cJSON *items = cJSON_GetObjectItemCaseSensitive(r->expected, list);
    size_t n = (size_t)cJSON_GetArraySize(items), i = 0;
    *out = calloc(n + 1, sizeof **out);
    if (!*out) return 0;
    const cJSON *q;
    cJSON_ArrayForEach(q, items)
    {
        long long v;
        if (!mt_test_json_int(cJSON_GetObjectItemCaseSensitive(q, key), &v) || v < 0 ||
            v > INT32_MAX) {
            fail_key(r, list, "entry %zu has no valid %s", i, key);
            v = 0;
        }
        (*out)[i++] = (uint32_t)v;
    }
    return n;
}

/* VERTEX_RING and VALENCE of every listed vertex, in one batch each. */
static void check_vertex_queries(const run *r)
{
    uint32_t *ids = NULL;
    size_t n = query_ids(r, "vertex_queries", "vertex", &ids);
    meshtopo_reply_t ring, val;
    if (n == 0 || !query(r, "vertex_queries", MESHTOPO_QUERY_T_VERTEX_RING, ids, n, n, &ring)) {
        free(ids);
        return;
    }
    int have_val = query(r, "vertex_queries valence", MESHTOPO_QUERY_T_VALENCE, ids, n, n, &val);
    const cJSON *q = cJSON_GetObjectItemCaseSensitive(r->expected, "vertex_queries")->child;
    for (size_t i = 0; i < n; i++, q = q->next) {
        char key[128];
        int32_t item_status = mt_client_reply_item(&ring, i).status;
        if (item_status != MESHTOPO_STATUS_CODE_T_OK)
            fail_key(r, "vertex_queries", "vertex %u: item status %d", ids[i], (int)item_status);
        uint32_t *nb = NULL, *faces = NULL;
        size_t nn = items_values(&ring, i, 1, 0, &nb);
        size_t nf = items_values(&ring, i, 1, 1, &faces);
        nn = nb ? mt_test_sort_unique(nb, nn, MT_NONE) : 0;
        nf = faces ? mt_test_sort_unique(faces, nf, MT_NONE) : 0;
        snprintf(key, sizeof key, "vertex_queries[%zu] (vertex %u).neighbors over LCM", i, ids[i]);
        mt_test_expect_ids(r->name, key, cJSON_GetObjectItemCaseSensitive(q, "neighbors"), nb, nn);
        snprintf(key, sizeof key, "vertex_queries[%zu] (vertex %u).faces over LCM", i, ids[i]);
        mt_test_expect_ids(r->name, key, cJSON_GetObjectItemCaseSensitive(q, "faces"), faces, nf);
        int32_t valence = 0;
        if (have_val && !item_single_value(&val, i, &valence))
            fail_key(r, "vertex_queries", "vertex %u: VALENCE answer is not one value", ids[i]);
        else if (have_val && (size_t)valence != nn)
            fail_key(r, "vertex_queries",
                     "vertex %u: VALENCE %" PRId32 ", distinct ring neighbours %zu", ids[i],
                     valence, nn);
        free(nb);
        free(faces);
    }
    if (have_val) mt_client_reply_free(&val);
    mt_client_reply_free(&ring);
    free(ids);
}

/* FACE_NEIGHBORS of every listed face in one batch, and the same through
 * EDGE_FACES on each side the FACE_NEIGHBORS answer names. */
static void check_face_queries(const run *r)
{
    uint32_t *ids = NULL;
    size_t n = query_ids(r, "face_queries", "face", &ids);
    meshtopo_reply_t fn;
    if (n == 0 || !query(r, "face_queries", MESHTOPO_QUERY_T_FACE_NEIGHBORS, ids, n, n, &fn)) {
        free(ids);
        return;
    }
    const cJSON *q = cJSON_GetObjectItemCaseSensitive(r->expected, "face_queries")->child;
    for (size_t i = 0; i < n; i++, q = q->next) {
        char key[128];
        const cJSON *want = cJSON_GetObjectItemCaseSensitive(q, "adjacent_faces");
        mt_client_item item = mt_client_reply_item(&fn, i);
        if (item.status != MESHTOPO_STATUS_CODE_T_OK)
            fail_key(r, "face_queries", "face %u: item status %d", ids[i], (int)item.status);
        uint32_t *adj = NULL;
        size_t na = items_values(&fn, i, 1, 0, &adj);
        na = adj ? mt_test_sort_unique(adj, na, ids[i]) : 0;
        snprintf(key, sizeof key, "face_queries[%zu] (face %u).adjacent_faces over LCM", i, ids[i]);
        mt_test_expect_ids(r->name, key, want, adj, na);
        free(adj);

        /* values2 holds each side's two vertices: ask EDGE_FACES for them all. */
        uint32_t *sides = NULL;
        size_t ns = items_values(&fn, i, 1, 1, &sides);
        meshtopo_reply_t ef;
        if (ns != 2 * item.num_groups) {
            fail_key(r, "face_queries", "face %u: FACE_NEIGHBORS sides are not vertex pairs",
                     ids[i]);
        } else if (ns > 0 && query(r, "face_queries edge faces", MESHTOPO_QUERY_T_EDGE_FACES, sides,
                                   ns, ns / 2, &ef)) {
            uint32_t *all = NULL;
            size_t nall = items_values(&ef, 0, mt_client_reply_num_items(&ef), 0, &all);
            nall = all ? mt_test_sort_unique(all, nall, ids[i]) : 0;
            snprintf(key, sizeof key,
                     "face_queries[%zu] (face %u).adjacent_faces via EDGE_FACES over LCM", i,
                     ids[i]);
            mt_test_expect_ids(r->name, key, want, all, nall);
            free(all);
            mt_client_reply_free(&ef);
        }
        free(sides);
    }
    mt_client_reply_free(&fn);
    free(ids);
}

/* COMPONENTS of each component's smallest face answers its number. */
static void check_components(const run *r)
{
    size_t n = r->report->connected_components;
    uint32_t *ids = calloc(n + 1, sizeof *ids);
    meshtopo_reply_t rep;
    for (size_t i = 0; ids && i < n; i++) ids[i] = r->report->components[i].min_face;
    if (ids && n > 0 && query(r, "components", MESHTOPO_QUERY_T_COMPONENTS, ids, n, n, &rep)) {
        for (size_t i = 0; i < n; i++) {
            int32_t component = -1;
            if (!item_single_value(&rep, i, &component) || component != (int32_t)i)
                fail_key(r, "components", "COMPONENTS of face %u does not answer %zu", ids[i], i);
        }
        mt_client_reply_free(&rep);
    }
    free(ids);
}

/* BOUNDARY_LOOPS: when the boundary graph's loops are simple cycles, the
 * half-edge rings have the report's lengths (as test_core checks them). */
static void check_boundary_loops(const run *r)
{
    const mt_report *rep = r->report;
    if (rep->boundary_loops_ambiguous || rep->nonmanifold_edges || rep->duplicate_directed_edges)
        return;
    meshtopo_reply_t bl;
    if (!query(r, "boundary_loops", MESHTOPO_QUERY_T_BOUNDARY_LOOPS, NULL, 0, rep->boundary_loops,
               &bl))
        return;
    size_t num_loops = mt_client_reply_num_items(&bl);
    uint32_t *lengths = calloc(num_loops + 1, sizeof *lengths);
    for (size_t i = 0; lengths && i < num_loops; i++)
        lengths[i] = (uint32_t)item_num_values(&bl, i, 0);
    if (lengths) {
        qsort(lengths, num_loops, sizeof *lengths, mt_test_compare_u32);
        for (uint32_t i = 0; i < rep->boundary_loops; i++)
            if (lengths[i] != rep->boundary_loop_lengths[i])
                fail_key(r, "boundary_loops",
                         "BOUNDARY_LOOPS ring %u (by length) has %u vertices, "
                         "report loop has %u edges",
                         i, lengths[i], rep->boundary_loop_lengths[i]);
    }
    free(lengths);
    mt_client_reply_free(&bl);
}

/* The report of the ack and of a REPORT query, then the element queries. */
static void check_daemon(run *r, const mt_client_ack *ack)
{
    char why[160], label[256];
    const meshtopo_topology_t *t = mt_client_ack_report(ack);
    if (!t) {
        fail_key(r, "ack", "carries no report");
        return;
    }
    if (strcmp(t->mesh_id, r->name) != 0 || t->version != ack->msg.version)
        fail_key(r, "ack", "report of %s v%d, submitted %s v%d", t->mesh_id, (int)t->version,
                 r->name, (int)ack->msg.version);
    if ((uint64_t)ack->msg.content_hash != ack->sent_content_hash)
        fail_key(r, "ack", "content hash %" PRIx64 ", sent %" PRIx64,
                 (uint64_t)ack->msg.content_hash, ack->sent_content_hash);
    mt_report from_ack;
    int cut = wire_report(t, &from_ack, why, sizeof why);
    if (cut < 0) fail_key(r, "ack report", "%s", why);
    if (cut > 0)
        printf(
            "%s: the ack's report lists only part (%s); its lists are checked through the "
            "REPORT query\n",
            r->name, why);
    if (cut == 0) {
        snprintf(label, sizeof label, "%s (ack over LCM)", r->name);
        mt_test_corpus_check_report(label, &from_ack, r->expected);
    }

    meshtopo_reply_t rq;
    mt_report from_query;
    memset(&from_query, 0, sizeof from_query);
    if (query(r, "report", MESHTOPO_QUERY_T_REPORT, NULL, 0, 0, &rq)) {
        if (rq.num_reports != 1) {
            fail_key(r, "report", "REPORT reply carries %d reports", (int)rq.num_reports);
        } else if (wire_report(&rq.reports[0], &from_query, why, sizeof why) != 0) {
            fail_key(r, "report", "REPORT query: %s", why);
        } else {
            snprintf(label, sizeof label, "%s (REPORT query over LCM)", r->name);
            mt_test_corpus_check_report(label, &from_query, r->expected);
        }
        mt_client_reply_free(&rq);
    }
    r->report = cut == 0 ? &from_ack : from_query.components ? &from_query : NULL;
    if (r->report) {
        check_vertex_queries(r);
        check_face_queries(r);
        check_components(r);
        check_boundary_loops(r);
    }
    r->report = NULL;
    wire_report_free(&from_ack);
    wire_report_free(&from_query);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: meshtopod_corpus_client NAME\n");
        return 2;
    }
    run r = {argv[1], NULL, NULL, NULL};
    char path[4096];
    cJSON *expected = mt_test_corpus_load(r.name, path, sizeof path);
    if (!expected) return 1;
    r.expected = expected;

    mt_face_list list;
    mt_diag diag;
    memset(&list, 0, sizeof list);
    mt_diag_clear(&diag);
    mt_status st = mt_read_file(path, MT_FORMAT_AUTO, &list, &diag);
    if (st != MT_OK) {
        fprintf(stderr, "%s: mt_read_file: %s (%s)\n", r.name, mt_strerror(st), diag.message);
        cJSON_Delete(expected);
        return 1;
    }
    /* mesh_t's content: 3 float64 per vertex, an int32 per face and per index. */
    uint64_t bytes = 24ull * list.num_verts + 4ull * list.num_faces + 4ull * list.num_indices;

    /* udpm delivers a message only when all its fragments fit the receive
     * buffer at once: a mesh that cannot is skipped, naming both sizes. */
    uint64_t buffer = udp_receive_buffer();
    if (buffer && bytes + MESH_MSG_OVERHEAD > buffer) {
        printf(
            "SKIP %s: its mesh_t message (%llu bytes) does not fit the UDP receive buffer "
            "udpm can get here (%llu bytes: recv_buf_size capped by net.core.rmem_max, "
            "doubled)\n",
            r.name, (unsigned long long)(bytes + MESH_MSG_OVERHEAD), (unsigned long long)buffer);
        mt_face_list_free(&list);
        cJSON_Delete(expected);
        return SKIP_STATUS;
    }

    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.timeout_ms = 3000;
    opts.retries = 4;
    opts.source = "meshtopod_corpus_client";
    mt_client_ack ack;
    memset(&ack, 0, sizeof ack);
    meshtopo_status_t *heartbeat = NULL;
    int status = 1;
    mt_diag_clear(&diag);
    st = mt_client_create(&opts, &r.client, &diag);
    if (st != MT_OK) {
        fprintf(stderr, "%s: mt_client_create: %s (%s)\n", r.name, mt_strerror(st), diag.message);
    } else if ((st = mt_client_wait_daemon(r.client, HEARTBEAT_WAIT_MS, &heartbeat, &diag)) !=
               MT_OK) {
        fprintf(stderr, "%s: %s (%s)\n", r.name, mt_strerror(st), diag.message);
    } else {
        printf("%s: heartbeat from meshtopod pid %d\n", r.name, (int)heartbeat->pid);
        st = mt_client_submit(r.client, r.name, &list, 0, &ack, &diag);
        if (st == MT_ERR_TOO_LARGE) {
            /* The mesh is refused for its size: say so and skip. */
            printf(
                "SKIP %s: %u vertices, %u faces, %llu indices (%llu bytes of mesh_t content) "
                "do not fit one LCM message of at most %d bytes: %s\n",
                r.name, list.num_verts, list.num_faces, (unsigned long long)list.num_indices,
                (unsigned long long)bytes, LCM_MAX_MESSAGE_SIZE, diag.message);
            status = SKIP_STATUS;
        } else if (st != MT_OK) {
            fprintf(stderr, "%s: mt_client_submit (%llu bytes): %s (%s)\n", r.name,
                    (unsigned long long)bytes, mt_strerror(st), diag.message);
        } else {
            printf("%s: ack: version %d (%llu bytes of mesh_t content sent)\n", r.name,
                   (int)ack.msg.version, (unsigned long long)bytes);
            check_daemon(&r, &ack);
            status = mt_test_failures() ? 1 : 0;
            printf("%s: %s\n", r.name,
                   status ? "FAIL: the daemon's answers differ from NAME.expected.json"
                          : "the daemon's report and answers equal NAME.expected.json");
        }
    }
    if (heartbeat) meshtopo_status_t_destroy(heartbeat);
    mt_client_ack_free(&ack);
    mt_client_destroy(r.client);
    mt_face_list_free(&list);
    cJSON_Delete(expected);
    return status;
}
