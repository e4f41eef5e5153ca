/* The meshtopod of a `meshtopo-bench rtt`, `transfer`, `soak` or `cluster`
 * run: started as a child process on the run's LCM URL, awaited by its first
 * heartbeat (mt__rtt_daemon_wait, rtt_client.c), stopped by its PID
 * (SIGTERM, then SIGKILL after 10 s), and its archive removed. */
#define _XOPEN_SOURCE 700 /* nftw */
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "rtt.h"

#define HEARTBEAT_WAIT_MS 10000
#define STOP_WAIT_MS 10000

bool mt__rtt_daemon_start(const char *path, const char *archive_dir, mt__rtt_daemon *out, char *err,
                          size_t err_size)
{
    const char *with_archive[] = {"--heartbeat-ms", "100", "--archive", archive_dir, NULL};
    const char *without[] = {"--heartbeat-ms", "100", NULL};
    return mt__rtt_daemon_start_with(path, archive_dir ? with_archive : without, out, err,
                                     err_size);
}

bool mt__rtt_daemon_start_with(const char *path, const char *const *args, mt__rtt_daemon *out,
                               char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    const char *tmp = getenv("TMPDIR");
    snprintf(out->log_path, sizeof out->log_path, "%s/meshtopo-rtt-daemon-XXXXXX",
             tmp && *tmp ? tmp : "/tmp");
    int log_fd = mkstemp(out->log_path);
    if (log_fd < 0) {
        snprintf(err, err_size, "cannot make the daemon's log file: %s", strerror(errno));
        out->log_path[0] = '\0';
        return false;
    }
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(err, err_size, "fork: %s", strerror(errno));
        close(log_fd);
        return false;
    }
    if (pid == 0) {
        dup2(log_fd, STDERR_FILENO);
        int null_fd = open("/dev/null", O_WRONLY);
        if (null_fd >= 0) dup2(null_fd, STDOUT_FILENO);
        const char *argv[64] = {path, "--lcm-url", MT__RTT_LCM_URL, "--log-level", "warn"};
        size_t n = 5;
        for (size_t i = 0; args[i] && n < 63; i++) argv[n++] = args[i];
        argv[n] = NULL;
        execv(path, (char *const *)argv);
        fprintf(stderr, "meshtopo-bench rtt: cannot start %s: %s\n", path, strerror(errno));
        _exit(127);
    }
    close(log_fd);
    out->pid = pid;
    if (!mt__rtt_daemon_wait(pid, HEARTBEAT_WAIT_MS)) {
        snprintf(err, err_size, "no heartbeat from %s (pid %d) within %d ms; its log: %s", path,
                 (int)pid, HEARTBEAT_WAIT_MS, out->log_path);
        char ignored[8];
        mt__rtt_daemon_stop(out, ignored, sizeof ignored);
        return false;
    }
    return true;
}

bool mt__rtt_daemon_stop(mt__rtt_daemon *daemon, char *err, size_t err_size)
{
    if (daemon->pid <= 0) return true;
    kill(daemon->pid, SIGTERM);
    int status = 0;
    pid_t done = 0;
    for (int waited = 0; waited < STOP_WAIT_MS; waited += 10) {
        done = waitpid(daemon->pid, &status, WNOHANG);
        if (done != 0) break;
        struct timespec pause = {0, 10 * 1000 * 1000};
        nanosleep(&pause, NULL);
    }
    bool clean = done == daemon->pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (done == 0) {
        kill(daemon->pid, SIGKILL);
        waitpid(daemon->pid, &status, 0);
        snprintf(err, err_size, "meshtopod (pid %d) still ran 10 s after SIGTERM: killed",
                 (int)daemon->pid);
    } else if (!clean) {
        snprintf(err, err_size, "meshtopod (pid %d) did not exit cleanly (status 0x%x); log: %s",
                 (int)daemon->pid, (unsigned)status, daemon->log_path);
    }
    daemon->pid = 0;
    if (clean && daemon->log_path[0]) unlink(daemon->log_path);
    return clean;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    remove(path);
    return 0;
}

void mt__rtt_daemon_remove_archive(const char *dir)
{
    nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

const char *mt__rtt_daemon_find(const char *given, char *buf, size_t size)
{
    if (given) return given;
    ssize_t n = readlink("/proc/self/exe", buf, size - 1);
    if (n > 0) {
        buf[n] = '\0';
        char *slash = strrchr(buf, '/');
        if (slash && (size_t)(slash - buf) + sizeof "/meshtopod" <= size) {
            strcpy(slash, "/meshtopod");
            if (access(buf, X_OK) == 0) return buf;
        }
    }
#ifdef MESHTOPO_BENCH_DAEMON_BUILD_PATH
    if (access(MESHTOPO_BENCH_DAEMON_BUILD_PATH, X_OK) == 0)
        return MESHTOPO_BENCH_DAEMON_BUILD_PATH;
#endif
    return "meshtopod";
}
