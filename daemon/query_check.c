/* meshtopod's checks of a query_t (query_check.h), driven by the query-kind
 * table: whether the kind exists, takes ids, takes them in pairs, and what
 * bounds them. Every id is checked before anything is answered: one out of
 * range gives OUT_OF_RANGE and no items. */
#include "query_check.h"

#include <inttypes.h>

#include "meshtopo/mesh.h"
#include "meshtopo/report.h"

const mt_msgs_query_kind *mtd_query_check(mtd_answer *a, const meshtopo_query_t *q)
{
    const mt_msgs_query_kind *k = mt_msgs_query_kind_of(q->kind);
    if (!k) {
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_UNKNOWN_KIND,
                        "kind: %" PRId32 " is not a query_t kind (%" PRId32 "..%" PRId32 ")",
                        q->kind, mt_msgs_query_kind_first(), mt_msgs_query_kind_last());
        return NULL;
    }
    if (k->ids == MT_MSGS_IDS_NEEDED && q->num_ids == 0)
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "ids: kind %" PRId32 " needs ids",
                        q->kind);
    else if (k->ids == MT_MSGS_IDS_NONE && q->num_ids != 0)
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST,
                        "ids: kind %" PRId32 " takes no ids, got %" PRId32, q->kind, q->num_ids);
    else if (k->pairs && q->num_ids % 2)
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST,
                        "ids: kind %" PRId32 " takes vertex pairs, got an odd count (%" PRId32 ")",
                        q->kind, q->num_ids);
    else if (k->space == MT_MSGS_ID_DEFECT_KIND) {
        for (int32_t i = 0; i < q->num_ids; i++)
            if (q->ids[i] < 0 || q->ids[i] >= (int32_t)MT_DEFECT_KIND_COUNT) {
                mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST,
                                "ids[%" PRId32 "] = %" PRId32
                                ": not a topology_t.DEFECT_* kind (0..%d)",
                                i, q->ids[i], (int)MT_DEFECT_KIND_COUNT - 1);
                break;
            }
    }
    if (mtd_answer_ok(a) && q->version < 0)
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "version: %" PRId32 " is negative",
                        q->version);
    return mtd_answer_ok(a) ? k : NULL;
}

void mtd_query_check_ids(mtd_answer *a, const mt_msgs_query_kind *k, const meshtopo_query_t *q,
                         const mt_mesh *mesh)
{
    uint32_t limit = 0;
    const char *what = "", *whats = "";
    switch (k->space) {
        case MT_MSGS_ID_VERTEX:
            limit = mt_mesh_num_verts(mesh), what = "vertex", whats = "vertices";
            break;
        case MT_MSGS_ID_FACE:
            limit = mt_mesh_num_faces(mesh), what = "face", whats = "faces";
            break;
        case MT_MSGS_ID_NONE:
        case MT_MSGS_ID_DEFECT_KIND: /* checked with the request */
            return;
    }
    for (int32_t i = 0; i < q->num_ids; i++) {
        if ((uint32_t)q->ids[i] >= limit) {
            mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE,
                            "ids[%" PRId32 "] = %" PRId32 ": no such %s (mesh '%s' has %" PRIu32
                            " %s)",
                            i, q->ids[i], what, q->mesh_id, limit, whats);
            return;
        }
    }
}
