/* The batch API from many threads at once: 8 POSIX threads make the process's FIRST batch call at the same moment
 * (a barrier releases them together), each on its own arrays and shape, and their results must be bit-identical to
 * a single-threaded reference computed afterwards. Meant to be run under ThreadSanitizer (make tsan), which reports
 * any unsynchronised shared state on that path, e.g. a lazily chosen instruction set. This program must make no
 * batch call before the threads start (a fresh process: ctest runs it as its own test).
 * SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ggx/ggx_batch.h"
#include "testlib.h"

enum { NT = 8, N = 4099, REPS = 3 };

typedef struct work {
    int id;
    ggx_shape s;
    float *v[3], *u[2], *m_in[3]; /* inputs */
    float *m[3], *d;              /* outputs: sampled normals, D of m_in */
} work;

static pthread_barrier_t start;

static float *alloc_floats(void)
{
    float *p = malloc(sizeof(float) * N);
    CHECK(p != NULL, "out of memory");
    return p;
}

/* The calls of one thread: even threads sample first, odd threads evaluate first, so that both kernels are entered
 * first somewhere; a few repetitions keep the threads overlapping after the first call. */
static void calls(work *w, float *m[3], float *d)
{
    for (int r = 0; r < REPS; r++) {
        if (w->id % 2) ggx_batch_ndf(d, N, &w->s, w->m_in[0], w->m_in[1], w->m_in[2]);
        ggx_batch_sample_vndf(m[0], m[1], m[2], N, &w->s, w->v[0], w->v[1], w->v[2], w->u[0], w->u[1]);
        if (!(w->id % 2)) ggx_batch_ndf(d, N, &w->s, w->m_in[0], w->m_in[1], w->m_in[2]);
    }
}

static void *worker(void *p)
{
    work *w = p;
    pthread_barrier_wait(&start);
    calls(w, w->m, w->d);
    return NULL;
}

static void first_calls_concurrent(void **state)
{
    (void)state;
    static work w[NT];
    pthread_t tid[NT];
    for (int t = 0; t < NT; t++) {
        w[t].id = t;
        rng r = {700 + (uint64_t)t};
        shape_params p = random_shape(&r, t % 2 ? 0.5 : 0.0);
        if (t % 4 == 0) p.tx = p.ty = p.tz = 0; /* diagonal shapes take another kernel path */
        make_shape(&w[t].s, p);
        for (int k = 0; k < 3; k++) {
            w[t].v[k] = alloc_floats(), w[t].m_in[k] = alloc_floats(), w[t].m[k] = alloc_floats();
        }
        w[t].u[0] = alloc_floats(), w[t].u[1] = alloc_floats(), w[t].d = alloc_floats();
        for (int i = 0; i < N; i++) {
            ggx_vec3 v = random_view(&r), m = t_dir(acos(rng_range(&r, 0.0, 1.0)), rng_range(&r, -GGX_PI, GGX_PI));
            w[t].v[0][i] = (float)v.x, w[t].v[1][i] = (float)v.y, w[t].v[2][i] = (float)v.z;
            w[t].m_in[0][i] = (float)m.x, w[t].m_in[1][i] = (float)m.y, w[t].m_in[2][i] = (float)m.z;
            w[t].u[0][i] = (float)rng_uniform(&r), w[t].u[1][i] = (float)rng_uniform(&r);
        }
    }
    CHECK(pthread_barrier_init(&start, NULL, NT) == 0, "barrier");
    int started = 0;
    for (int t = 0; t < NT; t++) started += pthread_create(&tid[t], NULL, worker, &w[t]) == 0;
    CHECK(started == NT, "only %d of %d threads started", started, NT); /* the barrier would wait forever */
    for (int t = 0; t < NT; t++) pthread_join(tid[t], NULL);
    pthread_barrier_destroy(&start);
    /* the reference: the same calls, one thread after another */
    printf("batch isa %s\n", ggx_batch_isa_name(ggx_batch_get_isa()));
    float *m[3] = {alloc_floats(), alloc_floats(), alloc_floats()}, *d = alloc_floats();
    for (int t = 0; t < NT; t++) {
        calls(&w[t], m, d);
        for (int k = 0; k < 3; k++)
            CHECK(memcmp(m[k], w[t].m[k], sizeof(float) * N) == 0, "thread %d: sample_vndf component %d differs", t, k);
        CHECK(memcmp(d, w[t].d, sizeof(float) * N) == 0, "thread %d: ndf differs", t);
    }
    for (int k = 0; k < 3; k++) free(m[k]);
    free(d);
    for (int t = 0; t < NT; t++) {
        for (int k = 0; k < 3; k++) free(w[t].v[k]), free(w[t].m_in[k]), free(w[t].m[k]);
        free(w[t].u[0]), free(w[t].u[1]), free(w[t].d);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(first_calls_concurrent)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
