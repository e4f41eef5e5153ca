/* `meshtopo query ID KIND IDS...`: one batch query to meshtopod (one-rings,
 * valences, face neighbours, edge faces, boundary loops, components, the
 * report, the defect lists, dihedral angles, angle deficits, convexity) and
 * its answer, one line per item (fans and
 * sides labelled) or one JSON object per item. The reply's offsets come from
 * the network and are checked before any array is indexed with them. */
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/geometry.h"
#include "meshtopo/report.h"
#include "remote.h"

/* Most ids one command line may expand to (the daemon has its own limit). */
#define MAX_QUERY_IDS ((size_t)1 << 24)

typedef enum { IDS_NEEDED, IDS_OPTIONAL, IDS_NONE } ids_rule;

typedef struct query_kind {
    const char *name;
    int32_t kind;   /* query_t kind */
    ids_rule ids;   /* whether it takes ids */
    const char *of; /* what an id names, for labels: "vertex", "face", ... */
} query_kind;

static const query_kind kinds[] = {
    {"ring", MESHTOPO_QUERY_T_VERTEX_RING, IDS_NEEDED, "vertex"},
    {"valence", MESHTOPO_QUERY_T_VALENCE, IDS_NEEDED, "vertex"},
    {"face-neighbors", MESHTOPO_QUERY_T_FACE_NEIGHBORS, IDS_NEEDED, "face"},
    {"edge-faces", MESHTOPO_QUERY_T_EDGE_FACES, IDS_NEEDED, "edge"},
    {"boundary-loops", MESHTOPO_QUERY_T_BOUNDARY_LOOPS, IDS_NONE, "loop"},
    {"components", MESHTOPO_QUERY_T_COMPONENTS, IDS_OPTIONAL, "face"},
    {"report", MESHTOPO_QUERY_T_REPORT, IDS_NONE, ""},
    {"defects", MESHTOPO_QUERY_T_DEFECTS, IDS_OPTIONAL, "kind"},
    {"dihedral", MESHTOPO_QUERY_T_DIHEDRAL_ANGLES, IDS_NEEDED, "edge"},
    {"deficit", MESHTOPO_QUERY_T_ANGLE_DEFICITS, IDS_NEEDED, "vertex"},
    {"convexity", MESHTOPO_QUERY_T_CONVEXITY, IDS_NONE, "mesh"},
};

/* Kinds whose ids are vertex pairs naming edges. */
static bool takes_pairs(int32_t kind)
{
    return kind == MESHTOPO_QUERY_T_EDGE_FACES || kind == MESHTOPO_QUERY_T_DIHEDRAL_ANGLES;
}

/* Real values a reply of this kind carries for num_items items. */
static int32_t expected_reals(int32_t kind, int32_t num_items)
{
    if (kind == MESHTOPO_QUERY_T_DIHEDRAL_ANGLES || kind == MESHTOPO_QUERY_T_ANGLE_DEFICITS)
        return num_items;
    return kind == MESHTOPO_QUERY_T_CONVEXITY ? 1 : 0;
}
static const size_t num_kinds = sizeof kinds / sizeof kinds[0];

static const mt_cli_option options[] = {
    {"version", "N", "query this version of the mesh (default: the latest)"},
    {"json", NULL, "print one JSON object: mesh_id, version, kind and an object per item"},
    MT_CLI_REMOTE_OPTIONS,
};

/* ---- Reading the reply ------------------------------------------------- */

/* True when every offset array has its documented length, starts at 0, never
 * decreases and stays within the array it points into. */
static bool offsets_ok(const int32_t *offsets, int32_t count, int32_t expected_count, int32_t limit)
{
    if (count != expected_count) return false;
    if (count > 0 && offsets[0] != 0) return false;
    for (int32_t i = 0; i < count; i++) {
        if (offsets[i] < 0 || offsets[i] > limit) return false;
        if (i > 0 && offsets[i] < offsets[i - 1]) return false;
    }
    return true;
}

static bool reply_consistent(const meshtopo_reply_t *r)
{
    int32_t items = r->num_items, groups = r->num_groups;
    /* "both 1 when there is nothing"; tolerate 0 for an empty list too */
    if (items == 0 && r->num_item_offsets == 0 && groups == 0 && r->num_value_offsets == 0)
        return true;
    return offsets_ok(r->item_offsets, r->num_item_offsets, items + 1, groups) &&
           offsets_ok(r->value_offsets, r->num_value_offsets, groups + 1, r->num_values) &&
           offsets_ok(r->value2_offsets, r->num_value_offsets, groups + 1, r->num_values2);
}

typedef struct span {
    const int32_t *v;
    int32_t n;
} span;

/* A group's values; an empty array may be NULL, so no arithmetic on it then. */
static span span_of(const int32_t *array, const int32_t *offsets, int32_t g)
{
    span s = {NULL, offsets[g + 1] - offsets[g]};
    if (s.n > 0) s.v = array + offsets[g];
    return s;
}

static span values_of(const meshtopo_reply_t *r, int32_t g)
{
    return span_of(r->values, r->value_offsets, g);
}

static span values2_of(const meshtopo_reply_t *r, int32_t g)
{
    return span_of(r->values2, r->value2_offsets, g);
}

static const char *defect_name(int64_t kind)
{
    return kind >= 0 && kind < MT_DEFECT_KIND_COUNT ? mt_defect_key((mt_defect_kind)kind)
                                                    : "unknown";
}

/* The element an item answers: the queried id, or its position when the
 * kind lists every element (boundary loops, components or defects without ids). */
static int64_t item_subject(const mt_id_list *ids, int32_t kind, int32_t i)
{
    if (takes_pairs(kind)) return ids->ids[2 * (size_t)i];
    if ((size_t)i < ids->count) return ids->ids[i];
    return i;
}

/* ---- Readable output --------------------------------------------------- */

static void print_span(span s)
{
    if (s.n == 0) printf(" none");
    for (int32_t k = 0; k < s.n; k++) printf(" %" PRId32, s.v[k]);
}

static const char *shape_name(int32_t shape)
{
    return shape >= 0 && shape <= MT_EDGE_DEGENERATE ? mt_edge_shape_name((mt_edge_shape)shape)
                                                     : "unknown";
}

/* The rest of a geometry item's line (after its label); false for other kinds. */
static bool print_geometry_text(const meshtopo_reply_t *r, int32_t kind, int32_t i, int32_t g0,
                                int32_t g1)
{
    const double degrees = 180.0 / 3.14159265358979323846;
    if (kind == MESHTOPO_QUERY_T_DIHEDRAL_ANGLES) {
        span v = values_of(r, g0);
        double angle = r->reals[i];
        printf(" %s", v.n == 1 ? shape_name(v.v[0]) : "?");
        if (isnan(angle))
            printf(" (no dihedral angle)\n");
        else
            printf(", dihedral angle %.9g rad (%.6g deg)\n", angle, angle * degrees);
        return true;
    }
    if (kind == MESHTOPO_QUERY_T_ANGLE_DEFICITS) {
        printf(" angle deficit %.9g rad%s\n", r->reals[i],
               r->group_boundary[g0] ? " (boundary: pi minus the corner angles)" : "");
        return true;
    }
    if (kind != MESHTOPO_QUERY_T_CONVEXITY) return false;
    span head = values_of(r, g0), edges = g1 > g0 + 1 ? values_of(r, g0 + 1) : (span){NULL, 0};
    if (head.n != 4) {
        printf(" malformed answer\n");
        return true;
    }
    char reasons[256];
    mt_convexity_describe((uint32_t)head.v[1], reasons, sizeof reasons);
    printf(" %s", head.v[0] ? "convex" : "not convex");
    if (!head.v[0]) printf(" (%s)", reasons);
    printf(", volume %.9g", r->reals[0]);
    if (head.v[3]) printf(", %" PRId32 " degenerate faces", head.v[3]);
    if (head.v[2]) {
        printf(", %" PRId32 " reflex edges:", head.v[2]);
        for (int32_t k = 0; k + 1 < edges.n; k += 2)
            printf(" %" PRId32 "-%" PRId32, edges.v[k], edges.v[k + 1]);
    }
    putchar('\n');
    return true;
}

static void print_item_text(const meshtopo_reply_t *r, const query_kind *qk, const mt_id_list *ids,
                            int32_t i)
{
    int64_t subject = item_subject(ids, qk->kind, i);
    if (takes_pairs(qk->kind))
        printf("edge %" PRId64 "-%" PRIu32 ":", subject, ids->ids[2 * (size_t)i + 1]);
    else if (qk->kind == MESHTOPO_QUERY_T_CONVEXITY)
        printf("mesh:");
    else if (qk->kind == MESHTOPO_QUERY_T_DEFECTS)
        printf("%s:", defect_name(subject));
    else
        printf("%s %" PRId64 ":", qk->of, subject);
    if (r->item_status[i] != MESHTOPO_STATUS_CODE_T_OK) {
        printf(" %s\n", r->item_status[i] == MESHTOPO_STATUS_CODE_T_NOT_FOUND
                            ? "not found"
                            : mt_msgs_code_name(r->item_status[i]));
        return;
    }
    int32_t g0 = r->item_offsets[i], g1 = r->item_offsets[i + 1];
    if (print_geometry_text(r, qk->kind, i, g0, g1)) return;
    if (qk->kind == MESHTOPO_QUERY_T_VERTEX_RING && g0 == g1) printf(" isolated (no fans)");
    for (int32_t g = g0; g < g1; g++) {
        span v = values_of(r, g), v2 = values2_of(r, g);
        const char *sep = g > g0 ? " |" : "";
        switch (qk->kind) {
            case MESHTOPO_QUERY_T_VERTEX_RING:
                printf("%s fan %" PRId32 " %s: vertices", sep, g - g0,
                       r->group_boundary[g] ? "open" : "closed");
                print_span(v);
                printf("; faces");
                print_span(v2);
                break;
            case MESHTOPO_QUERY_T_FACE_NEIGHBORS:
                printf("%s side %" PRId32, sep, g - g0);
                if (v2.n == 2) printf(" (%" PRId32 "-%" PRId32 ")", v2.v[0], v2.v[1]);
                if (r->group_boundary[g])
                    printf(": boundary");
                else {
                    printf(": faces");
                    print_span(v);
                }
                break;
            case MESHTOPO_QUERY_T_VALENCE:
                printf(" valence");
                print_span(v);
                break;
            case MESHTOPO_QUERY_T_COMPONENTS:
                printf(" component");
                print_span(v);
                break;
            case MESHTOPO_QUERY_T_BOUNDARY_LOOPS:
                printf(" %" PRId32 " vertices:", v.n);
                print_span(v);
                break;
            case MESHTOPO_QUERY_T_DEFECTS:
                printf(" %" PRId32 " %s", v.n / 3, v.n / 3 == 1 ? "defect" : "defects");
                for (int32_t k = 0; k + 2 < v.n; k += 3)
                    printf("%s (%" PRId32 ", %" PRId32 ", %" PRId32 ")", k ? "," : "", v.v[k],
                           v.v[k + 1], v.v[k + 2]);
                break;
            default: /* EDGE_FACES */
                printf(" faces");
                print_span(v);
                break;
        }
    }
    putchar('\n');
}

/* ---- JSON output ------------------------------------------------------- */

static void write_span(mt_json *j, span s)
{
    mt_json_array_begin(j);
    for (int32_t k = 0; k < s.n; k++) mt_json_int(j, s.v[k]);
    mt_json_array_end(j);
}

/* The fields of a geometry item; false for other kinds. */
static bool write_geometry_json(mt_json *j, const meshtopo_reply_t *r, int32_t kind, int32_t i,
                                int32_t g0, int32_t g1)
{
    if (kind == MESHTOPO_QUERY_T_DIHEDRAL_ANGLES) {
        if (g1 > g0) {
            span v = values_of(r, g0);
            mt_json_key(j, "shape");
            mt_json_string(j, v.n == 1 ? shape_name(v.v[0]) : "unknown");
        }
        mt_json_key(j, "dihedral_angle");
        mt_json_double(j, r->reals[i]);
        return true;
    }
    if (kind == MESHTOPO_QUERY_T_ANGLE_DEFICITS) {
        mt_json_key(j, "angle_deficit");
        mt_json_double(j, r->reals[i]);
        mt_json_key(j, "boundary");
        mt_json_bool(j, g1 > g0 && r->group_boundary[g0] != 0);
        return true;
    }
    if (kind != MESHTOPO_QUERY_T_CONVEXITY) return false;
    span head = g1 > g0 ? values_of(r, g0) : (span){NULL, 0};
    span edges = g1 > g0 + 1 ? values_of(r, g0 + 1) : (span){NULL, 0};
    char reasons[256];
    mt_json_key(j, "convex");
    mt_json_bool(j, head.n == 4 && head.v[0] != 0);
    mt_json_key(j, "reasons");
    mt_convexity_describe(head.n == 4 ? (uint32_t)head.v[1] : 0, reasons, sizeof reasons);
    mt_json_string(j, reasons);
    mt_json_key(j, "degenerate_faces");
    mt_json_int(j, head.n == 4 ? head.v[3] : 0);
    mt_json_key(j, "reflex_edges");
    mt_json_array_begin(j);
    for (int32_t k = 0; k + 1 < edges.n; k += 2) {
        mt_json_array_begin(j);
        mt_json_int(j, edges.v[k]);
        mt_json_int(j, edges.v[k + 1]);
        mt_json_array_end(j);
    }
    mt_json_array_end(j);
    mt_json_key(j, "volume");
    mt_json_double(j, r->reals[0]);
    return true;
}

static void write_item_json(mt_json *j, const meshtopo_reply_t *r, const query_kind *qk,
                            const mt_id_list *ids, int32_t i)
{
    int64_t subject = item_subject(ids, qk->kind, i);
    mt_json_object_begin(j);
    if (takes_pairs(qk->kind)) {
        mt_json_key(j, "edge");
        mt_json_array_begin(j);
        mt_json_int(j, subject);
        mt_json_uint(j, ids->ids[2 * (size_t)i + 1]);
        mt_json_array_end(j);
    } else if (qk->kind == MESHTOPO_QUERY_T_DEFECTS) {
        mt_json_key(j, "kind");
        mt_json_string(j, defect_name(subject));
        mt_json_key(j, "kind_id");
        mt_json_int(j, subject);
    } else if (qk->kind != MESHTOPO_QUERY_T_CONVEXITY) {
        mt_json_key(j, qk->of);
        mt_json_int(j, subject);
    }
    mt_json_key(j, "status");
    mt_json_string(j, mt_msgs_code_name(r->item_status[i]));
    int32_t g0 = r->item_offsets[i], g1 = r->item_offsets[i + 1];
    if (write_geometry_json(j, r, qk->kind, i, g0, g1)) {
        mt_json_object_end(j);
        return;
    }
    switch (qk->kind) {
        case MESHTOPO_QUERY_T_VERTEX_RING:
            mt_json_key(j, "fans");
            mt_json_array_begin(j);
            for (int32_t g = g0; g < g1; g++) {
                mt_json_object_begin(j);
                mt_json_key(j, "boundary");
                mt_json_bool(j, r->group_boundary[g] != 0);
                mt_json_key(j, "vertices");
                write_span(j, values_of(r, g));
                mt_json_key(j, "faces");
                write_span(j, values2_of(r, g));
                mt_json_object_end(j);
            }
            mt_json_array_end(j);
            break;
        case MESHTOPO_QUERY_T_FACE_NEIGHBORS:
            mt_json_key(j, "sides");
            mt_json_array_begin(j);
            for (int32_t g = g0; g < g1; g++) {
                mt_json_object_begin(j);
                mt_json_key(j, "vertices");
                write_span(j, values2_of(r, g));
                mt_json_key(j, "boundary");
                mt_json_bool(j, r->group_boundary[g] != 0);
                mt_json_key(j, "faces");
                write_span(j, values_of(r, g));
                mt_json_object_end(j);
            }
            mt_json_array_end(j);
            break;
        case MESHTOPO_QUERY_T_DEFECTS:
            mt_json_key(j, "defects");
            mt_json_array_begin(j);
            for (int32_t g = g0; g < g1; g++) {
                span v = values_of(r, g);
                for (int32_t k = 0; k + 2 < v.n; k += 3) {
                    mt_json_object_begin(j);
                    mt_json_key(j, "a");
                    mt_json_int(j, v.v[k]);
                    mt_json_key(j, "b");
                    mt_json_int(j, v.v[k + 1]);
                    mt_json_key(j, "c");
                    mt_json_int(j, v.v[k + 2]);
                    mt_json_object_end(j);
                }
            }
            mt_json_array_end(j);
            break;
        default: {
            /* one group of plain values */
            const char *key = qk->kind == MESHTOPO_QUERY_T_VALENCE      ? "valence"
                              : qk->kind == MESHTOPO_QUERY_T_COMPONENTS ? "component"
                              : qk->kind == MESHTOPO_QUERY_T_EDGE_FACES ? "faces"
                                                                        : "vertices";
            bool scalar =
                qk->kind == MESHTOPO_QUERY_T_VALENCE || qk->kind == MESHTOPO_QUERY_T_COMPONENTS;
            mt_json_key(j, key);
            if (g1 == g0) {
                mt_json_null(j);
            } else if (scalar) {
                span v = values_of(r, g0);
                if (v.n == 1)
                    mt_json_int(j, v.v[0]);
                else
                    write_span(j, v);
            } else {
                write_span(j, values_of(r, g0));
            }
            break;
        }
    }
    mt_json_object_end(j);
}

static void print_json(const meshtopo_reply_t *r, const query_kind *qk, const mt_id_list *ids)
{
    mt_json j;
    mt_json_init(&j, stdout);
    mt_json_object_begin(&j);
    mt_json_key(&j, "mesh_id");
    mt_json_string(&j, r->mesh_id);
    mt_json_key(&j, "version");
    mt_json_int(&j, r->version);
    mt_json_key(&j, "kind");
    mt_json_string(&j, qk->name);
    if (qk->kind == MESHTOPO_QUERY_T_REPORT) {
        mt_json_key(&j, "report");
        mt_cli_topology_write_json(&j, &r->reports[0]);
    } else {
        mt_json_key(&j, "items");
        mt_json_array_begin(&j);
        for (int32_t i = 0; i < r->num_items; i++) write_item_json(&j, r, qk, ids, i);
        mt_json_array_end(&j);
    }
    mt_json_object_end(&j);
    mt_json_finish(&j);
}

/* ---- The command ------------------------------------------------------- */

static const query_kind *kind_find(const char *name)
{
    for (size_t i = 0; i < num_kinds; i++)
        if (strcmp(kinds[i].name, name) == 0) return &kinds[i];
    return NULL;
}

/* Appends the ids of every positional from the third on to *out. */
static int parse_ids(const mt_cli_args *args, mt_id_list *out)
{
    memset(out, 0, sizeof *out);
    for (size_t p = 2; p < args->num_positionals; p++) {
        mt_id_list part;
        char err[160];
        if (!mt_id_list_parse(args->positionals[p], UINT32_MAX, MAX_QUERY_IDS - out->count, &part,
                              err, sizeof err)) {
            mt_cli_error("query", "ids '%s': %s", args->positionals[p], err);
            mt_id_list_free(out);
            return MT_CLI_EXIT_USAGE;
        }
        uint32_t *ids = realloc(out->ids, (out->count + part.count + 1) * sizeof *ids);
        if (!ids) {
            mt_id_list_free(&part);
            mt_id_list_free(out);
            mt_cli_error("query", "out of memory");
            return MT_CLI_EXIT_USAGE;
        }
        if (part.count) memcpy(ids + out->count, part.ids, part.count * sizeof *ids);
        out->ids = ids;
        out->count += part.count;
        mt_id_list_free(&part);
    }
    return MT_CLI_EXIT_OK;
}

static int run_query(const mt_cli_args *args)
{
    const char *mesh_id = args->positionals[0];
    const query_kind *qk = kind_find(args->positionals[1]);
    if (!qk) {
        mt_cli_error("query",
                     "unknown kind '%s' (ring, valence, face-neighbors, edge-faces, "
                     "boundary-loops, components, report, defects, dihedral, deficit, "
                     "convexity)",
                     args->positionals[1]);
        return MT_CLI_EXIT_USAGE;
    }
    int version = 0;
    const char *version_text = mt_cli_arg(args, "version");
    if (version_text && (!mt_cli_parse_int(version_text, &version) || version == 0)) {
        mt_cli_error("query", "--version: expected 1, 2, ..., got '%s'", version_text);
        return MT_CLI_EXIT_USAGE;
    }
    mt_cli_remote remote;
    int code = mt_cli_remote_parse(args, &remote);
    if (code != MT_CLI_EXIT_OK) return code;
    mt_id_list ids;
    code = parse_ids(args, &ids);
    if (code != MT_CLI_EXIT_OK) return code;
    if (qk->ids == IDS_NEEDED && ids.count == 0) {
        mt_cli_error("query", "%s needs %s ids", qk->name,
                     takes_pairs(qk->kind) ? "vertex pair" : qk->of);
        code = MT_CLI_EXIT_USAGE;
    } else if (qk->ids == IDS_NONE && ids.count > 0) {
        mt_cli_error("query", "%s takes no ids", qk->name);
        code = MT_CLI_EXIT_USAGE;
    } else if (takes_pairs(qk->kind) && ids.count % 2 != 0) {
        mt_cli_error("query", "%s takes vertex pairs: an even number of ids, got %zu", qk->name,
                     ids.count);
        code = MT_CLI_EXIT_USAGE;
    }
    if (code != MT_CLI_EXIT_OK) {
        mt_id_list_free(&ids);
        return code;
    }

    mt_client *client = NULL;
    code = mt_cli_client_create("query", &remote, &client);
    if (code != MT_CLI_EXIT_OK) {
        mt_id_list_free(&ids);
        return code;
    }
    meshtopo_reply_t reply;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st =
        mt_client_query(client, mesh_id, version, qk->kind, ids.ids, ids.count, &reply, &diag);
    if (st != MT_OK) {
        code = mt_cli_call_failed("query", mesh_id, &remote, st, reply.mesh_id != NULL, &diag);
    } else if (!reply_consistent(&reply) ||
               (qk->kind == MESHTOPO_QUERY_T_REPORT && reply.num_reports != 1) ||
               (takes_pairs(qk->kind) && (size_t)reply.num_items * 2 != ids.count) ||
               (ids.count > 0 && !takes_pairs(qk->kind) && (size_t)reply.num_items != ids.count) ||
               reply.num_reals != expected_reals(qk->kind, reply.num_items) ||
               (qk->kind == MESHTOPO_QUERY_T_CONVEXITY && reply.num_items != 1)) {
        mt_cli_error("query", "mesh '%s': the reply's items and offsets do not fit together",
                     mesh_id);
        code = MT_CLI_EXIT_REFUSED;
    } else if (mt_cli_flag(args, "json")) {
        print_json(&reply, qk, &ids);
    } else if (qk->kind == MESHTOPO_QUERY_T_REPORT) {
        mt_cli_topology_print_text(&reply.reports[0], stdout);
    } else {
        for (int32_t i = 0; i < reply.num_items; i++) print_item_text(&reply, qk, &ids, i);
    }
    code = mt_cli_finish_output("query", code, MT_CLI_EXIT_USAGE);
    mt_client_reply_free(&reply);
    mt_client_destroy(client);
    mt_id_list_free(&ids);
    return code;
}

const mt_cli_command mt_cli_cmd_query = {
    .name = "query",
    .summary = "ask meshtopod one batch query about a held mesh",
    .synopsis = "ID KIND [IDS...] [--version N] [--json] [--lcm-url URL] [--prefix PREFIX]",
    .description =
        "Sends one query about mesh ID (its latest version unless --version) and prints the\n"
        "answer, one line per item. KIND and the IDS it takes (lists like 0,5,10-20 or\n"
        "separate arguments):\n"
        "  ring            vertex ids: each vertex's fans in rotation order (open/closed),\n"
        "                  the neighbour vertices and the faces of each fan\n"
        "  valence         vertex ids: the valence\n"
        "  face-neighbors  face ids: per side k (vertex k to k+1) the faces across it\n"
        "  edge-faces      vertex pairs (a b a b ...): the faces on edge a-b\n"
        "  boundary-loops  no ids: each boundary loop's vertices\n"
        "  components      face ids (none = every face): the component of each face\n"
        "  report          no ids: the topology report\n"
        "  defects         defect kinds 0-7 (none = every kind): the defects of each kind\n"
        "  dihedral        vertex pairs (a b ...): how edge a-b bends (convex, flat, reflex,\n"
        "                  or why it has no angle) and its interior dihedral angle\n"
        "  deficit         vertex ids: the angle deficit (2 pi minus the corner angles; pi\n"
        "                  minus them on the boundary)\n"
        "  convexity       no ids: whether the mesh bounds a convex polytope, why not, its\n"
        "                  reflex edges and enclosed volume\n"
        "An item the build left out (a rejected face, an edge no face has) prints\n"
        "\"not found\". --json prints {mesh_id, version, kind, items: [an object per item]}\n"
        "({..., report} for report).\n"
        "\n"
        "The geometry kinds (dihedral, deficit, convexity) need a mesh sent with positions.\n"
        "\n"
        "exit codes: 0 answered, 2 usage error, 5 meshtopod refused the query (unknown mesh\n"
        "or version, id out of range, no positions, ...), 6 no answer from meshtopod.\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 2,
    .max_positionals = SIZE_MAX,
    .run = run_query,
};
