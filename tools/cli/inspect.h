/* The pieces of `meshtopo inspect` shared by its files: growing query
 * buffers, the default choice of queried elements (DEFINITIONS.md
 * "Queries"), and the JSON and readable printers. */
#ifndef MESHTOPO_CLI_INSPECT_H
#define MESHTOPO_CLI_INSPECT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "cli.h"
#include "meshtopo/geometry.h"
#include "meshtopo/json_writer.h"
#include "meshtopo/mesh.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"

/* The geometric checks of --self-intersections (whole-mesh queries of
 * meshtopo/geometry.h) and how long they took. */
typedef struct inspect_geometry {
    mt_face_pair *pairs; /* faces passing through or touching each other */
    size_t num_pairs;
    mt_face_shape *faces; /* self-crossing or warped faces */
    size_t num_faces;
    mt_loop_crossing *loops; /* boundary loops crossing themselves */
    size_t num_loops;
    double ms; /* how long the checks took, negative when not known */
} inspect_geometry;

/* Runs the three checks; on failure returns the library's status (diag
 * says why) and leaves *g empty. */
mt_status inspect_geometry_compute(const mt_mesh *mesh, inspect_geometry *g, mt_diag *diag);
void inspect_geometry_free(inspect_geometry *g);
/* Pairs, faces and loops found: what --fail-on-defect counts. */
size_t inspect_geometry_findings(const inspect_geometry *g);
/* The three counts (self_intersecting_pairs, non_simple_faces,
 * self_intersecting_boundary_loops) and the "self_intersections" lists as
 * members of the open JSON object. */
void inspect_geometry_json(mt_json *j, const inspect_geometry *g);
/* Readable: counts, then up to limit items of each list (0 = all). */
void inspect_geometry_text(FILE *out, const inspect_geometry *g, size_t limit);

/* What to print and about which elements. */
typedef struct inspect_request {
    const char *path;                 /* as given on the command line */
    const cli_mesh *mesh;             /* read and built */
    mt_id_list vertices;              /* queried vertices, in order */
    mt_id_list faces;                 /* queried faces, in order */
    bool json_defects;                /* --json-defects: add the defect list to the JSON */
    const inspect_geometry *geometry; /* --self-intersections, else NULL */
    size_t limit;                     /* items per list in the readable output, 0 = all */
} inspect_request;

/* Sorts ids ascending and drops repeats in place; returns the new count. */
size_t inspect_sort_unique(uint32_t *ids, size_t count);

/* How side i of a face (corner i to corner i+1) is used, in the terms of
 * DEFINITIONS.md: uses = faces having it as a side (this one included),
 * same_direction = uses == 2 and the other face runs a -> b as well. */
typedef struct mt_side_use {
    size_t uses;
    bool same_direction;
} mt_side_use;

mt_status inspect_side_use(const mt_mesh *mesh, const mt_face_corners *corners,
                           const mt_face_adjacency *adj, size_t side, mt_face_corners *scratch,
                           mt_side_use *out);

/* Fills the default vertex and/or face queries (DEFINITIONS.md "Queries",
 * chosen by mt_report_json_default_queries). */
mt_status inspect_default_queries(const mt_mesh *mesh, bool want_vertices, mt_id_list *out_vertices,
                                  bool want_faces, mt_id_list *out_faces);

/* The JSON document (the corpus reference answers' keys, in their order,
 * plus "defects" at the end with json_defects). Returns an exit code. */
int inspect_print_json(const inspect_request *req, FILE *out);

/* --blocks SIZE: reads `path`, splits it into blocks of side `size` on the
 * grid (block_split.h), puts them one by one into an mt_map (exact weld)
 * and fills *out as cli_mesh_load would with --weld exact: out->list is
 * mt_map_face_list's union (ids are map ids), out->mesh its build (the map
 * keeps counts only, so the full report comes from that build), out->weld
 * the blocks and what the weld merged. Fails (CLI_EXIT_BUILD, after a
 * message naming the counts) when the map's incremental counts differ from
 * that build's. Returns an exit code, as cli_mesh_load. */
int inspect_blocks_load(const char *path, const char *format_name, uint64_t max_input, double size,
                        cli_mesh *out);

/* The readable summary, then the queried one-rings and face neighbours. */
int inspect_print_text(const inspect_request *req, FILE *out);

#endif
