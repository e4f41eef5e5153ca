/* meshtopo::msgs: every LCM type survives an encode/decode round trip with
 * every field intact, and the safe decoder (mt_msgs_decode) refuses truncated
 * bytes, wrong fingerprints, hostile lengths and random garbage with an error
 * naming the field, never a crash, a leak or a read out of bounds (this suite
 * also runs under ASan and UBSan). Every successful decode is paired with its
 * decode_cleanup. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "meshtopo/msgs.h"
#include "meshtopo/report.h"
#include "msgs_samples.h"

/* ---- Helpers ---------------------------------------------------------- */

/* Deterministic xorshift64 so a failure reproduces. */
static uint64_t next_random(uint64_t *state)
{
    uint64_t x = *state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    *state = x;
    return x;
}

static int all_zero(const void *p, size_t size)
{
    const uint8_t *b = p;
    for (size_t i = 0; i < size; i++)
        if (b[i]) return 0;
    return 1;
}

/* A message struct big enough for any meshtopo type, suitably aligned. */
typedef union any_msg {
    meshtopo_mesh_t mesh;
    meshtopo_ack_t ack;
    meshtopo_topology_t topology;
    meshtopo_query_t query;
    meshtopo_reply_t reply;
    meshtopo_status_t status;
    meshtopo_status_code_t status_code;
} any_msg;

/* Decodes bytes that must be refused: checks the error text is set and the
 * output struct is left zeroed. Returns the error text (static). */
static const char *expect_refused(const mt_msgs_type *type, const void *buf, size_t size)
{
    static char error[MT_MSGS_ERROR_SIZE];
    any_msg msg;
    memset(&msg, 0xab, sizeof msg);
    int status = mt_msgs_decode(type, buf, size, &msg, error, sizeof error);
    CHECK_EQ(status, -1);
    if (status == 0) {
        type->decode_cleanup(&msg);
        return "";
    }
    CHECK(error[0] != '\0');
    CHECK(all_zero(&msg, type->struct_size));
    CHECK_EQ(mt_msgs_check(type, buf, size, NULL, 0), -1);
    return error;
}

static void check_error_names(const char *error, const char *expected)
{
    if (strstr(error, expected) == NULL)
        mt_test_fail(__FILE__, __LINE__, "error \"%s\" does not mention \"%s\"", error, expected);
}

/* Decodes bytes that may or may not be a message: never crashes; when they
 * decode, re-encoding gives them back exactly. */
static void decode_any(const mt_msgs_type *type, const uint8_t *buf, size_t size)
{
    char error[MT_MSGS_ERROR_SIZE];
    any_msg msg;
    if (mt_msgs_decode(type, buf, size, &msg, error, sizeof error) != 0) {
        CHECK(error[0] != '\0');
        CHECK(all_zero(&msg, type->struct_size));
        return;
    }
    size_t again_size = 0;
    uint8_t *again = mt_msgs_encode_alloc(type, &msg, &again_size);
    CHECK(again != NULL);
    CHECK_EQ(again_size, size);
    if (again && again_size == size) CHECK(memcmp(again, buf, size) == 0);
    free(again);
    type->decode_cleanup(&msg);
}

/* Big-endian writer for messages built by hand. */
typedef struct bytes {
    uint8_t data[1024];
    size_t size;
} bytes;

static void put_be(bytes *b, uint64_t v, int width)
{
    for (int i = width - 1; i >= 0; i--) b->data[b->size++] = (uint8_t)(v >> (8 * i));
}

static void put_raw(bytes *b, const void *p, size_t n)
{
    memcpy(b->data + b->size, p, n);
    b->size += n;
}

/* A string as LCM writes it: length counting the NUL, bytes, NUL. */
static void put_string(bytes *b, const char *s)
{
    put_be(b, strlen(s) + 1, 4);
    put_raw(b, s, strlen(s) + 1);
}

/* How to spoil the mesh_t that build_mesh writes. */
typedef struct mesh_spoiler {
    int use_reply_channel_bytes;  /* write reply_channel_bytes instead of a good string */
    int32_t reply_channel_length; /* the length to claim */
    const char *reply_channel_bytes;
    size_t reply_channel_size;     /* bytes actually written */
    int32_t num_position_values;   /* claimed count */
    int32_t position_values_given; /* doubles actually written */
} mesh_spoiler;

/* A mesh_t written field by field: 2 vertices, positions as the spoiler
 * says, one degenerate face (1 index). */
static void build_mesh(bytes *b, const mesh_spoiler *s)
{
    b->size = 0;
    put_be(b, (uint64_t)mt_msgs_type_mesh.fingerprint(), 8);
    put_be(b, 1700000000000000, 8); /* utime */
    put_be(b, 99, 8);               /* request_id */
    if (s->use_reply_channel_bytes) {
        put_be(b, (uint32_t)s->reply_channel_length, 4);
        put_raw(b, s->reply_channel_bytes, s->reply_channel_size);
    } else {
        put_string(b, "REPLY");
    }
    put_string(b, "mesh-a"); /* mesh_id */
    put_string(b, "test");   /* source */
    put_be(b, 1, 1);         /* strict */
    put_be(b, 2, 4);         /* num_verts */
    put_be(b, (uint32_t)s->num_position_values, 4);
    for (int32_t i = 0; i < s->position_values_given; i++) put_be(b, 0x3ff0000000000000, 8);
    put_be(b, 1, 4); /* num_faces */
    put_be(b, 1, 4); /* face_vertex_counts */
    put_be(b, 1, 4); /* num_indices */
    put_be(b, 0, 4); /* face_vertex_indices */
}

static const mesh_spoiler good_mesh = {0, 0, NULL, 0, 6, 6};

/* Offset of reply_t.num_items in an encoded reply. */
static size_t reply_num_items_offset(const meshtopo_reply_t *r)
{
    return 8 + 8 + 8 + 4 + (4 + strlen(r->error) + 1) + (4 + strlen(r->mesh_id) + 1) + 4 + 4;
}

/* ---- Round trips ---------------------------------------------------------- */

static void round_trip_sample(const mt_msgs_sample *sample)
{
    const mt_msgs_type *type = sample->type;
    any_msg original, decoded, raw;
    memset(&original, 0, sizeof original);
    sample->fill(&original);

    size_t size = 0;
    uint8_t *buf = mt_msgs_encode_alloc(type, &original, &size);
    CHECK(buf != NULL);
    if (buf == NULL) return;
    CHECK(mt_msgs_type_of(buf, size) == type);

    char error[MT_MSGS_ERROR_SIZE] = "";
    CHECK_EQ(mt_msgs_check(type, buf, size, error, sizeof error), 0);
    int status = mt_msgs_decode(type, buf, size, &decoded, error, sizeof error);
    if (status != 0) {
        mt_test_fail(__FILE__, __LINE__, "%s: %s", sample->name, error);
        free(buf);
        return;
    }
    char where[256];
    if (!mt_msgs_equal(type, &original, &decoded, where, sizeof where))
        mt_test_fail(__FILE__, __LINE__, "%s: decoded %s differs", sample->name, where);

    /* The generated decoder reads the same. */
    memset(&raw, 0, sizeof raw);
    CHECK_EQ(type->decode(buf, 0, (int)size, &raw), (long long)size);
    if (!mt_msgs_equal(type, &raw, &decoded, where, sizeof where))
        mt_test_fail(__FILE__, __LINE__, "%s: LCM's decoder differs at %s", sample->name, where);
    type->decode_cleanup(&raw);

    /* Encoding the decoded message gives the same bytes. */
    size_t again_size = 0;
    uint8_t *again = mt_msgs_encode_alloc(type, &decoded, &again_size);
    CHECK(again != NULL);
    CHECK_EQ(again_size, size);
    if (again && again_size == size) CHECK(memcmp(again, buf, size) == 0);
    free(again);
    type->decode_cleanup(&decoded);
    free(buf);
}

static void round_trip_type(const mt_msgs_type *type)
{
    int samples = 0;
    for (size_t i = 0; i < mt_msgs_num_samples; i++) {
        if (mt_msgs_samples[i].type != type) continue;
        round_trip_sample(&mt_msgs_samples[i]);
        samples++;
    }
    CHECK(samples > 0);
}

static void round_trip_mesh(void)
{
    round_trip_type(&mt_msgs_type_mesh);

    /* The bits that a careless copy would lose, checked by hand. */
    meshtopo_mesh_t original, decoded;
    memset(&original, 0, sizeof original);
    mt_msgs_samples[0].fill(&original);
    CHECK(mt_msgs_samples[0].type == &mt_msgs_type_mesh);
    size_t size = 0;
    uint8_t *buf = mt_msgs_encode_alloc(&mt_msgs_type_mesh, &original, &size);
    CHECK(buf != NULL);
    if (buf == NULL) return;
    if (mt_msgs_decode(&mt_msgs_type_mesh, buf, size, &decoded, NULL, 0) == 0) {
        CHECK_EQ(decoded.num_position_values, 18);
        CHECK(isnan(decoded.positions[10]));
        CHECK(decoded.positions[11] == 0.0 && signbit(decoded.positions[11]));
        CHECK(decoded.positions[15] == original.positions[15] && decoded.positions[15] > 0);
        CHECK(strcmp(decoded.source, "scanner_d435_\xc3\xa9") == 0);
        CHECK_EQ(decoded.face_vertex_indices[8], 9);
        CHECK_EQ(decoded.request_id, 0x0123456789abcdefLL);
        meshtopo_mesh_t_decode_cleanup(&decoded);
    } else {
        CHECK(!"mesh_bowtie decodes");
    }
    free(buf);
}

static void round_trip_topology(void)
{
    round_trip_type(&mt_msgs_type_topology);
}

static void round_trip_ack(void)
{
    round_trip_type(&mt_msgs_type_ack);
}

static void round_trip_query(void)
{
    round_trip_type(&mt_msgs_type_query);
}

static void round_trip_reply(void)
{
    round_trip_type(&mt_msgs_type_reply);
}

static void round_trip_status(void)
{
    round_trip_type(&mt_msgs_type_status);
}

static void round_trip_status_code(void)
{
    round_trip_type(&mt_msgs_type_status_code);
}

/* Together the samples of a type set every one of its fields, so the round
 * trips above exercise them all (a new field needs a sample value). */
static void samples_set_every_field(void)
{
    CHECK_EQ(mt_msgs_num_types, 11);
    for (size_t t = 0; t < mt_msgs_num_types; t++) {
        const mt_msgs_type *type = mt_msgs_types[t];
        CHECK(type->struct_size <= sizeof(any_msg));
        for (int f = 0, n = type->num_fields(); f < n; f++) {
            const char *name = "?";
            int set = 0;
            for (size_t i = 0; i < mt_msgs_num_samples; i++) {
                if (mt_msgs_samples[i].type != type) continue;
                any_msg msg;
                memset(&msg, 0, sizeof msg);
                mt_msgs_samples[i].fill(&msg);
                set |= mt_msgs_field_is_set(type, &msg, f, &name);
            }
            if (!set) mt_test_fail(__FILE__, __LINE__, "no sample sets %s.%s", type->name, name);
        }
    }
}

/* ---- Refusals ------------------------------------------------------------- */

static void truncated_bytes_are_refused(void)
{
    for (size_t i = 0; i < mt_msgs_num_samples; i++) {
        const mt_msgs_sample *sample = &mt_msgs_samples[i];
        any_msg msg;
        memset(&msg, 0, sizeof msg);
        sample->fill(&msg);
        size_t size = 0;
        uint8_t *buf = mt_msgs_encode_alloc(sample->type, &msg, &size);
        CHECK(buf != NULL);
        if (buf == NULL) continue;
        for (size_t cut = 0; cut < size; cut++) {
            /* An exact-size copy, so ASan sees any read past the cut. */
            uint8_t *part = malloc(cut ? cut : 1);
            memcpy(part, buf, cut);
            expect_refused(sample->type, part, cut);
            free(part);
        }
        free(buf);
    }
    /* A cut inside the nested report is reported there. */
    any_msg reply;
    memset(&reply, 0, sizeof reply);
    for (size_t i = 0; i < mt_msgs_num_samples; i++)
        if (strcmp(mt_msgs_samples[i].name, "reply_report") == 0) mt_msgs_samples[i].fill(&reply);
    size_t size = 0;
    uint8_t *buf = mt_msgs_encode_alloc(&mt_msgs_type_reply, &reply, &size);
    CHECK(buf != NULL);
    if (buf) check_error_names(expect_refused(&mt_msgs_type_reply, buf, size - 60), "reports[0]");
    free(buf);
}

static void wrong_fingerprint_is_refused(void)
{
    for (size_t i = 0; i < mt_msgs_num_samples; i++) {
        const mt_msgs_sample *sample = &mt_msgs_samples[i];
        any_msg msg;
        memset(&msg, 0, sizeof msg);
        sample->fill(&msg);
        size_t size = 0;
        uint8_t *buf = mt_msgs_encode_alloc(sample->type, &msg, &size);
        CHECK(buf != NULL);
        if (buf == NULL) continue;
        /* The bytes of one type decoded as every other type. */
        for (size_t t = 0; t < mt_msgs_num_types; t++) {
            if (mt_msgs_types[t] == sample->type) continue;
            const char *error = expect_refused(mt_msgs_types[t], buf, size);
            check_error_names(error, "wrong fingerprint");
            check_error_names(error, sample->type->name);
        }
        /* Any bit of the fingerprint flipped. */
        for (int bit = 0; bit < 64; bit++) {
            buf[bit / 8] ^= (uint8_t)(1u << (bit % 8));
            check_error_names(expect_refused(sample->type, buf, size), "fingerprint");
            CHECK(mt_msgs_type_of(buf, size) == NULL);
            buf[bit / 8] ^= (uint8_t)(1u << (bit % 8));
        }
        free(buf);
    }
}

static void type_of_names_every_type(void)
{
    for (size_t t = 0; t < mt_msgs_num_types; t++) {
        const mt_msgs_type *type = mt_msgs_types[t];
        uint8_t fingerprint[8];
        uint64_t value = (uint64_t)type->fingerprint();
        for (int i = 0; i < 8; i++) fingerprint[i] = (uint8_t)(value >> (56 - 8 * i));
        CHECK(mt_msgs_type_of(fingerprint, 8) == type);
        CHECK(mt_msgs_type_of(fingerprint, 7) == NULL);
        for (size_t u = t + 1; u < mt_msgs_num_types; u++)
            CHECK(type->fingerprint() != mt_msgs_types[u]->fingerprint());
    }
    CHECK(mt_msgs_type_of(NULL, 0) == NULL);
    CHECK(mt_msgs_type_of("\0\0\0\0\0\0\0\0", 8) == NULL);
}

static void hostile_lengths_are_refused(void)
{
    bytes b;
    char error[MT_MSGS_ERROR_SIZE];

    /* The hand-written baseline is a valid message. */
    build_mesh(&b, &good_mesh);
    meshtopo_mesh_t mesh;
    CHECK_EQ(mt_msgs_decode(&mt_msgs_type_mesh, b.data, b.size, &mesh, error, sizeof error), 0);
    CHECK_EQ(mesh.num_position_values, 6);
    CHECK(strcmp(mesh.mesh_id, "mesh-a") == 0);
    meshtopo_mesh_t_decode_cleanup(&mesh);

    /* Array lengths: negative, larger than the message, and large enough
     * that LCM's own int arithmetic would wrap (0x20000001 * 8 = 8 mod 2^32). */
    static const struct {
        int32_t claimed, given;
        const char *expected;
    } arrays[] = {
        {-1, 0, "mesh_t.positions: negative array length -1"},
        {INT32_MIN, 0, "negative array length"},
        {INT32_MAX, 0, "mesh_t.positions: 2147483647 values need"},
        {0x20000001, 4, "mesh_t.positions: 536870913 values need"},
        {7, 6, "mesh_t.num_indices: 1 values need 4 bytes, 0 left"},
        {5, 6, "mesh_t"}, /* one double too many: the counts after it are off */
    };
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) {
        mesh_spoiler s = good_mesh;
        s.num_position_values = arrays[i].claimed;
        s.position_values_given = arrays[i].given;
        build_mesh(&b, &s);
        check_error_names(expect_refused(&mt_msgs_type_mesh, b.data, b.size), arrays[i].expected);
    }

    /* Strings: the length counts the NUL, which must be the last byte. */
    static const struct {
        int32_t claimed;
        const char *bytes;
        size_t given;
        const char *expected;
    } strings[] = {
        {-5, "", 0, "mesh_t.reply_channel: string length -5"},
        {0, "", 0, "mesh_t.reply_channel: string length 0"},
        {1000000, "abc", 4, "mesh_t.reply_channel: string of 1000000 bytes"},
        {3, "abc", 3, "does not end with a NUL"},
        {4, "a\0b", 4, "has a NUL at byte 1"},
    };
    for (size_t i = 0; i < sizeof strings / sizeof strings[0]; i++) {
        mesh_spoiler s = good_mesh;
        s.use_reply_channel_bytes = 1;
        s.reply_channel_length = strings[i].claimed;
        s.reply_channel_bytes = strings[i].bytes;
        s.reply_channel_size = strings[i].given;
        build_mesh(&b, &s);
        check_error_names(expect_refused(&mt_msgs_type_mesh, b.data, b.size), strings[i].expected);
    }

    /* A negative int8_t array length (LCM's decoder would memcpy
     * (size_t)-1 bytes) and a huge one. */
    any_msg reply;
    memset(&reply, 0, sizeof reply);
    for (size_t i = 0; i < mt_msgs_num_samples; i++)
        if (strcmp(mt_msgs_samples[i].name, "reply_ring") == 0) mt_msgs_samples[i].fill(&reply);
    size_t size = 0;
    uint8_t *buf = mt_msgs_encode_alloc(&mt_msgs_type_reply, &reply, &size);
    CHECK(buf != NULL);
    if (buf == NULL) return;
    size_t at = reply_num_items_offset(&reply.reply);
    CHECK_EQ(buf[at + 3], 3); /* num_items of the sample */
    memset(buf + at, 0xff, 4);
    check_error_names(expect_refused(&mt_msgs_type_reply, buf, size),
                      "reply_t.item_status: negative array length -1");
    buf[at] = 0x7f;
    check_error_names(expect_refused(&mt_msgs_type_reply, buf, size), "reply_t.item_status");
    free(buf);
}

static void trailing_bytes_are_refused(void)
{
    bytes b;
    build_mesh(&b, &good_mesh);
    put_raw(&b, "xyz", 3);
    check_error_names(expect_refused(&mt_msgs_type_mesh, b.data, b.size),
                      "3 bytes after the end of the message");
}

/* Whatever the error buffer's size, the text is cut and NUL-terminated
 * inside it (ASan checks the writes). */
static void error_text_fits_any_buffer(void)
{
    bytes b;
    mesh_spoiler s = good_mesh;
    s.num_position_values = -1;
    build_mesh(&b, &s);
    for (size_t n = 1; n <= 80; n++) {
        char *error = malloc(n);
        CHECK_EQ(mt_msgs_check(&mt_msgs_type_mesh, b.data, b.size, error, n), -1);
        CHECK(memchr(error, '\0', n) != NULL);
        free(error);
    }
    CHECK_EQ(mt_msgs_check(&mt_msgs_type_mesh, b.data, b.size, NULL, 0), -1);
    char one;
    CHECK_EQ(mt_msgs_check(&mt_msgs_type_mesh, b.data, b.size, &one, 0), -1);
}

static void random_bytes_are_refused(void)
{
    uint64_t state = 0x9e3779b97f4a7c15ULL;
    for (int round = 0; round < 20000; round++) {
        size_t size = next_random(&state) % 200;
        uint8_t *buf = malloc(size ? size : 1);
        for (size_t i = 0; i < size; i++) buf[i] = (uint8_t)next_random(&state);
        const mt_msgs_type *type = mt_msgs_types[round % mt_msgs_num_types];
        if (round % 2 == 0) {
            /* Pure garbage: the fingerprint cannot match. */
            if (mt_msgs_type_of(buf, size) == NULL) expect_refused(type, buf, size);
        } else if (size >= 8) {
            /* Garbage after a good fingerprint: refused, or a message that
             * re-encodes to the same bytes. */
            uint64_t fingerprint = (uint64_t)type->fingerprint();
            for (int i = 0; i < 8; i++) buf[i] = (uint8_t)(fingerprint >> (56 - 8 * i));
            decode_any(type, buf, size);
        }
        free(buf);
    }
}

/* Samples with a few bytes changed (lengths, strings, fingerprint alike). */
static void mutated_messages_never_crash(void)
{
    uint64_t state = 0x1234567887654321ULL;
    for (size_t i = 0; i < mt_msgs_num_samples; i++) {
        const mt_msgs_sample *sample = &mt_msgs_samples[i];
        any_msg msg;
        memset(&msg, 0, sizeof msg);
        sample->fill(&msg);
        size_t size = 0;
        uint8_t *buf = mt_msgs_encode_alloc(sample->type, &msg, &size);
        CHECK(buf != NULL);
        if (buf == NULL) continue;
        uint8_t *copy = malloc(size);
        for (int round = 0; round < 3000; round++) {
            memcpy(copy, buf, size);
            int changes = 1 + (int)(next_random(&state) % 4);
            for (int c = 0; c < changes; c++) {
                /* Mostly after the fingerprint, where the lengths are. */
                size_t at = 8 + (size_t)(next_random(&state) % (size - 8));
                uint64_t r = next_random(&state);
                copy[at] = (r & 0x300) == 0 ? 0xff : (r & 0x300) == 0x100 ? 0x80 : (uint8_t)r;
            }
            size_t cut = next_random(&state) % 8 == 0 ? size - next_random(&state) % size : size;
            decode_any(sample->type, copy, cut);
        }
        free(copy);
        free(buf);
    }
}

/* ---- Constants ------------------------------------------------------------ */

static void defect_kinds_match_core(void)
{
    CHECK_EQ(MESHTOPO_TOPOLOGY_T_DEFECT_OUT_OF_RANGE_INDEX, MT_DEFECT_OUT_OF_RANGE_INDEX);
    CHECK_EQ(MESHTOPO_TOPOLOGY_T_DEFECT_DEGENERATE_FACE, MT_DEFECT_DEGENERATE_FACE);
    CHECK_EQ(MESHTOPO_TOPOLOGY_T_DEFECT_DUPLICATE_FACE, MT_DEFECT_DUPLICATE_FACE);
    CHECK_EQ(MESHTOPO_TOPOLOGY_T_DEFECT_NONMANIFOLD_EDGE, MT_DEFECT_NONMANIFOLD_EDGE);
    CHECK_EQ(MESHTOPO_TOPOLOGY_T_DEFECT_SAME_DIRECTION_EDGE, MT_DEFECT_SAME_DIRECTION_EDGE);
    CHECK_EQ(MESHTOPO_TOPOLOGY_T_DEFECT_NONMANIFOLD_VERTEX, MT_DEFECT_NONMANIFOLD_VERTEX);
    CHECK_EQ(MESHTOPO_TOPOLOGY_T_DEFECT_ISOLATED_VERTEX, MT_DEFECT_ISOLATED_VERTEX);
    CHECK_EQ(MESHTOPO_TOPOLOGY_T_DEFECT_NONFINITE_COORD, MT_DEFECT_NONFINITE_COORD);
    /* A new core defect kind needs a constant in topology_t.lcm. */
    CHECK_EQ(MT_DEFECT_KIND_COUNT, MESHTOPO_TOPOLOGY_T_DEFECT_NONFINITE_COORD + 1);
}

static void query_kinds_and_status_codes_are_distinct(void)
{
    const int kinds[] = {
        MESHTOPO_QUERY_T_VERTEX_RING,    MESHTOPO_QUERY_T_VALENCE,
        MESHTOPO_QUERY_T_FACE_NEIGHBORS, MESHTOPO_QUERY_T_EDGE_FACES,
        MESHTOPO_QUERY_T_BOUNDARY_LOOPS, MESHTOPO_QUERY_T_COMPONENTS,
        MESHTOPO_QUERY_T_REPORT,         MESHTOPO_QUERY_T_DEFECTS,
        MESHTOPO_QUERY_T_LIST_MESHES,
    };
    /* 1 .. 9 in order: 0 is no query. */
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) CHECK_EQ(kinds[i], (int)i + 1);
    const int codes[] = {
        MESHTOPO_STATUS_CODE_T_OK,           MESHTOPO_STATUS_CODE_T_BAD_REQUEST,
        MESHTOPO_STATUS_CODE_T_UNDECODABLE,  MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH,
        MESHTOPO_STATUS_CODE_T_UNKNOWN_KIND, MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE,
        MESHTOPO_STATUS_CODE_T_NOT_FOUND,    MESHTOPO_STATUS_CODE_T_TOO_LARGE,
        MESHTOPO_STATUS_CODE_T_BUILD_FAILED, MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED,
        MESHTOPO_STATUS_CODE_T_BUSY,         MESHTOPO_STATUS_CODE_T_INTERNAL,
    };
    /* 0 .. 11 in order; reply_t.item_status holds them in an int8_t. */
    for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++) {
        CHECK_EQ(codes[i], (int)i);
        CHECK(codes[i] <= INT8_MAX);
    }
}

static const mt_test_case cases[] = {
    {"round_trip_mesh", round_trip_mesh},
    {"round_trip_topology", round_trip_topology},
    {"round_trip_ack", round_trip_ack},
    {"round_trip_query", round_trip_query},
    {"round_trip_reply", round_trip_reply},
    {"round_trip_status", round_trip_status},
    {"round_trip_status_code", round_trip_status_code},
    {"samples_set_every_field", samples_set_every_field},
    {"truncated_bytes_are_refused", truncated_bytes_are_refused},
    {"wrong_fingerprint_is_refused", wrong_fingerprint_is_refused},
    {"type_of_names_every_type", type_of_names_every_type},
    {"hostile_lengths_are_refused", hostile_lengths_are_refused},
    {"trailing_bytes_are_refused", trailing_bytes_are_refused},
    {"error_text_fits_any_buffer", error_text_fits_any_buffer},
    {"random_bytes_are_refused", random_bytes_are_refused},
    {"mutated_messages_never_crash", mutated_messages_never_crash},
    {"defect_kinds_match_core", defect_kinds_match_core},
    {"query_kinds_and_status_codes_are_distinct", query_kinds_and_status_codes_are_distinct},
};
const mt_test_table mt_tests_msgs = {cases, sizeof cases / sizeof cases[0]};
