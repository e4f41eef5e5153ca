/* A C++ peer program (OpenMesh, CGAL) measured as a child process. The
 * driver starts it with posix_spawn on one raw input file and talks to it
 * over two pipes, one line at a time (the protocol is in peer_common.hpp):
 *   peer -> "ready key=value ..."  after loading and one warm-up build
 *   "run"  -> "rep key=value ..."  one timed build, sweeps, loops, components
 *   "quit" (or EOF) -> exits 0;    "error <text>" and a non-zero exit on failure
 * Only the child started here is ever waited for. */
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"

extern char **environ;

typedef struct peer_state {
    pid_t pid;
    FILE *to_peer;
    FILE *from_peer;
} peer_state;

static void set_cloexec(int fd)
{
    fcntl(fd, F_SETFD, fcntl(fd, F_GETFD) | FD_CLOEXEC);
}

/* Reads one line from the peer into buf (newline removed). */
static bool peer_read_line(peer_state *s, char *buf, size_t size, const char *library,
                           mt__bench_result *result)
{
    if (!fgets(buf, (int)size, s->from_peer)) {
        snprintf(result->message, sizeof result->message,
                 "%s peer ended without answering (see its messages above)", library);
        return false;
    }
    buf[strcspn(buf, "\r\n")] = '\0';
    if (strncmp(buf, "error", 5) == 0) {
        snprintf(result->message, sizeof result->message, "%s peer: %.440s", library, buf);
        return false;
    }
    return true;
}

/* Finds key=value in a protocol line (keys are whole words). */
static const char *field(const char *line, const char *key)
{
    size_t n = strlen(key);
    for (const char *p = line; (p = strstr(p, key)) != NULL; p += n) {
        bool word_start = p == line || p[-1] == ' ';
        if (word_start && p[n] == '=') return p + n + 1;
    }
    return NULL;
}

static bool field_u64(const char *line, const char *key, uint64_t *out)
{
    const char *v = field(line, key);
    if (!v) return false;
    char *end;
    errno = 0;
    unsigned long long x = strtoull(v, &end, 10);
    if (errno || end == v) return false;
    *out = x;
    return true;
}

static bool field_i64(const char *line, const char *key, int64_t *out)
{
    const char *v = field(line, key);
    if (!v) return false;
    char *end;
    errno = 0;
    long long x = strtoll(v, &end, 10);
    if (errno || end == v) return false;
    *out = x;
    return true;
}

static bool field_double(const char *line, const char *key, double *out)
{
    const char *v = field(line, key);
    if (!v) return false;
    char *end;
    double x = strtod(v, &end);
    if (end == v) return false;
    *out = x;
    return true;
}

static void peer_stop(mt__bench_runner *runner)
{
    peer_state *s = runner->state;
    if (!s) return;
    if (s->to_peer) {
        fputs("quit\n", s->to_peer);
        fclose(s->to_peer);
    }
    if (s->from_peer) {
        char buf[1024];
        while (fgets(buf, sizeof buf, s->from_peer)) {
        }
        fclose(s->from_peer);
    }
    if (s->pid > 0) {
        int status = 0;
        while (waitpid(s->pid, &status, 0) < 0 && errno == EINTR) {
        }
        if (WIFSIGNALED(status)) {
            fprintf(stderr, "meshtopo-bench: %s peer (pid %ld) killed by signal %d\n",
                    runner->library, (long)s->pid, WTERMSIG(status));
        } else if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
            fprintf(stderr, "meshtopo-bench: %s peer (pid %ld) exited with status %d\n",
                    runner->library, (long)s->pid, WEXITSTATUS(status));
        }
    }
    free(s);
    runner->state = NULL;
}

static bool peer_spawn(mt__bench_runner *runner, peer_state *s, const char *input_path,
                       bool no_reserve, mt__bench_result *result)
{
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
    char no_reserve_flag[] = "--no-reserve";
    char *argv[5] = {runner->exe, (char *)input_path, NULL, NULL, NULL};
    int argc = 2;
    if (runner->peer_flag) argv[argc++] = (char *)runner->peer_flag;
    if (no_reserve) argv[argc++] = no_reserve_flag;
    int err = posix_spawn(&s->pid, runner->exe, &actions, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    close(to_child[0]);
    close(from_child[1]);
    if (err != 0) {
        close(to_child[1]);
        close(from_child[0]);
        s->pid = 0;
        snprintf(result->message, sizeof result->message, "cannot start %.300s: %s", runner->exe,
                 strerror(err));
        return false;
    }
    s->to_peer = fdopen(to_child[1], "w");
    s->from_peer = fdopen(from_child[0], "r");
    if (!s->to_peer || !s->from_peer) {
        if (!s->to_peer) close(to_child[1]);
        if (!s->from_peer) close(from_child[0]);
        goto fail_errno;
    }
    return true;
fail_errno:
    snprintf(result->message, sizeof result->message, "cannot start %.300s: %s", runner->exe,
             strerror(errno));
    return false;
}

/* The counts and sweep totals both protocol lines carry. */
static bool seen_parse(const char *line, mt__bench_topology *t)
{
    return field_u64(line, "boundary_loops", &t->boundary_loops) &&
           field_u64(line, "components", &t->components) &&
           field_u64(line, "loop_verts", &t->loop_verts) &&
           field_u64(line, "ring_neighbours", &t->ring_neighbours) &&
           field_u64(line, "ring_sum", &t->ring_sum) &&
           field_u64(line, "adj_neighbours", &t->adj_neighbours) &&
           field_u64(line, "adj_sum", &t->adj_sum);
}

static bool peer_start(mt__bench_runner *runner, const mt__bench_case *bench_case,
                       const mt__bench_options *options, mt__bench_result *result)
{
    peer_state *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(result->message, sizeof result->message, "out of memory");
        return false;
    }
    runner->state = s;
    if (!peer_spawn(runner, s, bench_case->path, options->peer_no_reserve, result)) return false;

    char line[1024];
    if (!peer_read_line(s, line, sizeof line, runner->library, result)) return false;
    mt__bench_topology *t = &result->topology;
    const char *version = field(line, "version");
    if (strncmp(line, "ready ", 6) != 0 || !version || !field_u64(line, "V", &t->verts) ||
        !field_u64(line, "E", &t->edges) || !field_u64(line, "F", &t->faces) ||
        !field_u64(line, "failed_faces", &t->rejected_faces) || !seen_parse(line, t)) {
        snprintf(result->message, sizeof result->message, "%s peer: unexpected line '%.400s'",
                 runner->library, line);
        return false;
    }
    snprintf(result->version, sizeof result->version, "%.*s", (int)strcspn(version, " "), version);
    return true;
}

static bool peer_rep(mt__bench_runner *runner, mt__bench_sample *out, mt__bench_result *result)
{
    peer_state *s = runner->state;
    if (fputs("run\n", s->to_peer) == EOF || fflush(s->to_peer) != 0) {
        snprintf(result->message, sizeof result->message, "%s peer: cannot send: %s",
                 runner->library, strerror(errno));
        return false;
    }
    char line[1024];
    if (!peer_read_line(s, line, sizeof line, runner->library, result)) return false;
    memset(out, 0, sizeof *out);
    if (strncmp(line, "rep ", 4) != 0 || !field_double(line, "build_ms", &out->build_ms) ||
        !field_double(line, "ring_ms", &out->ring_ms) ||
        !field_double(line, "adj_ms", &out->adj_ms) ||
        !field_double(line, "loops_ms", &out->loops_ms) ||
        !field_double(line, "components_ms", &out->components_ms) ||
        !seen_parse(line, &out->seen) || !field_i64(line, "heap_bytes", &out->heap_bytes)) {
        snprintf(result->message, sizeof result->message, "%s peer: unexpected line '%.400s'",
                 runner->library, line);
        return false;
    }
    return true;
}

void mt__bench_runner_peer(mt__bench_runner *out, const char *library, const char *peer_flag)
{
    memset(out, 0, sizeof *out);
    snprintf(out->library, sizeof out->library, "%s", library);
    out->kind = MT__BENCH_LIBRARY;
    out->peer_flag = peer_flag;
    out->start = peer_start;
    out->rep = peer_rep;
    out->stop = peer_stop;
}
