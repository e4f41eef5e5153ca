/* A peer program as a child process, as every meshtopo-bench subcommand that
 * has one talks to it: found next to the driver (or installed, or in the
 * build tree), started with posix_spawn on two pipes, read one
 * "word key=value ..." line at a time, and stopped by "quit" and a wait for
 * that one child only. The line protocols themselves are in peer_common.hpp
 * (build), peer_cgal_selfx.cpp (selfx) and peer_map.cpp (map). */
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"

extern char **environ;

static bool is_executable(const char *dir, const char *name, char *out, size_t size)
{
    int n = snprintf(out, size, "%s/%s", dir, name);
    return n > 0 && (size_t)n < size && access(out, X_OK) == 0;
}

bool mt__bench_peer_find(const char *peer_dir, const char *name, char *out, size_t size)
{
    if (peer_dir) return is_executable(peer_dir, name, out, size);
    char self[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n > 0) {
        self[n] = '\0';
        char *slash = strrchr(self, '/');
        if (slash) {
            *slash = '\0';
            if (is_executable(self, name, out, size)) return true;
            char libexec[PATH_MAX];
            int m = snprintf(libexec, sizeof libexec, "%s/../libexec/meshtopo", self);
            if (m > 0 && (size_t)m < sizeof libexec && is_executable(libexec, name, out, size)) {
                return true;
            }
        }
    }
#ifdef MESHTOPO_BENCH_BUILD_PEER_DIR
    if (is_executable(MESHTOPO_BENCH_BUILD_PEER_DIR, name, out, size)) return true;
#endif
    return false;
}

static void set_cloexec(int fd)
{
    fcntl(fd, F_SETFD, fcntl(fd, F_GETFD) | FD_CLOEXEC);
}

bool mt__bench_child_start(mt__bench_child *child, char *const argv[], char *err, size_t err_size)
{
    memset(child, 0, sizeof *child);
    int to_child[2], from_child[2];
    if (pipe(to_child) != 0) goto fail_errno;
    if (pipe(from_child) != 0) {
        close(to_child[0]);
        close(to_child[1]);
        goto fail_errno;
    }
    for (int i = 0; i < 2; i++) {
        set_cloexec(to_child[i]);
        set_cloexec(from_child[i]);
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, to_child[0], STDIN_FILENO);
    posix_spawn_file_actions_adddup2(&actions, from_child[1], STDOUT_FILENO);
    int spawn_err = posix_spawn(&child->pid, argv[0], &actions, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    close(to_child[0]);
    close(from_child[1]);
    if (spawn_err != 0) {
        close(to_child[1]);
        close(from_child[0]);
        child->pid = 0;
        snprintf(err, err_size, "cannot start %.300s: %s", argv[0], strerror(spawn_err));
        return false;
    }
    child->to_child = fdopen(to_child[1], "w");
    child->from_child = fdopen(from_child[0], "r");
    if (!child->to_child || !child->from_child) {
        if (!child->to_child) close(to_child[1]);
        if (!child->from_child) close(from_child[0]);
        goto fail_errno;
    }
    return true;
fail_errno:
    snprintf(err, err_size, "cannot start %.300s: %s", argv[0], strerror(errno));
    return false;
}

bool mt__bench_child_send(mt__bench_child *child, const char *line, char *err, size_t err_size)
{
    if (fputs(line, child->to_child) == EOF || fputc('\n', child->to_child) == EOF ||
        fflush(child->to_child) != 0) {
        snprintf(err, err_size, "cannot send '%s': %s", line, strerror(errno));
        return false;
    }
    return true;
}

bool mt__bench_child_read_line(mt__bench_child *child, char *buf, size_t size, char *err,
                               size_t err_size)
{
    if (!fgets(buf, (int)size, child->from_child)) {
        snprintf(err, err_size, "ended without answering (see its messages above)");
        return false;
    }
    buf[strcspn(buf, "\r\n")] = '\0';
    if (strncmp(buf, "error", 5) == 0) {
        snprintf(err, err_size, "%.440s", buf);
        return false;
    }
    return true;
}

void mt__bench_child_stop(mt__bench_child *child, const char *name)
{
    if (child->to_child) {
        fputs("quit\n", child->to_child);
        fclose(child->to_child);
        child->to_child = NULL;
    }
    if (child->from_child) {
        char buf[1024];
        while (fgets(buf, sizeof buf, child->from_child)) {
        }
        fclose(child->from_child);
        child->from_child = NULL;
    }
    if (child->pid > 0) {
        int status = 0;
        while (waitpid(child->pid, &status, 0) < 0 && errno == EINTR) {
        }
        if (WIFSIGNALED(status)) {
            fprintf(stderr, "meshtopo-bench: %s peer (pid %ld) killed by signal %d\n", name,
                    (long)child->pid, WTERMSIG(status));
        } else if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
            fprintf(stderr, "meshtopo-bench: %s peer (pid %ld) exited with status %d\n", name,
                    (long)child->pid, WEXITSTATUS(status));
        }
        child->pid = 0;
    }
}

const char *mt__bench_field(const char *line, const char *key)
{
    size_t n = strlen(key);
    for (const char *p = line; (p = strstr(p, key)) != NULL; p += n) {
        bool word_start = p == line || p[-1] == ' ';
        if (word_start && p[n] == '=') return p + n + 1;
    }
    return NULL;
}

bool mt__bench_field_u64(const char *line, const char *key, uint64_t *out)
{
    const char *v = mt__bench_field(line, key);
    if (!v) return false;
    char *end;
    errno = 0;
    unsigned long long x = strtoull(v, &end, 10);
    if (errno || end == v) return false;
    *out = x;
    return true;
}

bool mt__bench_field_i64(const char *line, const char *key, int64_t *out)
{
    const char *v = mt__bench_field(line, key);
    if (!v) return false;
    char *end;
    errno = 0;
    long long x = strtoll(v, &end, 10);
    if (errno || end == v) return false;
    *out = x;
    return true;
}

bool mt__bench_field_double(const char *line, const char *key, double *out)
{
    const char *v = mt__bench_field(line, key);
    if (!v) return false;
    char *end;
    double x = strtod(v, &end);
    if (end == v) return false;
    *out = x;
    return true;
}
