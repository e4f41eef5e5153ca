/* The pieces the `meshtopo archive` subcommands share (archive_common.h):
 * opening the archive as meshtopod does (content hash checked on load) and
 * the --version option. */
#include <stdlib.h>

#include "archive_common.h"

int cli_archive_open(const char *dir, bool read_only, mt_archive **out)
{
    mt_archive_options open_options = {.read_only = read_only};
    mt_diag diag;
    mt_status st = mt_archive_open(dir, &open_options, out, &diag);
    if (st == MT_OK) {
        /* Check content as meshtopod does on load. */
        mt_archive_set_content_hash(*out, mt_archive_content_hash, NULL);
        return CLI_EXIT_OK;
    }
    cli_error("archive", "%s", diag.message);
    return CLI_EXIT_READ;
}

int cli_archive_version(const cli_args *args, uint32_t *out)
{
    *out = 0;
    const char *text = cli_arg(args, "version");
    if (!text) return CLI_EXIT_OK;
    char *end = NULL;
    unsigned long long v = text[0] >= '0' && text[0] <= '9' ? strtoull(text, &end, 10) : 0;
    if (!end || *end != '\0' || v == 0 || v > UINT32_MAX) {
        cli_error("archive", "--version: expected a version number (1 or more), got '%s'", text);
        return CLI_EXIT_USAGE;
    }
    *out = (uint32_t)v;
    return CLI_EXIT_OK;
}
