/* Tests of msgs/'s protocol rules (meshtopo/protocol.h, channels.h): the
 * mesh-id rule, the status code table, which reply channels a daemon answers
 * on, and the .lcm limits against the datagram size they
 * exist for. */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "meshtopo/channels.h"
#include "meshtopo/msgs.h"
#include "meshtopo/protocol.h"
#include "meshtopo/query_kinds.h"

static void expect_refused(const char *id, uint64_t byte_offset, const char *needle, int line)
{
    mt_diag diag;
    if (mt_msgs_mesh_id_check(id, &diag) != MT_ERR_INVALID_ARG) {
        mt_test_fail(__FILE__, line, "mesh id was accepted");
        return;
    }
    if (diag.status != MT_ERR_INVALID_ARG || diag.byte_offset != byte_offset)
        mt_test_fail(__FILE__, line, "diag status %d byte %llu, expected byte %llu",
                     (int)diag.status, (unsigned long long)diag.byte_offset,
                     (unsigned long long)byte_offset);
    if (!strstr(diag.message, needle))
        mt_test_fail(__FILE__, line, "'%s' does not name '%s'", diag.message, needle);
}

static void mesh_id_rule(void)
{
    char longest[MESHTOPO_MESH_T_MESH_ID_MAX + 2];
    memset(longest, 'x', sizeof longest);
    longest[MESHTOPO_MESH_T_MESH_ID_MAX] = '\0';
    mt_diag diag;
    CHECK_EQ(mt_msgs_mesh_id_check(longest, &diag), MT_OK);
    CHECK_EQ(mt_msgs_mesh_id_check("room 3.v2 ~robot-1_a", &diag), MT_OK);
    CHECK_EQ(mt_msgs_mesh_id_check("x", NULL), MT_OK);
    longest[MESHTOPO_MESH_T_MESH_ID_MAX] = 'x';
    longest[MESHTOPO_MESH_T_MESH_ID_MAX + 1] = '\0';
    expect_refused(longest, UINT64_MAX, "256 bytes long", __LINE__);
    expect_refused(NULL, UINT64_MAX, "NULL", __LINE__);
    expect_refused("", UINT64_MAX, "empty", __LINE__);
    expect_refused("a/b", 1, "'/'", __LINE__);
    expect_refused("ab..", 2, "\"..\"", __LINE__);
    expect_refused("a\nb", 1, "0x0a", __LINE__);
    expect_refused("ab\x7f", 2, "0x7f", __LINE__);
    expect_refused("\xc3\xa9", 0, "printable ASCII", __LINE__);
    CHECK_EQ(mt_msgs_mesh_id_check("a/b", NULL), MT_ERR_INVALID_ARG);
}

static void status_codes(void)
{
    /* Every code status_code_t defines has its own name; the mapping is the
     * client's documented one. */
    const char *seen[MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED + 1];
    for (int32_t code = 0; code <= MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED; code++) {
        seen[code] = mt_msgs_code_name(code);
        CHECK(strcmp(seen[code], "UNKNOWN_CODE") != 0);
        for (int32_t other = 0; other < code; other++) CHECK(strcmp(seen[code], seen[other]) != 0);
    }
    CHECK(strcmp(mt_msgs_code_name(MESHTOPO_STATUS_CODE_T_OK), "OK") == 0);
    CHECK(strcmp(mt_msgs_code_name(MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH), "UNKNOWN_MESH") == 0);
    CHECK(strcmp(mt_msgs_code_name(MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED), "ARCHIVE_FAILED") == 0);
    CHECK(strcmp(mt_msgs_code_name(-1), "UNKNOWN_CODE") == 0);
    CHECK(strcmp(mt_msgs_code_name(999), "UNKNOWN_CODE") == 0);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_OK), MT_OK);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_BAD_REQUEST), MT_ERR_INVALID_ARG);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_UNDECODABLE), MT_ERR_PARSE);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH), MT_ERR_NOT_FOUND);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE), MT_ERR_OUT_OF_RANGE);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_TOO_LARGE), MT_ERR_TOO_LARGE);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED), MT_ERR_DEFECT);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_NO_GEOMETRY), MT_ERR_NO_GEOMETRY);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_BUSY), MT_ERR_IO);
    CHECK_EQ(mt_msgs_status_of_code(999), MT_ERR_IO);
}

static void status_codes_both_ways(void)
{
    /* What the daemon sends for a library status: the table's codes, else
     * the caller's. */
    const int32_t other = MESHTOPO_STATUS_CODE_T_BUILD_FAILED;
    CHECK_EQ(mt_msgs_code_of_status(MT_OK, other), MESHTOPO_STATUS_CODE_T_OK);
    CHECK_EQ(mt_msgs_code_of_status(MT_ERR_INVALID_ARG, other), MESHTOPO_STATUS_CODE_T_BAD_REQUEST);
    CHECK_EQ(mt_msgs_code_of_status(MT_ERR_TOO_LARGE, other), MESHTOPO_STATUS_CODE_T_TOO_LARGE);
    CHECK_EQ(mt_msgs_code_of_status(MT_ERR_NOMEM, other), MESHTOPO_STATUS_CODE_T_INTERNAL);
    CHECK_EQ(mt_msgs_code_of_status(MT_ERR_NO_GEOMETRY, other), MESHTOPO_STATUS_CODE_T_NO_GEOMETRY);
    CHECK_EQ(mt_msgs_code_of_status(MT_ERR_CORRUPT, other), other);
    CHECK_EQ(mt_msgs_code_of_status(MT_ERR_IO, MESHTOPO_STATUS_CODE_T_INTERNAL),
             MESHTOPO_STATUS_CODE_T_INTERNAL);
    /* Every status sent as a code reads back as itself. */
    for (int s = MT_OK; s <= MT_ERR_NO_GEOMETRY; s++) {
        int32_t code = mt_msgs_code_of_status((mt_status)s, -1);
        if (code >= 0 && s != MT_ERR_NOMEM) CHECK_EQ(mt_msgs_status_of_code(code), (mt_status)s);
    }
}

static void query_kinds_table(void)
{
    /* One row per query_t constant, numbered from VERTEX_RING to
     * SELF_INTERSECTIONS without gaps; names unique and found again. */
    size_t n = mt_msgs_query_kind_count();
    CHECK_EQ(mt_msgs_query_kind_first(), MESHTOPO_QUERY_T_VERTEX_RING);
    CHECK_EQ(mt_msgs_query_kind_last(), MESHTOPO_QUERY_T_SELF_INTERSECTIONS);
    CHECK_EQ(n, (size_t)(mt_msgs_query_kind_last() - mt_msgs_query_kind_first() + 1));
    CHECK(mt_msgs_query_kind_at(n) == NULL);
    CHECK(mt_msgs_query_kind_of(mt_msgs_query_kind_first() - 1) == NULL);
    CHECK(mt_msgs_query_kind_of(mt_msgs_query_kind_last() + 1) == NULL);
    CHECK(mt_msgs_query_kind_named("no-such-kind") == NULL);
    CHECK(mt_msgs_query_kind_named(NULL) == NULL);
    for (size_t i = 0; i < n; i++) {
        const mt_msgs_query_kind *k = mt_msgs_query_kind_at(i);
        CHECK(mt_msgs_query_kind_of(k->kind) == k);
        CHECK(mt_msgs_query_kind_named(k->name) == k);
        for (size_t j = 0; j < i; j++) {
            CHECK(mt_msgs_query_kind_at(j)->kind != k->kind);
            CHECK(strcmp(mt_msgs_query_kind_at(j)->wire_name, k->wire_name) != 0);
        }
        /* The columns agree with each other. */
        CHECK_EQ(k->ids == MT_MSGS_IDS_NONE, k->space == MT_MSGS_ID_NONE);
        if (k->pairs) CHECK_EQ(k->space, MT_MSGS_ID_VERTEX);
        if (k->reply == MT_MSGS_REPLY_PER_ID) CHECK(k->ids != MT_MSGS_IDS_NONE);
        if (k->on_worker) CHECK_EQ(k->reply, MT_MSGS_REPLY_MESH);
        CHECK(strcmp(mt_msgs_ids_rule_name(k->ids), "?") != 0);
        CHECK(strcmp(mt_msgs_id_space_name(k->space), "?") != 0);
        CHECK(strcmp(mt_msgs_reply_shape_name(k->reply), "?") != 0);
    }
    const mt_msgs_query_kind *ring = mt_msgs_query_kind_of(MESHTOPO_QUERY_T_VERTEX_RING);
    CHECK(strcmp(ring->wire_name, "VERTEX_RING") == 0 && strcmp(ring->name, "ring") == 0);
    CHECK(mt_msgs_query_kind_of(MESHTOPO_QUERY_T_EDGE_FACES)->pairs);
    CHECK(mt_msgs_query_kind_of(MESHTOPO_QUERY_T_SELF_INTERSECTIONS)->on_worker);
}

/* A string of n 'c' bytes (the longest channel or id a message carries). */
static char *filled(size_t n)
{
    char *s = malloc(n + 1);
    memset(s, 'c', n);
    s[n] = '\0';
    return s;
}

/* The pieces the limits describe fit one datagram even at their largest:
 * a full part, a pull of RANGES_MAX ranges, a status of MISSING_MAX gaps. */
static void limits_fit_one_datagram(void)
{
    char *channel = filled(63); /* LCM's longest channel name */
    uint8_t *data = calloc(MESHTOPO_REPLY_PART_T_PART_SIZE, 1);
    meshtopo_reply_part_t part;
    memset(&part, 0, sizeof part);
    part.part_size = part.length = MESHTOPO_REPLY_PART_T_PART_SIZE;
    part.data = data;
    CHECK(meshtopo_reply_part_t_encoded_size(&part) <= MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX);

    int64_t *ranges = calloc(MESHTOPO_REPLY_PULL_T_RANGES_MAX, sizeof *ranges);
    meshtopo_reply_pull_t pull;
    memset(&pull, 0, sizeof pull);
    pull.reply_channel = channel;
    pull.num_ranges = MESHTOPO_REPLY_PULL_T_RANGES_MAX;
    pull.offsets = pull.lengths = ranges;
    CHECK(meshtopo_reply_pull_t_encoded_size(&pull) <= MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX);

    int64_t *gaps = calloc(MESHTOPO_MESH_TRANSFER_T_MISSING_MAX, sizeof *gaps);
    char *error = filled(511); /* the daemon's longest error text */
    meshtopo_mesh_transfer_t status;
    memset(&status, 0, sizeof status);
    status.error = error;
    status.num_missing = MESHTOPO_MESH_TRANSFER_T_MISSING_MAX;
    status.missing_offsets = status.missing_lengths = gaps;
    CHECK(meshtopo_mesh_transfer_t_encoded_size(&status) <=
          MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX);
    /* A part is smaller than the message it is cut from. */
    CHECK(MESHTOPO_REPLY_PART_T_PART_SIZE < MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX);
    CHECK(MESHTOPO_REPLY_PULL_T_PARTS_PER_PULL_MAX >= MESHTOPO_REPLY_PART_T_FIRST_PARTS);
    free(error);
    free(gaps);
    free(ranges);
    free(data);
    free(channel);
}

/* A reply channel may not be or start with a daemon channel of its prefix. */
static void reply_channel_allowed(void)
{
    const char *refused[] = {"MESHTOPO_SUBMIT",     "MESHTOPO_SUBMIT_CHUNK",
                             "MESHTOPO_QUERY",      "MESHTOPO_QUERY_PULL",
                             "MESHTOPO_TOPOLOGY",   "MESHTOPO_STATUS",
                             "MESHTOPO_STATUS_ACK", "MESHTOPO_QUERYX",
                             "MESHTOPO_SUBMIT_",    "",
                             "with space"};
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++)
        if (mt_msgs_reply_channel_allowed("MESHTOPO_", refused[i]))
            mt_test_fail(__FILE__, __LINE__, "'%s' allowed", refused[i]);
    const char *allowed[] = {"MESHTOPO_REPLY_host_42_0000beef", "MESHTOPO_STATU", "MESHTOPO_",
                             "ROBOT7_QUERY", "reply"};
    for (size_t i = 0; i < sizeof allowed / sizeof allowed[0]; i++)
        if (!mt_msgs_reply_channel_allowed("MESHTOPO_", allowed[i]))
            mt_test_fail(__FILE__, __LINE__, "'%s' refused", allowed[i]);
    /* Another prefix has its own daemon channels. */
    CHECK(!mt_msgs_reply_channel_allowed("ROBOT7_", "ROBOT7_QUERY"));
    CHECK(mt_msgs_reply_channel_allowed("ROBOT7_", "MESHTOPO_QUERY"));
    CHECK(!mt_msgs_reply_channel_allowed(NULL, "reply"));
}

static const mt_test_case cases[] = {
    {"reply_channel_allowed", reply_channel_allowed},
    {"mesh_id_rule", mesh_id_rule},
    {"status_codes", status_codes},
    {"status_codes_both_ways", status_codes_both_ways},
    {"query_kinds_table", query_kinds_table},
    {"limits_fit_one_datagram", limits_fit_one_datagram},
};
const mt_test_table mt_tests_protocol = {cases, sizeof cases / sizeof cases[0]};
