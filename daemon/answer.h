/* meshtopod's query answers being built: the reply_t arrays as two-level CSR
 * (items -> groups -> values, values2, reals), bounded by the reply limit,
 * and the first error met while building them. The answerers
 * (answer_topology.c, answer_geometry.c, answer_list.c) fill one per query;
 * query_route.c sends it. One thread per answer. */
#ifndef MESHTOPOD_ANSWER_H
#define MESHTOPOD_ANSWER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cluster.h"
#include "error_log.h"
#include "mesh_store.h"
#include "meshtopo/msgs.h"
#include "meshtopo/status.h"

/* A reply whose arrays would exceed this many bytes is refused (TOO_LARGE). */
#define MTD_REPLY_MAX_BYTES (64u << 20)

/* A growable array of int32_t (int8_t ones are stored widened, then narrowed). */
typedef struct mtd_ivec {
    int32_t *v;
    size_t n, cap;
} mtd_ivec;

typedef struct mtd_answer {
    mtd_ivec item_status, item_offsets, group_boundary, value_offsets, value2_offsets, values,
        values2;
    double *reals; /* reply_t.reals */
    size_t num_reals, reals_cap;
    size_t bytes;
    int32_t status; /* status_code_t: OK until the first failure */
    char error[MTD_ERROR_MAX];
    meshtopo_topology_t report; /* REPORT: reply_t.reports[0] when have_report */
    bool have_report;
    meshtopo_reply_t list; /* LIST_MESHES: its list_* arrays when have_list */
    bool have_list;
} mtd_answer;

/* What an answerer answers from. */
typedef struct mtd_answer_input {
    const meshtopo_query_t *query;
    const mt_mesh *mesh;       /* the version asked for; NULL for LIST_MESHES */
    const mtd_mesh_info *info; /* its store entry's; NULL for LIST_MESHES */
    mtd_store *store;          /* LIST_MESHES: what is held */
    mtd_cluster *cluster;      /* LIST_MESHES: the ids this member owns (NULL: all) */
} mtd_answer_input;

/* Fills a's items for one checked query (ids in range, as query_check.h
 * checks them), or fails a. */
typedef void mtd_answerer(mtd_answer *a, const mtd_answer_input *in);

void mtd_answer_init(mtd_answer *a);
void mtd_answer_free(mtd_answer *a);

/* The one failure of a (later ones are ignored): status_code_t `code` and
 * a printf-style error. */
void mtd_answer_fail(mtd_answer *a, int32_t code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* A library call's failure while answering `what` (of element `id`): the
 * status's code (meshtopo/protocol.h), INTERNAL when it has none of its
 * own, since the query was checked before. NO_GEOMETRY names the missing
 * positions. */
void mtd_answer_fail_status(mtd_answer *a, mt_status s, const char *what, int32_t id);

static inline bool mtd_answer_ok(const mtd_answer *a)
{
    return a->status == MESHTOPO_STATUS_CODE_T_OK;
}

void mtd_answer_push(mtd_answer *a, mtd_ivec *vec, int32_t value);
void mtd_answer_push_real(mtd_answer *a, double value);
static inline void mtd_answer_value(mtd_answer *a, int32_t value)
{
    mtd_answer_push(a, &a->values, value);
}
static inline void mtd_answer_value2(mtd_answer *a, int32_t value)
{
    mtd_answer_push(a, &a->values2, value);
}

/* Ends a group of the current item; ends an item whose groups were just added. */
void mtd_answer_group_end(mtd_answer *a, bool boundary);
void mtd_answer_item_end(mtd_answer *a, int32_t item_status);

/* Grows a uint32_t buffer to hold at least `need` elements; false (a
 * failed) when it would pass the reply limit or memory runs out. */
bool mtd_answer_reserve_u32(mtd_answer *a, uint32_t **buf, size_t *cap, size_t need);

/* The answerers, one per kind (msgs query_t; the table in query_route.c). */
mtd_answerer mtd_answer_rings, mtd_answer_valences, mtd_answer_face_neighbors,
    mtd_answer_edge_faces, mtd_answer_boundary_loops, mtd_answer_components, mtd_answer_report,
    mtd_answer_defects, mtd_answer_list_meshes, mtd_answer_dihedral_angles,
    mtd_answer_angle_deficits, mtd_answer_convexity, mtd_answer_self_intersections;

#endif
