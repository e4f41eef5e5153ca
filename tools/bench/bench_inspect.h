/* `meshtopo-bench inspect`: whole-process `meshtopo inspect` and reading
 * speed against OpenMesh (bench_inspect.c; the peer is
 * peer_openmesh_inspect.cpp). */
#ifndef MESHTOPO_BENCH_INSPECT_H
#define MESHTOPO_BENCH_INSPECT_H

/* Entry point: `meshtopo-bench inspect [options]` (argv[0] is "inspect").
 * Returns 0 when every run succeeded and the counts agree (a missed target
 * included), 1 when a run failed or the counts disagree, 2 on a usage
 * error. */
int mt__bench_inspect_command(int argc, char **argv);

#endif
