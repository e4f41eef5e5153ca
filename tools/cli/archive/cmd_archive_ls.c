/* `meshtopo archive ls DIR [--json]`: every archived mesh version with its
 * time, source, file size and topology summary, read from the files'
 * attributes only; unreadable files are listed with the reason. */
#include <inttypes.h>
#include <stdio.h>
#include <time.h>

#include "archive_common.h"
#include "cmd_archive.h"
#include "meshtopo/json_writer.h"
#include "remote.h"

/* utime (microseconds since the epoch) as "2026-11-22T07:44:03.123456Z". */
static const char *utime_text(int64_t utime, char *buf, size_t size)
{
    time_t seconds = (time_t)(utime / 1000000);
    long micros = (long)(utime % 1000000);
    if (micros < 0) {
        micros += 1000000;
        seconds--;
    }
    struct tm tm;
    if (!gmtime_r(&seconds, &tm)) {
        snprintf(buf, size, "%" PRId64, utime);
        return buf;
    }
    char date[32];
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%S", &tm);
    snprintf(buf, size, "%s.%06ldZ", date, micros);
    return buf;
}

static void print_text(const char *dir, const mt_archive_listing *l)
{
    char hash[24], when[64];
    size_t good = 0;
    for (size_t i = 0; i < l->count; i++) good += l->entries[i].status == MT_OK;
    printf("%s: %zu archived version%s", dir, good, good == 1 ? "" : "s");
    if (good < l->count)
        printf(", %zu unreadable file%s", l->count - good, l->count - good == 1 ? "" : "s");
    printf("\n");
    if (good > 0)
        printf("%-24s %7s  %-27s %10s %9s %9s %7s %5s %5s  %-16s  %s\n", "MESH", "VERSION",
               "TIME (UTC)", "BYTES", "VERTICES", "FACES", "DEFECTS", "COMPS", "GENUS",
               "CONTENT HASH", "SOURCE");
    for (size_t i = 0; i < l->count; i++) {
        const mt_archive_entry *e = &l->entries[i];
        if (e->status != MT_OK) continue;
        const mt_archive_summary *s = &e->summary;
        char genus[16];
        if (s->genus < 0)
            snprintf(genus, sizeof genus, "-");
        else
            snprintf(genus, sizeof genus, "%" PRId32, s->genus);
        printf("%-24s %7" PRIu32 "  %-27s %10" PRIu64 " %9" PRIu32 " %9" PRIu32 " %7" PRIu64
               " %5" PRIu32 " %5s  %-16s  %s\n",
               e->mesh_id, e->version, utime_text(e->utime, when, sizeof when), e->file_bytes,
               s->num_verts, s->num_faces, s->num_defects, s->connected_components, genus,
               cli_hash_text((int64_t)e->content_hash, hash, sizeof hash), e->source);
    }
    for (size_t i = 0; i < l->count; i++)
        if (l->entries[i].status != MT_OK) printf("unreadable: %s\n", l->entries[i].diag.message);
}

static void print_json(const char *dir, const mt_archive_listing *l)
{
    char hash[24], when[64];
    mt_json j;
    mt_json_init(&j, stdout);
    mt_json_object_begin(&j);
    mt_json_key(&j, "archive");
    mt_json_string(&j, dir);
    mt_json_key(&j, "meshes");
    mt_json_array_begin(&j);
    for (size_t i = 0; i < l->count; i++) {
        const mt_archive_entry *e = &l->entries[i];
        if (e->status != MT_OK) continue;
        const mt_archive_summary *s = &e->summary;
        mt_json_object_begin(&j);
        mt_json_key(&j, "mesh_id");
        mt_json_string(&j, e->mesh_id);
        mt_json_key(&j, "version");
        mt_json_uint(&j, e->version);
        mt_json_key(&j, "utime");
        mt_json_int(&j, e->utime);
        mt_json_key(&j, "time");
        mt_json_string(&j, utime_text(e->utime, when, sizeof when));
        mt_json_key(&j, "source");
        mt_json_string(&j, e->source);
        mt_json_key(&j, "content_hash");
        mt_json_string(&j, cli_hash_text((int64_t)e->content_hash, hash, sizeof hash));
        mt_json_key(&j, "file");
        mt_json_string(&j, e->file_name);
        mt_json_key(&j, "file_bytes");
        mt_json_uint(&j, e->file_bytes);
        mt_json_key(&j, "num_verts");
        mt_json_uint(&j, s->num_verts);
        mt_json_key(&j, "num_faces");
        mt_json_uint(&j, s->num_faces);
        mt_json_key(&j, "num_faces_valid");
        mt_json_uint(&j, s->num_faces_valid);
        mt_json_key(&j, "num_edges");
        mt_json_uint(&j, s->num_edges);
        mt_json_key(&j, "num_defects");
        mt_json_uint(&j, s->num_defects);
        mt_json_key(&j, "connected_components");
        mt_json_uint(&j, s->connected_components);
        mt_json_key(&j, "boundary_loops");
        mt_json_uint(&j, s->boundary_loops);
        mt_json_key(&j, "euler_characteristic");
        mt_json_int(&j, s->euler_characteristic);
        mt_json_key(&j, "genus");
        if (s->genus < 0)
            mt_json_null(&j);
        else
            mt_json_int(&j, s->genus);
        mt_json_key(&j, "closed");
        mt_json_bool(&j, s->closed);
        mt_json_key(&j, "manifold");
        mt_json_bool(&j, s->manifold);
        mt_json_key(&j, "orientable");
        mt_json_bool(&j, s->orientable);
        mt_json_object_end(&j);
    }
    mt_json_array_end(&j);
    mt_json_key(&j, "unreadable");
    mt_json_array_begin(&j);
    for (size_t i = 0; i < l->count; i++) {
        const mt_archive_entry *e = &l->entries[i];
        if (e->status == MT_OK) continue;
        mt_json_object_begin(&j);
        mt_json_key(&j, "file");
        mt_json_string(&j, e->file_name);
        mt_json_key(&j, "error");
        mt_json_string(&j, e->diag.message);
        mt_json_object_end(&j);
    }
    mt_json_array_end(&j);
    mt_json_object_end(&j);
    mt_json_finish(&j);
}

int cli_archive_ls(const cli_args *args)
{
    const char *dir = args->positionals[1];
    mt_archive *archive = NULL;
    int code = cli_archive_open(dir, true, &archive);
    if (code != CLI_EXIT_OK) return code;
    mt_archive_listing listing;
    mt_diag diag;
    if (mt_archive_list(archive, &listing, &diag) != MT_OK) {
        cli_error("archive", "%s", diag.message);
        mt_archive_close(archive);
        return CLI_EXIT_READ;
    }
    if (cli_flag(args, "json"))
        print_json(dir, &listing);
    else
        print_text(dir, &listing);
    mt_archive_listing_free(&listing);
    mt_archive_close(archive);
    return cli_finish_output("archive", CLI_EXIT_OK, CLI_EXIT_READ);
}
