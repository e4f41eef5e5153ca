/* Tests of defect_record.c: every kind's record names its ids and values in
 * the fields README.md "Defect records" gives, MT_NONE everywhere else;
 * records convert back to the same defect; records no defect gives (an
 * unknown kind, a field that does not apply holding a value, an index no
 * entry reads as) are refused. */
#include <string.h>

#include "harness.h"
#include "meshtopo/defect_record.h"
#include "meshtopo/mesh.h"
#include "meshtopo/validate.h"

static mt_defect_record all_none(uint32_t kind)
{
    mt_defect_record r;
    memset(&r, 0xff, sizeof r);
    r.kind = kind;
    r.index = MT_NONE;
    return r;
}

static void expect_record(mt_defect d, mt_defect_record want, int line)
{
    const mt_defect_record got = mt_defect_to_record(&d);
    if (memcmp(&got, &want, sizeof got) != 0)
        mt_test_fail(__FILE__, line, "record of defect kind %u (%u, %u, %u) differs", d.kind, d.a,
                     d.b, d.c);
    mt_defect back = {99, 99, 99, 99};
    if (mt_defect_from_record(&got, &back) != MT_OK || back.kind != d.kind || back.a != d.a ||
        back.b != d.b || back.c != d.c)
        mt_test_fail(__FILE__, line, "record of kind %u does not convert back", d.kind);
}

#define EXPECT_RECORD(d, want) expect_record((d), (want), __LINE__)

static void test_defect_record_kinds(void)
{
    mt_defect_record r = all_none(MT_DEFECT_OUT_OF_RANGE_INDEX);
    r.faces[0] = 12;
    r.index = -1;
    r.position = 2;
    EXPECT_RECORD(((mt_defect){MT_DEFECT_OUT_OF_RANGE_INDEX, 12, 0xffffffffu, 2}), r);
    r.index = 1000;
    EXPECT_RECORD(((mt_defect){MT_DEFECT_OUT_OF_RANGE_INDEX, 12, 1000, 2}), r);

    r = all_none(MT_DEFECT_DEGENERATE_FACE);
    r.faces[0] = 4;
    r.distinct_vertices = 2;
    r.face_size = 3;
    EXPECT_RECORD(((mt_defect){MT_DEFECT_DEGENERATE_FACE, 4, 2, 3}), r);

    r = all_none(MT_DEFECT_DUPLICATE_FACE);
    r.faces[0] = 9;
    r.faces[1] = 2;
    EXPECT_RECORD(((mt_defect){MT_DEFECT_DUPLICATE_FACE, 9, 2, 0}), r);

    r = all_none(MT_DEFECT_NONMANIFOLD_EDGE);
    r.vertices[0] = r.edge[0] = 7;
    r.vertices[1] = r.edge[1] = 8;
    r.face_count = 3;
    EXPECT_RECORD(((mt_defect){MT_DEFECT_NONMANIFOLD_EDGE, 7, 8, 3}), r);

    r = all_none(MT_DEFECT_SAME_DIRECTION_EDGE);
    r.vertices[0] = r.edge[0] = 5;
    r.vertices[1] = r.edge[1] = 1;
    r.face_count = 2;
    EXPECT_RECORD(((mt_defect){MT_DEFECT_SAME_DIRECTION_EDGE, 5, 1, 2}), r);

    r = all_none(MT_DEFECT_NONMANIFOLD_VERTEX);
    r.vertices[0] = 590;
    r.fans = 3;
    r.on_nonmanifold_edge = 1;
    EXPECT_RECORD(((mt_defect){MT_DEFECT_NONMANIFOLD_VERTEX, 590, 3, 1}), r);

    r = all_none(MT_DEFECT_ISOLATED_VERTEX);
    r.vertices[0] = 6;
    EXPECT_RECORD(((mt_defect){MT_DEFECT_ISOLATED_VERTEX, 6, 0, 0}), r);

    r = all_none(MT_DEFECT_NONFINITE_COORD);
    r.vertices[0] = 8;
    r.axis = 1;
    EXPECT_RECORD(((mt_defect){MT_DEFECT_NONFINITE_COORD, 8, 1, 0}), r);

    /* An unknown kind keeps its number and nothing else; it does not convert back. */
    const mt_defect unknown = {MT_DEFECT_KIND_COUNT, 1, 2, 3};
    const mt_defect_record u = mt_defect_to_record(&unknown);
    const mt_defect_record want = all_none(MT_DEFECT_KIND_COUNT);
    CHECK(memcmp(&u, &want, sizeof u) == 0);
    mt_defect back;
    CHECK_STATUS(mt_defect_from_record(&u, &back), MT_ERR_INVALID_ARG);
}

static void test_defect_record_refused(void)
{
    const mt_defect d = {MT_DEFECT_ISOLATED_VERTEX, 6, 0, 0};
    mt_defect back = {1, 2, 3, 4};
    mt_defect_record r = mt_defect_to_record(&d);
    r.fans = 2; /* a field isolated_vertex does not have */
    CHECK_STATUS(mt_defect_from_record(&r, &back), MT_ERR_INVALID_ARG);
    CHECK(back.kind == 0 && back.a == 0 && back.b == 0 && back.c == 0);
    r = mt_defect_to_record(&d);
    r.vertices[1] = 7; /* a second vertex */
    CHECK_STATUS(mt_defect_from_record(&r, &back), MT_ERR_INVALID_ARG);
    const mt_defect e = {MT_DEFECT_NONMANIFOLD_EDGE, 7, 8, 3};
    r = mt_defect_to_record(&e);
    r.vertices[1] = 9; /* vertices and edge disagree */
    CHECK_STATUS(mt_defect_from_record(&r, &back), MT_ERR_INVALID_ARG);
    const mt_defect o = {MT_DEFECT_OUT_OF_RANGE_INDEX, 3, 1000, 0};
    r = mt_defect_to_record(&o);
    r.index = 0x80000000ll; /* no entry reads as 2^31 */
    CHECK_STATUS(mt_defect_from_record(&r, &back), MT_ERR_INVALID_ARG);
    r.index = -0x80000001ll;
    CHECK_STATUS(mt_defect_from_record(&r, &back), MT_ERR_INVALID_ARG);
    r.index = -0x80000000ll;
    CHECK_OK(mt_defect_from_record(&r, &back));
    CHECK_EQ(back.b, 0x80000000u);
    r.kind = 77;
    CHECK_STATUS(mt_defect_from_record(&r, &back), MT_ERR_INVALID_ARG);
}

/* A built mesh's defects: every record converts back, in bulk too. */
static void test_defect_record_built(void)
{
    static const uint32_t sizes[] = {3, 3, 3, 3, 2, 3, 3};
    static const uint32_t idx[] = {0, 1, 2, 1, 0, 3, 0, 1, 4, 0, 5, 6, 3, 4, 0, 17, 1, 0, 1, 2};
    mt_face_list list = {
        10, 7, sizeof idx / sizeof idx[0], NULL, (uint32_t *)sizes, (uint32_t *)idx};
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(&list, NULL, &mesh, NULL));
    CHECK_OK(mt_mesh_validate(mesh, NULL));
    const mt_report *r = mt_mesh_report(mesh);
    if (!r) return;
    CHECK(r->num_defects >= 5);
    mt_defect_record records[64];
    CHECK(r->num_defects <= 64);
    mt_defect_to_records(r->defects, r->num_defects, records);
    for (size_t i = 0; i < r->num_defects && i < 64; i++) {
        const mt_defect_record one = mt_defect_to_record(&r->defects[i]);
        CHECK(memcmp(&one, &records[i], sizeof one) == 0);
        mt_defect back;
        CHECK_OK(mt_defect_from_record(&records[i], &back));
        CHECK(memcmp(&back, &r->defects[i], sizeof back) == 0);
    }
    mt_mesh_destroy(mesh);
}

static const mt_test_case cases[] = {
    {"defect_record_kinds", test_defect_record_kinds},
    {"defect_record_refused", test_defect_record_refused},
    {"defect_record_built", test_defect_record_built},
};

const mt_test_table mt_tests_defect_record = {cases, sizeof cases / sizeof cases[0]};
