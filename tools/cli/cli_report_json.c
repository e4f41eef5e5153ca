/* A report from meshtopod as JSON (send, query report, watch): the summary
 * `inspect --json` writes too (meshtopo::json, with the counts only the
 * daemon's reports carry), wrapped with provenance and the listed defects
 * (defect records, README.md "Defect records"). */
#include "cli_report.h"
#include "meshtopo/report_json.h"
#include "remote.h"

bool cli_report_write_json(mt_json *j, const cli_report *cr)
{
    const mt_report *r = &cr->report;
    char hash[24];
    mt_json_object_begin(j);
    mt_json_key(j, "mesh_id");
    mt_json_string(j, cr->mesh_id);
    mt_json_key(j, "version");
    mt_json_int(j, cr->version);
    mt_json_key(j, "source");
    mt_json_string(j, cr->source);
    mt_json_key(j, "content_hash");
    mt_json_string(j, cli_hash_text(cr->content_hash, hash, sizeof hash));
    mt_json_key(j, "build_duration_us");
    mt_json_int(j, cr->build_duration_us);
    bool ok = mt_report_json_write_summary(j, r, cr->num_loop_lengths, cr->num_components,
                                           MT_REPORT_JSON_KEYS_DAEMON);
    mt_json_key(j, "num_defects");
    mt_json_uint(j, cr->num_defects_found);
    mt_json_key(j, "defects");
    mt_report_json_write_defects(j, r->defects, r->num_defects);
    mt_json_object_end(j);
    return ok;
}
