/* meshtopo::archive against a hostile or failing directory: symbolic links
 * planted at guessable temporary names, at the next version's name and in
 * place of a version file (nothing outside the directory is ever written,
 * every refusal names the file), files of another owner, FIFOs and
 * directories with archive names; files damaged after archiving (face list,
 * half-edge arrays, report, digest), where loading and verification must
 * report the same fault; permission denied, a full disk and a file size
 * limit, whose errno text must reach the message; no /proc; setting a file
 * aside. Tests that need privileges (a mount namespace, another uid) run in
 * a child process and say why when they are skipped. */
#define _GNU_SOURCE /* unshare, CLONE_NEWNS */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <sched.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "archive_legacy.h"
#include "archive_test_util.h"
#include "harness.h"
#include "meshtopo/core.h"
#include "restore_check.h"

/* Exit status of a child that skipped its test (it prints why). */
#define SKIPPED 77

/* The user a privileged test drops to. */
#define NOBODY 65534

/* A scratch archive plus a file outside it that nothing may touch. */
typedef struct scene {
    char dir[512], outside[512];
    char precious[600], reference[600];
    mt_archive *archive;
} scene;

static bool scene_open(scene *s)
{
    memset(s, 0, sizeof *s);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    if (!at_tmpdir(s->dir, sizeof s->dir) || !at_tmpdir(s->outside, sizeof s->outside))
        return false;
    snprintf(s->precious, sizeof s->precious, "%s/precious", s->outside);
    snprintf(s->reference, sizeof s->reference, "%s/reference", s->outside);
    const char text[] = "bytes outside the archive that no write may reach\n";
    CHECK(at_write_bytes(s->precious, text, sizeof text - 1));
    CHECK(at_write_bytes(s->reference, text, sizeof text - 1));
    CHECK_OK(mt_archive_open(s->dir, NULL, &s->archive, NULL));
    if (s->archive) mt_archive_set_content_hash(s->archive, at_hash, NULL);
    return s->archive != NULL;
}

/* The file outside is byte for byte what it was. */
static void scene_check_outside(const scene *s)
{
    CHECK(at_same_bytes(s->precious, s->reference));
}

static void scene_close(scene *s)
{
    scene_check_outside(s);
    mt_archive_close(s->archive);
    at_rmdir(s->dir);
    at_rmdir(s->outside);
}

static void path_of(const scene *s, const char *id, uint32_t version, char *path, size_t size)
{
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(id, version, name, sizeof name);
    snprintf(path, size, "%s/%s", s->dir, name);
}

/* Archives a 10 x 6 torus as id/version with the test hash; *out_built
 * (may be NULL) keeps the built mesh. */
static mt_status write_torus(mt_archive *archive, const char *id, uint32_t version,
                             mt_mesh **out_built)
{
    mt_face_list list;
    CHECK_OK(mt_gen_torus(10, 6, &list));
    uint64_t hash = 0;
    at_hash(NULL, &list, &hash, NULL);
    mt_status st = at_archive_list(archive, id, version, &list, hash, out_built);
    mt_face_list_free(&list);
    return st;
}

/* Entries of the directory whose name starts with prefix. */
static int count_named(const char *dir, const char *prefix)
{
    int n = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL)
        if (strncmp(e->d_name, prefix, strlen(prefix)) == 0) n++;
    if (d) closedir(d);
    return n;
}

/* Runs body in a child process; the test fails when the child reports a
 * failure, and is skipped (the child says why) when it exits SKIPPED. */
static void in_child(void (*body)(void *), void *ctx)
{
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    CHECK(pid >= 0);
    if (pid == 0) {
        int before = mt_test_failures();
        body(ctx);
        fflush(stdout);
        fflush(stderr);
        _exit(mt_test_failures() > before ? 1 : 0);
    }
    int status = 0;
    CHECK(waitpid(pid, &status, 0) == pid);
    CHECK(WIFEXITED(status));
    if (WIFEXITED(status) && WEXITSTATUS(status) == SKIPPED) return;
    CHECK_EQ(WEXITSTATUS(status), 0);
}

/* load, load_mesh, verify and the listing all refuse `name`: MT_ERR_IO,
 * fault UNSAFE, a message naming the file and `why`. */
static void expect_refused(const scene *s, const char *name, const char *why)
{
    mt_diag diag;
    mt_archive_record rec;
    mt_status st = mt_archive_load_file(s->archive, name, &rec, &diag);
    CHECK_STATUS(st, MT_ERR_IO);
    CHECK(strstr(diag.message, name) != NULL);
    CHECK(strstr(diag.message, why) != NULL);
    if (getenv("MT_TEST_VERBOSE") || !strstr(diag.message, why))
        printf("load: %s (expected \"%s\")\n", diag.message, why);
    if (st == MT_OK) mt_archive_record_free(&rec);
    mt_mesh *mesh = NULL;
    mt_archive_load_info info;
    CHECK_STATUS(mt_archive_load_mesh_file(s->archive, name, false, NULL, &mesh, &info, &diag),
                 MT_ERR_IO);
    CHECK(mesh == NULL);
    CHECK_EQ(info.fault, MT_ARCHIVE_FAULT_UNSAFE);
    CHECK(strstr(diag.message, why) != NULL);
    mt_archive_fault fault = MT_ARCHIVE_FAULT_NONE;
    CHECK_STATUS(mt_archive_verify_file_with(s->archive, name, NULL, NULL, &fault, &diag),
                 MT_ERR_IO);
    CHECK_EQ(fault, MT_ARCHIVE_FAULT_UNSAFE);
    mt_archive_listing l;
    CHECK_OK(mt_archive_list(s->archive, &l, NULL));
    bool listed = false;
    for (size_t i = 0; i < l.count; i++)
        if (strcmp(l.entries[i].file_name, name) == 0) {
            listed = true;
            CHECK_STATUS(l.entries[i].status, MT_ERR_IO);
            CHECK_EQ(l.entries[i].fault, MT_ARCHIVE_FAULT_UNSAFE);
            CHECK(strstr(l.entries[i].diag.message, why) != NULL);
        }
    CHECK(listed);
    mt_archive_listing_free(&l);
}

/* Symbolic links planted at every temporary name an attacker could guess
 * (the former "<pid>-<counter>" names and all-zero random parts), pointing
 * outside: writes still succeed, nothing is written through them, and the
 * leftover cleanup neither follows nor removes them. */
static void test_symlink_at_tmp_names(void)
{
    scene s;
    if (!scene_open(&s)) return;
    char link_path[1024];
    for (int i = 0; i < 64; i++) {
        snprintf(link_path, sizeof link_path, "%s/.mt-tmp-%ld-%d.part", s.dir, (long)getpid(), i);
        CHECK(symlink(s.precious, link_path) == 0);
    }
    snprintf(link_path, sizeof link_path, "%s/.mt-tmp-%ld-0000000000000000.part", s.dir,
             (long)getpid());
    CHECK(symlink(s.precious, link_path) == 0);
    /* A dead writer's name, for the cleanup at open. */
    snprintf(link_path, sizeof link_path, "%s/.mt-tmp-2147483000-7.part", s.dir);
    CHECK(symlink(s.precious, link_path) == 0);
    for (uint32_t v = 1; v <= 8; v++) CHECK_OK(write_torus(s.archive, "t", v, NULL));
    scene_check_outside(&s);
    mt_archive *again = NULL;
    CHECK_OK(mt_archive_open(s.dir, NULL, &again, NULL));
    CHECK_EQ(mt_archive_leftovers_removed(again), 0);
    mt_archive_close(again);
    CHECK_EQ(count_named(s.dir, ".mt-tmp-"), 66); /* every planted link, nothing of ours */
    struct stat sb;
    CHECK(lstat(link_path, &sb) == 0 && S_ISLNK(sb.st_mode));
    for (uint32_t v = 1; v <= 8; v++) {
        char name[64];
        snprintf(name, sizeof name, "t.v%u.hdf", v);
        CHECK_OK(mt_archive_verify_file(s.archive, name, at_hash, NULL, NULL));
    }
    scene_close(&s);
}

/* Something already at the next version's name: a symbolic link (to a file
 * outside, dangling, to a directory) or a directory. The write fails
 * cleanly naming it, writes nothing through it and leaves no temporary
 * file; the next version number works. */
static void test_symlink_at_final_name(void)
{
    scene s;
    if (!scene_open(&s)) return;
    CHECK_OK(write_torus(s.archive, "m", 1, NULL));
    char v2[1024], dangling[1024];
    path_of(&s, "m", 2, v2, sizeof v2);
    snprintf(dangling, sizeof dangling, "%s/created-through-a-link", s.outside);
    const char *targets[3] = {s.precious, dangling, s.outside};
    for (int k = 0; k < 4; k++) {
        if (k < 3)
            CHECK(symlink(targets[k], v2) == 0);
        else
            CHECK(mkdir(v2, 0700) == 0);
        mt_diag diag;
        CHECK_STATUS(write_torus(s.archive, "m", 2, NULL), MT_ERR_INVALID_ARG);
        mt_face_list list;
        CHECK_OK(mt_gen_torus(10, 6, &list));
        mt_mesh *mesh = NULL;
        CHECK_OK(mt_mesh_build(&list, NULL, &mesh, NULL));
        mt_archive_meta meta = {"m", 2, 1, "node", 0};
        CHECK_STATUS(mt_archive_write(s.archive, &meta, &list, mesh, NULL, &diag),
                     MT_ERR_INVALID_ARG);
        CHECK(strstr(diag.message, "m.v2.hdf") != NULL);
        CHECK(strstr(diag.message, k < 3 ? "a symbolic link" : "a directory") != NULL);
        CHECK(strstr(diag.message, "nothing was written through it") != NULL);
        if (getenv("MT_TEST_VERBOSE")) printf("final name taken: %s\n", diag.message);
        mt_mesh_destroy(mesh);
        mt_face_list_free(&list);
        CHECK(access(dangling, F_OK) != 0);
        CHECK_EQ(count_named(s.dir, ".mt-tmp-"), 0);
        scene_check_outside(&s);
        if (k < 3)
            CHECK(unlink(v2) == 0);
        else
            CHECK(rmdir(v2) == 0);
    }
    CHECK(symlink(s.precious, v2) == 0);
    CHECK_OK(write_torus(s.archive, "m", 3, NULL));
    CHECK(unlink(v2) == 0);
    scene_close(&s);
}

/* A version file replaced by a symbolic link (to a good archive file
 * outside), and a FIFO and a directory with archive names: every read
 * refuses them without following, opening or blocking, naming them; the
 * other files still load; a link can be set aside (the link itself). */
static void test_non_regular_version_files(void)
{
    scene s;
    if (!scene_open(&s)) return;
    CHECK_OK(write_torus(s.archive, "good", 1, NULL));
    CHECK_OK(write_torus(s.archive, "linked", 1, NULL));
    char path[1024], moved[1024], fifo[1024], sub[1024];
    path_of(&s, "linked", 1, path, sizeof path);
    snprintf(moved, sizeof moved, "%s/linked.v1.hdf", s.outside);
    CHECK(rename(path, moved) == 0);
    CHECK(symlink(moved, path) == 0);
    expect_refused(&s, "linked.v1.hdf", "a symbolic link");
    path_of(&s, "fifo", 1, fifo, sizeof fifo);
    CHECK(mkfifo(fifo, 0600) == 0);
    expect_refused(&s, "fifo.v1.hdf", "a FIFO");
    path_of(&s, "sub", 1, sub, sizeof sub);
    CHECK(mkdir(sub, 0700) == 0);
    expect_refused(&s, "sub.v1.hdf", "a directory");
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_archive_load_mesh(s.archive, "good", 1, false, NULL, &mesh, NULL, NULL));
    mt_mesh_destroy(mesh);
    /* The highest version by name is the link: refused, not followed. */
    CHECK_STATUS(mt_archive_load_mesh(s.archive, "linked", 0, false, NULL, &mesh, NULL, NULL),
                 MT_ERR_IO);
    char aside[300];
    CHECK_OK(mt_archive_set_aside(s.archive, "linked.v1.hdf", aside, sizeof aside, NULL));
    CHECK(strncmp(aside, ".mt-aside-linked.v1.hdf.", 24) == 0);
    char aside_path[1000];
    snprintf(aside_path, sizeof aside_path, "%s/%s", s.dir, aside);
    struct stat sb;
    CHECK(lstat(aside_path, &sb) == 0 && S_ISLNK(sb.st_mode));
    CHECK(lstat(moved, &sb) == 0 && S_ISREG(sb.st_mode)); /* the target is untouched */
    CHECK(!mt_archive_contains(s.archive, "linked", 1));
    unlink(aside_path);
    unlink(fifo);
    rmdir(sub);
    scene_close(&s);
}

/* A file owned by another user is refused (when root can make one). */
static void test_foreign_owner(void)
{
    if (geteuid() != 0) {
        printf("skipped: not root, cannot make a file owned by another user\n");
        return;
    }
    scene s;
    if (!scene_open(&s)) return;
    CHECK_OK(write_torus(s.archive, "theirs", 1, NULL));
    char path[1024];
    path_of(&s, "theirs", 1, path, sizeof path);
    CHECK(chown(path, NOBODY, NOBODY) == 0);
    expect_refused(&s, "theirs.v1.hdf", "owned by uid 65534");
    /* Leftover-like files of another user are not removed either. */
    char other[1024];
    snprintf(other, sizeof other, "%s/.mt-tmp-2147483000-1.part", s.dir);
    CHECK(at_write_bytes(other, "x", 1));
    CHECK(chown(other, NOBODY, NOBODY) == 0);
    mt_archive *again = NULL;
    CHECK_OK(mt_archive_open(s.dir, NULL, &again, NULL));
    CHECK_EQ(mt_archive_leftovers_removed(again), 0);
    mt_archive_close(again);
    CHECK(access(other, F_OK) == 0);
    unlink(other);
    scene_close(&s);
}

/* What a load (info.fault, status) and a verification report for `name`
 * must be the same fault; a DERIVED file loads (rebuilt) and fails
 * verification with MT_ERR_CORRUPT. Returns the loaded mesh (or NULL). */
static mt_mesh *expect_fault(mt_archive *archive, const char *name, mt_archive_fault expected,
                             const char *text)
{
    mt_mesh *mesh = NULL;
    mt_archive_load_info info;
    mt_diag diag, vdiag;
    mt_status st = mt_archive_load_mesh_file(archive, name, false, NULL, &mesh, &info, &diag);
    mt_archive_fault vfault = MT_ARCHIVE_FAULT_NONE;
    mt_status vst = mt_archive_verify_file_with(archive, name, NULL, NULL, &vfault, &vdiag);
    CHECK_EQ(info.fault, expected);
    CHECK_EQ(vfault, expected);
    bool loads = expected == MT_ARCHIVE_FAULT_NONE || expected == MT_ARCHIVE_FAULT_DERIVED;
    CHECK_EQ(st == MT_OK, loads);
    CHECK_EQ(vst == MT_OK, expected == MT_ARCHIVE_FAULT_NONE);
    if (expected == MT_ARCHIVE_FAULT_DERIVED) {
        CHECK_STATUS(vst, MT_ERR_CORRUPT);
        CHECK(!info.restored);
    }
    const char *message = st == MT_OK ? info.fallback.message : diag.message;
    if (text) {
        CHECK(strstr(message, name) != NULL);
        CHECK(strstr(message, text) != NULL);
        CHECK(strstr(vdiag.message, text) != NULL);
    }
    if (getenv("MT_TEST_VERBOSE") || (text && !strstr(message, text)) || info.fault != expected ||
        vfault != expected)
        printf("%s: load %s (%s), verify %s (%s): %s | %s\n", name, mt_strerror(st),
               mt_archive_fault_name(info.fault), mt_strerror(vst), mt_archive_fault_name(vfault),
               message, vdiag.message);
    return mesh;
}

/* A face list changed after archiving: the load fails with MT_ERR_CORRUPT
 * naming the file and both hashes (fault CONTENT), and verify says the
 * same; with the daemon's hash (computed a block at a time from the file)
 * as with a caller's. The file can then be set aside. */
static void test_face_list_altered(void)
{
    scene s;
    if (!scene_open(&s)) return;
    mt_face_list list;
    CHECK_OK(mt_gen_torus(10, 6, &list));
    uint64_t fake = 0, real = 0;
    at_hash(NULL, &list, &fake, NULL);
    CHECK_OK(mt_archive_content_hash(NULL, &list, &real, NULL));
    CHECK_OK(at_archive_list(s.archive, "fake", 1, &list, fake, NULL));
    CHECK_OK(at_archive_list(s.archive, "real", 1, &list, real, NULL));
    mt_face_list_free(&list);
    mt_archive_load_info info;
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_archive_load_mesh(s.archive, "fake", 1, false, NULL, &mesh, &info, NULL));
    CHECK(info.restored && info.hash_checked);
    CHECK_EQ(info.fault, MT_ARCHIVE_FAULT_NONE);
    mt_mesh_destroy(mesh);
    char path[1024];
    path_of(&s, "fake", 1, path, sizeof path);
    uint32_t first = at_peek_u32(path, "/meshtopo/face_vertex_indices", 0);
    CHECK(at_poke_u32(path, "/meshtopo/face_vertex_indices", 0, first == 0 ? 1 : 0));
    char both[64];
    snprintf(both, sizeof both, "the file says %016llx", (unsigned long long)fake);
    mt_diag diag;
    CHECK_STATUS(mt_archive_load_mesh(s.archive, "fake", 1, false, NULL, &mesh, &info, &diag),
                 MT_ERR_CORRUPT);
    CHECK(strstr(diag.message, "fake.v1.hdf: content hash mismatch") != NULL);
    CHECK(strstr(diag.message, both) != NULL);
    CHECK(strstr(diag.message, "the face list hashes to ") != NULL);
    mt_mesh_destroy(
        expect_fault(s.archive, "fake.v1.hdf", MT_ARCHIVE_FAULT_CONTENT, "content hash mismatch"));
    /* The daemon's hash. */
    mt_archive_set_content_hash(s.archive, mt_archive_content_hash, NULL);
    CHECK_OK(mt_archive_load_mesh(s.archive, "real", 1, false, NULL, &mesh, &info, NULL));
    CHECK(info.restored && info.hash_checked);
    mt_mesh_destroy(mesh);
    CHECK_OK(mt_archive_verify_file(s.archive, "real.v1.hdf", NULL, NULL, NULL));
    path_of(&s, "real", 1, path, sizeof path);
    /* One face a vertex shorter, the next one longer: still a face list. */
    uint32_t c2 = at_peek_u32(path, "/meshtopo/face_vertex_counts", 2);
    uint32_t c3 = at_peek_u32(path, "/meshtopo/face_vertex_counts", 3);
    CHECK(at_poke_u32(path, "/meshtopo/face_vertex_counts", 2, c2 - 1));
    CHECK(at_poke_u32(path, "/meshtopo/face_vertex_counts", 3, c3 + 1));
    snprintf(both, sizeof both, "the file says %016llx", (unsigned long long)real);
    mesh = expect_fault(s.archive, "real.v1.hdf", MT_ARCHIVE_FAULT_CONTENT, both);
    CHECK(mesh == NULL);
    /* Set aside: out of the listing and of the way. */
    char aside[300];
    CHECK_OK(mt_archive_set_aside(s.archive, "real.v1.hdf", aside, sizeof aside, NULL));
    CHECK(!mt_archive_contains(s.archive, "real", 1));
    mt_archive_listing l;
    CHECK_OK(mt_archive_list(s.archive, &l, NULL));
    CHECK_EQ(l.count, 1);
    mt_archive_listing_free(&l);
    mt_archive *again = NULL, *ro = NULL;
    CHECK_OK(mt_archive_open(s.dir, NULL, &again, NULL));
    CHECK_EQ(count_named(s.dir, ".mt-aside-real.v1.hdf."), 1);
    mt_archive_options read_only = {.read_only = true};
    CHECK_OK(mt_archive_open(s.dir, &read_only, &ro, NULL));
    CHECK_STATUS(mt_archive_set_aside(ro, "fake.v1.hdf", NULL, 0, NULL), MT_ERR_UNSUPPORTED);
    CHECK_STATUS(mt_archive_set_aside(again, "real.v1.hdf", NULL, 0, NULL), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_archive_set_aside(again, "../x.v1.hdf", NULL, 0, NULL), MT_ERR_INVALID_ARG);
    mt_archive_close(ro);
    mt_archive_close(again);
    char aside_path[1000];
    snprintf(aside_path, sizeof aside_path, "%s/%s", s.dir, aside);
    unlink(aside_path);
    scene_close(&s);
}

/* Half-edge arrays, report or digest changed after archiving, the face
 * list intact: loads succeed, rebuilt from the face list (restored false,
 * fault DERIVED, the reason named), answering like the build; verification
 * fails with the same fault. */
static void test_derived_data_altered(void)
{
    scene s;
    if (!scene_open(&s)) return;
    mt_mesh *built = NULL;
    CHECK_OK(write_torus(s.archive, "t", 1, &built));
    if (!built) {
        scene_close(&s);
        return;
    }
    mt_mesh_parts parts;
    mt_mesh_get_parts(built, &parts);
    char path[1024], copy[1024];
    path_of(&s, "t", 1, path, sizeof path);
    snprintf(copy, sizeof copy, "%s/t.copy", s.outside);
    CHECK(at_copy_file(path, copy, -1));
    mt_mesh *mesh = expect_fault(s.archive, "t.v1.hdf", MT_ARCHIVE_FAULT_NONE, NULL);
    CHECK(mesh != NULL);
    mt_mesh_destroy(mesh);

    /* Another outgoing half-edge of vertex 0: still a valid mesh, only the
     * digest tells it is not the one archived. */
    uint32_t h = parts.vert_he[0];
    CHECK(at_poke_u32(path, "/meshtopo/halfedge/vertex_halfedge", 0, parts.he_next[h ^ 1]));
    mesh = expect_fault(s.archive, "t.v1.hdf", MT_ARCHIVE_FAULT_DERIVED, "not what was archived");
    if (mesh) CHECK(rc_same_answers(built, mesh, "vertex_halfedge altered"));
    mt_mesh_destroy(mesh);
    /* Arrays that fail validation. */
    CHECK(at_copy_file(copy, path, -1));
    CHECK(at_poke_u32(path, "/meshtopo/halfedge/next", 0, parts.he_next[2]));
    mt_mesh_destroy(
        expect_fault(s.archive, "t.v1.hdf", MT_ARCHIVE_FAULT_DERIVED, "fail validation"));
    /* The report: with the content hash vouching for the face list, the
     * rebuild's report is served. */
    CHECK(at_copy_file(copy, path, -1));
    CHECK(at_set_attr_i64(path, "/meshtopo/report", "genus", 2));
    mesh = expect_fault(s.archive, "t.v1.hdf", MT_ARCHIVE_FAULT_DERIVED, "not what was archived");
    if (mesh) CHECK_EQ(mt_mesh_report(mesh)->genus, 1);
    mt_mesh_destroy(mesh);
    /* ... and without a hash nothing tells which of the two is damaged. */
    mt_archive_set_content_hash(s.archive, NULL, NULL);
    mt_mesh_destroy(expect_fault(s.archive, "t.v1.hdf", MT_ARCHIVE_FAULT_CONTENT,
                                 "differs from the stored one"));
    mt_archive_set_content_hash(s.archive, at_hash, NULL);
    /* The digest itself changed, or missing. */
    CHECK(at_copy_file(copy, path, -1));
    CHECK(at_set_attr_u64(path, "/meshtopo/halfedge", "digest", 12345));
    mt_mesh_destroy(
        expect_fault(s.archive, "t.v1.hdf", MT_ARCHIVE_FAULT_DERIVED, "not what was archived"));
    CHECK(at_copy_file(copy, path, -1));
    CHECK(at_delete_attr(path, "/meshtopo/halfedge", "digest"));
    mt_mesh_destroy(expect_fault(s.archive, "t.v1.hdf", MT_ARCHIVE_FAULT_DERIVED, "digest"));
    /* Positions are served too: covered by the digest. */
    CHECK(at_copy_file(copy, path, -1));
    {
        hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
        hid_t d = H5Dopen2(f, "/meshtopo/positions", H5P_DEFAULT);
        double row[3] = {9, 9, 9};
        hsize_t at[2] = {3, 0}, n[2] = {1, 3};
        hid_t space = H5Dget_space(d), mem = H5Screate_simple(2, n, NULL);
        H5Sselect_hyperslab(space, H5S_SELECT_SET, at, NULL, n, NULL);
        CHECK(H5Dwrite(d, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, row) >= 0);
        H5Sclose(mem);
        H5Sclose(space);
        H5Dclose(d);
        H5Fclose(f);
    }
    mt_archive_set_content_hash(s.archive, NULL, NULL); /* the digest alone catches it */
    mt_mesh_destroy(
        expect_fault(s.archive, "t.v1.hdf", MT_ARCHIVE_FAULT_DERIVED, "not what was archived"));
    mt_archive_set_content_hash(s.archive, at_hash, NULL); /* the face list is damaged */
    mt_mesh_destroy(
        expect_fault(s.archive, "t.v1.hdf", MT_ARCHIVE_FAULT_CONTENT, "content hash mismatch"));
    unlink(copy);
    mt_mesh_destroy(built);
    scene_close(&s);
}

/* Load and verification agree on files of every format and damage: each
 * row makes a file from a fresh copy and names the fault both must find. */
static void test_load_and_verify_agree(void)
{
    scene s;
    if (!scene_open(&s)) return;
    mt_mesh *built = NULL;
    CHECK_OK(write_torus(s.archive, "a", 1, &built));
    if (!built) {
        scene_close(&s);
        return;
    }
    mt_mesh_parts parts;
    mt_mesh_get_parts(built, &parts);
    char path[1024], copy[1024];
    path_of(&s, "a", 1, path, sizeof path);
    snprintf(copy, sizeof copy, "%s/a.copy", s.outside);
    CHECK(at_copy_file(path, copy, -1));
    const uint32_t h = parts.vert_he[0], other = parts.he_next[h ^ 1];
    for (int row = 0; row < 13; row++) {
        CHECK(at_copy_file(copy, path, -1));
        mt_archive_fault fault = MT_ARCHIVE_FAULT_NONE;
        switch (row) {
            case 0: /* intact */
                break;
            case 1: /* format 3: no digest; arrays compared with a rebuild */
                CHECK(at_delete_attr(path, "/meshtopo/halfedge", "digest"));
                CHECK(al_set_format(path, 3));
                break;
            case 2: /* format 3 with arrays that are not the build's */
                CHECK(at_delete_attr(path, "/meshtopo/halfedge", "digest"));
                CHECK(al_set_format(path, 3));
                CHECK(at_poke_u32(path, "/meshtopo/halfedge/vertex_halfedge", 0, other));
                fault = MT_ARCHIVE_FAULT_DERIVED;
                break;
            case 3: /* format 2: the former hash, not checked */
                CHECK(al_set_format(path, 2));
                CHECK(at_set_attr_u64(path, "/meshtopo", "content_hash", 1));
                break;
            case 4: /* format 1: no arrays, a rebuild */
                CHECK(at_delete(path, "/meshtopo/halfedge"));
                CHECK(al_set_format(path, 1));
                break;
            case 5: /* a newer meshtopo's file */
                CHECK(at_set_attr_i64(path, "/meshtopo", "format_version", 99));
                fault = MT_ARCHIVE_FAULT_NEWER;
                break;
            case 6: /* arrays not the build's */
                CHECK(at_poke_u32(path, "/meshtopo/halfedge/vertex_halfedge", 0, other));
                fault = MT_ARCHIVE_FAULT_DERIVED;
                break;
            case 7: /* the arrays' group gone */
                CHECK(at_delete(path, "/meshtopo/halfedge"));
                fault = MT_ARCHIVE_FAULT_DERIVED;
                break;
            case 8: /* the face list changed */
                CHECK(at_poke_u32(path, "/meshtopo/face_vertex_indices", 5,
                                  at_peek_u32(copy, "/meshtopo/face_vertex_indices", 5) ? 0 : 1));
                fault = MT_ARCHIVE_FAULT_CONTENT;
                break;
            case 9: /* the face list unreadable */
                CHECK(at_delete(path, "/meshtopo/face_vertex_counts"));
                fault = MT_ARCHIVE_FAULT_CONTENT;
                break;
            case 10: /* truncated */
                CHECK(at_copy_file(copy, path, 4000));
                fault = MT_ARCHIVE_FAULT_CONTENT;
                break;
            case 11: /* the VTKHDF view only: loads do not read it */
                CHECK(at_delete(path, "/VTKHDF/Types"));
                break;
            case 12: /* the provenance */
                CHECK(at_set_attr_u64(path, "/meshtopo", "version", 7));
                fault = MT_ARCHIVE_FAULT_CONTENT;
                break;
        }
        mt_mesh *mesh = NULL;
        mt_archive_load_info info;
        mt_diag diag;
        mt_status st =
            mt_archive_load_mesh_file(s.archive, "a.v1.hdf", false, NULL, &mesh, &info, &diag);
        mt_archive_fault vfault = MT_ARCHIVE_FAULT_NONE;
        mt_diag vdiag;
        mt_status vst =
            mt_archive_verify_file_with(s.archive, "a.v1.hdf", NULL, NULL, &vfault, &vdiag);
        CHECK_EQ(info.fault, fault);
        CHECK_EQ(vfault, row == 11 ? MT_ARCHIVE_FAULT_VTK : fault);
        CHECK_EQ(st == MT_OK, fault == MT_ARCHIVE_FAULT_NONE || fault == MT_ARCHIVE_FAULT_DERIVED);
        CHECK_EQ(vst == MT_OK, fault == MT_ARCHIVE_FAULT_NONE && row != 11);
        if (mesh) CHECK(rc_same_answers(built, mesh, "agree"));
        if (getenv("MT_TEST_VERBOSE") || info.fault != fault)
            printf("row %d: load %s %s restored=%d (%s%s), verify %s %s (%s)\n", row,
                   mt_strerror(st), mt_archive_fault_name(info.fault), info.restored,
                   st == MT_OK ? "" : diag.message, info.fallback.message, mt_strerror(vst),
                   mt_archive_fault_name(vfault), vdiag.message);
        mt_mesh_destroy(mesh);
    }
    unlink(copy);
    mt_mesh_destroy(built);
    scene_close(&s);
}

/* Every corpus mesh (defective ones included) archived with the daemon's
 * content hash loads restored with the hash checked block by block from
 * the file, and verifies with the same hash computed from the decoded face
 * list: the two computations agree. */
static void archive_corpus_mesh(const char *name, const mt_face_list *list, void *ctx)
{
    mt_archive *archive = ctx;
    uint64_t hash = 0;
    CHECK_OK(mt_archive_content_hash(NULL, list, &hash, NULL));
    mt_mesh *built = NULL;
    CHECK_OK(at_archive_list(archive, name, 1, list, hash, &built));
    char file[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(name, 1, file, sizeof file);
    mt_mesh *mesh = NULL;
    mt_archive_load_info info;
    mt_diag diag;
    mt_status st = mt_archive_load_mesh_file(archive, file, false, NULL, &mesh, &info, &diag);
    CHECK_OK(st);
    CHECK(info.restored && info.hash_checked);
    if (st != MT_OK || !info.restored)
        printf("%s: %s %s\n", name, diag.message, info.fallback.message);
    if (mesh && built) CHECK(rc_same_answers(built, mesh, name));
    mt_mesh_destroy(mesh);
    mt_mesh_destroy(built);
    st = mt_archive_verify_file(archive, file, NULL, NULL, &diag);
    CHECK_OK(st);
    if (st != MT_OK) printf("%s: %s\n", name, diag.message);
}

static void test_daemon_hash_corpus(void)
{
    char dir[512];
    CHECK(at_tmpdir(dir, sizeof dir));
    mt_archive *archive = NULL;
    CHECK_OK(mt_archive_open(dir, NULL, &archive, NULL));
    if (!archive) return;
    mt_archive_set_content_hash(archive, mt_archive_content_hash, NULL);
    CHECK(at_for_each_corpus_mesh(archive_corpus_mesh, archive) >= 20);
    mt_face_list empty;
    memset(&empty, 0, sizeof empty);
    archive_corpus_mesh("empty", &empty, archive);
    mt_archive_close(archive);
    at_rmdir(dir);
}

/* Permission denied: a version file the process may not read is reported
 * as "Permission denied" (not as a damaged file) by every read, with fault
 * SYSTEM; a directory it may not write, by the write. Root bypasses
 * permissions, so a root test drops to uid 65534 in a child. */
static void permission_body(void *ctx)
{
    const char *dir = ctx;
    if (geteuid() == 0 && (setgid(NOBODY) != 0 || setuid(NOBODY) != 0)) {
        printf("skipped: cannot drop to uid %d: %s\n", NOBODY, strerror(errno));
        _exit(SKIPPED);
    }
    if (access(dir, R_OK | W_OK | X_OK) != 0) {
        printf("skipped: uid %d cannot reach %s: %s\n", NOBODY, dir, strerror(errno));
        _exit(SKIPPED);
    }
    mt_archive *archive = NULL;
    mt_diag diag;
    CHECK_OK(mt_archive_open(dir, NULL, &archive, &diag));
    if (!archive) return;
    mt_archive_record rec;
    CHECK_STATUS(mt_archive_load(archive, "closed", 1, &rec, &diag), MT_ERR_IO);
    CHECK(strstr(diag.message, "closed.v1.hdf") != NULL);
    CHECK(strstr(diag.message, "Permission denied") != NULL);
    CHECK(strstr(diag.message, "not a readable HDF5") == NULL);
    if (getenv("MT_TEST_VERBOSE")) printf("unreadable: %s\n", diag.message);
    mt_mesh *mesh = NULL;
    mt_archive_load_info info;
    CHECK_STATUS(mt_archive_load_mesh(archive, "closed", 1, false, NULL, &mesh, &info, &diag),
                 MT_ERR_IO);
    CHECK_EQ(info.fault, MT_ARCHIVE_FAULT_SYSTEM);
    CHECK(strstr(diag.message, "Permission denied") != NULL);
    mt_archive_fault fault = MT_ARCHIVE_FAULT_NONE;
    CHECK_STATUS(mt_archive_verify_file_with(archive, "closed.v1.hdf", NULL, NULL, &fault, &diag),
                 MT_ERR_IO);
    CHECK_EQ(fault, MT_ARCHIVE_FAULT_SYSTEM);
    mt_archive_listing l;
    CHECK_OK(mt_archive_list(archive, &l, NULL));
    CHECK_EQ(l.count, 1);
    if (l.count == 1) {
        CHECK_EQ(l.entries[0].fault, MT_ARCHIVE_FAULT_SYSTEM);
        CHECK(strstr(l.entries[0].diag.message, "Permission denied") != NULL);
    }
    mt_archive_listing_free(&l);
    /* A directory it may not write. */
    CHECK(chmod(dir, 0500) == 0);
    mt_face_list list;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &list));
    mt_mesh *cube = NULL;
    CHECK_OK(mt_mesh_build(&list, NULL, &cube, NULL));
    mt_archive_meta meta = {"new", 1, 1, "node", 0};
    CHECK_STATUS(mt_archive_write(archive, &meta, &list, cube, NULL, &diag), MT_ERR_IO);
    CHECK(strstr(diag.message, "Permission denied") != NULL);
    CHECK(strstr(diag.message, dir) != NULL);
    if (getenv("MT_TEST_VERBOSE")) printf("unwritable: %s\n", diag.message);
    CHECK(chmod(dir, 0700) == 0);
    mt_mesh_destroy(cube);
    mt_face_list_free(&list);
    mt_archive_close(archive);
}

static void test_permission_denied(void)
{
    char dir[512], path[1024];
    CHECK(at_tmpdir(dir, sizeof dir));
    mt_archive *archive = NULL;
    CHECK_OK(mt_archive_open(dir, NULL, &archive, NULL));
    if (!archive) return;
    CHECK_OK(write_torus(archive, "closed", 1, NULL));
    mt_archive_close(archive);
    snprintf(path, sizeof path, "%s/closed.v1.hdf", dir);
    if (geteuid() == 0) {
        CHECK(chown(dir, NOBODY, NOBODY) == 0);
        CHECK(chown(path, NOBODY, NOBODY) == 0);
    }
    CHECK(chmod(path, 0) == 0);
    in_child(permission_body, dir);
    at_rmdir(dir);
}

/* A big mesh whose file takes several megabytes. */
static mt_status write_big(mt_archive *archive, const char *id, mt_diag *diag)
{
    mt_face_list list;
    CHECK_OK(mt_gen_grid(200, 200, true, &list));
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(&list, NULL, &mesh, NULL));
    mt_archive_meta meta = {id, 1, 1, "node", 0};
    mt_status st = mt_archive_write(archive, &meta, &list, mesh, NULL, diag);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    return st;
}

/* A full disk: a 1 MiB tmpfs mounted on the archive directory in a private
 * mount namespace. The write fails naming the temporary file, "No space
 * left on device" and the free space, and leaves nothing behind. */
static void disk_full_body(void *ctx)
{
    const char *dir = ctx;
    if (unshare(CLONE_NEWNS) != 0 || mount(NULL, "/", NULL, MS_REC | MS_PRIVATE, NULL) != 0 ||
        mount("tmpfs", dir, "tmpfs", 0, "size=1m") != 0) {
        printf("skipped: cannot mount a small tmpfs (needs root and mount namespaces): %s\n",
               strerror(errno));
        _exit(SKIPPED);
    }
    mt_archive *archive = NULL;
    CHECK_OK(mt_archive_open(dir, NULL, &archive, NULL));
    if (!archive) return;
    mt_diag diag;
    CHECK_STATUS(write_big(archive, "big", &diag), MT_ERR_IO);
    CHECK(strstr(diag.message, "No space left on device") != NULL);
    CHECK(strstr(diag.message, "bytes free on the file system of") != NULL);
    CHECK(strstr(diag.message, "/.mt-tmp-") != NULL);
    if (getenv("MT_TEST_VERBOSE") || !strstr(diag.message, "No space left on device"))
        printf("disk full: %s\n", diag.message);
    CHECK_EQ(count_named(dir, ".mt-tmp-"), 0);
    CHECK(!mt_archive_contains(archive, "big", 1));
    mt_archive_close(archive);
}

static void test_disk_full(void)
{
    char dir[512];
    CHECK(at_tmpdir(dir, sizeof dir));
    in_child(disk_full_body, dir);
    at_rmdir(dir);
}

/* A file size limit (RLIMIT_FSIZE, SIGXFSZ ignored): the write fails with
 * "File too large" and the limit, and leaves nothing behind. */
static void file_size_body(void *ctx)
{
    const char *dir = ctx;
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit lim = {256 * 1024, 256 * 1024};
    CHECK(setrlimit(RLIMIT_FSIZE, &lim) == 0);
    mt_archive *archive = NULL;
    CHECK_OK(mt_archive_open(dir, NULL, &archive, NULL));
    if (!archive) return;
    mt_diag diag;
    CHECK_STATUS(write_big(archive, "big", &diag), MT_ERR_IO);
    CHECK(strstr(diag.message, "File too large") != NULL);
    CHECK(strstr(diag.message, "RLIMIT_FSIZE, is 262144 bytes") != NULL);
    CHECK(strstr(diag.message, "/.mt-tmp-") != NULL);
    if (getenv("MT_TEST_VERBOSE") || !strstr(diag.message, "File too large"))
        printf("size limit: %s\n", diag.message);
    CHECK_EQ(count_named(dir, ".mt-tmp-"), 0);
    mt_archive_close(archive);
}

static void test_file_size_limit(void)
{
    char dir[512];
    CHECK(at_tmpdir(dir, sizeof dir));
    in_child(file_size_body, dir);
    at_rmdir(dir);
}

/* Without /proc (an empty tmpfs over it, in a private mount namespace):
 * HDF5 is handed names instead of /proc/self/fd, and the fallbacks still
 * write, load, verify and refuse links. */
static void no_proc_body(void *ctx)
{
    scene *s = ctx;
    if (unshare(CLONE_NEWNS) != 0 || mount(NULL, "/", NULL, MS_REC | MS_PRIVATE, NULL) != 0 ||
        mount("tmpfs", "/proc", "tmpfs", 0, "size=16k") != 0) {
        printf("skipped: cannot hide /proc (needs root and mount namespaces): %s\n",
               strerror(errno));
        _exit(SKIPPED);
    }
    CHECK(access("/proc/self/fd", F_OK) != 0);
    CHECK_OK(write_torus(s->archive, "p", 1, NULL));
    mt_mesh *mesh = NULL;
    mt_archive_load_info info;
    CHECK_OK(mt_archive_load_mesh(s->archive, "p", 1, false, NULL, &mesh, &info, NULL));
    CHECK(info.restored && info.hash_checked);
    mt_mesh_destroy(mesh);
    CHECK_OK(mt_archive_verify_file(s->archive, "p.v1.hdf", NULL, NULL, NULL));
    char v2[1024];
    path_of(s, "p", 2, v2, sizeof v2);
    CHECK(symlink(s->precious, v2) == 0);
    CHECK_STATUS(write_torus(s->archive, "p", 2, NULL), MT_ERR_INVALID_ARG);
    expect_refused(s, "p.v2.hdf", "a symbolic link");
    CHECK(unlink(v2) == 0);
    CHECK_EQ(count_named(s->dir, ".mt-tmp-"), 0);
}

static void test_without_proc(void)
{
    scene s;
    if (!scene_open(&s)) return;
    in_child(no_proc_body, &s);
    scene_close(&s);
}

static const mt_test_case cases[] = {
    {"safety_symlink_at_tmp_names", test_symlink_at_tmp_names},
    {"safety_symlink_at_final_name", test_symlink_at_final_name},
    {"safety_non_regular_version_files", test_non_regular_version_files},
    {"safety_foreign_owner", test_foreign_owner},
    {"safety_face_list_altered", test_face_list_altered},
    {"safety_derived_data_altered", test_derived_data_altered},
    {"safety_load_and_verify_agree", test_load_and_verify_agree},
    {"safety_daemon_hash_corpus", test_daemon_hash_corpus},
    {"safety_permission_denied", test_permission_denied},
    {"safety_disk_full", test_disk_full},
    {"safety_file_size_limit", test_file_size_limit},
    {"safety_without_proc", test_without_proc},
};
const mt_test_table mt_tests_archive_safety = {cases, sizeof cases / sizeof cases[0]};
