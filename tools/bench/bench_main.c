/* The meshtopo-bench executable (also run as `meshtopo bench`):
 *   meshtopo-bench [build] [options]   the core build benchmark (bench.c)
 *   meshtopo-bench rtt [options]       query round trips to meshtopod (rtt.c)
 *   meshtopo-bench transfer [options]  large submissions vs a raw LCM push (bench_transfer.c)
 *   meshtopo-bench archive [options]   archive write and reload vs bare HDF5
 *                                      (bench_archive.c)
 *   meshtopo-bench soak [options]      meshtopod under normal and hostile traffic (soak.c)
 *   meshtopo-bench cluster [options]   1 vs 2 members of a cluster, failover (bench_cluster.c)
 *   meshtopo-bench selfx [options]     self-intersections vs CGAL (bench_selfx.c)
 *   meshtopo-bench inspect [options]   whole-process `meshtopo inspect` and reading vs
 *                                      OpenMesh (bench_inspect.c)
 *   meshtopo-bench map [options]       an mt_map updated block by block vs a full build,
 *                                      OpenMesh and CGAL (bench_map.c) */
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "bench_archive.h"
#include "bench_cluster.h"
#include "bench_inspect.h"
#include "bench_map.h"
#include "bench_selfx.h"
#include "bench_transfer.h"
#include "rtt.h"
#include "soak.h"

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "rtt") == 0) return mt__bench_rtt_command(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "transfer") == 0)
        return mt__bench_transfer_command(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "archive") == 0)
        return mt__bench_archive_command(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "soak") == 0) return mt__bench_soak_command(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "cluster") == 0)
        return mt__bench_cluster_command(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "selfx") == 0)
        return mt__bench_selfx_command(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "inspect") == 0)
        return mt__bench_inspect_command(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "map") == 0) return mt__bench_map_command(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "build") == 0) return mt__bench_command(argc - 1, argv + 1);
    return mt__bench_command(argc, argv);
}
