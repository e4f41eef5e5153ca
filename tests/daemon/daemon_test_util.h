/* Helpers shared by the daemon tests: small built meshes, checked with
 * mt_mesh_validate, and a one-shot gate for holding a thread at a point. */
#ifndef MESHTOPO_TEST_DAEMON_UTIL_H
#define MESHTOPO_TEST_DAEMON_UTIL_H

#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>

#include "meshtopo/core.h"

/* Builds a Platonic solid and validates it; NULL (failure recorded) on error. */
mt_mesh *dt_build_platonic(mt_platonic kind);

/* Vertex count of each Platonic solid, for checking which one a mesh is. */
uint32_t dt_platonic_verts(mt_platonic kind);

/* Records a failure unless mesh validates. */
void dt_check_valid(const mt_mesh *mesh, const char *file, int line);
#define DT_CHECK_VALID(mesh) dt_check_valid((mesh), __FILE__, __LINE__)

/* A gate threads wait at until it is opened. */
typedef struct dt_gate {
    pthread_mutex_t lock;
    pthread_cond_t cond;
    bool open;
} dt_gate;

void dt_gate_init(dt_gate *gate);
void dt_gate_destroy(dt_gate *gate);
void dt_gate_open(dt_gate *gate);
void dt_gate_wait(dt_gate *gate);

/* Sleeps about `ms` milliseconds. */
void dt_sleep_ms(unsigned ms);

#endif
