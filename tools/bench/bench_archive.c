/* `meshtopo-bench archive`: a triangle grid archived with
 * mt_archive_write_with (with the daemon's content hash) and reloaded with
 * mt_archive_load_mesh_file, checking it as the daemon does, each
 * timed (medians) next to bare HDF5 writes and reads of the same datasets in
 * the same layout (archive_bare.c) and next to a rebuild from the face list,
 * for contiguous storage, shuffle + deflate level 1 and Blosc LZ4 (when
 * HDF5 finds its filter plugin). Options: --faces N, --reps N, --dir DIR,
 * --keep, --quick, --scan. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench.h"
#include "bench_archive.h"
#include "meshtopo/archive.h"
#include "meshtopo/core.h"

/* fsync is timed separately; archive and bare writes alternate which goes
 * first and the four read steps take turns at going first (use a multiple of
 * 4 reps). --scan permutes vertex and face order and jitters the positions,
 * like a scanned mesh (a generated grid's arrays compress unrealistically
 * well). Page cache is not dropped: reads are from memory. */

enum {
    M_WRITE,
    M_TOPOLOGY,
    M_BARE_WRITE,
    M_FSYNC,
    M_BARE_FSYNC,
    M_RELOAD,
    M_BARE_READ,
    M_FACES_BUILD,
    M_FACES_REBUILD_CHECK,
    M_COUNT
};

#define MAX_REPS 101

/* The layouts measured, in the table's order. */
enum { NUM_LAYOUTS = 3 };
static const mt_archive_compression layouts[NUM_LAYOUTS] = {
    MT_ARCHIVE_COMPRESSION_NONE, MT_ARCHIVE_COMPRESSION_DEFLATE, MT_ARCHIVE_COMPRESSION_LZ4};
static const char *const layout_names[NUM_LAYOUTS] = {"contiguous", "shuffle+deflate 1",
                                                      "blosc lz4"};
static const char *const layout_ids[NUM_LAYOUTS] = {"grid-contiguous", "grid-deflate", "grid-lz4"};

typedef struct layout_result {
    bool measured;
    double ms[M_COUNT][MAX_REPS];
    double median[M_COUNT];
    uint64_t file_bytes, bare_file_bytes;
} layout_result;

typedef struct options {
    uint32_t faces, reps;
    const char *dir;
    bool keep, scan;
} options;

static void usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo-bench archive [--faces N] [--reps N (>= 5)] [--dir DIR] "
            "[--keep] [--quick] [--scan]\n");
}

/* Returns 0, 1 (--help) or 2 (usage error, printed). */
static int parse_options(int argc, char **argv, options *o)
{
    /* The options usage() names. */
    static const mt__option option_table[] = {
        {"quick", NULL, NULL}, {"scan", NULL, NULL}, {"keep", NULL, NULL},
        {"faces", "N", NULL},  {"reps", "N", NULL},  {"dir", "DIR", NULL},
    };
    static const char program[] = "meshtopo-bench archive";
    *o = (options){1000000, 5, NULL, false, false};
    mt__args args;
    int read =
        mt__bench_args_read(program, option_table, sizeof option_table / sizeof option_table[0],
                            argc - 1, argv + 1, &args);
    if (read != 0) return read;
    if (mt__args_flag(&args, "quick")) o->faces = 20000;
    bool ok = mt__bench_arg_u32(&args, program, "faces", 2, UINT32_MAX, &o->faces, NULL) &&
              mt__bench_arg_u32(&args, program, "reps", 5, MAX_REPS, &o->reps, NULL);
    o->scan = mt__args_flag(&args, "scan");
    o->keep = mt__args_flag(&args, "keep");
    o->dir = mt__args_value(&args, "dir");
    mt__args_free(&args);
    return ok ? 0 : 2;
}

static uint64_t file_size(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (uint64_t)sb.st_size : 0;
}

/* Whether two meshes hold identical arrays (the reload is the build). */
static bool same_arrays(const mt_mesh *a, const mt_mesh *b)
{
    mt_mesh_parts x, y;
    mt_mesh_get_parts(a, &x);
    mt_mesh_get_parts(b, &y);
    if (x.num_half_edges != y.num_half_edges || x.num_faces != y.num_faces ||
        x.num_verts_internal != y.num_verts_internal)
        return false;
    size_t he = (size_t)x.num_half_edges * sizeof(uint32_t);
    return memcmp(x.he_head, y.he_head, he) == 0 && memcmp(x.he_next, y.he_next, he) == 0 &&
           memcmp(x.he_face, y.he_face, he) == 0 &&
           memcmp(x.face_he, y.face_he, (size_t)x.num_faces * sizeof(uint32_t)) == 0 &&
           memcmp(x.vert_he, y.vert_he, (size_t)x.num_verts_internal * sizeof(uint32_t)) == 0;
}

/* One read step of round r: 0 reload (restore), 1 bare read, 2 face list
 * read + build, 3 face list read + build + validate + report check. */
static bool read_step(const mt_archive *archive, const char *name, const mt_mesh *mesh,
                      const mt__bare_set *set, const char *bare_path, int step, uint32_t r,
                      layout_result *res)
{
    mt_diag diag;
    char err[512];
    double t0 = mt__bench_now_ms();
    if (step == 0) {
        mt_mesh *loaded = NULL;
        mt_archive_load_info info;
        mt_status st = mt_archive_load_mesh_file(archive, name, false, NULL, &loaded, &info, &diag);
        res->ms[M_RELOAD][r] = mt__bench_now_ms() - t0;
        bool ok = st == MT_OK && info.restored && same_arrays(loaded, mesh);
        if (!ok)
            fprintf(stderr, "meshtopo-bench archive: reload of %s: %s\n", name,
                    st != MT_OK      ? diag.message
                    : !info.restored ? info.fallback.message
                                     : "the reloaded arrays differ from the build's");
        mt_mesh_destroy(loaded);
        return ok;
    }
    if (step == 1) {
        bool ok = mt__bare_read(set, bare_path, &res->ms[M_BARE_READ][r], err, sizeof err);
        if (!ok) fprintf(stderr, "meshtopo-bench archive: bare read: %s\n", err);
        return ok;
    }
    mt_archive_record rec;
    mt_mesh *built = NULL;
    mt_status st = mt_archive_load_file(archive, name, &rec, &diag);
    if (st == MT_OK && step == 2) st = mt_mesh_build(&rec.faces, NULL, &built, &diag);
    if (st == MT_OK && step == 3) st = mt_archive_record_build(&rec, &built, &diag);
    res->ms[step == 2 ? M_FACES_BUILD : M_FACES_REBUILD_CHECK][r] = mt__bench_now_ms() - t0;
    mt_mesh_destroy(built);
    mt_archive_record_free(&rec);
    if (st != MT_OK)
        fprintf(stderr, "meshtopo-bench archive: face list + build: %s\n", diag.message);
    return st == MT_OK;
}

/* Round r of one layout: archive write, bare write, reload, bare read,
 * face list read + build. false (message printed) on any failure. */
static bool run_round(const options *o, mt_archive *archive, const mt_face_list *list,
                      const mt_mesh *mesh, const mt__bare_set *set, int layout, uint32_t r,
                      layout_result *res)
{
    const char *id = layout_ids[layout];
    const mt_archive_compression compression = layouts[layout];
    mt_archive_write_options wo = {.compression = compression, .deflate_level = 1};
    mt_archive_meta meta = {id, 0, 1700000000000000, "meshtopo-bench", 0};
    char err[512], bare_path[4096 + 64];
    mt_diag diag;
    /* The hash the daemon acknowledges with: reloads check it, as the daemon's do. */
    if (mt_archive_content_hash(NULL, list, &meta.content_hash, &diag) != MT_OK) {
        fprintf(stderr, "meshtopo-bench archive: content hash: %s\n", diag.message);
        return false;
    }
    meta.version = r + 1;
    snprintf(bare_path, sizeof bare_path, "%s/bare-%s-%u.h5", o->dir, id, r);
    if (r % 2 == 1 && !mt__bare_write(set, bare_path, compression, &res->ms[M_BARE_WRITE][r],
                                      &res->ms[M_BARE_FSYNC][r], err, sizeof err)) {
        fprintf(stderr, "meshtopo-bench archive: bare write: %s\n", err);
        return false;
    }
    mt_archive_write_stats stats;
    double t0 = mt__bench_now_ms();
    if (mt_archive_write_with(archive, &meta, list, mesh, &wo, &stats, &diag) != MT_OK) {
        fprintf(stderr, "meshtopo-bench archive: write: %s\n", diag.message);
        return false;
    }
    double total = mt__bench_now_ms() - t0;
    res->ms[M_WRITE][r] = total - stats.fsync_ms;
    res->ms[M_FSYNC][r] = stats.fsync_ms;
    res->ms[M_TOPOLOGY][r] = stats.topology_ms;
    res->file_bytes = stats.file_bytes;

    if (r % 2 == 0 && !mt__bare_write(set, bare_path, compression, &res->ms[M_BARE_WRITE][r],
                                      &res->ms[M_BARE_FSYNC][r], err, sizeof err)) {
        fprintf(stderr, "meshtopo-bench archive: bare write: %s\n", err);
        return false;
    }
    res->bare_file_bytes = file_size(bare_path);

    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(id, meta.version, name, sizeof name);
    /* The first read after a write pays for memory the write left
     * behind (pages zeroed anew): the read steps take turns at going
     * first. */
    for (int k = 0; k < 4; k++) {
        int step = (k + (int)r) % 4;
        if (!read_step(archive, name, mesh, set, bare_path, step, r, res)) return false;
    }
    if (!o->keep) unlink(bare_path);
    return true;
}

/* Removes what the benchmark wrote in its own scratch directory. */
static void remove_scratch(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    char path[4096 + 512];
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        unlink(path);
    }
    closedir(d);
    rmdir(dir);
}

static double mb_per_s(uint64_t bytes, double ms)
{
    return ms > 0 ? (double)bytes / 1e6 / (ms / 1e3) : 0;
}

static void print_row(const char *label, const layout_result *res, int metric, uint64_t bytes)
{
    printf("| %-52s |", label);
    for (int l = 0; l < NUM_LAYOUTS; l++) {
        double ms = res[l].median[metric];
        if (!res[l].measured)
            printf(" %9s | %8s |", "-", "");
        else if (bytes)
            printf(" %9.1f | %8.0f |", ms, mb_per_s(bytes, ms));
        else
            printf(" %9.1f | %8s |", ms, "");
    }
    printf("\n");
}

static void print_table(const options *o, const mt_face_list *list, const mt__bare_set *set,
                        const layout_result *res)
{
    const uint64_t write_bytes = mt__bare_set_write_bytes(set);
    const uint64_t reload_bytes = mt__bare_set_reload_bytes(set);
    const uint64_t face_bytes =
        (uint64_t)list->num_faces * 4 + list->num_indices * 4 + (uint64_t)list->num_verts * 24;
    printf(
        "\nmeshtopo-bench archive: %sgrid of %u triangles (%u vertices), medians of %u "
        "repetitions, in %s\n",
        o->scan ? "scan-like (permuted, jittered) " : "", list->num_faces, list->num_verts, o->reps,
        o->dir);
    printf(
        "payload: %.1f MB written per file, %.1f MB read by a reload (half-edge arrays + "
        "positions), %.1f MB of face list; MB/s = payload / time; reads hit the page "
        "cache\n\n",
        (double)write_bytes / 1e6, (double)reload_bytes / 1e6, (double)face_bytes / 1e6);
    printf("| %-52s | %9s | %8s | %9s | %8s | %9s | %8s |\n", "step", "contig ms", "MB/s",
           "deflate ms", "MB/s", "lz4 ms", "MB/s");
    printf("|%s|%s|%s|%s|%s|%s|%s|\n", "------------------------------------------------------",
           "----------:", "---------:", "----------:", "---------:", "----------:", "---------:");
    print_row("archive write (mt_archive_write_with, no fsync)", res, M_WRITE, write_bytes);
    print_row("  of which topology arrays worked out (VTK data)", res, M_TOPOLOGY, 0);
    print_row("bare write (H5Dwrite, same datasets and layout)", res, M_BARE_WRITE, write_bytes);
    print_row("fsync: archive (file, link, directory)", res, M_FSYNC, 0);
    print_row("fsync: bare (file)", res, M_BARE_FSYNC, 0);
    print_row("reload: file -> queryable mesh (restore)", res, M_RELOAD, reload_bytes);
    print_row("bare read (H5Dread of the reload's datasets)", res, M_BARE_READ, reload_bytes);
    print_row("face list read + mt_mesh_build", res, M_FACES_BUILD, face_bytes);
    print_row("face list read + build + validate + report check", res, M_FACES_REBUILD_CHECK,
              face_bytes);
    printf("| %-52s |", "file size, MB (archive)");
    for (int l = 0; l < NUM_LAYOUTS; l++) printf(" %20.1f |", res[l].file_bytes / 1e6);
    printf("\n| %-52s |", "bytes per face (archive)");
    for (int l = 0; l < NUM_LAYOUTS; l++)
        printf(" %20.1f |", (double)res[l].file_bytes / list->num_faces);
    printf("\n| %-52s |", "file size, MB (bare)");
    for (int l = 0; l < NUM_LAYOUTS; l++) printf(" %20.1f |", res[l].bare_file_bytes / 1e6);
    printf("\n\ntargets:\n");
    for (int l = 0; l < NUM_LAYOUTS; l++) {
        if (!res[l].measured) {
            printf("  %-18s not measured: HDF5 finds no Blosc filter plugin\n", layout_names[l]);
            continue;
        }
        double ratio = res[l].median[M_WRITE] / res[l].median[M_BARE_WRITE];
        printf("  %-18s archive write / bare write = %.2fx (target <= 1.5x): %s\n", layout_names[l],
               ratio, ratio <= 1.5 ? "met" : "MISS");
        double speed = res[l].median[M_FACES_BUILD] / res[l].median[M_RELOAD];
        printf(
            "  %-18s reload %.1f ms vs face list + build %.1f ms = %.2fx faster "
            "(target > 1x): %s\n",
            layout_names[l], res[l].median[M_RELOAD], res[l].median[M_FACES_BUILD], speed,
            speed > 1 ? "met" : "MISS");
        if (l == 0) continue;
        printf(
            "  %-18s file %.2fx smaller than contiguous, write %.2fx and reload %.2fx the "
            "contiguous time\n",
            layout_names[l],
            (double)res[0].file_bytes / (double)(res[l].file_bytes ? res[l].file_bytes : 1),
            res[l].median[M_WRITE] / res[0].median[M_WRITE],
            res[l].median[M_RELOAD] / res[0].median[M_RELOAD]);
    }
    if (res[2].measured) {
        const double per_face = (double)res[2].file_bytes / list->num_faces;
        const double vs_bare = res[2].median[M_WRITE] / res[0].median[M_BARE_WRITE];
        printf(
            "  blosc lz4          %.1f bytes per face (target <= ~50), write %.2fx the bare "
            "contiguous write (target <= 1.5x): %s\n",
            per_face, vs_bare, per_face <= 55 && vs_bare <= 1.5 ? "met" : "MISS");
    }
}

int mt__bench_archive_command(int argc, char **argv)
{
    options o;
    int parsed = parse_options(argc, argv, &o);
    if (parsed != 0) return mt__bench_usage_exit(parsed, usage);
    char scratch[4096];
    if (!o.dir) {
        /* /var/tmp rather than /tmp: /tmp is often tmpfs, where fsync costs nothing. */
        const char *base = getenv("TMPDIR") ? getenv("TMPDIR") : "/var/tmp";
        snprintf(scratch, sizeof scratch, "%s/meshtopo-bench-archive-XXXXXX", base);
        if (!mkdtemp(scratch)) {
            fprintf(stderr, "meshtopo-bench archive: cannot make %s: %s\n", scratch,
                    strerror(errno));
            return 1;
        }
    } else {
        snprintf(scratch, sizeof scratch, "%s/meshtopo-bench-archive-XXXXXX", o.dir);
        if (!mkdtemp(scratch)) {
            fprintf(stderr, "meshtopo-bench archive: cannot make %s: %s\n", scratch,
                    strerror(errno));
            return 1;
        }
    }
    o.dir = scratch;

    uint32_t side = (uint32_t)floor(sqrt((double)o.faces / 2));
    if (side < 1) side = 1;
    mt_face_list list;
    mt_mesh *mesh = NULL;
    mt_diag diag;
    mt_status st = mt_gen_grid(side, side, true, &list);
    if (st == MT_OK && o.scan) {
        st = mt_face_list_permute(&list, 12345, &diag);
        uint64_t x = 88172645463325252ull;
        for (uint64_t i = 0; st == MT_OK && i < 3 * (uint64_t)list.num_verts; i++) {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            list.positions[i] += ((double)(x >> 11) / 9007199254740992.0 - 0.5) * 1e-3;
        }
    }
    if (st == MT_OK) st = mt_mesh_build(&list, NULL, &mesh, &diag);
    if (st == MT_OK) st = mt_mesh_validate(mesh, &diag);
    mt__bare_set *set = st == MT_OK ? mt__bare_set_make(&list, mesh) : NULL;
    mt_archive *archive = NULL;
    mt_archive_options ao = {false, false};
    if (set) st = mt_archive_open(o.dir, &ao, &archive, &diag);
    if (archive) mt_archive_set_content_hash(archive, mt_archive_content_hash, NULL);
    layout_result *res = calloc(NUM_LAYOUTS, sizeof *res);
    bool ok = st == MT_OK && set && archive && res;
    if (!ok) fprintf(stderr, "meshtopo-bench archive: setup failed: %s\n", diag.message);
    /* Rounds of every layout in turn, so that a change in the machine's
     * load falls on all of them. */
    for (int l = 0; ok && l < NUM_LAYOUTS; l++)
        res[l].measured = layouts[l] != MT_ARCHIVE_COMPRESSION_LZ4 || mt_archive_lz4_available();
    if (ok) fprintf(stderr, "meshtopo-bench archive: %u rounds of each layout...\n", o.reps);
    for (uint32_t r = 0; ok && r < o.reps; r++)
        for (int l = 0; ok && l < NUM_LAYOUTS; l++)
            if (res[l].measured) ok = run_round(&o, archive, &list, mesh, set, l, r, &res[l]);
    for (int l = 0; ok && l < NUM_LAYOUTS; l++)
        for (int m = 0; m < M_COUNT; m++)
            res[l].median[m] = mt__bench_median_of(res[l].ms[m], o.reps);
    if (ok) print_table(&o, &list, set, res);
    free(res);
    mt_archive_close(archive);
    mt__bare_set_free(set);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    if (!o.keep) remove_scratch(o.dir);
    return ok ? 0 : 1;
}
