/* `meshtopo list`: the mesh versions meshtopod holds (LIST_MESHES), one line
 * each with id, version, counts, defects and source, or one JSON object. */
#include <inttypes.h>
#include <string.h>

#include "remote.h"

static const mt_cli_option options[] = {
    {"json", NULL, "print {\"meshes\": [an object per mesh version]}"},
    MT_CLI_REMOTE_OPTIONS,
};

static void print_json(const meshtopo_reply_t *r)
{
    char hash[24];
    mt_json j;
    mt_json_init(&j, stdout);
    mt_json_object_begin(&j);
    mt_json_key(&j, "meshes");
    mt_json_array_begin(&j);
    for (int32_t i = 0; i < r->num_meshes; i++) {
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
        mt_json_string(&j, mt_cli_hash_text(r->list_content_hashes[i], hash, sizeof hash));
        mt_json_object_end(&j);
    }
    mt_json_array_end(&j);
    mt_json_object_end(&j);
    mt_json_finish(&j);
}

static void print_text(const meshtopo_reply_t *r)
{
    char hash[24];
    if (r->num_meshes == 0) {
        printf("no meshes held\n");
        return;
    }
    printf("%-24s %7s %10s %10s %8s  %-16s  %s\n", "MESH", "VERSION", "VERTICES", "FACES",
           "DEFECTS", "CONTENT HASH", "SOURCE");
    for (int32_t i = 0; i < r->num_meshes; i++)
        printf("%-24s %7" PRId32 " %10" PRId32 " %10" PRId32 " %8" PRId64 "  %-16s  %s\n",
               r->list_mesh_ids[i], r->list_versions[i], r->list_num_verts[i], r->list_num_faces[i],
               r->list_num_defects[i],
               mt_cli_hash_text(r->list_content_hashes[i], hash, sizeof hash), r->list_sources[i]);
}

static int run_list(const mt_cli_args *args)
{
    mt_cli_remote remote;
    int code = mt_cli_remote_parse(args, &remote);
    if (code != MT_CLI_EXIT_OK) return code;
    mt_client *client = NULL;
    code = mt_cli_client_create("list", &remote, &client);
    if (code != MT_CLI_EXIT_OK) return code;
    meshtopo_reply_t reply;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_client_list(client, NULL, &reply, &diag);
    if (st != MT_OK)
        code = mt_cli_call_failed("list", NULL, &remote, st, reply.mesh_id != NULL, &diag);
    else if (mt_cli_flag(args, "json"))
        print_json(&reply);
    else
        print_text(&reply);
    code = mt_cli_finish_output("list", code, MT_CLI_EXIT_USAGE);
    mt_client_reply_free(&reply);
    mt_cli_client_destroy("list", &remote, client);
    return code;
}

const mt_cli_command mt_cli_cmd_list = {
    .name = "list",
    .summary = "list the mesh versions meshtopod holds",
    .synopsis = "[--json] [--lcm-url URL] [--prefix PREFIX]",
    .description =
        "Asks meshtopod for every mesh version it holds and prints one line per version: id,\n"
        "version, vertex and face counts, defect count, content hash and source. With --json:\n"
        "{\"meshes\": [{mesh_id, version, source, utime, num_verts, num_faces, num_defects,\n"
        "content_hash}, ...]}, ordered by mesh id then version.\n"
        "\n"
        "exit codes: 0 listed, 2 usage error, 5 meshtopod answered with an error, 6 no answer.\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 0,
    .max_positionals = 0,
    .run = run_list,
};
