/* Shared declarations of `meshtopo-bench rtt`: query round trips to a real
 * meshtopod, measured in the same run as a raw LCM ping-pong of the same
 * message sizes, and query throughput from several client processes. Every
 * process of the run lives in a private network namespace that the benchmark
 * makes for itself (rtt_netns.c), so no packet reaches the host's network. */
#ifndef MESHTOPO_BENCH_RTT_H
#define MESHTOPO_BENCH_RTT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "bench.h"
#include "meshtopo/client.h"
#include "meshtopo/mesh.h"

/* LCM URL of every process of the run (inside the private namespace). The
 * queried grid is one mesh_t message of about 1 MB, so both ends ask for a
 * receive buffer that holds it. */
#define MT__RTT_LCM_URL "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
#define MT__RTT_MESH_ID "rtt-grid"
#define MT__RTT_MAX_REPS 99
#define MT__RTT_MAX_CLIENTS 64

typedef struct mt__rtt_options {
    const char *daemon_path; /* NULL: next to this program, then the build tree */
    uint32_t grid;           /* the queried mesh: a grid of grid x grid quads, 2 triangles each */
    uint32_t round_trips;    /* timed round trips per latency sample set */
    uint32_t reps;           /* repetitions of every measurement (medians are shown) */
    double seconds;          /* length of one throughput run */
    uint32_t clients;        /* client processes in the throughput runs */
    uint32_t batch;          /* vertex ids per query in the batched throughput run */
    uint32_t window;         /* queries in flight per client in the throughput runs */
    uint64_t seed;           /* queried vertex ids */
    const char *csv_path;    /* NULL: no CSV */
    const char *md_path;     /* NULL: no Markdown */
    bool quick;              /* small and short: a smoke test of the whole run */
} mt__rtt_options;

/* Entry point: `meshtopo-bench rtt [options]` (argv[0] is "rtt"). Returns the
 * exit status: 0 when every measurement ran and every answer was right, 1
 * when one failed, 2 on a usage error, 77 when no private network namespace
 * can be made here. */
int mt__bench_rtt_command(int argc, char **argv);

/* ---- rtt_netns.c --------------------------------------------------------- */

/* Moves this process (which must not have started threads yet) into a new
 * network namespace, as root or through a new user namespace, and sets up
 * loopback multicast there: lo up with MULTICAST, route 224.0.0.0/4 dev lo.
 * Returns 0, or 77 when namespaces cannot be made here, or 1 on a setup
 * error; err then says why. */
int mt__rtt_enter_private_network(char *err, size_t err_size);

/* ---- rtt_daemon.c -------------------------------------------------------- */

/* A meshtopod started by the benchmark (stderr goes to log_path). */
typedef struct mt__rtt_daemon {
    pid_t pid;
    char log_path[256];
} mt__rtt_daemon;

/* The meshtopod to start: `given` when not NULL, else the one next to this
 * program (installed side by side), else the build tree's, else "meshtopod"
 * on PATH. buf holds the path found. */
const char *mt__rtt_daemon_find(const char *given, char *buf, size_t size);

/* Starts meshtopod on MT__RTT_LCM_URL (archiving into archive_dir unless it
 * is NULL) and waits for its first heartbeat. */
bool mt__rtt_daemon_start(const char *path, const char *archive_dir, mt__rtt_daemon *out, char *err,
                          size_t err_size);

/* The same with the flags of args (NULL-terminated) after --lcm-url and
 * --log-level warn. */
bool mt__rtt_daemon_start_with(const char *path, const char *const *args, mt__rtt_daemon *out,
                               char *err, size_t err_size);

/* Removes an archive directory a run's daemons wrote, and all it holds
 * (symbolic links are removed, never followed). */
void mt__rtt_daemon_remove_archive(const char *dir);

/* SIGTERM to the daemon's PID, SIGKILL after 10 s; true on a clean exit. */
bool mt__rtt_daemon_stop(mt__rtt_daemon *daemon, char *err, size_t err_size);

/* ---- rtt_client.c -------------------------------------------------------- */

/* A client on MT__RTT_LCM_URL (1 s per attempt, 3 retries). NULL on failure,
 * said on stderr. */
mt_client *mt__rtt_client_new(const char *source);

/* Waits, through a client of its own that is destroyed before returning,
 * until a heartbeat of the meshtopod with this PID arrives; false after
 * timeout_ms. */
bool mt__rtt_daemon_wait(pid_t pid, int timeout_ms);

/* ---- rtt_pingpong.c ------------------------------------------------------ */

/* The raw LCM baseline: an echo process answers every ping with a pong of
 * the size the ping names, on LCM alone (no meshtopo code between). Started
 * once, measured several times, stopped at the end. */
typedef struct mt__rtt_echo {
    pid_t pid;
} mt__rtt_echo;

bool mt__rtt_echo_start(mt__rtt_echo *out, char *err, size_t err_size);
void mt__rtt_echo_stop(mt__rtt_echo *echo);

/* Times `count` ping-pongs (ping_size bytes out, pong_size back) one after
 * another, after a few untimed ones, writing each round trip in microseconds
 * to out_us. */
bool mt__rtt_pingpong(size_t ping_size, size_t pong_size, uint32_t count, double *out_us, char *err,
                      size_t err_size);

/* ---- rtt_query.c --------------------------------------------------------- */

/* Times `count` single-id VERTEX_RING queries one after another through
 * mt_client_query, each for a random vertex, and checks every answer against
 * `local` (the same grid built in this process). Also reports the encoded
 * sizes of the last query and reply, for the ping-pong. */
bool mt__rtt_query_latency(mt_client *client, const mt_mesh *local, uint32_t count, uint64_t seed,
                           double *out_us, size_t *out_query_bytes, size_t *out_reply_bytes,
                           char *err, size_t err_size);

/* Result of one throughput run. */
typedef struct mt__rtt_throughput {
    double seconds;    /* from the common start to the last client's end */
    uint64_t queries;  /* answered queries, all clients */
    uint64_t answers;  /* answered vertex one-rings (ids), all clients */
    uint64_t failures; /* queries that failed or got a wrong answer */
} mt__rtt_throughput;

/* Forks `clients` processes; each keeps `window` VERTEX_RING queries of
 * `batch` random vertex ids in flight for `seconds`, checking the shape of
 * every answer and the content of the first one against `local`. */
bool mt__rtt_query_throughput(const mt_mesh *local, uint32_t clients, uint32_t batch,
                              uint32_t window, double seconds, uint64_t seed,
                              mt__rtt_throughput *out, char *err, size_t err_size);

/* Checks one VERTEX_RING reply item against mt_vert_ring on `local`; false
 * with the difference in err. */
bool mt__rtt_ring_matches(const mt_mesh *local, const meshtopo_reply_t *reply, uint32_t item,
                          uint32_t vert, char *err, size_t err_size);

#endif
