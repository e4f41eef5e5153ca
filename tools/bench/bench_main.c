/* The meshtopo-bench executable (also run as `meshtopo bench`):
 *   meshtopo-bench [build] [options]   the core build benchmark (bench.c)
 *   meshtopo-bench rtt [options]       query round trips to meshtopod (rtt.c) */
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "rtt.h"

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "rtt") == 0) return mt__bench_rtt_command(argc - 1, argv + 1);
    if (argc > 1 && strcmp(argv[1], "build") == 0) return mt__bench_command(argc - 1, argv + 1);
    return mt__bench_command(argc, argv);
}
