/* meshtopod's answers being built (answer.h): growable arrays bounded by the
 * reply limit, and the one failure helper every answerer calls. */
#include "answer.h"

#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/protocol.h"
#include "topology.h"

void mtd_answer_fail(mtd_answer *a, int32_t code, const char *fmt, ...)
{
    if (a->status != MESHTOPO_STATUS_CODE_T_OK) return;
    a->status = code;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(a->error, sizeof a->error, fmt, ap);
    va_end(ap);
}

void mtd_answer_fail_status(mtd_answer *a, mt_status s, const char *what, int32_t id)
{
    int32_t code = mt_msgs_code_of_status(s, MESHTOPO_STATUS_CODE_T_INTERNAL);
    if (code == MESHTOPO_STATUS_CODE_T_NO_GEOMETRY)
        mtd_answer_fail(a, code, "%s: the mesh was submitted without positions", what);
    else
        mtd_answer_fail(a, code, "%s of %" PRId32 ": %s", what, id, mt_strerror(s));
}

static bool over_limit(mtd_answer *a, size_t grown)
{
    a->bytes += grown;
    if (a->bytes <= MTD_REPLY_MAX_BYTES) return false;
    mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_TOO_LARGE,
                    "the answer exceeds the daemon's reply limit of %u bytes; ask for fewer ids",
                    (unsigned)MTD_REPLY_MAX_BYTES);
    return true;
}

void mtd_answer_push(mtd_answer *a, mtd_ivec *vec, int32_t value)
{
    if (a->status != MESHTOPO_STATUS_CODE_T_OK) return;
    if (vec->n == vec->cap) {
        if (over_limit(a, vec->cap * sizeof(int32_t))) return;
        size_t cap = vec->cap ? 2 * vec->cap : 64;
        int32_t *v = realloc(vec->v, cap * sizeof *v);
        if (!v) {
            mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL,
                            "out of memory building the answer");
            return;
        }
        vec->v = v;
        vec->cap = cap;
    }
    vec->v[vec->n++] = value;
}

void mtd_answer_push_real(mtd_answer *a, double value)
{
    if (a->status != MESHTOPO_STATUS_CODE_T_OK) return;
    if (a->num_reals == a->reals_cap) {
        if (over_limit(a, a->reals_cap * sizeof(double))) return;
        size_t cap = a->reals_cap ? 2 * a->reals_cap : 64;
        double *v = realloc(a->reals, cap * sizeof *v);
        if (!v) {
            mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL,
                            "out of memory building the answer");
            return;
        }
        a->reals = v;
        a->reals_cap = cap;
    }
    a->reals[a->num_reals++] = value;
}

void mtd_answer_init(mtd_answer *a)
{
    memset(a, 0, sizeof *a);
    a->status = MESHTOPO_STATUS_CODE_T_OK;
    mtd_answer_push(a, &a->item_offsets, 0);
    mtd_answer_push(a, &a->value_offsets, 0);
    mtd_answer_push(a, &a->value2_offsets, 0);
}

static void free_list(meshtopo_reply_t *list)
{
    for (int32_t i = 0; list->list_mesh_ids && i < list->num_meshes; i++) {
        free(list->list_mesh_ids[i]);
        free(list->list_sources[i]);
    }
    free(list->list_mesh_ids);
    free(list->list_versions);
    free(list->list_sources);
    free(list->list_utimes);
    free(list->list_num_verts);
    free(list->list_num_faces);
    free(list->list_num_defects);
    free(list->list_content_hashes);
}

void mtd_answer_free(mtd_answer *a)
{
    mtd_ivec *vecs[] = {&a->item_status,    &a->item_offsets, &a->group_boundary, &a->value_offsets,
                        &a->value2_offsets, &a->values,       &a->values2};
    for (size_t i = 0; i < sizeof vecs / sizeof vecs[0]; i++) free(vecs[i]->v);
    free(a->reals);
    if (a->have_report) mtd_topology_free(&a->report);
    free_list(&a->list);
}

void mtd_answer_group_end(mtd_answer *a, bool boundary)
{
    mtd_answer_push(a, &a->group_boundary, boundary);
    mtd_answer_push(a, &a->value_offsets, (int32_t)a->values.n);
    mtd_answer_push(a, &a->value2_offsets, (int32_t)a->values2.n);
}

void mtd_answer_item_end(mtd_answer *a, int32_t item_status)
{
    mtd_answer_push(a, &a->item_status, item_status);
    mtd_answer_push(a, &a->item_offsets, (int32_t)a->group_boundary.n);
}

bool mtd_answer_reserve_u32(mtd_answer *a, uint32_t **buf, size_t *cap, size_t need)
{
    if (need <= *cap) return true;
    if (need > MTD_REPLY_MAX_BYTES / sizeof(uint32_t)) {
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_TOO_LARGE,
                        "the answer exceeds the daemon's reply limit");
        return false;
    }
    uint32_t *p = realloc(*buf, need * sizeof *p);
    if (!p) {
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory building the answer");
        return false;
    }
    *buf = p;
    *cap = need;
    return true;
}
