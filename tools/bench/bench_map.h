/* `meshtopo-bench map`: an mt_map (meshtopo/map.h) of a TSDF-like surface
 * built block by block, then steps that each replace 1 % of its blocks with
 * changed versions, timed against a full mt_mesh_build of the union and,
 * when their peers are built, against OpenMesh and CGAL Surface_mesh doing
 * the same steps (bench_map.c; the input is map_surface.h). */
#ifndef MESHTOPO_BENCH_MAP_H
#define MESHTOPO_BENCH_MAP_H

/* Entry point: `meshtopo-bench map [options]` (argv[0] is "map"). Returns
 * 0 when everything ran and the map equals a rebuild of its union (missed
 * targets included), 1 when something failed or they differ, 2 on a usage
 * error. */
int mt__bench_map_command(int argc, char **argv);

#endif
