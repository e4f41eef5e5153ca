/* Defect lists of a build: one mt_defect pushed onto a part's own list (the
 * parallel phases) or onto the build's merged list (the sequential phases
 * and the report parts). Below every phase, so that each one records what it
 * finds without depending on another. */
#include "build/build_state.h"

mt_status mt__push_defect(mt__vec *defects, mt_defect_kind kind, uint32_t x, uint32_t y, uint32_t z)
{
    mt_defect d = {(uint32_t)kind, x, y, z};
    return mt__vec_push(defects, &d);
}

mt_status mt__add_defect(mt__build *b, mt_defect_kind kind, uint32_t x, uint32_t y, uint32_t z)
{
    return mt__push_defect(&b->defects, kind, x, y, z);
}
