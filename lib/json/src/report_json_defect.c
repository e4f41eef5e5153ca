/* A defect as JSON: its record of named fields (meshtopo/defect_record.h,
 * README.md "Defect records"), every field present in the record's order,
 * null where it does not apply, lists of ids as arrays, plus its English
 * description. `inspect --json-defects`, `query defects --json`, the
 * reports of meshtopod and `archive show --json` all write it. */
#include "meshtopo/defect_record.h"
#include "meshtopo/report_json.h"

static void write_count(mt_json *j, const char *key, uint32_t value)
{
    mt_json_key(j, key);
    if (value == MT_NONE)
        mt_json_null(j);
    else
        mt_json_uint(j, value);
}

/* The ids of a two-id list before its first MT_NONE. */
static void write_ids(mt_json *j, const char *key, const uint32_t ids[2])
{
    mt_json_key(j, key);
    mt_json_array_begin(j);
    for (int k = 0; k < 2 && ids[k] != MT_NONE; k++) mt_json_uint(j, ids[k]);
    mt_json_array_end(j);
}

void mt_report_json_write_defect(mt_json *j, const mt_defect *defect)
{
    const mt_defect_record r = mt_defect_to_record(defect);
    char text[256];
    mt_defect_describe(defect, text, sizeof text);
    mt_json_object_begin(j);
    mt_json_key(j, "kind");
    mt_json_string(j, mt_defect_key((mt_defect_kind)r.kind));
    write_ids(j, "vertices", r.vertices);
    write_ids(j, "faces", r.faces);
    mt_json_key(j, "edge");
    if (r.edge[0] == MT_NONE) {
        mt_json_null(j);
    } else {
        mt_json_array_begin(j);
        mt_json_uint(j, r.edge[0]);
        mt_json_uint(j, r.edge[1]);
        mt_json_array_end(j);
    }
    write_count(j, "face_count", r.face_count);
    mt_json_key(j, "index");
    if (r.index == MT_NONE)
        mt_json_null(j);
    else
        mt_json_int(j, r.index);
    write_count(j, "position", r.position);
    write_count(j, "face_size", r.face_size);
    write_count(j, "distinct_vertices", r.distinct_vertices);
    write_count(j, "fans", r.fans);
    mt_json_key(j, "on_nonmanifold_edge");
    if (r.on_nonmanifold_edge == MT_NONE)
        mt_json_null(j);
    else
        mt_json_bool(j, r.on_nonmanifold_edge != 0);
    write_count(j, "axis", r.axis);
    mt_json_key(j, "description");
    mt_json_string(j, text);
    mt_json_object_end(j);
}

void mt_report_json_write_defects(mt_json *j, const mt_defect *defects, size_t count)
{
    mt_json_array_begin(j);
    for (size_t i = 0; i < count; i++) mt_report_json_write_defect(j, &defects[i]);
    mt_json_array_end(j);
}
