/* The fits from many threads at once (ggx_fit.h: any number of concurrent calls, results independent of the
 * options' thread count): 4 POSIX threads released together, each fitting its own normals with 1, 2, 3 or 5 worker
 * threads of its own, and a height field; every result bit-identical to a single-threaded reference computed
 * afterwards. Meant for ThreadSanitizer (make tsan) as well as the plain suite. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ggx/ggx_fit.h"
#include "testlib.h"

enum { NT = 4, N = 140000 }; /* 3 units of 65536 samples: the worker threads share the passes */

typedef struct work {
    int id;
    ggx_shape s, out;
    ggx_vec3 *m;
    double *h;
    ggx_fit_info info, hinfo;
    ggx_shape hout;
    ggx_status st, hst;
} work;

static pthread_barrier_t start;

static void *run(void *arg)
{
    work *w = arg;
    ggx_fit_options o;
    memset(&o, 0, sizeof o);
    o.threads = (const int[]){1, 2, 3, 5}[w->id];
    pthread_barrier_wait(&start);
    w->st = ggx_fit_normals(&w->out, w->m, NULL, N, &o, &w->info);
    w->hst = ggx_fit_heightfield(&w->hout, w->h, 300, 200, 1.0, 1.0, NULL, &o, &w->hinfo);
    return NULL;
}

static void concurrent_fits(void **state)
{
    (void)state;
    work w[NT];
    rng r = {43};
    for (int k = 0; k < NT; k++) {
        memset(&w[k], 0, sizeof w[k]);
        w[k].id = k;
        make_shape(&w[k].s, (shape_params){0.1 + 0.1 * k, 0.3, 0.2 * k, -0.1, 0.5 * k});
        w[k].m = malloc(N * sizeof *w[k].m);
        for (int i = 0; i < N; i++) w[k].m[i] = ggx_sample_ndf(&w[k].s, rng_uniform(&r), rng_uniform(&r));
        w[k].h = malloc(300 * 200 * sizeof *w[k].h);
        for (int i = 0; i < 300 * 200; i++) w[k].h[i] = rng_range(&r, -0.1, 0.1) + 0.01 * (i % 300);
    }
    pthread_barrier_init(&start, NULL, NT);
    pthread_t tid[NT];
    for (int k = 0; k < NT; k++) pthread_create(&tid[k], NULL, run, &w[k]);
    for (int k = 0; k < NT; k++) pthread_join(tid[k], NULL);
    pthread_barrier_destroy(&start);
    for (int k = 0; k < NT; k++) {
        ggx_shape ref, href;
        ggx_fit_info info, hinfo;
        CHECK(w[k].st == GGX_OK && w[k].hst == GGX_OK, "thread %d: %d %d", k, (int)w[k].st, (int)w[k].hst);
        assert_int_equal(ggx_fit_normals(&ref, w[k].m, NULL, N, NULL, &info), GGX_OK);
        assert_int_equal(ggx_fit_heightfield(&href, w[k].h, 300, 200, 1.0, 1.0, NULL, NULL, &hinfo), GGX_OK);
        CHECK(memcmp(&ref, &w[k].out, sizeof ref) == 0 && memcmp(&info, &w[k].info, sizeof info) == 0,
              "thread %d (%d workers): normals' fit differs from the serial one", k, k);
        CHECK(memcmp(&href, &w[k].hout, sizeof href) == 0 && memcmp(&hinfo, &w[k].hinfo, sizeof hinfo) == 0,
              "thread %d: height field's fit differs", k);
        free(w[k].m), free(w[k].h);
    }
    printf("concurrent_fits: %d threads with 1, 2, 3 and 5 workers, bit-identical to the serial fits\n", NT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(concurrent_fits)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
