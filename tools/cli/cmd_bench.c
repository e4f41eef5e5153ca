/* `meshtopo bench [build|rtt] [options]`: runs the benchmark program
 * meshtopo-bench with the same arguments. It is a separate executable because
 * it starts child processes of its own (the OpenMesh and CGAL peers, a
 * meshtopod in a private network namespace) and links what the tool does not
 * need; this command only finds it: next to meshtopo (installed side by
 * side), then in the build tree, then on PATH. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

#define BENCH_PROGRAM "meshtopo-bench"

static const char *find_bench(char *buf, size_t size)
{
    ssize_t n = readlink("/proc/self/exe", buf, size - 1);
    if (n > 0) {
        buf[n] = '\0';
        char *slash = strrchr(buf, '/');
        if (slash && (size_t)(slash - buf) + sizeof "/" BENCH_PROGRAM <= size) {
            strcpy(slash, "/" BENCH_PROGRAM);
            if (access(buf, X_OK) == 0) return buf;
        }
    }
#ifdef MESHTOPO_BENCH_BUILD_PATH
    if (access(MESHTOPO_BENCH_BUILD_PATH, X_OK) == 0) return MESHTOPO_BENCH_BUILD_PATH;
#endif
    return BENCH_PROGRAM; /* execvp searches PATH */
}

static int bench_run(int argc, char **argv)
{
    char path[PATH_MAX];
    const char *program = find_bench(path, sizeof path);
    char **args = calloc((size_t)argc + 2, sizeof *args);
    if (!args) {
        cli_error("bench", "out of memory");
        return CLI_EXIT_USAGE;
    }
    args[0] = (char *)BENCH_PROGRAM;
    for (int i = 0; i < argc; i++) args[i + 1] = argv[i];
    fflush(NULL);
    execvp(program, args);
    cli_error("bench", "cannot run %s: %s (it is built with -DMESHTOPO_BUILD_BENCH=ON)", program,
              strerror(errno));
    free(args);
    return CLI_EXIT_USAGE;
}

const cli_command cli_cmd_bench = {
    .name = "bench",
    .summary = "benchmarks: core build vs OpenMesh/CGAL, query round trips, soak",
    .synopsis = "[build|rtt|transfer|archive|soak|cluster] [options]",
    .description =
        "  meshtopo bench [build] [options]  build a 1M-triangle grid from a face list and\n"
        "                                    sweep its one-rings, against OpenMesh and CGAL\n"
        "                                    when installed (meshtopo bench build --help)\n"
        "  meshtopo bench rtt [options]      one-ring query round trips to a meshtopod\n"
        "                                    against a raw LCM ping-pong of the same sizes,\n"
        "                                    and query throughput, in a private network\n"
        "                                    namespace made for the run (needs root or\n"
        "                                    user namespaces; meshtopo bench rtt --help)\n"
        "  meshtopo bench soak [--seconds S] meshtopod under normal and hostile traffic for\n"
        "                                    S seconds in a private network namespace: lost\n"
        "                                    acks, latency against a baseline, memory\n"
        "                                    (meshtopo bench soak --help)\n"
        "  meshtopo bench cluster [options]  build throughput of a meshtopod cluster of 1\n"
        "                                    and 2 members, and the failover time of a\n"
        "                                    member killed (meshtopo bench cluster --help)\n"
        "The exit status is meshtopo-bench's: 0 when every measurement ran and all\n"
        "answers agree; missed targets are printed but do not fail.\n",
    .run_raw = bench_run,
};
