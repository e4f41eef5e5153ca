/* The meshtopo-bench executable: all of it lives in mt__bench_command so the
 * same benchmark can also run as a subcommand of the meshtopo tool. */
#include "bench.h"

int main(int argc, char **argv)
{
    return mt__bench_command(argc, argv);
}
