/* `meshtopo query ID KIND IDS...`: one batch query to meshtopod (one-rings,
 * valences, face neighbours, edge faces, boundary loops, components, the
 * report, the defect lists, dihedral angles, angle deficits, convexity,
 * self-intersections) and
 * its answer, one line per item (fans and sides labelled) or one JSON object
 * per item. The reply is read through the client's accessors
 * (meshtopo/client_reply.h), which the client checked before handing it out. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "inspect.h"
#include "meshtopo/geometry.h"
#include "meshtopo/query_kinds.h"
#include "meshtopo/report.h"
#include "meshtopo/report_json.h"
#include "remote.h"

/* Most ids one command line may expand to (the daemon has its own limit). */
#define MAX_QUERY_IDS ((size_t)1 << 24)

/* The kinds come from the query-kind table (meshtopo/query_kinds.h): their
 * names, the ids they take, what an item names and what the reply holds. */
typedef mt_msgs_query_kind query_kind;

/* Kinds answered by one item about the whole mesh. */
static bool about_mesh(const query_kind *qk)
{
    return qk->reply == MT_MSGS_REPLY_MESH;
}

/* Whether `meshtopo query` takes the kind: all but the listing, which is
 * `meshtopo list`'s. */
static bool queried(const query_kind *qk)
{
    return qk->reply != MT_MSGS_REPLY_LIST;
}

static const cli_option options[] = {
    {"version", "N", "query this version of the mesh (default: the latest)"},
    {"json", NULL, "print one JSON object: mesh_id, version, kind and an object per item"},
    CLI_REMOTE_OPTIONS,
};

/* ---- Reading the reply ------------------------------------------------- */

/* Whether a reply the client accepted has the items, reports and reals this
 * query asked for. */
static bool reply_fits(const meshtopo_reply_t *r, const query_kind *qk, const mt_id_list *ids)
{
    size_t items = mt_client_reply_num_items(r);
    if (qk->reply == MT_MSGS_REPLY_REPORT && r->num_reports != 1) return false;
    if (qk->pairs && items * 2 != ids->count) return false;
    if (ids->count > 0 && !qk->pairs && items != ids->count) return false;
    if (about_mesh(qk) && items != 1) return false;
    if (qk->reals_per_item == MT_MSGS_REALS_VARY) return true; /* checked when read */
    return (int64_t)r->num_reals == (int64_t)qk->reals_per_item * r->num_items;
}

/* Group k of an item, or an empty one when the item has fewer groups. */
static mt_client_group group_of(const meshtopo_reply_t *r, const mt_client_item *item, size_t k)
{
    if (k < item->num_groups) return mt_client_item_group(r, item, k);
    mt_client_group none = {false, NULL, 0, NULL, 0};
    return none;
}

/* A defect of a DEFECTS answer: its kind (the item) and the a, b, c the
 * wire carries as int32 (reply_t), back to the report's uint32. */
static mt_defect defect_of(int64_t kind, const int32_t abc[3])
{
    mt_defect d = {kind >= 0 && kind < MT_DEFECT_KIND_COUNT ? (uint32_t)kind : MT_DEFECT_KIND_COUNT,
                   (uint32_t)abc[0], (uint32_t)abc[1], (uint32_t)abc[2]};
    return d;
}

static const char *defect_name(int64_t kind)
{
    return kind >= 0 && kind < MT_DEFECT_KIND_COUNT ? mt_defect_key((mt_defect_kind)kind)
                                                    : "unknown";
}

/* The element an item answers: the queried id, or its position when the
 * kind lists every element (boundary loops, components or defects without ids). */
static int64_t item_subject(const mt_id_list *ids, const query_kind *qk, size_t i)
{
    if (qk->pairs) return ids->ids[2 * i];
    if (i < ids->count) return ids->ids[i];
    return (int64_t)i;
}

/* ---- Readable output --------------------------------------------------- */

static void print_values(const int32_t *v, size_t n)
{
    if (n == 0) printf(" none");
    for (size_t k = 0; k < n; k++) printf(" %" PRId32, v[k]);
}

static const char *shape_name(int32_t shape)
{
    return shape >= 0 && shape <= MT_EDGE_DEGENERATE ? mt_edge_shape_name((mt_edge_shape)shape)
                                                     : "unknown";
}

/* A SELF_INTERSECTIONS item as the lists of `inspect --self-intersections`
 * (msgs/reply_t.lcm: three groups, one real per non-simple face); false
 * when the groups do not have that shape. Free with inspect_geometry_free. */
static bool read_self_intersections(const meshtopo_reply_t *r, const mt_client_item *item,
                                    inspect_geometry *g)
{
    *g = (inspect_geometry){.ms = -1};
    mt_client_group pairs = group_of(r, item, 0), faces = group_of(r, item, 1),
                    loops = group_of(r, item, 2);
    if (item->num_groups != 3 || pairs.num_values % 2 || faces.num_values % 4 ||
        loops.num_values % 5 || (size_t)r->num_reals != faces.num_values / 4)
        return false;
    g->num_pairs = pairs.num_values / 2;
    g->num_faces = faces.num_values / 4;
    g->num_loops = loops.num_values / 5;
    g->pairs = calloc(g->num_pairs + 1, sizeof *g->pairs);
    g->faces = calloc(g->num_faces + 1, sizeof *g->faces);
    g->loops = calloc(g->num_loops + 1, sizeof *g->loops);
    if (!g->pairs || !g->faces || !g->loops) {
        inspect_geometry_free(g);
        return false;
    }
    for (size_t i = 0; i < g->num_pairs; i++)
        g->pairs[i] =
            (mt_face_pair){(uint32_t)pairs.values[2 * i], (uint32_t)pairs.values[2 * i + 1]};
    for (size_t i = 0; i < g->num_faces; i++) {
        const int32_t *v = faces.values + 4 * i;
        g->faces[i] = (mt_face_shape){(uint32_t)v[0], (mt_face_shape_kind)v[1], (uint32_t)v[2],
                                      (uint32_t)v[3], mt_client_reply_real(r, i)};
    }
    for (size_t i = 0; i < g->num_loops; i++) {
        const int32_t *v = loops.values + 5 * i;
        g->loops[i] = (mt_loop_crossing){
            (uint32_t)v[0], {(uint32_t)v[1], (uint32_t)v[2]}, {(uint32_t)v[3], (uint32_t)v[4]}};
    }
    return true;
}

/* The rest of a geometry item's line (after its label); false for other kinds. */
static bool print_geometry_text(const meshtopo_reply_t *r, int32_t kind, size_t i,
                                const mt_client_item *item)
{
    const double degrees = 180.0 / 3.14159265358979323846;
    mt_client_group first = group_of(r, item, 0);
    if (kind == MESHTOPO_QUERY_T_DIHEDRAL_ANGLES) {
        double angle = mt_client_reply_real(r, i);
        printf(" %s", first.num_values == 1 ? shape_name(first.values[0]) : "?");
        if (isnan(angle))
            printf(" (no dihedral angle)\n");
        else
            printf(", dihedral angle %.9g rad (%.6g deg)\n", angle, angle * degrees);
        return true;
    }
    if (kind == MESHTOPO_QUERY_T_ANGLE_DEFICITS) {
        printf(" angle deficit %.9g rad%s\n", mt_client_reply_real(r, i),
               first.boundary ? " (boundary: pi minus the corner angles)" : "");
        return true;
    }
    if (kind == MESHTOPO_QUERY_T_SELF_INTERSECTIONS) {
        inspect_geometry g;
        if (!read_self_intersections(r, item, &g)) {
            printf(" malformed answer\n");
            return true;
        }
        putchar('\n');
        inspect_geometry_text(stdout, &g, 0);
        inspect_geometry_free(&g);
        return true;
    }
    if (kind != MESHTOPO_QUERY_T_CONVEXITY) return false;
    mt_client_group edges = group_of(r, item, 1);
    if (first.num_values != 4) {
        printf(" malformed answer\n");
        return true;
    }
    const int32_t *head = first.values;
    char reasons[256];
    mt_convexity_describe((uint32_t)head[1], reasons, sizeof reasons);
    printf(" %s", head[0] ? "convex" : "not convex");
    if (!head[0]) printf(" (%s)", reasons);
    printf(", volume %.9g", mt_client_reply_real(r, 0));
    if (head[3]) printf(", %" PRId32 " degenerate faces", head[3]);
    if (head[2]) {
        printf(", %" PRId32 " reflex edges:", head[2]);
        for (size_t k = 0; k + 1 < edges.num_values; k += 2)
            printf(" %" PRId32 "-%" PRId32, edges.values[k], edges.values[k + 1]);
    }
    putchar('\n');
    return true;
}

static void print_item_text(const meshtopo_reply_t *r, const query_kind *qk, const mt_id_list *ids,
                            size_t i)
{
    int64_t subject = item_subject(ids, qk, i);
    if (qk->pairs)
        printf("edge %" PRId64 "-%" PRIu32 ":", subject, ids->ids[2 * i + 1]);
    else if (about_mesh(qk))
        printf("mesh:");
    else if (qk->space == MT_MSGS_ID_DEFECT_KIND)
        printf("%s:", defect_name(subject));
    else
        printf("%s %" PRId64 ":", qk->of, subject);
    mt_client_item item = mt_client_reply_item(r, i);
    if (item.status != MESHTOPO_STATUS_CODE_T_OK) {
        printf(" %s\n", item.status == MESHTOPO_STATUS_CODE_T_NOT_FOUND
                            ? "not found"
                            : mt_msgs_code_name(item.status));
        return;
    }
    if (print_geometry_text(r, qk->kind, i, &item)) return;
    if (qk->kind == MESHTOPO_QUERY_T_VERTEX_RING && item.num_groups == 0)
        printf(" isolated (no fans)");
    for (size_t k = 0; k < item.num_groups; k++) {
        mt_client_group g = mt_client_item_group(r, &item, k);
        const char *sep = k > 0 ? " |" : "";
        switch (qk->kind) {
            case MESHTOPO_QUERY_T_VERTEX_RING:
                printf("%s fan %zu %s: vertices", sep, k, g.boundary ? "open" : "closed");
                print_values(g.values, g.num_values);
                printf("; faces");
                print_values(g.values2, g.num_values2);
                break;
            case MESHTOPO_QUERY_T_FACE_NEIGHBORS:
                printf("%s side %zu", sep, k);
                if (g.num_values2 == 2)
                    printf(" (%" PRId32 "-%" PRId32 ")", g.values2[0], g.values2[1]);
                if (g.boundary)
                    printf(": boundary");
                else {
                    printf(": faces");
                    print_values(g.values, g.num_values);
                }
                break;
            case MESHTOPO_QUERY_T_VALENCE:
                printf(" valence");
                print_values(g.values, g.num_values);
                break;
            case MESHTOPO_QUERY_T_COMPONENTS:
                printf(" component");
                print_values(g.values, g.num_values);
                break;
            case MESHTOPO_QUERY_T_BOUNDARY_LOOPS:
                printf(" %zu vertices:", g.num_values);
                print_values(g.values, g.num_values);
                break;
            case MESHTOPO_QUERY_T_DEFECTS:
                printf(" %zu %s", g.num_values / 3, g.num_values / 3 == 1 ? "defect" : "defects");
                for (size_t d = 0; d + 2 < g.num_values; d += 3) {
                    char text[256];
                    const mt_defect defect = defect_of(subject, &g.values[d]);
                    mt_defect_describe(&defect, text, sizeof text);
                    printf("%s %s", d ? ";" : ":", text);
                }
                break;
            case MESHTOPO_QUERY_T_EDGE_FACES:
                printf(" faces");
                print_values(g.values, g.num_values);
                break;
            default: /* a kind without a printer of its own: its groups as they come */
                printf("%s values", sep);
                print_values(g.values, g.num_values);
                if (g.num_values2) {
                    printf("; values2");
                    print_values(g.values2, g.num_values2);
                }
                break;
        }
    }
    putchar('\n');
}

/* ---- JSON output ------------------------------------------------------- */

static void write_values(mt_json *j, const int32_t *v, size_t n)
{
    mt_json_array_begin(j);
    for (size_t k = 0; k < n; k++) mt_json_int(j, v[k]);
    mt_json_array_end(j);
}

/* The fields of a geometry item; false for other kinds. */
static bool write_geometry_json(mt_json *j, const meshtopo_reply_t *r, int32_t kind, size_t i,
                                const mt_client_item *item)
{
    mt_client_group first = group_of(r, item, 0);
    if (kind == MESHTOPO_QUERY_T_DIHEDRAL_ANGLES) {
        if (item->num_groups > 0) {
            mt_json_key(j, "shape");
            mt_json_string(j, first.num_values == 1 ? shape_name(first.values[0]) : "unknown");
        }
        mt_json_key(j, "dihedral_angle");
        mt_json_double(j, mt_client_reply_real(r, i));
        return true;
    }
    if (kind == MESHTOPO_QUERY_T_ANGLE_DEFICITS) {
        mt_json_key(j, "angle_deficit");
        mt_json_double(j, mt_client_reply_real(r, i));
        mt_json_key(j, "boundary");
        mt_json_bool(j, first.boundary);
        return true;
    }
    if (kind == MESHTOPO_QUERY_T_SELF_INTERSECTIONS) {
        inspect_geometry g;
        if (!read_self_intersections(r, item, &g)) {
            mt_json_key(j, "malformed");
            mt_json_bool(j, true);
            return true;
        }
        inspect_geometry_json(j, &g);
        inspect_geometry_free(&g);
        return true;
    }
    if (kind != MESHTOPO_QUERY_T_CONVEXITY) return false;
    mt_client_group edges = group_of(r, item, 1);
    const int32_t *head = first.num_values == 4 ? first.values : NULL;
    char reasons[256];
    mt_json_key(j, "convex");
    mt_json_bool(j, head && head[0] != 0);
    mt_json_key(j, "reasons");
    mt_convexity_describe(head ? (uint32_t)head[1] : 0, reasons, sizeof reasons);
    mt_json_string(j, reasons);
    mt_json_key(j, "degenerate_faces");
    mt_json_int(j, head ? head[3] : 0);
    mt_json_key(j, "reflex_edges");
    mt_json_array_begin(j);
    for (size_t k = 0; k + 1 < edges.num_values; k += 2) {
        mt_json_array_begin(j);
        mt_json_int(j, edges.values[k]);
        mt_json_int(j, edges.values[k + 1]);
        mt_json_array_end(j);
    }
    mt_json_array_end(j);
    mt_json_key(j, "volume");
    mt_json_double(j, mt_client_reply_real(r, 0));
    return true;
}

static void write_item_json(mt_json *j, const meshtopo_reply_t *r, const query_kind *qk,
                            const mt_id_list *ids, size_t i)
{
    int64_t subject = item_subject(ids, qk, i);
    mt_json_object_begin(j);
    if (qk->pairs) {
        mt_json_key(j, "edge");
        mt_json_array_begin(j);
        mt_json_int(j, subject);
        mt_json_uint(j, ids->ids[2 * i + 1]);
        mt_json_array_end(j);
    } else if (qk->space == MT_MSGS_ID_DEFECT_KIND) {
        mt_json_key(j, "kind");
        mt_json_string(j, defect_name(subject));
        mt_json_key(j, "kind_id");
        mt_json_int(j, subject);
    } else if (!about_mesh(qk)) {
        mt_json_key(j, qk->of);
        mt_json_int(j, subject);
    }
    mt_client_item item = mt_client_reply_item(r, i);
    mt_json_key(j, "status");
    mt_json_string(j, mt_msgs_code_name(item.status));
    if (write_geometry_json(j, r, qk->kind, i, &item)) {
        mt_json_object_end(j);
        return;
    }
    switch (qk->kind) {
        case MESHTOPO_QUERY_T_VERTEX_RING:
            mt_json_key(j, "fans");
            mt_json_array_begin(j);
            for (size_t k = 0; k < item.num_groups; k++) {
                mt_client_group g = mt_client_item_group(r, &item, k);
                mt_json_object_begin(j);
                mt_json_key(j, "boundary");
                mt_json_bool(j, g.boundary);
                mt_json_key(j, "vertices");
                write_values(j, g.values, g.num_values);
                mt_json_key(j, "faces");
                write_values(j, g.values2, g.num_values2);
                mt_json_object_end(j);
            }
            mt_json_array_end(j);
            break;
        case MESHTOPO_QUERY_T_FACE_NEIGHBORS:
            mt_json_key(j, "sides");
            mt_json_array_begin(j);
            for (size_t k = 0; k < item.num_groups; k++) {
                mt_client_group g = mt_client_item_group(r, &item, k);
                mt_json_object_begin(j);
                mt_json_key(j, "vertices");
                write_values(j, g.values2, g.num_values2);
                mt_json_key(j, "boundary");
                mt_json_bool(j, g.boundary);
                mt_json_key(j, "faces");
                write_values(j, g.values, g.num_values);
                mt_json_object_end(j);
            }
            mt_json_array_end(j);
            break;
        case MESHTOPO_QUERY_T_DEFECTS:
            mt_json_key(j, "defects");
            mt_json_array_begin(j);
            for (size_t k = 0; k < item.num_groups; k++) {
                mt_client_group g = mt_client_item_group(r, &item, k);
                for (size_t d = 0; d + 2 < g.num_values; d += 3) {
                    const mt_defect defect = defect_of(subject, &g.values[d]);
                    mt_report_json_write_defect(j, &defect);
                }
            }
            mt_json_array_end(j);
            break;
        default: {
            /* one group of plain values (the first, for a kind without a
             * printer of its own) */
            const char *key = qk->kind == MESHTOPO_QUERY_T_VALENCE          ? "valence"
                              : qk->kind == MESHTOPO_QUERY_T_COMPONENTS     ? "component"
                              : qk->kind == MESHTOPO_QUERY_T_EDGE_FACES     ? "faces"
                              : qk->kind == MESHTOPO_QUERY_T_BOUNDARY_LOOPS ? "vertices"
                                                                            : "values";
            bool scalar =
                qk->kind == MESHTOPO_QUERY_T_VALENCE || qk->kind == MESHTOPO_QUERY_T_COMPONENTS;
            mt_client_group g = group_of(r, &item, 0);
            mt_json_key(j, key);
            if (item.num_groups == 0)
                mt_json_null(j);
            else if (scalar && g.num_values == 1)
                mt_json_int(j, g.values[0]);
            else
                write_values(j, g.values, g.num_values);
            break;
        }
    }
    mt_json_object_end(j);
}

/* report: the REPORT query's report converted, NULL for the other kinds. */
static void print_json(const meshtopo_reply_t *r, const query_kind *qk, const mt_id_list *ids,
                       const cli_report *report)
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
    if (report) {
        mt_json_key(&j, "report");
        cli_report_write_json(&j, report);
    } else {
        mt_json_key(&j, "items");
        mt_json_array_begin(&j);
        for (size_t i = 0; i < mt_client_reply_num_items(r); i++)
            write_item_json(&j, r, qk, ids, i);
        mt_json_array_end(&j);
    }
    mt_json_object_end(&j);
    mt_json_finish(&j);
}

/* ---- The command ------------------------------------------------------- */

static const query_kind *kind_find(const char *name)
{
    const query_kind *qk = mt_msgs_query_kind_named(name);
    return qk && queried(qk) ? qk : NULL;
}

/* The names kind_find takes, "ring, valence, ...", into text. */
static void kind_names(char *text, size_t size)
{
    size_t used = 0;
    text[0] = '\0';
    for (size_t i = 0; i < mt_msgs_query_kind_count(); i++) {
        const query_kind *qk = mt_msgs_query_kind_at(i);
        if (!queried(qk)) continue;
        int n = snprintf(text + used, size - used, "%s%s", used ? ", " : "", qk->name);
        if (n < 0 || (size_t)n >= size - used) break;
        used += (size_t)n;
    }
}

/* Appends the ids of every positional from the third on to *out. */
static int parse_ids(const cli_args *args, mt_id_list *out)
{
    memset(out, 0, sizeof *out);
    for (size_t p = 2; p < args->num_positionals; p++) {
        mt_id_list part;
        char err[160];
        if (!mt_id_list_parse(args->positionals[p], UINT32_MAX, MAX_QUERY_IDS - out->count, &part,
                              err, sizeof err)) {
            cli_error("query", "ids '%s': %s", args->positionals[p], err);
            mt_id_list_free(out);
            return CLI_EXIT_USAGE;
        }
        uint32_t *ids = realloc(out->ids, (out->count + part.count + 1) * sizeof *ids);
        if (!ids) {
            mt_id_list_free(&part);
            mt_id_list_free(out);
            cli_error("query", "out of memory");
            return CLI_EXIT_USAGE;
        }
        if (part.count) memcpy(ids + out->count, part.ids, part.count * sizeof *ids);
        out->ids = ids;
        out->count += part.count;
        mt_id_list_free(&part);
    }
    return CLI_EXIT_OK;
}

static int run_query(const cli_args *args)
{
    const char *mesh_id = args->positionals[0];
    const query_kind *qk = kind_find(args->positionals[1]);
    if (!qk) {
        char names[512];
        kind_names(names, sizeof names);
        cli_error("query", "unknown kind '%s' (%s)", args->positionals[1], names);
        return CLI_EXIT_USAGE;
    }
    int version = 0;
    const char *version_text = cli_arg(args, "version");
    if (version_text && (!cli_parse_int(version_text, &version) || version == 0)) {
        cli_error("query", "--version: expected 1, 2, ..., got '%s'", version_text);
        return CLI_EXIT_USAGE;
    }
    cli_remote remote;
    int code = cli_remote_parse(args, &remote);
    if (code != CLI_EXIT_OK) return code;
    mt_id_list ids;
    code = parse_ids(args, &ids);
    if (code != CLI_EXIT_OK) return code;
    if (qk->ids == MT_MSGS_IDS_NEEDED && ids.count == 0) {
        cli_error("query", "%s needs %s ids", qk->name, qk->pairs ? "vertex pair" : qk->of);
        code = CLI_EXIT_USAGE;
    } else if (qk->ids == MT_MSGS_IDS_NONE && ids.count > 0) {
        cli_error("query", "%s takes no ids", qk->name);
        code = CLI_EXIT_USAGE;
    } else if (qk->pairs && ids.count % 2 != 0) {
        cli_error("query", "%s takes vertex pairs: an even number of ids, got %zu", qk->name,
                  ids.count);
        code = CLI_EXIT_USAGE;
    }
    if (code != CLI_EXIT_OK) {
        mt_id_list_free(&ids);
        return code;
    }

    mt_client *client = NULL;
    code = cli_client_create("query", &remote, &client);
    if (code != CLI_EXIT_OK) {
        mt_id_list_free(&ids);
        return code;
    }
    meshtopo_reply_t reply;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st =
        mt_client_query(client, mesh_id, version, qk->kind, ids.ids, ids.count, &reply, &diag);
    size_t num_items = mt_client_reply_num_items(&reply);
    bool answered = reply.mesh_id != NULL, json = cli_flag(args, "json");
    cli_report report;
    memset(&report, 0, sizeof report);
    if ((st == MT_ERR_CORRUPT && !answered) || (st == MT_OK && !reply_fits(&reply, qk, &ids))) {
        /* Unanswered MT_ERR_CORRUPT: the client refused a reply whose offsets
         * do not describe its arrays. */
        cli_error("query", "mesh '%s': the reply's items and offsets do not fit together", mesh_id);
        code = CLI_EXIT_REFUSED;
    } else if (st != MT_OK) {
        code = cli_call_failed("query", mesh_id, &remote, st, answered, &diag);
    } else if (qk->reply == MT_MSGS_REPLY_REPORT) {
        code = cli_report_take("query", &reply.reports[0], &report);
        if (code == CLI_EXIT_OK && json)
            print_json(&reply, qk, &ids, &report);
        else if (code == CLI_EXIT_OK)
            cli_report_print_text(&report, stdout);
    } else if (json) {
        print_json(&reply, qk, &ids, NULL);
    } else {
        for (size_t i = 0; i < num_items; i++) print_item_text(&reply, qk, &ids, i);
    }
    cli_report_free(&report);
    code = cli_finish_output("query", code, CLI_EXIT_USAGE);
    mt_client_reply_free(&reply);
    cli_client_destroy("query", &remote, client);
    mt_id_list_free(&ids);
    return code;
}

const cli_command cli_cmd_query = {
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
        "  self-intersections  no ids: faces passing through or touching each other (exact),\n"
        "                  faces crossing themselves or warped, boundary loops crossing\n"
        "                  themselves (as `meshtopo inspect --self-intersections`)\n"
        "An item the build left out (a rejected face, an edge no face has) prints\n"
        "\"not found\". --json prints {mesh_id, version, kind, items: [an object per item]}\n"
        "({..., report} for report); a defects item lists its defects as records\n"
        "(README.md \"Defect records\": kind, vertices, faces, edge, face_count, ...).\n"
        "\n"
        "The geometry kinds (dihedral, deficit, convexity, self-intersections) need a mesh\n"
        "sent with positions.\n"
        "\n"
        "exit codes: 0 answered, 2 usage error, 5 meshtopod refused the query (unknown mesh\n"
        "or version, id out of range, no positions, ...), 6 no answer from meshtopod.\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 2,
    .max_positionals = SIZE_MAX,
    .run = run_query,
};
