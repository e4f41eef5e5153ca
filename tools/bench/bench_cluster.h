/* `meshtopo-bench cluster` (bench_cluster.c): build throughput of a
 * meshtopod cluster of 1 and 2 members, and the failover time of a member
 * killed with SIGKILL. */
#ifndef MESHTOPO_BENCH_CLUSTER_H
#define MESHTOPO_BENCH_CLUSTER_H

/* argv[0] is "cluster". Returns the exit status (0, 1, 2, or 77 without a
 * private network namespace). */
int mt__bench_cluster_command(int argc, char **argv);

#endif
