/* Helpers shared by the daemon tests (see daemon_test_util.h). */
#include "daemon_test_util.h"

#include <time.h>

#include "harness.h"

mt_mesh *dt_build_platonic(mt_platonic kind)
{
    mt_face_list fl;
    mt_status s = mt_gen_platonic(kind, &fl);
    if (s != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "mt_gen_platonic: %s", mt_strerror(s));
        return NULL;
    }
    mt_mesh *mesh = NULL;
    mt_diag diag;
    s = mt_mesh_build(&fl, NULL, &mesh, &diag);
    mt_face_list_free(&fl);
    if (s != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "mt_mesh_build: %s", diag.message);
        return NULL;
    }
    dt_check_valid(mesh, __FILE__, __LINE__);
    return mesh;
}

uint32_t dt_platonic_verts(mt_platonic kind)
{
    static const uint32_t verts[] = {4, 8, 6, 20, 12};
    return verts[kind];
}

void dt_check_valid(const mt_mesh *mesh, const char *file, int line)
{
    mt_diag diag;
    if (!mesh) {
        mt_test_fail(file, line, "no mesh to validate");
        return;
    }
    if (mt_mesh_validate(mesh, &diag) != MT_OK)
        mt_test_fail(file, line, "mt_mesh_validate: %s", diag.message);
}

void dt_gate_init(dt_gate *gate)
{
    pthread_mutex_init(&gate->lock, NULL);
    pthread_cond_init(&gate->cond, NULL);
    gate->open = false;
}

void dt_gate_destroy(dt_gate *gate)
{
    pthread_cond_destroy(&gate->cond);
    pthread_mutex_destroy(&gate->lock);
}

void dt_gate_open(dt_gate *gate)
{
    pthread_mutex_lock(&gate->lock);
    gate->open = true;
    pthread_cond_broadcast(&gate->cond);
    pthread_mutex_unlock(&gate->lock);
}

void dt_gate_wait(dt_gate *gate)
{
    pthread_mutex_lock(&gate->lock);
    while (!gate->open) pthread_cond_wait(&gate->cond, &gate->lock);
    pthread_mutex_unlock(&gate->lock);
}

void dt_sleep_ms(unsigned ms)
{
    struct timespec ts = {(time_t)(ms / 1000), (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}
