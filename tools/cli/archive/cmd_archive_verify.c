/* `meshtopo archive verify DIR [--json]`: checks every archive file with
 * the checks meshtopod's loads make (safe open, content hash as the daemon
 * computes it, stored arrays against their digest or a rebuild, report),
 * plus the VTKHDF cells, and names each bad file, its problem and what kind
 * of fault it is (mt_archive_fault: derived data rebuilt on load, content
 * set aside by the daemon, unsafe entries never opened, ...). Exit 0 only
 * when every file passes. */
#include <stdio.h>

#include "archive_common.h"
#include "cmd_archive.h"
#include "meshtopo/json_writer.h"

int cli_archive_verify(const cli_args *args)
{
    const char *dir = args->positionals[1];
    bool json = cli_flag(args, "json");
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
    mt_json j;
    if (json) {
        mt_json_init(&j, stdout);
        mt_json_object_begin(&j);
        mt_json_key(&j, "archive");
        mt_json_string(&j, dir);
        mt_json_key(&j, "files");
        mt_json_array_begin(&j);
    }
    size_t bad = 0;
    for (size_t i = 0; i < listing.count; i++) {
        const char *name = listing.entries[i].file_name;
        mt_archive_fault fault = MT_ARCHIVE_FAULT_NONE;
        mt_status st = mt_archive_verify_file_with(archive, name, NULL, NULL, &fault, &diag);
        if (st != MT_OK) bad++;
        if (json) {
            mt_json_object_begin(&j);
            mt_json_key(&j, "file");
            mt_json_string(&j, name);
            mt_json_key(&j, "ok");
            mt_json_bool(&j, st == MT_OK);
            mt_json_key(&j, "fault");
            mt_json_string(&j, mt_archive_fault_name(fault));
            mt_json_key(&j, "error");
            if (st == MT_OK)
                mt_json_null(&j);
            else
                mt_json_string(&j, diag.message);
            mt_json_object_end(&j);
        } else if (st == MT_OK) {
            printf("ok   %s\n", name);
        } else {
            printf("BAD  [%s] %s\n", mt_archive_fault_name(fault), diag.message);
        }
    }
    if (json) {
        mt_json_array_end(&j);
        mt_json_key(&j, "checked");
        mt_json_uint(&j, listing.count);
        mt_json_key(&j, "bad");
        mt_json_uint(&j, bad);
        mt_json_object_end(&j);
        mt_json_finish(&j);
    } else {
        printf("%zu file%s checked, %zu bad\n", listing.count, listing.count == 1 ? "" : "s", bad);
    }
    if (bad > 0) {
        cli_error("archive", "verify: %zu of %zu files in %s are bad", bad, listing.count, dir);
        code = CLI_EXIT_READ;
    }
    mt_archive_listing_free(&listing);
    mt_archive_close(archive);
    return cli_finish_output("archive", code, CLI_EXIT_READ);
}
