/* The report's defect list in words: counting the entries of one kind and a
 * one-line English description of each entry naming its elements, for CLI
 * output, logs and diagnostics. snprintf semantics: the text is always
 * NUL-terminated and the full length is returned. */
#include <stdio.h>

#include "meshtopo/face_list.h"
#include "meshtopo/report.h"

size_t mt_report_count_defects(const mt_report *report, mt_defect_kind kind)
{
    if (!report || !report->defects) return 0;
    size_t n = 0;
    for (size_t i = 0; i < report->num_defects; i++)
        if (report->defects[i].kind == (uint32_t)kind) n++;
    return n;
}

static const char *axis_name(uint32_t axis)
{
    switch (axis) {
        case 0:
            return "x";
        case 1:
            return "y";
        case 2:
            return "z";
        default:
            return "unknown";
    }
}

static int describe(const mt_defect *d, char *buf, size_t size)
{
    switch (d->kind) {
        case MT_DEFECT_OUT_OF_RANGE_INDEX:
            return snprintf(buf, size, "face %u uses vertex index %lld, out of range (position %u)",
                            d->a, (long long)mt_index_as_signed(d->b), d->c);
        case MT_DEFECT_DEGENERATE_FACE:
            return snprintf(buf, size,
                            "face %u has %u distinct vertices out of %u entries (degenerate)", d->a,
                            d->b, d->c);
        case MT_DEFECT_DUPLICATE_FACE:
            return snprintf(buf, size, "face %u repeats face %u (duplicate)", d->a, d->b);
        case MT_DEFECT_NONMANIFOLD_EDGE:
            return snprintf(buf, size, "edge %u-%u is used by %u faces (non-manifold)", d->a, d->b,
                            d->c);
        case MT_DEFECT_SAME_DIRECTION_EDGE:
            return snprintf(buf, size,
                            "side %u->%u is used by %u faces in the same direction "
                            "(inconsistent orientation)",
                            d->a, d->b, d->c);
        case MT_DEFECT_NONMANIFOLD_VERTEX:
            if (d->b > 1)
                return snprintf(buf, size, "vertex %u has %u separate fans (bowtie)%s", d->a, d->b,
                                d->c ? " and lies on a non-manifold edge" : "");
            if (d->c)
                return snprintf(buf, size,
                                "vertex %u lies on a non-manifold edge (a vertex of its link "
                                "has degree > 2)",
                                d->a);
            return snprintf(buf, size, "vertex %u is non-manifold", d->a);
        case MT_DEFECT_ISOLATED_VERTEX:
            return snprintf(buf, size, "vertex %u is used by no valid face (isolated)", d->a);
        case MT_DEFECT_NONFINITE_COORD:
            return snprintf(buf, size, "vertex %u has a NaN or infinite %s coordinate", d->a,
                            axis_name(d->b));
        default:
            break;
    }
    return snprintf(buf, size, "unknown defect kind %u (%u, %u, %u)", d->kind, d->a, d->b, d->c);
}

size_t mt_defect_describe(const mt_defect *defect, char *buf, size_t size)
{
    if (!buf) size = 0;
    if (!defect) {
        if (size > 0) buf[0] = '\0';
        return 0;
    }
    int n = describe(defect, size > 0 ? buf : NULL, size);
    if (n < 0) {
        if (size > 0) buf[0] = '\0';
        return 0;
    }
    return (size_t)n;
}
