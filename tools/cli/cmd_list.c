/* `meshtopo list`: the mesh versions meshtopod holds (LIST_MESHES), one line
 * each with id, version, counts, defects and source, or one JSON object. A
 * cluster's members are each asked for the ids they own, and the listings
 * merged. */
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "members.h"
#include "remote.h"

static const cli_option options[] = {
    {"json", NULL, "print {\"meshes\": [an object per mesh version]}"},
    CLI_REMOTE_OPTIONS,
};

/* One listed version: row i of reply r. */
typedef struct list_row {
    const meshtopo_reply_t *r;
    int32_t i;
} list_row;

static int row_cmp(const void *pa, const void *pb)
{
    const list_row *a = pa, *b = pb;
    int c = strcmp(a->r->list_mesh_ids[a->i], b->r->list_mesh_ids[b->i]);
    if (c) return c;
    int32_t va = a->r->list_versions[a->i], vb = b->r->list_versions[b->i];
    return va < vb ? -1 : va > vb;
}

static void print_json(const list_row *rows, size_t n)
{
    char hash[24];
    mt_json j;
    mt_json_init(&j, stdout);
    mt_json_object_begin(&j);
    mt_json_key(&j, "meshes");
    mt_json_array_begin(&j);
    for (size_t k = 0; k < n; k++) {
        const meshtopo_reply_t *r = rows[k].r;
        int32_t i = rows[k].i;
        mt_json_object_begin(&j);
        mt_json_key(&j, "mesh_id");
        mt_json_string(&j, r->list_mesh_ids[i]);
        mt_json_key(&j, "version");
        mt_json_int(&j, r->list_versions[i]);
        mt_json_key(&j, "source");
        mt_json_string(&j, r->list_sources[i]);
        mt_json_key(&j, "utime");
        mt_json_int(&j, r->list_utimes[i]);
        mt_json_key(&j, "num_verts");
        mt_json_int(&j, r->list_num_verts[i]);
        mt_json_key(&j, "num_faces");
        mt_json_int(&j, r->list_num_faces[i]);
        mt_json_key(&j, "num_defects");
        mt_json_int(&j, r->list_num_defects[i]);
        mt_json_key(&j, "content_hash");
        mt_json_string(&j, cli_hash_text(r->list_content_hashes[i], hash, sizeof hash));
        mt_json_object_end(&j);
    }
    mt_json_array_end(&j);
    mt_json_object_end(&j);
    mt_json_finish(&j);
}

static void print_text(const list_row *rows, size_t n)
{
    char hash[24];
    if (n == 0) {
        printf("no meshes held\n");
        return;
    }
    printf("%-24s %7s %10s %10s %8s  %-16s  %s\n", "MESH", "VERSION", "VERTICES", "FACES",
           "DEFECTS", "CONTENT HASH", "SOURCE");
    for (size_t k = 0; k < n; k++) {
        const meshtopo_reply_t *r = rows[k].r;
        int32_t i = rows[k].i;
        printf("%-24s %7" PRId32 " %10" PRId32 " %10" PRId32 " %8" PRId64 "  %-16s  %s\n",
               r->list_mesh_ids[i], r->list_versions[i], r->list_num_verts[i], r->list_num_faces[i],
               r->list_num_defects[i], cli_hash_text(r->list_content_hashes[i], hash, sizeof hash),
               r->list_sources[i]);
    }
}

/* Every version the replies list, by mesh id then version, each once (two
 * members answer for an id while their views of the cluster differ). */
static list_row *merge(const meshtopo_reply_t *replies, int num_replies, size_t *out_n)
{
    size_t total = 0;
    for (int m = 0; m < num_replies; m++) total += (size_t)replies[m].num_meshes;
    list_row *rows = malloc((total + 1) * sizeof *rows);
    if (!rows) return NULL;
    size_t n = 0;
    for (int m = 0; m < num_replies; m++)
        for (int32_t i = 0; i < replies[m].num_meshes; i++) rows[n++] = (list_row){&replies[m], i};
    qsort(rows, n, sizeof *rows, row_cmp);
    size_t kept = 0;
    for (size_t k = 0; k < n; k++)
        if (kept == 0 || row_cmp(&rows[kept - 1], &rows[k]) != 0) rows[kept++] = rows[k];
    *out_n = kept;
    return rows;
}

static int run_list(const cli_args *args)
{
    cli_remote remote;
    int code = cli_remote_parse(args, &remote);
    if (code != CLI_EXIT_OK) return code;
    mt_client *client = NULL;
    code = cli_client_create("list", &remote, &client);
    if (code != CLI_EXIT_OK) return code;
    /* One daemon answers for every mesh; each member of a cluster for its
     * own, so each is asked in turn. */
    static cli_members members;
    cli_members_find(client, remote.timeout_ms, &members);
    const int asked = members.cluster[0] ? members.count : 1;
    meshtopo_reply_t *replies = calloc((size_t)asked, sizeof *replies);
    int answered = 0;
    for (int m = 0; replies && m < asked; m++) {
        mt_diag diag;
        mt_diag_clear(&diag);
        const char *instance = members.cluster[0] ? members.instances[m] : NULL;
        mt_status st = mt_client_list_from(client, instance, NULL, &replies[answered], &diag);
        if (st == MT_OK) {
            answered++;
            continue;
        }
        if (instance)
            fprintf(stderr, "meshtopo list: member '%s' (instance %s) of cluster '%s':\n",
                    members.names[m], instance, members.cluster);
        code = cli_call_failed("list", NULL, &remote, st, replies[answered].mesh_id != NULL, &diag);
        mt_client_reply_free(&replies[answered]);
    }
    size_t n = 0;
    list_row *rows = replies && answered ? merge(replies, answered, &n) : NULL;
    if (answered && !rows) {
        cli_error("list", "out of memory merging %d listings", answered);
        code = CLI_EXIT_NO_ANSWER;
    } else if (answered && cli_flag(args, "json")) {
        print_json(rows, n);
    } else if (answered) {
        print_text(rows, n);
    }
    code = cli_finish_output("list", code, CLI_EXIT_USAGE);
    free(rows);
    for (int m = 0; m < answered; m++) mt_client_reply_free(&replies[m]);
    free(replies);
    cli_client_destroy("list", &remote, client);
    return code;
}

const cli_command cli_cmd_list = {
    .name = "list",
    .summary = "list the mesh versions meshtopod holds",
    .synopsis = "[--json] [--lcm-url URL] [--prefix PREFIX]",
    .description =
        "Asks meshtopod for every mesh version it holds and prints one line per version: id,\n"
        "version, vertex and face counts, defect count, content hash and source. With --json:\n"
        "{\"meshes\": [{mesh_id, version, source, utime, num_verts, num_faces, num_defects,\n"
        "content_hash}, ...]}, ordered by mesh id then version. The daemons are learnt from\n"
        "their heartbeats first: in a cluster (meshtopod --cluster) each member is asked for\n"
        "the meshes it owns and the lists are merged; a member that does not answer is named.\n"
        "\n"
        "exit codes: 0 listed, 2 usage error, 5 meshtopod answered with an error, 6 no answer.\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 0,
    .max_positionals = 0,
    .run = run_list,
};
