/* meshtopo::msgs: the one table of query kinds (msgs/query_t.lcm): for each
 * kind its number, its names, what its ids are and how many it takes, what
 * the reply holds (msgs/reply_t.lcm) and whether a worker answers it. The
 * daemon validates and routes queries by it, the CLI parses and prints by
 * it, the client checks by it and Python reads it through its binding; the
 * kind numbers themselves are written only in query_t.lcm. Pure data, any
 * thread. */
#ifndef MESHTOPO_QUERY_KINDS_H
#define MESHTOPO_QUERY_KINDS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Whether a kind takes ids. */
typedef enum mt_msgs_ids_rule {
    MT_MSGS_IDS_NEEDED = 0,   /* at least one id (BAD_REQUEST without) */
    MT_MSGS_IDS_OPTIONAL = 1, /* none means every element, in order */
    MT_MSGS_IDS_NONE = 2,     /* none (BAD_REQUEST with some) */
} mt_msgs_ids_rule;

/* What bounds an id: the daemon answers OUT_OF_RANGE for an id at or past
 * the mesh's count, BAD_REQUEST for a defect kind past topology_t's. */
typedef enum mt_msgs_id_space {
    MT_MSGS_ID_NONE = 0,        /* takes no ids */
    MT_MSGS_ID_VERTEX = 1,      /* vertex ids (pairs of them for an edge) */
    MT_MSGS_ID_FACE = 2,        /* face ids */
    MT_MSGS_ID_DEFECT_KIND = 3, /* topology_t.DEFECT_* kinds */
} mt_msgs_id_space;

/* What a reply of the kind holds (msgs/reply_t.lcm). */
typedef enum mt_msgs_reply_shape {
    MT_MSGS_REPLY_PER_ID = 0,   /* one item per id (per pair); without ids, per element */
    MT_MSGS_REPLY_PER_LOOP = 1, /* one item per boundary loop */
    MT_MSGS_REPLY_MESH = 2,     /* one item about the whole mesh */
    MT_MSGS_REPLY_REPORT = 3,   /* no items; the report in reports[0] */
    MT_MSGS_REPLY_LIST = 4,     /* no items; the mesh versions in the list_* arrays */
} mt_msgs_reply_shape;

/* reals_per_item of a kind whose count of reals depends on the answer
 * (SELF_INTERSECTIONS: one per face of its second group). */
#define MT_MSGS_REALS_VARY (-1)

/* One query kind. */
typedef struct mt_msgs_query_kind {
    int32_t kind;           /* query_t's constant: MESHTOPO_QUERY_T_... */
    const char *wire_name;  /* that constant's name in query_t.lcm: "VERTEX_RING" */
    const char *name;       /* the name `meshtopo query` and Python take: "ring" */
    mt_msgs_ids_rule ids;   /* whether it takes ids */
    bool pairs;             /* ids come as vertex pairs a0 b0 a1 b1 ... naming edges */
    mt_msgs_id_space space; /* what bounds an id */
    const char *of;         /* what an item names, for labels: "vertex", "edge", ... ("" none) */
    mt_msgs_reply_shape reply;
    int32_t reals_per_item; /* reply_t.reals per item, or MT_MSGS_REALS_VARY */
    bool geometry;          /* needs a mesh submitted with positions (else NO_GEOMETRY) */
    bool on_worker;         /* answered by a worker thread, one such query at a time */
} mt_msgs_query_kind;

/* The number of kinds, and kind i of them (in query_t order), NULL past
 * the end. */
size_t mt_msgs_query_kind_count(void);
const mt_msgs_query_kind *mt_msgs_query_kind_at(size_t i);

/* The kind with this query_t number, or NULL: not a kind. */
const mt_msgs_query_kind *mt_msgs_query_kind_of(int32_t kind);

/* The kind with this name (mt_msgs_query_kind.name, e.g. "ring"), or NULL. */
const mt_msgs_query_kind *mt_msgs_query_kind_named(const char *name);

/* The smallest and largest kind numbers (query_t's constants run between,
 * every one a kind). */
int32_t mt_msgs_query_kind_first(void);
int32_t mt_msgs_query_kind_last(void);

/* The names of the enumerations' values, for bindings and messages:
 * "needed", "optional", "none"; "none", "vertex", "face", "defect_kind";
 * "per_id", "per_loop", "mesh", "report", "list". "?" for any other value. */
const char *mt_msgs_ids_rule_name(mt_msgs_ids_rule rule);
const char *mt_msgs_id_space_name(mt_msgs_id_space space);
const char *mt_msgs_reply_shape_name(mt_msgs_reply_shape shape);

#ifdef __cplusplus
}
#endif

#endif
