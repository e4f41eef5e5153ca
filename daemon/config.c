/* meshtopod's flags and MESHTOPOD_* variables, from one table. Parsing is
 * over that table: the same entry serves the flag (read by meshtopo::args,
 * as every meshtopo program reads its command line), its variable, range
 * checks and the help text.
 * Runs once, on the main thread, before any other thread starts. */
#include "config.h"

#include <errno.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include "meshtopo/args.h"

/* --max-archive-bytes until the archive directory is known. */
#define DERIVED_FROM_ARCHIVE UINT64_MAX

typedef enum setting_kind {
    KIND_TEXT,
    KIND_CHANNEL,
    KIND_U32,
    KIND_BYTES,
    KIND_LEVEL,
    KIND_ARCHIVE_MODE,
    KIND_ARCHIVE_COMPRESSION,
    KIND_SWITCH /* a flag without a value (--preload); its variable takes 1/0, yes/no */
} setting_kind;

typedef struct setting {
    const char *flag; /* without the leading "--" */
    const char *env;
    setting_kind kind;
    size_t offset; /* into mtd_config */
    size_t size;   /* of the text buffer (text kinds) */
    uint64_t min, max;
    const char *help;
} setting;

#define TEXT_FIELD(field) offsetof(mtd_config, field), sizeof(((mtd_config *)0)->field)
#define FIELD(field) offsetof(mtd_config, field), 0

static const setting settings[] = {
    {"lcm-url", "MESHTOPOD_LCM_URL", KIND_TEXT, TEXT_FIELD(lcm_url), 0, 0,
     "LCM provider URL (default: LCM's own, from LCM_DEFAULT_URL)"},
    {"prefix", "MESHTOPOD_PREFIX", KIND_CHANNEL, TEXT_FIELD(channel_prefix), 0, 0,
     "channel prefix: PREFIX + SUBMIT, QUERY, TOPOLOGY, STATUS"},
    {"name", "MESHTOPOD_NAME", KIND_CHANNEL, TEXT_FIELD(name), 1, 0,
     "instance name reported in the heartbeat"},
    {"workers", "MESHTOPOD_WORKERS", KIND_U32, FIELD(workers), 1, 64,
     "threads building meshes (queries are never queued behind builds)"},
    {"max-verts", "MESHTOPOD_MAX_VERTS", KIND_U32, FIELD(max_verts), 1, 0x7fffffff,
     "largest vertex count accepted"},
    {"max-faces", "MESHTOPOD_MAX_FACES", KIND_U32, FIELD(max_faces), 1, 0x7fffffff,
     "largest face count accepted"},
    {"max-indices", "MESHTOPOD_MAX_INDICES", KIND_BYTES, FIELD(max_indices), 1, 0x7fffffff,
     "largest face-index count accepted (suffixes k, M, G allowed)"},
    {"prepare-faces", "MESHTOPOD_PREPARE_FACES", KIND_U32, FIELD(prepare_faces), 0, 0x7fffffff,
     "at start, build a grid of about this many triangles into the kept build memory, so "
     "that the first mesh up to that size finds its memory ready, 0 = none"},
    {"max-store-bytes", "MESHTOPOD_MAX_STORE_BYTES", KIND_BYTES, FIELD(max_store_bytes), 0,
     UINT64_MAX - 1,
     "memory for built meshes, 0 = no limit (k, M, G; default: half the memory of the "
     "machine or its cgroup)"},
    {"max-archive-bytes", "MESHTOPOD_MAX_ARCHIVE_BYTES", KIND_BYTES, FIELD(max_archive_bytes), 0,
     UINT64_MAX - 1,
     "archive files, 0 = no limit (k, M, G; default: half the free space of the archive's "
     "file system at start)"},
    {"max-claim-ratio", "MESHTOPOD_MAX_CLAIM_RATIO", KIND_U32, FIELD(max_claim_ratio), 0,
     UINT32_MAX,
     "a mesh may claim at most this many times the bytes it carries in memory, 0 = no limit"},
    {"max-versions", "MESHTOPOD_MAX_VERSIONS", KIND_U32, FIELD(max_versions), 0, UINT32_MAX,
     "versions kept per mesh id, 0 = all"},
    {"heartbeat-ms", "MESHTOPOD_HEARTBEAT_MS", KIND_U32, FIELD(heartbeat_ms), 10, 3600000,
     "period of the status message"},
    {"max-transfer-bytes", "MESHTOPOD_MAX_TRANSFER_BYTES", KIND_BYTES, FIELD(max_transfer_bytes), 1,
     UINT64_MAX,
     "memory held by unfinished chunked submissions; more is refused (k, M, G; default: a "
     "quarter of --max-store-bytes' default, at most 1 GiB)"},
    {"transfer-timeout-ms", "MESHTOPOD_TRANSFER_TIMEOUT_MS", KIND_U32, FIELD(transfer_timeout_ms),
     10, 3600000, "a chunked submission without a chunk for this long is dropped"},
    {"log-level", "MESHTOPOD_LOG_LEVEL", KIND_LEVEL, FIELD(log_level), 0, 0,
     "error, warn, info or debug"},
    {"archive", "MESHTOPOD_ARCHIVE", KIND_TEXT, TEXT_FIELD(archive_dir), 0, 0,
     "directory archiving every built mesh (HDF5), served again after a restart"},
    {"archive-mode", "MESHTOPOD_ARCHIVE_MODE", KIND_ARCHIVE_MODE, FIELD(archive_mode), 0, 0,
     "sync (archived before the ack), async (after it) or off (write nothing)"},
    {"archive-compression", "MESHTOPOD_ARCHIVE_COMPRESSION", KIND_ARCHIVE_COMPRESSION,
     FIELD(archive_compression), 0, 0,
     "none, lz4 (about half the size; HDF5 and every reader of the files need the Blosc "
     "filter plugin) or deflate (slow)"},
    {"archive-queue", "MESHTOPOD_ARCHIVE_QUEUE", KIND_U32, FIELD(archive_queue), 1, 1u << 20,
     "meshes waiting for the async writer; builds wait for room beyond it"},
    {"preload", "MESHTOPOD_PRELOAD", KIND_SWITCH, FIELD(preload), 0, 1,
     "load every archived mesh at start (default: on its first query)"},
    {"memory-budget", "MESHTOPOD_MEMORY_BUDGET", KIND_BYTES, FIELD(memory_budget), 0, UINT64_MAX,
     "memory for meshes: least recently queried archived ones beyond it are dropped and "
     "reloaded on demand, 0 = none (k, M, G)"},
    {"cluster", "MESHTOPOD_CLUSTER", KIND_CHANNEL, TEXT_FIELD(cluster), 0, 0,
     "cluster name: daemons of one prefix with the same name and one shared --archive "
     "(sync) split the mesh ids between them (default: none, one daemon per prefix)"},
    {"test-ignore-member", "MESHTOPOD_TEST_IGNORE_MEMBER", KIND_CHANNEL,
     TEXT_FIELD(test_ignore_member), 0, 0,
     "testing only: ignore the heartbeats of the cluster member with this --name"},
};

#define NUM_SETTINGS (sizeof settings / sizeof settings[0])

/* The memory this process may use: the machine's, or its cgroup's
 * memory.max (cgroup v2) when that is lower. 0 when unknown. */
static uint64_t usable_memory(void)
{
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    uint64_t bytes = pages > 0 && page > 0 ? (uint64_t)pages * (uint64_t)page : 0;
    FILE *f = fopen("/sys/fs/cgroup/memory.max", "r");
    if (f) {
        unsigned long long limit = 0;
        if (fscanf(f, "%llu", &limit) == 1 && limit > 0 && (bytes == 0 || limit < bytes))
            bytes = limit;
        fclose(f);
    }
    return bytes;
}

/* Half the space unprivileged users may still fill on the file system of
 * dir, or of its nearest existing parent (the daemon creates dir). 0 when
 * unknown. */
static uint64_t half_free_space(const char *dir)
{
    char path[MTD_CONFIG_TEXT_MAX];
    snprintf(path, sizeof path, "%s", dir);
    struct statvfs fs;
    while (statvfs(path, &fs) != 0) {
        char *slash = strrchr(path, '/');
        if (!slash) {
            if (strcmp(path, ".") == 0) return 0;
            strcpy(path, ".");
            continue;
        }
        if (slash == path) {
            if (path[1] == '\0') return 0;
            path[1] = '\0';
        } else {
            *slash = '\0';
        }
    }
    return (uint64_t)fs.f_bavail * (uint64_t)fs.f_frsize / 2;
}

static void set_defaults(mtd_config *c)
{
    memset(c, 0, sizeof *c);
    strcpy(c->channel_prefix, "MESHTOPO_");
    strcpy(c->name, "meshtopod");
    c->workers = 2;
    c->max_verts = 16u << 20;
    c->max_faces = 32u << 20;
    c->max_indices = 128u << 20;
    c->max_versions = 8;
    c->heartbeat_ms = 1000;
    c->max_store_bytes = usable_memory() / 2;
    c->max_transfer_bytes = c->max_store_bytes / 4;
    if (c->max_transfer_bytes == 0 || c->max_transfer_bytes > 1ull << 30)
        c->max_transfer_bytes = 1ull << 30;
    c->max_archive_bytes = DERIVED_FROM_ARCHIVE;
    c->max_claim_ratio = 16;
    c->transfer_timeout_ms = 10000;
    c->log_level = MTD_LOG_INFO;
    c->archive_mode = MTD_ARCHIVE_SYNC;
    c->archive_queue = 256;
}

static const char *const archive_mode_names[] = {"sync", "async", "off"};

const char *mtd_archive_mode_name(mtd_archive_mode mode)
{
    return (unsigned)mode < 3 ? archive_mode_names[mode] : "?";
}

static const char *const compression_names[] = {"none", "deflate", "lz4"};

const char *mtd_archive_compression_name(mtd_archive_compression compression)
{
    return (unsigned)compression < 3 ? compression_names[compression] : "?";
}

/* Fills diag with "ORIGIN 'VALUE': problem" and returns MT_ERR_INVALID_ARG. */
static mt_status fail(mt_diag *diag, const char *origin, const char *value, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static mt_status fail(mt_diag *diag, const char *origin, const char *value, const char *fmt, ...)
{
    char problem[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(problem, sizeof problem, fmt, ap);
    va_end(ap);
    if (value)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "%s '%.200s': %s", origin, value, problem);
    return mt_diag_set(diag, MT_ERR_INVALID_ARG, "%s: %s", origin, problem);
}

/* Parses a decimal count with an optional binary suffix k, M or G. */
static int parse_count(const char *text, int allow_suffix, uint64_t *out)
{
    if (!text[0] || text[0] == '-' || text[0] == '+') return 0;
    errno = 0;
    char *end = NULL;
    unsigned long long v = strtoull(text, &end, 10);
    if (errno || end == text) return 0;
    unsigned shift = 0;
    if (allow_suffix && *end) {
        const char *suffixes = "kMG";
        const char *at = strchr(suffixes, *end);
        if (!at) return 0;
        shift = 10u * (unsigned)(at - suffixes + 1);
        end++;
    }
    if (*end) return 0;
    if (shift && v > (UINT64_MAX >> shift)) return 0;
    *out = (uint64_t)v << shift;
    return 1;
}

/* Channel-name text: printable ASCII without spaces (LCM channel names
 * travel in every packet and are matched as regexes by subscribers). */
static int channel_text_ok(const char *text)
{
    for (const char *p = text; *p; p++)
        if (*p <= ' ' || *p > '~') return 0;
    return 1;
}

static mt_status apply(const setting *s, const char *value, const char *origin, mtd_config *c,
                       mt_diag *diag)
{
    char *field = (char *)c + s->offset;
    uint64_t n = 0;
    switch (s->kind) {
        case KIND_TEXT:
        case KIND_CHANNEL:
            if (strlen(value) >= s->size)
                return fail(diag, origin, value, "longer than %zu bytes", s->size - 1);
            if (s->kind == KIND_CHANNEL && !channel_text_ok(value))
                return fail(diag, origin, value,
                            "only printable characters without spaces are allowed");
            if (s->min && !value[0]) return fail(diag, origin, value, "must not be empty");
            strcpy(field, value);
            return MT_OK;
        case KIND_LEVEL:
            if (mtd_log_level_parse(value, (mtd_log_level *)(void *)field) != MT_OK)
                return fail(diag, origin, value, "expected error, warn, info or debug");
            return MT_OK;
        case KIND_ARCHIVE_MODE:
            for (int m = 0; m < 3; m++)
                if (strcmp(value, archive_mode_names[m]) == 0) {
                    *(mtd_archive_mode *)(void *)field = (mtd_archive_mode)m;
                    return MT_OK;
                }
            return fail(diag, origin, value, "expected sync, async or off");
        case KIND_ARCHIVE_COMPRESSION:
            for (int m = 0; m < 3; m++)
                if (strcmp(value, compression_names[m]) == 0) {
                    *(mtd_archive_compression *)(void *)field = (mtd_archive_compression)m;
                    return MT_OK;
                }
            return fail(diag, origin, value, "expected none, lz4 or deflate");
        case KIND_SWITCH:
            if (strcmp(value, "1") == 0 || strcmp(value, "yes") == 0 || strcmp(value, "true") == 0)
                *(uint32_t *)(void *)field = 1;
            else if (strcmp(value, "0") == 0 || strcmp(value, "no") == 0 ||
                     strcmp(value, "false") == 0)
                *(uint32_t *)(void *)field = 0;
            else
                return fail(diag, origin, value, "expected 1, 0, yes, no, true or false");
            return MT_OK;
        case KIND_U32:
        case KIND_BYTES:
            if (!parse_count(value, s->kind == KIND_BYTES, &n))
                return fail(diag, origin, value, "expected a non-negative whole number%s",
                            s->kind == KIND_BYTES ? " (optionally with k, M or G)" : "");
            if (n < s->min || n > s->max)
                return fail(diag, origin, value, "must be between %llu and %llu",
                            (unsigned long long)s->min, (unsigned long long)s->max);
            if (s->kind == KIND_U32)
                *(uint32_t *)(void *)field = (uint32_t)n;
            else
                *(uint64_t *)(void *)field = n;
            return MT_OK;
    }
    return MT_ERR_INVALID_ARG;
}

/* The flags of the settings, and --version, for meshtopo::args. */
typedef struct flag_table {
    mt__option options[NUM_SETTINGS + 1];
} flag_table;

static void flag_table_make(flag_table *t)
{
    for (size_t i = 0; i < NUM_SETTINGS; i++) {
        const bool is_switch = settings[i].kind == KIND_SWITCH;
        t->options[i] =
            (mt__option){settings[i].flag, is_switch ? NULL : "VALUE", settings[i].help};
    }
    t->options[NUM_SETTINGS] = (mt__option){"version", NULL, "print the version"};
}

static mt_status fail_args(const mt__args *args, mt_diag *diag)
{
    switch (args->error) {
        case MT__ARGS_UNKNOWN_OPTION:
            return fail(diag, "option", args->at, "unknown (see --help)");
        case MT__ARGS_MISSING_VALUE:
            return fail(diag, "option", args->at, "needs a value");
        case MT__ARGS_UNEXPECTED_VALUE:
            return fail(diag, "option", args->at, "takes no value");
        case MT__ARGS_TOO_MANY_ARGUMENTS:
            return fail(diag, "argument", args->at, "meshtopod takes no positional arguments");
        case MT__ARGS_NO_MEMORY:
            return fail(diag, "arguments", "", "out of memory");
        default:
            return fail(diag, "arguments", args->at, "refused");
    }
}

mt_status mtd_config_parse(int argc, char **argv, mtd_config *out, mtd_config_action *out_action,
                           mt_diag *diag)
{
    mt_diag_clear(diag);
    set_defaults(out);
    *out_action = MTD_CONFIG_RUN;
    char origin[96];
    for (size_t i = 0; i < NUM_SETTINGS; i++) {
        const char *value = getenv(settings[i].env);
        if (!value) continue;
        snprintf(origin, sizeof origin, "environment variable %s", settings[i].env);
        mt_status s = apply(&settings[i], value, origin, out, diag);
        if (s != MT_OK) return s;
    }
    flag_table flags;
    flag_table_make(&flags);
    mt__args args;
    if (mt__args_parse(flags.options, NUM_SETTINGS + 1, 0, 0, argc > 0 ? argc - 1 : 0, argv + 1,
                       &args) != MT__ARGS_OK) {
        mt_status st = fail_args(&args, diag);
        mt__args_free(&args);
        return st;
    }
    if (args.help || args.values[NUM_SETTINGS]) {
        *out_action = args.help ? MTD_CONFIG_HELP : MTD_CONFIG_VERSION;
        mt__args_free(&args);
        return MT_OK;
    }
    for (size_t i = 0; i < NUM_SETTINGS; i++) {
        const char *value = args.values[i];
        if (!value) continue;
        if (settings[i].kind == KIND_SWITCH) value = "1"; /* given as a flag */
        snprintf(origin, sizeof origin, "option --%s", settings[i].flag);
        mt_status st = apply(&settings[i], value, origin, out, diag);
        if (st != MT_OK) {
            mt__args_free(&args);
            return st;
        }
    }
    mt__args_free(&args);
    if (out->cluster[0] && !out->archive_dir[0])
        return fail(diag, "option --cluster", out->cluster,
                    "needs --archive DIR, the directory all members share");
    if (out->cluster[0] && out->archive_mode != MTD_ARCHIVE_SYNC)
        return fail(diag, "option --cluster", out->cluster,
                    "needs --archive-mode sync: another member serves a mesh from the archive "
                    "once its builder is gone");
    if (out->prepare_faces > out->max_faces) {
        char text[24];
        snprintf(text, sizeof text, "%u", out->prepare_faces);
        return fail(diag, "option --prepare-faces", text,
                    "is more than --max-faces: no mesh that large is accepted");
    }
    if (out->max_archive_bytes == DERIVED_FROM_ARCHIVE)
        out->max_archive_bytes = out->archive_dir[0] ? half_free_space(out->archive_dir) : 0;
    return MT_OK;
}

void mtd_config_usage(FILE *to)
{
    fprintf(to,
            "usage: meshtopod [--OPTION VALUE]...\n"
            "The meshtopo daemon: builds the meshes submitted over LCM, answers topology\n"
            "queries and publishes reports and a heartbeat. Each option can also be set\n"
            "by its environment variable; the option wins. SIGINT or SIGTERM stop it.\n\n");
    mtd_config defaults;
    set_defaults(&defaults);
    for (size_t i = 0; i < NUM_SETTINGS; i++) {
        const setting *s = &settings[i];
        const char *field = (const char *)&defaults + s->offset;
        char shown[80];
        switch (s->kind) {
            case KIND_TEXT:
            case KIND_CHANNEL:
                snprintf(shown, sizeof shown, "\"%s\"", field);
                break;
            case KIND_LEVEL:
                snprintf(shown, sizeof shown, "%s",
                         mtd_log_level_name(*(const mtd_log_level *)(const void *)field));
                break;
            case KIND_ARCHIVE_MODE:
                snprintf(shown, sizeof shown, "%s",
                         mtd_archive_mode_name(*(const mtd_archive_mode *)(const void *)field));
                break;
            case KIND_ARCHIVE_COMPRESSION:
                snprintf(shown, sizeof shown, "%s",
                         mtd_archive_compression_name(
                             *(const mtd_archive_compression *)(const void *)field));
                break;
            case KIND_SWITCH:
                snprintf(shown, sizeof shown, "%s",
                         *(const uint32_t *)(const void *)field ? "on" : "off");
                break;
            case KIND_U32:
                snprintf(shown, sizeof shown, "%u", *(const uint32_t *)(const void *)field);
                break;
            case KIND_BYTES:
                if (*(const uint64_t *)(const void *)field == DERIVED_FROM_ARCHIVE)
                    snprintf(shown, sizeof shown, "from the archive's free space");
                else
                    snprintf(shown, sizeof shown, "%llu",
                             (unsigned long long)*(const uint64_t *)(const void *)field);
                break;
        }
        fprintf(to, "  --%-16s %s\n  %-18s env %s, default %s\n", s->flag, s->help, "", s->env,
                shown);
    }
    fprintf(to, "  --help             this text\n  --version          the version\n");
}

void mtd_config_log(const mtd_config *c)
{
    mtd_log(MTD_LOG_INFO, "config",
            "lcm_url=%s prefix=%s name=%s workers=%u max_verts=%u max_faces=%u "
            "max_indices=%llu prepare_faces=%u max_store_bytes=%llu max_archive_bytes=%llu "
            "max_claim_ratio=%u "
            "max_versions=%u heartbeat_ms=%u "
            "max_transfer_bytes=%llu "
            "transfer_timeout_ms=%u log_level=%s archive=%s archive_mode=%s "
            "archive_compression=%s archive_queue=%u preload=%u memory_budget=%llu cluster=%s",
            c->lcm_url[0] ? c->lcm_url : "(lcm default)", c->channel_prefix, c->name, c->workers,
            c->max_verts, c->max_faces, (unsigned long long)c->max_indices, c->prepare_faces,
            (unsigned long long)c->max_store_bytes, (unsigned long long)c->max_archive_bytes,
            c->max_claim_ratio, c->max_versions, c->heartbeat_ms,
            (unsigned long long)c->max_transfer_bytes, c->transfer_timeout_ms,
            mtd_log_level_name(c->log_level), c->archive_dir[0] ? c->archive_dir : "(none)",
            mtd_archive_mode_name(c->archive_mode),
            mtd_archive_compression_name(c->archive_compression), c->archive_queue, c->preload,
            (unsigned long long)c->memory_budget, c->cluster[0] ? c->cluster : "(none)");
}
