/* The one table of query kinds (meshtopo/query_kinds.h): one row per
 * constant of msgs/query_t.lcm, in its order, saying what the kind takes
 * and what its reply holds (msgs/reply_t.lcm). Adding a kind is adding its
 * constant there and its row here; tests/msgs checks the two agree. */
#include "meshtopo/query_kinds.h"

#include <string.h>

#include "meshtopo/msgs.h"

#define NEEDED MT_MSGS_IDS_NEEDED
#define OPTIONAL MT_MSGS_IDS_OPTIONAL
#define NO_IDS MT_MSGS_IDS_NONE
#define VARY MT_MSGS_REALS_VARY

/* clang-format off */
static const mt_msgs_query_kind kinds[] = {
    /* kind, wire name, name,
     *   ids, pairs, space, of, reply, reals per item, geometry, on a worker */
    {MESHTOPO_QUERY_T_VERTEX_RING, "VERTEX_RING", "ring",
     NEEDED, false, MT_MSGS_ID_VERTEX, "vertex", MT_MSGS_REPLY_PER_ID, 0, false, false},
    {MESHTOPO_QUERY_T_VALENCE, "VALENCE", "valence",
     NEEDED, false, MT_MSGS_ID_VERTEX, "vertex", MT_MSGS_REPLY_PER_ID, 0, false, false},
    {MESHTOPO_QUERY_T_FACE_NEIGHBORS, "FACE_NEIGHBORS", "face-neighbors",
     NEEDED, false, MT_MSGS_ID_FACE, "face", MT_MSGS_REPLY_PER_ID, 0, false, false},
    {MESHTOPO_QUERY_T_EDGE_FACES, "EDGE_FACES", "edge-faces",
     NEEDED, true, MT_MSGS_ID_VERTEX, "edge", MT_MSGS_REPLY_PER_ID, 0, false, false},
    {MESHTOPO_QUERY_T_BOUNDARY_LOOPS, "BOUNDARY_LOOPS", "boundary-loops",
     NO_IDS, false, MT_MSGS_ID_NONE, "loop", MT_MSGS_REPLY_PER_LOOP, 0, false, false},
    {MESHTOPO_QUERY_T_COMPONENTS, "COMPONENTS", "components",
     OPTIONAL, false, MT_MSGS_ID_FACE, "face", MT_MSGS_REPLY_PER_ID, 0, false, false},
    {MESHTOPO_QUERY_T_REPORT, "REPORT", "report",
     NO_IDS, false, MT_MSGS_ID_NONE, "", MT_MSGS_REPLY_REPORT, 0, false, false},
    {MESHTOPO_QUERY_T_DEFECTS, "DEFECTS", "defects",
     OPTIONAL, false, MT_MSGS_ID_DEFECT_KIND, "kind", MT_MSGS_REPLY_PER_ID, 0, false, false},
    {MESHTOPO_QUERY_T_LIST_MESHES, "LIST_MESHES", "list",
     NO_IDS, false, MT_MSGS_ID_NONE, "", MT_MSGS_REPLY_LIST, 0, false, false},
    {MESHTOPO_QUERY_T_DIHEDRAL_ANGLES, "DIHEDRAL_ANGLES", "dihedral",
     NEEDED, true, MT_MSGS_ID_VERTEX, "edge", MT_MSGS_REPLY_PER_ID, 1, true, false},
    {MESHTOPO_QUERY_T_ANGLE_DEFICITS, "ANGLE_DEFICITS", "deficit",
     NEEDED, false, MT_MSGS_ID_VERTEX, "vertex", MT_MSGS_REPLY_PER_ID, 1, true, false},
    {MESHTOPO_QUERY_T_CONVEXITY, "CONVEXITY", "convexity",
     NO_IDS, false, MT_MSGS_ID_NONE, "mesh", MT_MSGS_REPLY_MESH, 1, true, false},
    {MESHTOPO_QUERY_T_SELF_INTERSECTIONS, "SELF_INTERSECTIONS", "self-intersections",
     NO_IDS, false, MT_MSGS_ID_NONE, "mesh", MT_MSGS_REPLY_MESH, VARY, true, true},
};
/* clang-format on */

enum { NUM_KINDS = sizeof kinds / sizeof kinds[0] };

size_t mt_msgs_query_kind_count(void)
{
    return NUM_KINDS;
}

const mt_msgs_query_kind *mt_msgs_query_kind_at(size_t i)
{
    return i < NUM_KINDS ? &kinds[i] : NULL;
}

const mt_msgs_query_kind *mt_msgs_query_kind_of(int32_t kind)
{
    for (size_t i = 0; i < NUM_KINDS; i++)
        if (kinds[i].kind == kind) return &kinds[i];
    return NULL;
}

const mt_msgs_query_kind *mt_msgs_query_kind_named(const char *name)
{
    if (!name) return NULL;
    for (size_t i = 0; i < NUM_KINDS; i++)
        if (strcmp(kinds[i].name, name) == 0) return &kinds[i];
    return NULL;
}

int32_t mt_msgs_query_kind_first(void)
{
    int32_t first = kinds[0].kind;
    for (size_t i = 1; i < NUM_KINDS; i++)
        if (kinds[i].kind < first) first = kinds[i].kind;
    return first;
}

int32_t mt_msgs_query_kind_last(void)
{
    int32_t last = kinds[0].kind;
    for (size_t i = 1; i < NUM_KINDS; i++)
        if (kinds[i].kind > last) last = kinds[i].kind;
    return last;
}

const char *mt_msgs_ids_rule_name(mt_msgs_ids_rule rule)
{
    switch (rule) {
        case MT_MSGS_IDS_NEEDED:
            return "needed";
        case MT_MSGS_IDS_OPTIONAL:
            return "optional";
        case MT_MSGS_IDS_NONE:
            return "none";
    }
    return "?";
}

const char *mt_msgs_id_space_name(mt_msgs_id_space space)
{
    switch (space) {
        case MT_MSGS_ID_NONE:
            return "none";
        case MT_MSGS_ID_VERTEX:
            return "vertex";
        case MT_MSGS_ID_FACE:
            return "face";
        case MT_MSGS_ID_DEFECT_KIND:
            return "defect_kind";
    }
    return "?";
}

const char *mt_msgs_reply_shape_name(mt_msgs_reply_shape shape)
{
    switch (shape) {
        case MT_MSGS_REPLY_PER_ID:
            return "per_id";
        case MT_MSGS_REPLY_PER_LOOP:
            return "per_loop";
        case MT_MSGS_REPLY_MESH:
            return "mesh";
        case MT_MSGS_REPLY_REPORT:
            return "report";
        case MT_MSGS_REPLY_LIST:
            return "list";
    }
    return "?";
}
