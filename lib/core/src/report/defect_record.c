/* Conversions between a defect's compact form (mt_defect: kind, a, b, c,
 * meanings per kind as MT_DEFECT_TABLE says) and its record of named fields
 * (meshtopo/defect_record.h). A record converts back only when it is
 * exactly what mt_defect_to_record gives, so a record read from an untrusted
 * file either stands for one defect or is refused. */
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "meshtopo/defect_record.h"
#include "meshtopo/face_list.h"

_Static_assert(sizeof(mt_defect_record) == 64 && offsetof(mt_defect_record, index) == 32,
               "a record is 14 uint32 and one int64, without padding");

static mt_defect_record empty_record(uint32_t kind)
{
    mt_defect_record r;
    r.kind = kind;
    r.vertices[0] = r.vertices[1] = MT_NONE;
    r.faces[0] = r.faces[1] = MT_NONE;
    r.edge[0] = r.edge[1] = MT_NONE;
    r.face_count = MT_NONE;
    r.position = MT_NONE;
    r.face_size = MT_NONE;
    r.distinct_vertices = MT_NONE;
    r.fans = MT_NONE;
    r.on_nonmanifold_edge = MT_NONE;
    r.axis = MT_NONE;
    r.index = MT_NONE;
    return r;
}

mt_defect_record mt_defect_to_record(const mt_defect *d)
{
    mt_defect_record r = empty_record(d->kind);
    switch (d->kind) {
        case MT_DEFECT_OUT_OF_RANGE_INDEX:
            r.faces[0] = d->a;
            r.index = mt_index_as_signed(d->b);
            r.position = d->c;
            break;
        case MT_DEFECT_DEGENERATE_FACE:
            r.faces[0] = d->a;
            r.distinct_vertices = d->b;
            r.face_size = d->c;
            break;
        case MT_DEFECT_DUPLICATE_FACE:
            r.faces[0] = d->a;
            r.faces[1] = d->b;
            break;
        case MT_DEFECT_NONMANIFOLD_EDGE:
        case MT_DEFECT_SAME_DIRECTION_EDGE:
            r.vertices[0] = r.edge[0] = d->a;
            r.vertices[1] = r.edge[1] = d->b;
            r.face_count = d->c;
            break;
        case MT_DEFECT_NONMANIFOLD_VERTEX:
            r.vertices[0] = d->a;
            r.fans = d->b;
            r.on_nonmanifold_edge = d->c;
            break;
        case MT_DEFECT_ISOLATED_VERTEX:
            r.vertices[0] = d->a;
            break;
        case MT_DEFECT_NONFINITE_COORD:
            r.vertices[0] = d->a;
            r.axis = d->b;
            break;
        default:
            break;
    }
    return r;
}

void mt_defect_to_records(const mt_defect *defects, size_t count, mt_defect_record *out)
{
    for (size_t i = 0; i < count; i++) out[i] = mt_defect_to_record(&defects[i]);
}

static bool same_record(const mt_defect_record *x, const mt_defect_record *y)
{
    return x->kind == y->kind && x->vertices[0] == y->vertices[0] &&
           x->vertices[1] == y->vertices[1] && x->faces[0] == y->faces[0] &&
           x->faces[1] == y->faces[1] && x->edge[0] == y->edge[0] && x->edge[1] == y->edge[1] &&
           x->face_count == y->face_count && x->position == y->position &&
           x->face_size == y->face_size && x->distinct_vertices == y->distinct_vertices &&
           x->fans == y->fans && x->on_nonmanifold_edge == y->on_nonmanifold_edge &&
           x->axis == y->axis && x->index == y->index;
}

mt_status mt_defect_from_record(const mt_defect_record *r, mt_defect *out)
{
    mt_defect d = {r->kind, 0, 0, 0};
    switch (r->kind) {
        case MT_DEFECT_OUT_OF_RANGE_INDEX:
            d.a = r->faces[0];
            /* An entry reads as a value in [-2^31, 2^31); anything else is no index. */
            if (r->index < -(int64_t)0x80000000ll || r->index >= (int64_t)0x80000000ll) break;
            d.b = (uint32_t)(r->index < 0 ? r->index + 0x100000000ll : r->index);
            d.c = r->position;
            break;
        case MT_DEFECT_DEGENERATE_FACE:
            d.a = r->faces[0];
            d.b = r->distinct_vertices;
            d.c = r->face_size;
            break;
        case MT_DEFECT_DUPLICATE_FACE:
            d.a = r->faces[0];
            d.b = r->faces[1];
            break;
        case MT_DEFECT_NONMANIFOLD_EDGE:
        case MT_DEFECT_SAME_DIRECTION_EDGE:
            d.a = r->edge[0];
            d.b = r->edge[1];
            d.c = r->face_count;
            break;
        case MT_DEFECT_NONMANIFOLD_VERTEX:
            d.a = r->vertices[0];
            d.b = r->fans;
            d.c = r->on_nonmanifold_edge;
            break;
        case MT_DEFECT_ISOLATED_VERTEX:
            d.a = r->vertices[0];
            break;
        case MT_DEFECT_NONFINITE_COORD:
            d.a = r->vertices[0];
            d.b = r->axis;
            break;
        default:
            memset(out, 0, sizeof *out);
            return MT_ERR_INVALID_ARG;
    }
    const mt_defect_record back = mt_defect_to_record(&d);
    if (!same_record(&back, r)) {
        memset(out, 0, sizeof *out);
        return MT_ERR_INVALID_ARG;
    }
    *out = d;
    return MT_OK;
}
