/* Sample messages of every meshtopo type and generic comparison (see
 * msgs_samples.h). The values describe a small scan: a bowtie of two
 * triangles at vertex 0, a face with an out-of-range index, an isolated
 * vertex and a NaN coordinate; positions also hold -0.0 and a denormal so
 * that a round trip must keep every bit. */
#include "msgs_samples.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- mesh_t ------------------------------------------------------------- */

static void fill_mesh_bowtie(void *out)
{
    static double positions[] = {
        0.0,          0.0,    0.0,    /* vertex 0 */
        1.0,          -1.0,   0.25,   /* vertex 1 */
        1.0,          1.0,    0.25,   /* vertex 2 */
        -1.0,         NAN,    -0.0,   /* vertex 3 */
        -1.0,         1.0e-3, 2.5e10, /* vertex 4 */
        DBL_TRUE_MIN, -7.5,   3.25,   /* vertex 5: isolated */
    };
    static int32_t counts[] = {3, 3, 3};
    static int32_t indices[] = {0, 1, 2, 0, 3, 4, 1, 2, 9};
    meshtopo_mesh_t *m = out;
    m->utime = 1700000000123456;
    m->request_id = 0x0123456789abcdefLL;
    m->reply_channel = "MESHTOPO_REPLY_scanner_4242";
    m->mesh_id = "kitchen.scan-42";
    m->source = "scanner_d435_\xc3\xa9"; /* UTF-8 */
    m->strict = 0;
    m->num_verts = 6;
    m->num_position_values = 18;
    m->positions = positions;
    m->num_faces = 3;
    m->face_vertex_counts = counts;
    m->num_indices = 9;
    m->face_vertex_indices = indices;
}

static void fill_mesh_no_geometry(void *out)
{
    static int32_t counts[] = {3, 3, 3, 3};
    static int32_t indices[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    meshtopo_mesh_t *m = out;
    m->utime = 1700000000999999;
    m->request_id = -2;
    m->reply_channel = "MESHTOPO_REPLY_1";
    m->mesh_id = "tetrahedron";
    m->source = "unit-test";
    m->strict = 1;
    m->num_verts = 4;
    m->num_position_values = 0;
    m->positions = NULL;
    m->num_faces = 4;
    m->face_vertex_counts = counts;
    m->num_indices = 12;
    m->face_vertex_indices = indices;
}

/* ---- topology_t ----------------------------------------------------------- */

/* A messy scan: every defect count set, fewer defects listed than it has. */
static void fill_topology_scan(void *out)
{
    static int32_t loop_lengths[] = {3, 3, 12};
    static int32_t min_face[] = {0, 1};
    static int32_t faces[] = {1, 1};
    static int32_t vertices[] = {3, 3};
    static int64_t edges[] = {3, 3};
    static int64_t euler[] = {1, 1};
    static int64_t boundary_edges[] = {3, 3};
    static int32_t boundary_loops[] = {1, 1};
    static int8_t closed[] = {0, 0};
    static int8_t manifold[] = {1, 0};
    static int8_t orientable[] = {1, 1};
    static int32_t genus[] = {-1, -1};
    static int32_t genus_with_boundary[] = {0, -1};
    static int32_t size_keys[] = {3, 4};
    static int64_t size_counts[] = {3, 1};
    static int32_t use_keys[] = {1, 2, 3};
    static int64_t use_counts[] = {6, 2, 1};
    static int8_t kind[] = {
        MESHTOPO_TOPOLOGY_T_DEFECT_OUT_OF_RANGE_INDEX,
        MESHTOPO_TOPOLOGY_T_DEFECT_NONMANIFOLD_EDGE,
        MESHTOPO_TOPOLOGY_T_DEFECT_NONMANIFOLD_VERTEX,
        MESHTOPO_TOPOLOGY_T_DEFECT_NONFINITE_COORD,
    };
    static int32_t a[] = {2, 1, 0, 3};
    static int32_t b[] = {-5, 2, 2, 1};
    static int32_t c[] = {2, 3, 0, 0};
    meshtopo_topology_t *t = out;
    t->utime = 1700000000200000;
    t->mesh_id = "kitchen.scan-42";
    t->version = 3;
    t->source = "scanner_d435_\xc3\xa9";
    t->mesh_utime = 1700000000123456;
    t->build_duration_us = 1234;
    t->content_hash = (int64_t)0xcbf29ce484222325ULL;
    t->num_verts = 6;
    t->num_faces = 4;
    t->num_faces_valid = 3;
    t->num_edges = 9;
    t->num_half_edges = 13;
    t->boundary_edges = 18;
    t->boundary_loops = 4;
    t->boundary_loops_ambiguous = 1;
    t->num_boundary_loop_lengths = 3;
    t->boundary_loop_lengths = loop_lengths;
    t->nonmanifold_edges = 1;
    t->inconsistent_orientation_edges = 2;
    t->duplicate_directed_edges = 3;
    t->nonmanifold_vertices = 4;
    t->bowtie_vertices = 1;
    t->isolated_vertices = 2;
    t->unreferenced_vertices = 1;
    t->degenerate_faces = 5;
    t->duplicate_faces = 6;
    t->out_of_range_indices = 7;
    t->faces_with_out_of_range_indices = 1;
    t->nonfinite_vertices = 1;
    t->connected_components = 3;
    t->vertex_connected_components = 2;
    t->euler_characteristic = -3;
    t->closed = 0;
    t->manifold = 0;
    t->orientable = 1;
    t->consistently_oriented = 0;
    t->genus = -1;
    t->num_components_listed = 2;
    t->component_min_face = min_face;
    t->component_faces = faces;
    t->component_vertices = vertices;
    t->component_edges = edges;
    t->component_euler_characteristic = euler;
    t->component_boundary_edges = boundary_edges;
    t->component_boundary_loops = boundary_loops;
    t->component_closed = closed;
    t->component_manifold = manifold;
    t->component_orientable = orientable;
    t->component_genus = genus;
    t->component_genus_with_boundary = genus_with_boundary;
    t->num_face_size_bins = 2;
    t->face_size_keys = size_keys;
    t->face_size_counts = size_counts;
    t->num_edge_use_bins = 3;
    t->edge_use_keys = use_keys;
    t->edge_use_counts = use_counts;
    t->num_defects = 40;
    t->num_defects_listed = 4;
    t->defect_kind = kind;
    t->defect_a = a;
    t->defect_b = b;
    t->defect_c = c;
}

/* A clean torus (16 quads): closed, manifold, orientable, genus 1. */
static void fill_topology_torus(void *out)
{
    static int32_t zero32[] = {0};
    static int32_t sixteen[] = {16};
    static int64_t thirty_two64[] = {32};
    static int64_t zero64[] = {0};
    static int8_t yes[] = {1};
    static int32_t one[] = {1};
    static int32_t size_keys[] = {4};
    static int64_t size_counts[] = {16};
    static int32_t use_keys[] = {2};
    static int64_t use_counts[] = {32};
    meshtopo_topology_t *t = out;
    t->utime = 1700000001000000;
    t->mesh_id = "torus";
    t->version = 1;
    t->source = "generator";
    t->mesh_utime = 1700000000900000;
    t->build_duration_us = 17;
    t->content_hash = 0x12345678;
    t->num_verts = 16;
    t->num_faces = 16;
    t->num_faces_valid = 16;
    t->num_edges = 32;
    t->num_half_edges = 64;
    t->boundary_loops_ambiguous = 0;
    t->num_boundary_loop_lengths = 0;
    t->boundary_loop_lengths = NULL;
    t->connected_components = 1;
    t->vertex_connected_components = 1;
    t->euler_characteristic = 0;
    t->closed = 1;
    t->manifold = 1;
    t->orientable = 1;
    t->consistently_oriented = 1;
    t->genus = 1;
    t->num_components_listed = 1;
    t->component_min_face = zero32;
    t->component_faces = sixteen;
    t->component_vertices = sixteen;
    t->component_edges = thirty_two64;
    t->component_euler_characteristic = zero64;
    t->component_boundary_edges = zero64;
    t->component_boundary_loops = zero32;
    t->component_closed = yes;
    t->component_manifold = yes;
    t->component_orientable = yes;
    t->component_genus = one;
    t->component_genus_with_boundary = one;
    t->num_face_size_bins = 1;
    t->face_size_keys = size_keys;
    t->face_size_counts = size_counts;
    t->num_edge_use_bins = 1;
    t->edge_use_keys = use_keys;
    t->edge_use_counts = use_counts;
    t->num_defects = 0;
    t->num_defects_listed = 0;
}

/* ---- ack_t ----------------------------------------------------------------- */

static void fill_ack_refused(void *out)
{
    static meshtopo_topology_t report;
    memset(&report, 0, sizeof report);
    fill_topology_scan(&report);
    meshtopo_ack_t *a = out;
    a->utime = 1700000000300000;
    a->request_id = 0x0123456789abcdefLL;
    a->status = MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED;
    a->error = "strict: face 2 uses vertex 9, past the 6 vertices";
    a->mesh_id = "kitchen.scan-42";
    a->version = 0;
    a->content_hash = (int64_t)0xfedcba9876543210ULL;
    a->num_reports = 1;
    a->reports = &report;
}

static void fill_ack_ok(void *out)
{
    meshtopo_ack_t *a = out;
    a->utime = 1700000000400000;
    a->request_id = 7;
    a->status = MESHTOPO_STATUS_CODE_T_OK;
    a->error = "";
    a->mesh_id = "torus";
    a->version = 2;
    a->content_hash = 0x12345678;
    a->num_reports = 0;
    a->reports = NULL;
}

/* ---- query_t --------------------------------------------------------------- */

static void fill_query_ring(void *out)
{
    static int32_t ids[] = {0, 5, 3};
    meshtopo_query_t *q = out;
    q->utime = 1700000000500000;
    q->request_id = 42;
    q->reply_channel = "MESHTOPO_REPLY_scanner_4242";
    q->mesh_id = "kitchen.scan-42";
    q->version = 0;
    q->kind = MESHTOPO_QUERY_T_VERTEX_RING;
    q->num_ids = 3;
    q->ids = ids;
    q->instance = "";
}

static void fill_query_edges(void *out)
{
    static int32_t ids[] = {0, 1, 2, 1, 4, 5};
    meshtopo_query_t *q = out;
    q->utime = 1700000000600000;
    q->request_id = 43;
    q->reply_channel = "MESHTOPO_REPLY_scanner_4242";
    q->mesh_id = "kitchen.scan-42";
    q->version = 3;
    q->kind = MESHTOPO_QUERY_T_EDGE_FACES;
    q->num_ids = 6;
    q->ids = ids;
    q->instance = "robot-7:4242:1700000000000000";
}

/* ---- reply_t --------------------------------------------------------------- */

/* One-rings of vertices 0 (a bowtie: two open fans), 5 (isolated: no fan)
 * and 3 (one open fan). */
static void fill_reply_ring(void *out)
{
    static int8_t item_status[] = {
        MESHTOPO_STATUS_CODE_T_OK,
        MESHTOPO_STATUS_CODE_T_OK,
        MESHTOPO_STATUS_CODE_T_OK,
    };
    static int32_t item_offsets[] = {0, 2, 2, 3};
    static int8_t boundary[] = {1, 1, 1};
    static int32_t value_offsets[] = {0, 2, 4, 6};
    static int32_t value2_offsets[] = {0, 1, 2, 3};
    static int32_t neighbors[] = {1, 2, 3, 4, 4, 0};
    static int32_t faces[] = {0, 1, 1};
    meshtopo_reply_t *r = out;
    r->utime = 1700000000700000;
    r->request_id = 42;
    r->status = MESHTOPO_STATUS_CODE_T_OK;
    r->error = "";
    r->mesh_id = "kitchen.scan-42";
    r->version = 3;
    r->kind = MESHTOPO_QUERY_T_VERTEX_RING;
    r->num_items = 3;
    r->item_status = item_status;
    r->num_item_offsets = 4;
    r->item_offsets = item_offsets;
    r->num_groups = 3;
    r->group_boundary = boundary;
    r->num_value_offsets = 4;
    r->value_offsets = value_offsets;
    r->value2_offsets = value2_offsets;
    r->num_values = 6;
    r->values = neighbors;
    r->num_values2 = 3;
    r->values2 = faces;
}

/* Face neighbours of face 0 and of face 2, which the build rejected. */
static void fill_reply_face_neighbors(void *out)
{
    static int8_t item_status[] = {MESHTOPO_STATUS_CODE_T_OK, MESHTOPO_STATUS_CODE_T_NOT_FOUND};
    static int32_t item_offsets[] = {0, 3, 3};
    static int8_t boundary[] = {1, 0, 1};
    static int32_t value_offsets[] = {0, 0, 1, 1};
    static int32_t value2_offsets[] = {0, 2, 4, 6};
    static int32_t across[] = {3};
    static int32_t sides[] = {0, 1, 1, 2, 2, 0};
    meshtopo_reply_t *r = out;
    r->utime = 1700000000750000;
    r->request_id = 44;
    r->status = MESHTOPO_STATUS_CODE_T_OK;
    r->error = "";
    r->mesh_id = "kitchen.scan-42";
    r->version = 3;
    r->kind = MESHTOPO_QUERY_T_FACE_NEIGHBORS;
    r->num_items = 2;
    r->item_status = item_status;
    r->num_item_offsets = 3;
    r->item_offsets = item_offsets;
    r->num_groups = 3;
    r->group_boundary = boundary;
    r->num_value_offsets = 4;
    r->value_offsets = value_offsets;
    r->value2_offsets = value2_offsets;
    r->num_values = 1;
    r->values = across;
    r->num_values2 = 6;
    r->values2 = sides;
}

/* Dihedral angles of a reflex edge and of a boundary edge (no angle). */
static void fill_reply_dihedral(void *out)
{
    static int8_t item_status[] = {MESHTOPO_STATUS_CODE_T_OK, MESHTOPO_STATUS_CODE_T_OK};
    static int32_t item_offsets[] = {0, 1, 2};
    static int8_t boundary[] = {0, 0};
    static int32_t value_offsets[] = {0, 1, 2};
    static int32_t value2_offsets[] = {0, 0, 0};
    static int32_t shapes[] = {MESHTOPO_QUERY_T_SHAPE_REFLEX, MESHTOPO_QUERY_T_SHAPE_BOUNDARY};
    static double angles[] = {4.1887902047863905, NAN};
    meshtopo_reply_t *r = out;
    r->utime = 1700000000780000;
    r->request_id = 49;
    r->status = MESHTOPO_STATUS_CODE_T_OK;
    r->error = "";
    r->mesh_id = "dented-cube";
    r->version = 1;
    r->kind = MESHTOPO_QUERY_T_DIHEDRAL_ANGLES;
    r->num_items = 2;
    r->item_status = item_status;
    r->num_item_offsets = 3;
    r->item_offsets = item_offsets;
    r->num_groups = 2;
    r->group_boundary = boundary;
    r->num_value_offsets = 3;
    r->value_offsets = value_offsets;
    r->value2_offsets = value2_offsets;
    r->num_values = 2;
    r->values = shapes;
    r->num_reals = 2;
    r->reals = angles;
}

static void fill_reply_report(void *out)
{
    static int32_t offsets[] = {0};
    static meshtopo_topology_t report;
    memset(&report, 0, sizeof report);
    fill_topology_torus(&report);
    meshtopo_reply_t *r = out;
    r->utime = 1700000000800000;
    r->request_id = 45;
    r->status = MESHTOPO_STATUS_CODE_T_OK;
    r->error = "";
    r->mesh_id = "torus";
    r->version = 1;
    r->kind = MESHTOPO_QUERY_T_REPORT;
    r->num_item_offsets = 1;
    r->item_offsets = offsets;
    r->num_value_offsets = 1;
    r->value_offsets = offsets;
    r->value2_offsets = offsets;
    r->num_reports = 1;
    r->reports = &report;
}

static void fill_reply_list(void *out)
{
    static int32_t offsets[] = {0};
    static char *ids[] = {"kitchen.scan-42", "kitchen.scan-42", "torus"};
    static int32_t versions[] = {2, 3, 1};
    static char *sources[] = {"scanner_d435_\xc3\xa9", "scanner_d435_\xc3\xa9", "generator"};
    static int64_t utimes[] = {1700000000100000, 1700000000200000, 1700000001000000};
    static int32_t verts[] = {6, 6, 16};
    static int32_t faces[] = {3, 4, 16};
    static int64_t defects[] = {38, 40, 0};
    static int64_t hashes[] = {-1, (int64_t)0xcbf29ce484222325ULL, 0x12345678};
    meshtopo_reply_t *r = out;
    r->utime = 1700000000900000;
    r->request_id = 46;
    r->status = MESHTOPO_STATUS_CODE_T_OK;
    r->error = "";
    r->mesh_id = "";
    r->version = 0;
    r->kind = MESHTOPO_QUERY_T_LIST_MESHES;
    r->num_item_offsets = 1;
    r->item_offsets = offsets;
    r->num_value_offsets = 1;
    r->value_offsets = offsets;
    r->value2_offsets = offsets;
    r->num_meshes = 3;
    r->list_mesh_ids = ids;
    r->list_versions = versions;
    r->list_sources = sources;
    r->list_utimes = utimes;
    r->list_num_verts = verts;
    r->list_num_faces = faces;
    r->list_num_defects = defects;
    r->list_content_hashes = hashes;
}

static void fill_reply_error(void *out)
{
    static int32_t offsets[] = {0};
    meshtopo_reply_t *r = out;
    r->utime = 1700000000950000;
    r->request_id = 47;
    r->status = MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE;
    r->error = "vertex 99 is out of range: kitchen.scan-42 version 3 has 6 vertices";
    r->mesh_id = "kitchen.scan-42";
    r->version = 3;
    r->kind = MESHTOPO_QUERY_T_VALENCE;
    r->num_item_offsets = 1;
    r->item_offsets = offsets;
    r->num_value_offsets = 1;
    r->value_offsets = offsets;
    r->value2_offsets = offsets;
}

/* ---- status_t and status_code_t ---------------------------------------------- */

static void fill_status(void *out)
{
    meshtopo_status_t *s = out;
    s->utime = 1700000002000000;
    s->name = "meshtopod";
    s->instance = "robot-7:4242:1700000000000000";
    s->pid = 4242;
    s->uptime_us = 2000000;
    s->channel_prefix = "MESHTOPO_";
    s->meshes_held = 2;
    s->versions_held = 3;
    s->memory_bytes = 123456789;
    s->submissions = 5;
    s->builds = 4;
    s->queries = 1000;
    s->errors = 3;
    s->duplicate_requests = 2;
    s->worker_threads = 4;
    s->builds_in_progress = 1;
    s->builds_queued = 2;
    s->last_error = "unknown mesh \"kitchen.scan-41\"";
    s->last_error_utime = 1700000001500000;
    s->transfers_active = 1;
    s->transfer_bytes = 57344;
    s->chunks = 1200;
    s->transfers_completed = 2;
    s->transfers_expired = 1;
    s->transfers_refused = 1;
    s->archive_versions = 3;
    s->archive_writes = 2;
    s->archive_errors = 1;
    s->archive_loads = 1;
    s->archive_evictions = 1;
    s->archive_backlog = 1;
    s->archive_bytes = 4567890;
    s->memory_budget = 268435456;
    s->cluster = "mapping";
    s->cluster_members = 3;
    s->cluster_share = 0.3359375;
    s->cluster_view = 0x5ca1ab1e;
}

/* ---- mesh_chunk_t and mesh_transfer_t --------------------------------------- */

/* The second 8-byte piece of a 20-byte content, asking for the status. */
static void fill_mesh_chunk(void *out)
{
    static uint8_t data[] = {0x00, 0x00, 0x00, 0x03, 0x3f, 0xf0, 0x00, 0x00};
    meshtopo_mesh_chunk_t *c = out;
    c->utime = 1700000000050000;
    c->request_id = 48;
    c->reply_channel = "MESHTOPO_REPLY_robot-7_4242_1";
    c->mesh_id = "kitchen.scan-43";
    c->source = "scanner_d435";
    c->strict = 1;
    c->total_size = 20;
    c->content_hash = (int64_t)0x8f3a5c2e91d4b607ULL;
    c->want_status = 1;
    c->offset = 8;
    c->length = (int32_t)sizeof data;
    c->data = data;
}

/* A transfer missing two ranges. */
static void fill_mesh_transfer_missing(void *out)
{
    static int64_t offsets[] = {0, 16};
    static int64_t lengths[] = {8, 4};
    meshtopo_mesh_transfer_t *t = out;
    t->utime = 1700000000060000;
    t->request_id = 48;
    t->status = MESHTOPO_STATUS_CODE_T_OK;
    t->error = "";
    t->total_size = 20;
    t->received_bytes = 8;
    t->listed_until = 20;
    t->num_missing = 2;
    t->missing_offsets = offsets;
    t->missing_lengths = lengths;
}

/* A chunk that contradicted its transfer, which is complete otherwise. */
static void fill_mesh_transfer_refused(void *out)
{
    meshtopo_mesh_transfer_t *t = out;
    t->utime = 1700000000070000;
    t->request_id = 48;
    t->status = MESHTOPO_STATUS_CODE_T_BAD_REQUEST;
    t->error = "offset 24 + length 8 reaches past total_size 20";
    t->total_size = 20;
    t->received_bytes = 20;
    t->complete = 1;
    t->listed_until = 20;
}

/* ---- reply_part_t and reply_pull_t ----------------------------------------- */

/* The last, short part of a 20-byte answer sent in parts of 8 bytes. */
static void fill_reply_part(void *out)
{
    static uint8_t data[] = {0x00, 0x00, 0x00, 0x07};
    meshtopo_reply_part_t *p = out;
    p->utime = 1700000000080000;
    p->request_id = 49;
    p->total_size = 20;
    p->answer_hash = (int64_t)0x1b2c3d4e5f607182ULL;
    p->part_size = 8;
    p->offset = 16;
    p->length = (int32_t)sizeof data;
    p->data = data;
}

/* A pull for the first and the last part of that answer. */
static void fill_reply_pull(void *out)
{
    static int64_t offsets[] = {0, 16};
    static int64_t lengths[] = {8, 4};
    meshtopo_reply_pull_t *p = out;
    p->utime = 1700000000090000;
    p->request_id = 49;
    p->reply_channel = "MESHTOPO_REPLY_robot-7_4242_1";
    p->total_size = 20;
    p->answer_hash = (int64_t)0x1b2c3d4e5f607182ULL;
    p->num_ranges = 2;
    p->offsets = offsets;
    p->lengths = lengths;
}

static void fill_status_code(void *out)
{
    meshtopo_status_code_t *s = out;
    s->utime = 1700000003000000;
    s->code = MESHTOPO_STATUS_CODE_T_BUSY;
}

const mt_msgs_sample mt_msgs_samples[] = {
    {"mesh_bowtie", &mt_msgs_type_mesh, fill_mesh_bowtie},
    {"mesh_no_geometry", &mt_msgs_type_mesh, fill_mesh_no_geometry},
    {"topology_scan", &mt_msgs_type_topology, fill_topology_scan},
    {"topology_torus", &mt_msgs_type_topology, fill_topology_torus},
    {"ack_refused", &mt_msgs_type_ack, fill_ack_refused},
    {"ack_ok", &mt_msgs_type_ack, fill_ack_ok},
    {"query_ring", &mt_msgs_type_query, fill_query_ring},
    {"query_edges", &mt_msgs_type_query, fill_query_edges},
    {"reply_ring", &mt_msgs_type_reply, fill_reply_ring},
    {"reply_face_neighbors", &mt_msgs_type_reply, fill_reply_face_neighbors},
    {"reply_report", &mt_msgs_type_reply, fill_reply_report},
    {"reply_list", &mt_msgs_type_reply, fill_reply_list},
    {"reply_error", &mt_msgs_type_reply, fill_reply_error},
    {"reply_dihedral", &mt_msgs_type_reply, fill_reply_dihedral},
    {"mesh_chunk", &mt_msgs_type_mesh_chunk, fill_mesh_chunk},
    {"mesh_transfer_missing", &mt_msgs_type_mesh_transfer, fill_mesh_transfer_missing},
    {"mesh_transfer_refused", &mt_msgs_type_mesh_transfer, fill_mesh_transfer_refused},
    {"reply_part", &mt_msgs_type_reply_part, fill_reply_part},
    {"reply_pull", &mt_msgs_type_reply_pull, fill_reply_pull},
    {"status", &mt_msgs_type_status, fill_status},
    {"status_code", &mt_msgs_type_status_code, fill_status_code},
};
const size_t mt_msgs_num_samples = sizeof mt_msgs_samples / sizeof mt_msgs_samples[0];

uint8_t *mt_msgs_encode_alloc(const mt_msgs_type *type, const void *msg, size_t *out_size)
{
    int size = type->encoded_size(msg);
    if (size <= 0) return NULL;
    uint8_t *buf = malloc((size_t)size);
    if (buf == NULL) return NULL;
    if (type->encode(buf, 0, size, msg) != size) {
        free(buf);
        return NULL;
    }
    *out_size = (size_t)size;
    return buf;
}

/* ---- Generic field walks -------------------------------------------------- */

static const mt_msgs_type *nested_type(const char *typestr)
{
    for (size_t i = 0; i < mt_msgs_num_types; i++)
        if (strcmp(mt_msgs_types[i]->name, typestr) == 0) return mt_msgs_types[i];
    return NULL;
}

/* A field's elements: where they start and how many. Scalars count 1;
 * variable-length arrays are pointers in the struct, fixed ones inline.
 * Returns 0 for shapes our types do not use (several dimensions). */
static int field_elements(const lcm_field_t *f, const void **out_data, int64_t *out_count)
{
    if (f->num_dim == 0) {
        *out_data = f->data;
        *out_count = 1;
        return 1;
    }
    if (f->num_dim != 1) return 0;
    *out_count = f->dim_size[0];
    *out_data = f->dim_is_variable[0] ? *(void *const *)f->data : f->data;
    return 1;
}

static int equal_struct(const mt_msgs_type *type, const void *a, const void *b, char *where,
                        size_t where_size, const char *path);

static int equal_elements(const lcm_field_t *f, const void *a, const void *b, int64_t i,
                          char *where, size_t where_size, const char *path)
{
    size_t width = mt_msgs_field_width(f->type);
    if (width > 0)
        return memcmp((const uint8_t *)a + (size_t)i * width,
                      (const uint8_t *)b + (size_t)i * width, width) == 0;
    if (f->type == LCM_FIELD_STRING) {
        const char *sa = ((char *const *)a)[i], *sb = ((char *const *)b)[i];
        return sa && sb && strcmp(sa, sb) == 0;
    }
    const mt_msgs_type *nested = nested_type(f->typestr);
    if (nested == NULL) return 0;
    return equal_struct(nested, (const uint8_t *)a + (size_t)i * nested->struct_size,
                        (const uint8_t *)b + (size_t)i * nested->struct_size, where, where_size,
                        path);
}

static int equal_struct(const mt_msgs_type *type, const void *a, const void *b, char *where,
                        size_t where_size, const char *path)
{
    for (int i = 0, n = type->num_fields(); i < n; i++) {
        lcm_field_t fa, fb;
        memset(&fa, 0, sizeof fa);
        memset(&fb, 0, sizeof fb);
        type->get_field(a, i, &fa);
        type->get_field(b, i, &fb);
        char here[256];
        snprintf(here, sizeof here, "%s.%s", path, fa.name);
        const void *da, *db;
        int64_t na, nb;
        if (!field_elements(&fa, &da, &na) || !field_elements(&fb, &db, &nb) || na != nb) {
            snprintf(where, where_size, "%s (shape or length)", here);
            return 0;
        }
        for (int64_t e = 0; e < na; e++) {
            char element[300];
            if (fa.num_dim == 0)
                snprintf(element, sizeof element, "%s", here);
            else
                snprintf(element, sizeof element, "%s[%lld]", here, (long long)e);
            if (!equal_elements(&fa, da, db, e, where, where_size, element)) {
                if (where[0] == '\0' || fa.type != LCM_FIELD_USER_TYPE)
                    snprintf(where, where_size, "%s", element);
                return 0;
            }
        }
    }
    return 1;
}

int mt_msgs_equal(const mt_msgs_type *type, const void *a, const void *b, char *where,
                  size_t where_size)
{
    where[0] = '\0';
    return equal_struct(type, a, b, where, where_size, type->name);
}

int mt_msgs_field_is_set(const mt_msgs_type *type, const void *msg, int field,
                         const char **out_name)
{
    lcm_field_t f;
    memset(&f, 0, sizeof f);
    if (type->get_field(msg, field, &f) != 0) return 0;
    *out_name = f.name;
    const void *data;
    int64_t count;
    if (!field_elements(&f, &data, &count)) return 0;
    if (f.num_dim > 0) return count > 0;
    if (f.type == LCM_FIELD_STRING) return *(char *const *)data && **(char *const *)data;
    if (f.type == LCM_FIELD_USER_TYPE) return 1;
    static const uint8_t zeros[8];
    return memcmp(data, zeros, mt_msgs_field_width(f.type)) != 0;
}
