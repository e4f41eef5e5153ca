/* Tests of meshtopod's settings (flags over environment over defaults, and
 * the error naming a bad one) and of its one-line log. */
#define _DEFAULT_SOURCE /* setenv, unsetenv, mkstemp */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "config.h"
#include "harness.h"
#include "log.h"

static mt_status parse(mtd_config *c, mtd_config_action *action, mt_diag *diag, int argc,
                       const char **argv)
{
    return mtd_config_parse(argc, (char **)argv, c, action, diag);
}

static void config_defaults(void)
{
    unsetenv("MESHTOPOD_WORKERS");
    const char *argv[] = {"meshtopod"};
    mtd_config c;
    mtd_config_action action;
    mt_diag diag;
    CHECK_OK(parse(&c, &action, &diag, 1, argv));
    CHECK_EQ(action, MTD_CONFIG_RUN);
    CHECK(strcmp(c.channel_prefix, "MESHTOPO_") == 0);
    CHECK(strcmp(c.lcm_url, "") == 0);
    CHECK_EQ(c.workers, 2);
    CHECK_EQ(c.heartbeat_ms, 1000);
    CHECK_EQ(c.log_level, MTD_LOG_INFO);
    /* Limits from the machine: half its memory for the store, a quarter of
     * that (at most 1 GiB) for transfers; no archive, no archive limit. */
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    uint64_t machine = (uint64_t)pages * (uint64_t)page;
    CHECK(c.max_store_bytes > 0 && c.max_store_bytes <= machine / 2);
    CHECK(c.max_transfer_bytes > 0 && c.max_transfer_bytes <= c.max_store_bytes / 4 + 1 &&
          c.max_transfer_bytes <= 1ull << 30);
    CHECK_EQ(c.max_archive_bytes, 0);
    CHECK_EQ(c.max_claim_ratio, 16);
    CHECK_EQ(c.archive_compression, MTD_COMPRESSION_NONE); /* every reader opens the files */
    /* With an archive: half the free space of its file system (the
     * directory need not exist yet). */
    const char *with_archive[] = {"meshtopod", "--archive", "/tmp/meshtopo-no-such-dir/a"};
    CHECK_OK(parse(&c, &action, &diag, 3, with_archive));
    CHECK(c.max_archive_bytes > 0);
    const char *explicit_limit[] = {"meshtopod", "--archive", "/tmp", "--max-archive-bytes", "5M"};
    CHECK_OK(parse(&c, &action, &diag, 5, explicit_limit));
    CHECK_EQ(c.max_archive_bytes, 5u << 20);
    const char *lz4[] = {"meshtopod", "--archive", "/tmp", "--archive-compression", "lz4"};
    CHECK_OK(parse(&c, &action, &diag, 5, lz4));
    CHECK_EQ(c.archive_compression, MTD_COMPRESSION_LZ4);
    CHECK(strcmp(mtd_archive_compression_name(c.archive_compression), "lz4") == 0);
}

static void config_flags_override_environment(void)
{
    setenv("MESHTOPOD_WORKERS", "3", 1);
    setenv("MESHTOPOD_PREFIX", "ENV_", 1);
    const char *argv[] = {"meshtopod",         "--workers", "5",           "--lcm-url=memq://",
                          "--max-store-bytes", "2G",        "--log-level", "debug"};
    mtd_config c;
    mtd_config_action action;
    mt_diag diag;
    CHECK_OK(parse(&c, &action, &diag, 8, argv));
    CHECK_EQ(c.workers, 5);                       /* flag wins */
    CHECK(strcmp(c.channel_prefix, "ENV_") == 0); /* environment over default */
    CHECK(strcmp(c.lcm_url, "memq://") == 0);
    CHECK_EQ(c.max_store_bytes, 2ull << 30);
    CHECK_EQ(c.log_level, MTD_LOG_DEBUG);
    unsetenv("MESHTOPOD_WORKERS");
    unsetenv("MESHTOPOD_PREFIX");
}

/* Each bad value is refused with a message naming where it came from. */
static void config_bad_values_named(void)
{
    static const struct {
        const char *args[3];
        int argc;
        const char *expect;
    } cases[] = {
        {{"--workers", "0"}, 2, "option --workers '0': must be between 1 and 64"},
        {{"--workers", "many"}, 2, "option --workers 'many': expected a non-negative"},
        {{"--workers", "-3"}, 2, "option --workers '-3'"},
        {{"--max-store-bytes", "5T"}, 2, "option --max-store-bytes '5T'"},
        {{"--max-store-bytes", "99999999999999999G"}, 2, "option --max-store-bytes"},
        {{"--log-level", "loud"}, 2, "expected error, warn, info or debug"},
        {{"--archive-compression", "zip"},
         2,
         "option --archive-compression 'zip': expected none, lz4 or deflate"},
        {{"--prefix", "A B"}, 2, "option --prefix 'A B': only printable"},
        {{"--name", ""}, 2, "option --name '': must not be empty"},
        {{"--bogus", "1"}, 2, "option '--bogus': unknown"},
        {{"--workers"}, 1, "option '--workers': needs a value"},
        {{"extra"}, 1, "argument 'extra': meshtopod takes no positional arguments"},
        {{"--cluster", "map"}, 2, "option --cluster 'map': needs --archive DIR"},
        {{"--cluster=map", "--archive=/nonexistent/a", "--archive-mode=async"},
         3,
         "option --cluster 'map': needs --archive-mode sync"},
        {{"--cluster", "a b"}, 2, "option --cluster 'a b': only printable"},
        {{"--max-faces=1000", "--prepare-faces=1001"},
         2,
         "option --prepare-faces '1001': is more than --max-faces"},
        {{"--prepare-faces", "-1"}, 2, "option --prepare-faces '-1'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *argv[4] = {"meshtopod", cases[i].args[0], cases[i].args[1], cases[i].args[2]};
        mtd_config c;
        mtd_config_action action;
        mt_diag diag;
        CHECK_STATUS(parse(&c, &action, &diag, cases[i].argc + 1, argv), MT_ERR_INVALID_ARG);
        if (!strstr(diag.message, cases[i].expect))
            mt_test_fail(__FILE__, __LINE__, "case %zu: message '%s' lacks '%s'", i, diag.message,
                         cases[i].expect);
    }
    setenv("MESHTOPOD_HEARTBEAT_MS", "1", 1);
    const char *argv[] = {"meshtopod"};
    mtd_config c;
    mtd_config_action action;
    mt_diag diag;
    CHECK_STATUS(parse(&c, &action, &diag, 1, argv), MT_ERR_INVALID_ARG);
    CHECK(strstr(diag.message, "environment variable MESHTOPOD_HEARTBEAT_MS '1'") != NULL);
    unsetenv("MESHTOPOD_HEARTBEAT_MS");
}

static void config_help_and_version(void)
{
    const char *help[] = {"meshtopod", "--workers", "4", "--help"};
    const char *version[] = {"meshtopod", "--version"};
    mtd_config c;
    mtd_config_action action;
    mt_diag diag;
    CHECK_OK(parse(&c, &action, &diag, 4, help));
    CHECK_EQ(action, MTD_CONFIG_HELP);
    CHECK_OK(parse(&c, &action, &diag, 2, version));
    CHECK_EQ(action, MTD_CONFIG_VERSION);
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    mtd_config_usage(f);
    fclose(f);
    CHECK(strstr(text, "--max-store-bytes") && strstr(text, "MESHTOPOD_MAX_STORE_BYTES"));
    CHECK(strstr(text, "default \"MESHTOPO_\"") != NULL);
    free(text);
}

/* Reads what the log wrote to a temporary file. */
static size_t read_log(int fd, char *buf, size_t size)
{
    off_t end = lseek(fd, 0, SEEK_END);
    ssize_t n = pread(fd, buf, size - 1, 0);
    CHECK(end >= 0 && n >= 0);
    buf[n < 0 ? 0 : n] = '\0';
    return n < 0 ? 0 : (size_t)n;
}

static void log_one_line_per_event(void)
{
    char path[] = "/tmp/meshtopod-log-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd < 0) return;
    unlink(path);
    mtd_log_set_fd(fd);
    mtd_log_set_level(MTD_LOG_INFO);
    mtd_log(MTD_LOG_INFO, "submit", "mesh_id=%s version=%d", "room\nsecond", 3);
    mtd_log(MTD_LOG_DEBUG, "query", "dropped=%d", 1); /* above the level */
    char big[6000];
    memset(big, 'x', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    mtd_log(MTD_LOG_ERROR, "error", "detail=%s", big);
    static char text[16384];
    read_log(fd, text, sizeof text);
    mtd_log_set_fd(-1);
    close(fd);
    char *second = strchr(text, '\n');
    CHECK(second != NULL);
    if (!second) return;
    *second++ = '\0';
    CHECK(strstr(text, " info submit mesh_id=room second version=3") != NULL);
    CHECK(strstr(text, "meshtopod[") != NULL && text[4] == '-' && strchr(text, 'Z') != NULL);
    CHECK(strstr(second, "dropped") == NULL);
    CHECK(strstr(second, " error error detail=xxx") != NULL);
    size_t len = strlen(second);
    CHECK(len > 0 && len <= 4096 && second[len - 1] == '\n');
    CHECK(len >= 4 && memcmp(second + len - 4, "...\n", 4) == 0);
    CHECK(strchr(second, '\n') == second + len - 1);
}

static const mt_test_case cases[] = {
    {"config_defaults", config_defaults},
    {"config_flags_override_environment", config_flags_override_environment},
    {"config_bad_values_named", config_bad_values_named},
    {"config_help_and_version", config_help_and_version},
    {"log_one_line_per_event", log_one_line_per_event},
};
const mt_test_table mt_tests_config = {cases, sizeof cases / sizeof cases[0]};
