/* Shared machinery of the edits (edit_*.c): an edit context with an undo log
 * (every array write goes through it, so a refused or failed edit is rolled
 * back to the exact bytes it started from), array growth, and the two
 * primitives every edit is made of: removing a face and inserting one (the
 * face insertion and deletion of pmp-library's SurfaceMesh). */
#ifndef MESHTOPO_EDIT_INTERNAL_H
#define MESHTOPO_EDIT_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "mesh/mesh_internal.h"

/* One logged write: array, index and the value it held. */
enum { MT__A_HEAD, MT__A_NEXT, MT__A_FACE, MT__A_FACE_HE, MT__A_VERT_HE, MT__A_COMP, MT__A_DEL };
typedef struct mt__undo {
    uint32_t array, index, old;
} mt__undo;

/* An edit in progress. */
typedef struct mt__edit {
    mt_mesh *m;
    mt__edit_state *s;
    mt_diag *diag;
    mt_status status; /* MT_ERR_NOMEM once a write could not be logged */
    /* Counts at the start, restored by a rollback. */
    uint32_t num_verts, num_faces, num_half_edges, num_faces_valid, num_deleted_verts;
    uint32_t report_verts; /* the report's V: live vertices */
    uint64_t num_edges;
    int64_t euler;
    /* One vertex position an edit may move (MT_NONE: none moved). */
    uint32_t moved_vert;
    double moved_pos[3];
} mt__edit;

/* Starts an edit: checks the mesh is editable (MT_ERR_UNSUPPORTED when it
 * has copies or bundles) and saves the counts. `what` names the edit in
 * messages. */
mt_status mt__edit_begin(mt__edit *e, mt_mesh *m, mt_diag *diag, const char *what);

/* Ends an edit that went through: checks that every touched vertex keeps one
 * fan with at most one boundary gap and distinct neighbours (else rolls back
 * and returns MT_ERR_REFUSED naming it), then counts the edit. */
mt_status mt__edit_finish(mt__edit *e);

/* Undoes every logged write and restores the counts; returns `status` so
 * failures read `return mt__edit_abort(e, st)`. */
mt_status mt__edit_abort(mt__edit *e, mt_status status);

/* Makes room for `writes` more log entries. */
mt_status mt__edit_reserve(mt__edit *e, size_t writes);

/* Logged writes. */
void mt__edit_set(mt__edit *e, uint32_t array, uint32_t index, uint32_t value);
static inline void mt__set_next(mt__edit *e, uint32_t h, uint32_t v)
{
    mt__edit_set(e, MT__A_NEXT, h, v);
}
static inline void mt__set_vert_he(mt__edit *e, uint32_t v, uint32_t h)
{
    mt__edit_set(e, MT__A_VERT_HE, v, h);
}

/* New elements: a vertex (positions grow; pos NULL = origin), a face id (its
 * face_he MT_NONE until a face is inserted under it), an edge a -> b (the
 * half-edge from a to b is returned; next pointers unset). */
mt_status mt__edit_new_vert(mt__edit *e, const double *pos, uint32_t *out_vert);
mt_status mt__edit_new_face(mt__edit *e, uint32_t *out_face);
mt_status mt__edit_new_edge(mt__edit *e, uint32_t a, uint32_t b, uint32_t *out_he);
/* Moves a vertex (once per edit; the old position is restored on rollback). */
void mt__edit_move_vert(mt__edit *e, uint32_t v, const double *pos);
/* Marks an isolated vertex deleted. */
mt_status mt__edit_delete_vert(mt__edit *e, uint32_t v);
/* Notes a vertex for the final check. */
mt_status mt__edit_touch(mt__edit *e, uint32_t v);

/* Half-edge from a to b, MT_NONE when there is none. O(valence of a). */
uint32_t mt__edit_find_he(const mt_mesh *m, uint32_t a, uint32_t b);
/* The half-edge whose next is h, by rotation around h's tail. O(valence). */
uint32_t mt__edit_prev(const mt_mesh *m, uint32_t h);
/* Points v's outgoing half-edge at a boundary one when v has one. */
void mt__edit_adjust_vert(mt__edit *e, uint32_t v);
/* Number of valid faces around v / boundary half-edges leaving v. */
uint32_t mt__vert_valence(const mt_mesh *m, uint32_t v);
bool mt__vert_on_boundary(const mt_mesh *m, uint32_t v);

/* Appends the caller vertex ids of face f (stored order, first vertex first)
 * to vec; returns how many, 0 when f is not a live face. */
uint32_t mt__face_collect(const mt_mesh *m, uint32_t f, mt__vec *vec);

/* Rotates a cyclic vertex list so that it starts at `first` (left as it is
 * when `first` is not in it). */
void mt__list_rotate_to(uint32_t *list, uint32_t n, uint32_t first);

/* Checks of a caller vertex id: MT_OK, or OUT_OF_RANGE / NOT_FOUND (deleted)
 * with a message naming `what`. */
mt_status mt__edit_check_vert(mt__edit *e, uint32_t v, const char *what);
/* Edge a-b: half-edge a -> b in *out_he, or the status (with a message). */
mt_status mt__edit_check_edge(mt__edit *e, uint32_t a, uint32_t b, const char *what,
                              uint32_t *out_he);
/* Face id: MT_OK for a live face. */
mt_status mt__edit_check_face(mt__edit *e, uint32_t f, const char *what);

/* Removes face f (edit_delete.c): its sides become boundary, edges left
 * without faces are deleted, vertices left without faces become isolated.
 * Intermediate states may hold vertices with several boundary gaps. */
mt_status mt__face_remove(mt__edit *e, uint32_t f);

/* Inserts face verts[0..n) under id `face` (edit_add_face.c), whose record
 * must be empty. strict refuses what would make the mesh non-manifold;
 * non-strict also accepts intermediate states (a vertex with several fans)
 * that a later insertion of the same edit joins up. Checks come before any
 * write: a refusal changes nothing. */
mt_status mt__face_insert(mt__edit *e, const uint32_t *verts, uint32_t n, uint32_t face,
                          bool strict);

#endif
