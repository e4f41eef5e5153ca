/* `meshtopo send FILE --id ID`: read a mesh file (OFF, OBJ, PLY, gzip too)
 * with meshtopo::io, submit it to meshtopod as a new version of mesh ID and
 * print the acknowledgement: version, content hash and the daemon's topology
 * report, readable or as JSON. A large mesh goes in chunks; on a terminal a
 * progress bar (bytes, rate, ETA) is drawn on stderr. Exit codes as in
 * `meshtopo --help`. */
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "remote.h"

static const cli_option options[] = {
    {"id", "ID", "mesh id to store it under (required; 1-255 printable bytes, no '/' or '..')"},
    {"strict", NULL, "the daemon refuses the mesh if it has any defect (exit 5, report printed)"},
    {"json", NULL, "print the acknowledgement as one JSON object"},
    {"format", "NAME", "file format: auto (default), off, obj, ply-ascii, ply-le, ply-be"},
    {"quiet", NULL, "no progress bar (there is none either when stderr is not a terminal)"},
    CLI_REMOTE_OPTIONS,
};

/* The progress bar's state: when the transfer started, whether a bar is drawn. */
typedef struct send_progress {
    double start;
    int drawn;
} send_progress;

static double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Draws "sending [#####.....]  45%  25.2/56.0 MB  120.5 MB/s  ETA 0.3 s" on stderr. */
static void draw_progress(uint64_t done, uint64_t total, void *user)
{
    send_progress *p = user;
    double now = seconds_now();
    if (p->start == 0) p->start = now;
    double elapsed = now - p->start;
    double frac = total ? (double)done / (double)total : 1.0;
    char bar[31];
    int fill = (int)(frac * 30.0);
    for (int i = 0; i < 30; i++) bar[i] = i < fill ? '#' : '.';
    bar[30] = '\0';
    double rate = elapsed > 0 ? (double)done / elapsed : 0.0;
    char eta[32] = "ETA --";
    if (rate > 0 && done < total)
        snprintf(eta, sizeof eta, "ETA %.1f s", (double)(total - done) / rate);
    if (done >= total) snprintf(eta, sizeof eta, "%.1f s", elapsed);
    fprintf(stderr, "\rsending [%s] %3d%%  %.1f/%.1f MB  %.1f MB/s  %s   ", bar,
            (int)(frac * 100.0), (double)done / 1e6, (double)total / 1e6, rate / 1e6, eta);
    if (done >= total) fputc('\n', stderr);
    fflush(stderr);
    p->drawn = done < total;
}

/* report: the ack's report converted, NULL when it carries none. */
static void print_json(const char *path, const mt_client_ack *ack, const cli_report *report)
{
    char hash[24];
    mt_json j;
    mt_json_init(&j, stdout);
    mt_json_object_begin(&j);
    mt_json_key(&j, "file");
    mt_json_string(&j, path);
    mt_json_key(&j, "mesh_id");
    mt_json_string(&j, ack->msg.mesh_id);
    mt_json_key(&j, "status");
    mt_json_string(&j, mt_msgs_code_name(ack->msg.status));
    mt_json_key(&j, "error");
    mt_json_string(&j, ack->msg.error);
    mt_json_key(&j, "version");
    mt_json_int(&j, ack->msg.version);
    mt_json_key(&j, "content_hash");
    mt_json_string(&j, cli_hash_text(ack->msg.content_hash, hash, sizeof hash));
    mt_json_key(&j, "report");
    if (report)
        cli_report_write_json(&j, report);
    else
        mt_json_null(&j);
    mt_json_object_end(&j);
    mt_json_finish(&j);
}

static void print_text(const char *path, const mt_client_ack *ack, const cli_report *report)
{
    char hash[24];
    if (ack->msg.status == MESHTOPO_STATUS_CODE_T_OK)
        printf("sent %s as mesh %s version %d (content hash %s)\n", path, ack->msg.mesh_id,
               (int)ack->msg.version, cli_hash_text(ack->msg.content_hash, hash, sizeof hash));
    else
        printf("meshtopod refused %s as mesh %s: %s: %s\n", path, ack->msg.mesh_id,
               mt_msgs_code_name(ack->msg.status), ack->msg.error);
    if (report) cli_report_print_text(report, stdout);
}

static int run_send(const cli_args *args)
{
    const char *path = args->positionals[0];
    const char *id = cli_arg(args, "id");
    if (!id) {
        cli_error("send", "--id ID is required");
        return CLI_EXIT_USAGE;
    }
    cli_remote remote;
    int code = cli_remote_parse(args, &remote);
    if (code != CLI_EXIT_OK) return code;

    mt_face_list list;
    code = cli_face_list_read("send", path, cli_arg(args, "format"), &list);
    if (code != CLI_EXIT_OK) return code;

    mt_client *client = NULL;
    send_progress progress = {0, 0};
    bool show = !cli_flag(args, "quiet") && isatty(STDERR_FILENO);
    code = cli_client_create_progress("send", &remote, show ? draw_progress : NULL, &progress,
                                      &client);
    if (code != CLI_EXIT_OK) {
        mt_face_list_free(&list);
        return code;
    }
    mt_client_ack ack;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_client_submit(client, id, &list, cli_flag(args, "strict"), &ack, &diag);
    bool answered = ack.msg.mesh_id != NULL;
    if (progress.drawn) fputc('\n', stderr); /* a bar left unfinished by a failure */
    if (answered) {
        const meshtopo_topology_t *t = mt_client_ack_report(&ack);
        cli_report report;
        memset(&report, 0, sizeof report);
        if (t) code = cli_report_take("send", t, &report);
        const cli_report *shown = t && code == CLI_EXIT_OK ? &report : NULL;
        if (cli_flag(args, "json"))
            print_json(path, &ack, shown);
        else
            print_text(path, &ack, shown);
        cli_report_free(&report);
    }
    if (st != MT_OK) code = cli_call_failed("send", id, &remote, st, answered, &diag);
    code = cli_finish_output("send", code, CLI_EXIT_USAGE);
    mt_client_ack_free(&ack);
    cli_client_destroy("send", &remote, client);
    mt_face_list_free(&list);
    return code;
}

const cli_command cli_cmd_send = {
    .name = "send",
    .summary = "submit a mesh file to meshtopod and print its acknowledgement",
    .synopsis = "FILE --id ID [--strict] [--json] [--quiet] [--lcm-url URL] [--prefix PREFIX]",
    .description =
        "Reads FILE (OFF, OBJ or PLY, gzip-compressed too) and submits it to meshtopod over\n"
        "LCM as a new version of mesh ID (resubmitting an id makes a new version). Prints the\n"
        "version, the content hash and the topology report the daemon built; with --json one\n"
        "object {file, mesh_id, status, error, version, content_hash, report}.\n"
        "A mesh larger than one UDP datagram is sent in chunks the daemon acknowledges (lost\n"
        "ones are sent again); on a terminal a progress bar on stderr shows bytes, rate and\n"
        "ETA (not with --quiet, nor when stderr is a pipe or file).\n"
        "\n"
        "exit codes: 0 stored, 2 usage error (also a mesh id the client refuses), 3 FILE could\n"
        "not be read or parsed, 4 the mesh is too large for mesh_t, 5 meshtopod refused it\n"
        "(e.g. --strict and a defect: the report is printed too), 6 no answer from meshtopod.\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 1,
    .max_positionals = 1,
    .run = run_send,
};
