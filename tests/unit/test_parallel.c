/* The one parallel loop (src/common/parallel.h): every k in [0, count) runs exactly once, k = 0 on the calling
 * thread, all have returned when it returns; counts of 0, 1, a few, and more than its stack bookkeeping holds; and
 * from many threads at once. SPDX-License-Identifier: MIT */
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "common/parallel.h"

typedef struct tally {
    int count;
    int *runs;          /* runs[k]: how many times k ran */
    pthread_t caller;   /* the thread that called the loop */
    int zero_on_caller; /* k = 0 ran there */
} tally;

static void count_run(void *ctx, int k)
{
    tally *t = ctx;
    assert_true(k >= 0 && k < t->count);
    __atomic_fetch_add(&t->runs[k], 1, __ATOMIC_RELAXED);
    if (k == 0) t->zero_on_caller = pthread_equal(pthread_self(), t->caller);
}

static void run_count(int count)
{
    tally t = {count, calloc(count > 0 ? (size_t)count : 1, sizeof(int)), pthread_self(), 0};
    assert_non_null(t.runs);
    ggx_internal_parallel_for(count, count_run, &t);
    for (int k = 0; k < count; k++) assert_int_equal(t.runs[k], 1);
    if (count > 0) assert_true(t.zero_on_caller);
    free(t.runs);
}

static void every_k_once(void **state)
{
    (void)state;
    int counts[] = {0, 1, 2, 3, 16, 64, 65, 200};
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) run_count(counts[i]);
}

static void negative_count_runs_nothing(void **state)
{
    (void)state;
    tally t = {0, NULL, pthread_self(), 0};
    ggx_internal_parallel_for(-3, count_run, &t); /* count_run would fail its assertion on any k */
}

/* partial sums in fixed shares combined in share order: the same bits for every count of threads */
typedef struct sums {
    int shares;
    double part[64];
} sums;

static void share_sum(void *ctx, int k)
{
    sums *s = ctx;
    double acc = 0.0;
    for (int i = k; i < 100000; i += s->shares) acc += 1.0 / (1.0 + i);
    s->part[k] = acc;
}

static void *nested(void *arg)
{
    int *ok = arg;
    for (int rep = 0; rep < 20; rep++) {
        tally t = {8, calloc(8, sizeof(int)), pthread_self(), 0};
        ggx_internal_parallel_for(8, count_run, &t);
        for (int k = 0; k < 8; k++) *ok &= t.runs[k] == 1;
        *ok &= t.zero_on_caller;
        free(t.runs);
    }
    return NULL;
}

static void many_callers(void **state)
{
    (void)state;
    enum { CALLERS = 8 };
    pthread_t th[CALLERS];
    int ok[CALLERS];
    for (int i = 0; i < CALLERS; i++) {
        ok[i] = 1;
        assert_int_equal(pthread_create(&th[i], NULL, nested, &ok[i]), 0);
    }
    for (int i = 0; i < CALLERS; i++) {
        pthread_join(th[i], NULL);
        assert_true(ok[i]);
    }
}

static void shares_combine_alike(void **state)
{
    (void)state;
    sums a = {16, {0}}, b = {16, {0}};
    ggx_internal_parallel_for(16, share_sum, &a);
    for (int k = 0; k < 16; k++) share_sum(&b, k); /* the same shares, one thread */
    assert_memory_equal(a.part, b.part, sizeof a.part);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_k_once),
        cmocka_unit_test(negative_count_runs_nothing),
        cmocka_unit_test(shares_combine_alike),
        cmocka_unit_test(many_callers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
