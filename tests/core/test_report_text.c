/* Tests of report_text.c: the exact one-line description of every defect
 * kind, snprintf-style truncation and length, and counting the entries of
 * one kind in a report (also on a built mesh with every kind of defect). */
#include <string.h>

#include "harness.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"
#include "meshtopo/validate.h"

static void expect_text(uint32_t kind, uint32_t a, uint32_t b, uint32_t c, const char *want,
                        int line)
{
    mt_defect d = {kind, a, b, c};
    char buf[256];
    memset(buf, 'x', sizeof buf);
    size_t n = mt_defect_describe(&d, buf, sizeof buf);
    if (strcmp(buf, want) != 0)
        mt_test_fail(__FILE__, line, "described as \"%s\", expected \"%s\"", buf, want);
    if (n != strlen(want))
        mt_test_fail(__FILE__, line, "length %zu, expected %zu", n, strlen(want));
}

#define EXPECT_TEXT(kind, a, b, c, want) expect_text((kind), (a), (b), (c), (want), __LINE__)

static void test_defect_describe_kinds(void)
{
    EXPECT_TEXT(MT_DEFECT_OUT_OF_RANGE_INDEX, 12, 0xffffffffu, 2,
                "face 12 uses vertex index -1, out of range (position 2)");
    EXPECT_TEXT(MT_DEFECT_OUT_OF_RANGE_INDEX, 3, 1000, 0,
                "face 3 uses vertex index 1000, out of range (position 0)");
    EXPECT_TEXT(MT_DEFECT_DEGENERATE_FACE, 4, 2, 3,
                "face 4 has 2 distinct vertices out of 3 entries (degenerate)");
    EXPECT_TEXT(MT_DEFECT_DUPLICATE_FACE, 9, 2, 0, "face 9 repeats face 2 (duplicate)");
    EXPECT_TEXT(MT_DEFECT_NONMANIFOLD_EDGE, 7, 8, 3, "edge 7-8 is used by 3 faces (non-manifold)");
    EXPECT_TEXT(MT_DEFECT_SAME_DIRECTION_EDGE, 5, 1, 2,
                "side 5->1 is used by 2 faces in the same direction (inconsistent orientation)");
    EXPECT_TEXT(MT_DEFECT_NONMANIFOLD_VERTEX, 590, 2, 0, "vertex 590 has 2 separate fans (bowtie)");
    EXPECT_TEXT(MT_DEFECT_NONMANIFOLD_VERTEX, 590, 3, 1,
                "vertex 590 has 3 separate fans (bowtie) and lies on a non-manifold edge");
    EXPECT_TEXT(MT_DEFECT_NONMANIFOLD_VERTEX, 0, 1, 1,
                "vertex 0 lies on a non-manifold edge (a vertex of its link has degree > 2)");
    EXPECT_TEXT(MT_DEFECT_ISOLATED_VERTEX, 6, 0, 0, "vertex 6 is used by no valid face (isolated)");
    EXPECT_TEXT(MT_DEFECT_NONFINITE_COORD, 8, 1, 0, "vertex 8 has a NaN or infinite y coordinate");
    EXPECT_TEXT(MT_DEFECT_KIND_COUNT, 1, 2, 3, "unknown defect kind 8 (1, 2, 3)");
}

static void test_defect_describe_truncation(void)
{
    mt_defect d = {MT_DEFECT_NONMANIFOLD_EDGE, 7, 8, 3};
    const char *full = "edge 7-8 is used by 3 faces (non-manifold)";
    char buf[8];
    memset(buf, 'x', sizeof buf);
    CHECK_EQ(mt_defect_describe(&d, buf, sizeof buf), strlen(full));
    CHECK(strcmp(buf, "edge 7-") == 0);
    CHECK_EQ(mt_defect_describe(&d, buf, 1), strlen(full));
    CHECK_EQ(buf[0], '\0');
    buf[0] = 'x';
    CHECK_EQ(mt_defect_describe(&d, buf, 0), strlen(full)); /* writes nothing */
    CHECK_EQ(buf[0], 'x');
    CHECK_EQ(mt_defect_describe(&d, NULL, 0), strlen(full));
    CHECK_EQ(mt_defect_describe(&d, NULL, 100), strlen(full));
    CHECK_EQ(mt_defect_describe(NULL, buf, sizeof buf), 0);
    CHECK_EQ(buf[0], '\0');
}

static void test_report_count_defects(void)
{
    mt_defect defects[] = {
        {MT_DEFECT_OUT_OF_RANGE_INDEX, 0, 9, 1}, {MT_DEFECT_DEGENERATE_FACE, 1, 2, 3},
        {MT_DEFECT_DEGENERATE_FACE, 4, 2, 2},    {MT_DEFECT_NONMANIFOLD_EDGE, 0, 1, 3},
        {MT_DEFECT_ISOLATED_VERTEX, 5, 0, 0},    {MT_DEFECT_ISOLATED_VERTEX, 6, 0, 0},
        {MT_DEFECT_ISOLATED_VERTEX, 7, 0, 0},
    };
    mt_report r;
    memset(&r, 0, sizeof r);
    r.defects = defects;
    r.num_defects = sizeof defects / sizeof defects[0];
    CHECK_EQ(mt_report_count_defects(&r, MT_DEFECT_OUT_OF_RANGE_INDEX), 1);
    CHECK_EQ(mt_report_count_defects(&r, MT_DEFECT_DEGENERATE_FACE), 2);
    CHECK_EQ(mt_report_count_defects(&r, MT_DEFECT_DUPLICATE_FACE), 0);
    CHECK_EQ(mt_report_count_defects(&r, MT_DEFECT_NONMANIFOLD_EDGE), 1);
    CHECK_EQ(mt_report_count_defects(&r, MT_DEFECT_ISOLATED_VERTEX), 3);
    CHECK_EQ(mt_report_count_defects(&r, MT_DEFECT_NONFINITE_COORD), 0);
    CHECK_EQ(mt_report_count_defects(&r, MT_DEFECT_KIND_COUNT), 0);
    CHECK_EQ(mt_report_count_defects(NULL, MT_DEFECT_ISOLATED_VERTEX), 0);
    r.num_defects = 0;
    CHECK_EQ(mt_report_count_defects(&r, MT_DEFECT_ISOLATED_VERTEX), 0);
}

/* On a built mesh the counts agree with the report's own counters. */
static void test_report_count_defects_built(void)
{
    static const uint32_t sizes[] = {3, 3, 3, 3, 2, 3};
    static const uint32_t idx[] = {0, 1, 2, 1, 0, 3, 0, 1, 4, 0, 5, 6, 3, 4, 0, 17, 1};
    mt_face_list list = {
        10, 6, sizeof idx / sizeof idx[0], NULL, (uint32_t *)sizes, (uint32_t *)idx};
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(&list, NULL, &mesh, NULL));
    CHECK_OK(mt_mesh_validate(mesh, NULL));
    const mt_report *r = mt_mesh_report(mesh);
    if (!r) return;
    CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_OUT_OF_RANGE_INDEX), r->out_of_range_indices);
    CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_DEGENERATE_FACE), r->degenerate_faces);
    CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_NONMANIFOLD_EDGE), r->nonmanifold_edges);
    CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_NONMANIFOLD_VERTEX), r->nonmanifold_vertices);
    CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_ISOLATED_VERTEX), r->isolated_vertices);
    CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_NONMANIFOLD_EDGE), 1);
    CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_ISOLATED_VERTEX), 3); /* 7, 8, 9 */
    size_t total = 0;
    for (int k = 0; k < MT_DEFECT_KIND_COUNT; k++)
        total += mt_report_count_defects(r, (mt_defect_kind)k);
    CHECK_EQ(total, r->num_defects);
    char text[200];
    for (size_t i = 0; i < r->num_defects; i++) {
        size_t n = mt_defect_describe(&r->defects[i], text, sizeof text);
        CHECK(n > 0 && n == strlen(text));
        CHECK(strstr(text, "unknown") == NULL);
    }
    mt_mesh_destroy(mesh);
}

static const mt_test_case cases[] = {
    {"defect_describe_kinds", test_defect_describe_kinds},
    {"defect_describe_truncation", test_defect_describe_truncation},
    {"report_count_defects", test_report_count_defects},
    {"report_count_defects_built", test_report_count_defects_built},
};

const mt_test_table mt_tests_report_text = {cases, sizeof cases / sizeof cases[0]};
