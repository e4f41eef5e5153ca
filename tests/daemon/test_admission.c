/* Tests of meshtopod's admission by cost (daemon/admission.c): the estimate
 * against what the core really allocates, the claim ratio, the store and
 * archive limits alone (TOO_LARGE) and with what is held and reserved
 * (BUSY), the per-sender share, and reservations given back. */
#include <stdio.h>
#include <string.h>

#include "admission.h"
#include "harness.h"
#include "meshtopo/core.h"
#include "meshtopo/msgs.h"

#define CHECK_REFUSED(status, error, expected, needle)                                      \
    do {                                                                                    \
        CHECK_EQ((status), (expected));                                                     \
        if (!strstr((error), (needle)))                                                     \
            mt_test_fail(__FILE__, __LINE__, "'%s' does not name '%s'", (error), (needle)); \
    } while (0)

/* The estimate is close to what a build of a real mesh takes: at least its
 * arrays, at most twice them. */
static void estimate_tracks_the_core(void)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(300, 200, true, &grid));
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&grid, NULL, &mesh, &diag));
    mtd_cost cost = mtd_cost_estimate(grid.num_verts, true, grid.num_faces, grid.num_indices);
    size_t real = mt_mesh_memory_bytes(mesh);
    CHECK(cost.memory >= real);
    CHECK(cost.memory <= 2 * real);
    CHECK_EQ(cost.carried,
             16 + 24ull * grid.num_verts + 4ull * grid.num_faces + 4ull * grid.num_indices);
    CHECK(cost.archive > cost.carried + cost.memory);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&grid);
}

/* 16,777,216 vertices without positions and 6 faces: megabytes claimed by
 * a message of about a hundred bytes. */
static void claim_ratio(void)
{
    mtd_admission_limits limits = {.max_claim_ratio = 16};
    mtd_admission *a;
    CHECK_OK(mtd_admission_create(&limits, &a));
    char error[512];
    mtd_cost hostile = mtd_cost_estimate(16u << 20, false, 6, 18);
    CHECK_REFUSED(mtd_admission_take(a, "R", &hostile, 0, 0, error, sizeof error), error,
                  MESHTOPO_STATUS_CODE_T_TOO_LARGE, "--max-claim-ratio");
    char figures[128];
    snprintf(figures, sizeof figures, "claims %llu bytes of memory for the %llu bytes",
             (unsigned long long)hostile.memory, (unsigned long long)hostile.carried);
    CHECK(strstr(error, figures) != NULL);
    CHECK(hostile.carried < 200 && hostile.memory > (128u << 20));
    /* The same counts with positions carry their weight. */
    mtd_cost honest = mtd_cost_estimate(16u << 20, true, 6, 18);
    CHECK_EQ(mtd_admission_take(a, "R", &honest, 0, 0, error, sizeof error),
             MESHTOPO_STATUS_CODE_T_OK);
    mtd_admission_give_back(a, "R", &honest);
    /* A triangle soup without positions, a mesh of polygons: well under. */
    mtd_cost soup = mtd_cost_estimate(3000000, false, 1000000, 3000000);
    CHECK_EQ(mtd_admission_take(a, "R", &soup, 0, 0, error, sizeof error),
             MESHTOPO_STATUS_CODE_T_OK);
    mtd_admission_give_back(a, "R", &soup);
    /* Small meshes are never compared. */
    mtd_cost tiny = mtd_cost_estimate(1000, false, 1, 3);
    CHECK_EQ(mtd_admission_take(a, "R", &tiny, 0, 0, error, sizeof error),
             MESHTOPO_STATUS_CODE_T_OK);
    mtd_admission_give_back(a, "R", &tiny);
    mtd_admission_destroy(a);
    /* 0 turns the check off. */
    limits.max_claim_ratio = 0;
    CHECK_OK(mtd_admission_create(&limits, &a));
    CHECK_EQ(mtd_admission_take(a, "R", &hostile, 0, 0, error, sizeof error),
             MESHTOPO_STATUS_CODE_T_OK);
    mtd_admission_give_back(a, "R", &hostile);
    mtd_admission_destroy(a);
}

static void store_and_archive_limits(void)
{
    mtd_cost mesh = mtd_cost_estimate(100000, true, 200000, 600000);
    mtd_admission_limits limits = {.max_store_bytes = 3 * mesh.memory,
                                   .max_archive_bytes = 10 * mesh.archive};
    mtd_admission *a;
    CHECK_OK(mtd_admission_create(&limits, &a));
    char error[512];
    /* Alone over the store: TOO_LARGE, naming the flag and both figures. */
    mtd_cost huge = mtd_cost_estimate(400000, true, 800000, 2400000);
    CHECK_REFUSED(mtd_admission_take(a, "R", &huge, 0, 0, error, sizeof error), error,
                  MESHTOPO_STATUS_CODE_T_TOO_LARGE, "--max-store-bytes");
    /* Two fit beside what the store holds; the third is BUSY while they
     * are built, and fits once one is given back. */
    CHECK_EQ(mtd_admission_take(a, "R", &mesh, mesh.memory / 2, 0, error, sizeof error),
             MESHTOPO_STATUS_CODE_T_OK);
    CHECK_EQ(mtd_admission_take(a, "S", &mesh, mesh.memory / 2, 0, error, sizeof error),
             MESHTOPO_STATUS_CODE_T_OK);
    uint64_t memory, archive;
    mtd_admission_reserved(a, &memory, &archive);
    CHECK_EQ(memory, 2 * mesh.memory);
    CHECK_EQ(archive, 2 * mesh.archive);
    CHECK_REFUSED(mtd_admission_take(a, "T", &mesh, mesh.memory / 2, 0, error, sizeof error), error,
                  MESHTOPO_STATUS_CODE_T_BUSY, "retry later");
    mtd_admission_give_back(a, "R", &mesh);
    CHECK_EQ(mtd_admission_take(a, "T", &mesh, mesh.memory / 2, 0, error, sizeof error),
             MESHTOPO_STATUS_CODE_T_OK);
    /* The archive: what its files hold counts. */
    CHECK_REFUSED(mtd_admission_take(a, "U", &mesh, 0, 9 * mesh.archive, error, sizeof error),
                  error, MESHTOPO_STATUS_CODE_T_BUSY, "--max-archive-bytes");
    mtd_admission_give_back(a, "S", &mesh);
    mtd_admission_give_back(a, "T", &mesh);
    mtd_admission_reserved(a, &memory, &archive);
    CHECK_EQ(memory, 0);
    CHECK_EQ(archive, 0);
    mtd_admission_destroy(a);
}

static void share_per_sender(void)
{
    mtd_admission_limits limits = {.builds_per_sender = 3};
    mtd_admission *a;
    CHECK_OK(mtd_admission_create(&limits, &a));
    char error[512];
    mtd_cost cube = mtd_cost_estimate(8, true, 6, 24);
    for (int i = 0; i < 3; i++)
        CHECK_EQ(mtd_admission_take(a, "FLOOD", &cube, 0, 0, error, sizeof error),
                 MESHTOPO_STATUS_CODE_T_OK);
    CHECK_REFUSED(mtd_admission_take(a, "FLOOD", &cube, 0, 0, error, sizeof error), error,
                  MESHTOPO_STATUS_CODE_T_BUSY, "reply channel 'FLOOD' has 3 builds");
    /* Another sender is not held back by it. */
    CHECK_EQ(mtd_admission_take(a, "ROBOT", &cube, 0, 0, error, sizeof error),
             MESHTOPO_STATUS_CODE_T_OK);
    mtd_admission_give_back(a, "FLOOD", &cube);
    CHECK_EQ(mtd_admission_take(a, "FLOOD", &cube, 0, 0, error, sizeof error),
             MESHTOPO_STATUS_CODE_T_OK);
    for (int i = 0; i < 3; i++) mtd_admission_give_back(a, "FLOOD", &cube);
    mtd_admission_give_back(a, "ROBOT", &cube);
    /* A sender unknown to it: nothing happens. */
    mtd_admission_give_back(a, "NOBODY", &cube);
    uint64_t memory, archive;
    mtd_admission_reserved(a, &memory, &archive);
    CHECK_EQ(memory, 0);
    mtd_admission_destroy(a);
}

static const mt_test_case cases[] = {
    {"estimate_tracks_the_core", estimate_tracks_the_core},
    {"claim_ratio", claim_ratio},
    {"store_and_archive_limits", store_and_archive_limits},
    {"share_per_sender", share_per_sender},
};
const mt_test_table mt_tests_admission = {cases, sizeof cases / sizeof cases[0]};
