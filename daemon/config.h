/* meshtopod's settings: each one a command-line flag with an environment
 * default (flag > environment > built-in default), checked and reported by
 * name when wrong. The table in config.c is the one list: parsing, --help
 * and the unit file's documentation all follow it. Parsed once on the main
 * thread; every thread then reads the settings, nobody writes them. */
#ifndef MESHTOPOD_CONFIG_H
#define MESHTOPOD_CONFIG_H

#include <stdint.h>
#include <stdio.h>

#include "log.h"
#include "meshtopo/status.h"

#define MTD_CONFIG_TEXT_MAX 256

/* What --archive-mode asks for (with --archive DIR). */
typedef enum mtd_archive_mode {
    MTD_ARCHIVE_SYNC = 0,  /* archived before the submission is acknowledged */
    MTD_ARCHIVE_ASYNC = 1, /* acknowledged, then archived by a background writer */
    MTD_ARCHIVE_OFF = 2,   /* nothing written; what DIR holds is still served */
} mtd_archive_mode;

/* What --archive-compression asks for. */
typedef enum mtd_archive_compression {
    MTD_COMPRESSION_NONE = 0, /* contiguous: every HDF5 reader opens the files as they are */
    MTD_COMPRESSION_DEFLATE = 1,
    MTD_COMPRESSION_LZ4 = 2, /* Blosc LZ4: about half the size; readers need its plugin */
} mtd_archive_compression;

typedef struct mtd_config {
    char lcm_url[MTD_CONFIG_TEXT_MAX]; /* "" = LCM's own default (LCM_DEFAULT_URL) */
    char channel_prefix[64];           /* channels are PREFIX + SUBMIT, QUERY, ... */
    char name[64];                     /* instance name in the heartbeat */
    uint32_t workers;                  /* build threads */
    uint32_t max_verts;                /* largest mesh accepted */
    uint32_t max_faces;
    uint64_t max_indices;
    uint32_t prepare_faces;       /* a build of this many triangles at start, 0 = none */
    uint64_t max_store_bytes;     /* memory for built meshes, 0 = no limit */
    uint64_t max_archive_bytes;   /* archive files, 0 = no limit */
    uint32_t max_claim_ratio;     /* a mesh's memory over the bytes it carries, 0 = no limit */
    uint32_t max_versions;        /* versions kept per mesh id, 0 = all */
    uint32_t heartbeat_ms;        /* period of the status message */
    uint64_t max_transfer_bytes;  /* memory held by unfinished chunked submissions */
    uint32_t transfer_timeout_ms; /* a transfer without a chunk for this long is dropped */
    mtd_log_level log_level;
    char archive_dir[MTD_CONFIG_TEXT_MAX]; /* "" = no archive */
    mtd_archive_mode archive_mode;
    mtd_archive_compression archive_compression;
    uint32_t archive_queue;      /* versions the async writer may have waiting */
    uint32_t preload;            /* 1: load every archived version at start */
    uint64_t memory_budget;      /* evict archived meshes beyond this, 0 = no budget */
    char cluster[64];            /* cluster name, "" = none (one daemon per prefix) */
    char test_ignore_member[64]; /* testing: heartbeats of this member name are ignored */
} mtd_config;

/* What the command line asks for. */
typedef enum mtd_config_action {
    MTD_CONFIG_RUN = 0,
    MTD_CONFIG_HELP = 1,
    MTD_CONFIG_VERSION = 2,
} mtd_config_action;

/* Fills out with the defaults, then the MESHTOPOD_* environment variables,
 * then argv (argv[0] is the program name). Defaults that depend on the
 * machine are read from it: --max-store-bytes half its memory (or of the
 * cgroup's memory.max when lower), --max-transfer-bytes an eighth of that
 * (at most 1 GiB), --max-archive-bytes half the free space of the archive's
 * file system. On error returns
 * MT_ERR_INVALID_ARG with diag naming the flag or variable and the value;
 * --cluster without --archive, or with --archive-mode other than sync, is
 * such an error (a member's acknowledged meshes must survive it). */
mt_status mtd_config_parse(int argc, char **argv, mtd_config *out, mtd_config_action *out_action,
                           mt_diag *diag);

/* Writes the --help text: every flag, its variable, its default. */
void mtd_config_usage(FILE *to);

/* "sync", "async" or "off". */
const char *mtd_archive_mode_name(mtd_archive_mode mode);

/* "none", "deflate" or "lz4". */
const char *mtd_archive_compression_name(mtd_archive_compression compression);

/* Logs every setting at info level, one line (the "config" event). */
void mtd_config_log(const mtd_config *config);

#endif
