/* The one parallel loop (parallel.h), over POSIX threads. SPDX-License-Identifier: MIT */
#include <pthread.h>
#include <stdlib.h>

#include "parallel.h"

typedef struct task {
    void (*fn)(void *ctx, int k);
    void *ctx;
    int k;
} task;

static void *task_main(void *p)
{
    const task *t = p;
    t->fn(t->ctx, t->k);
    return NULL;
}

enum { STACK_TASKS = 64 };

void ggx_internal_parallel_for(int count, void (*fn)(void *ctx, int k), void *ctx)
{
    if (count < 1) return;
    if (count == 1) {
        fn(ctx, 0);
        return;
    }
    task stack_tasks[STACK_TASKS];
    pthread_t stack_tids[STACK_TASKS];
    int stack_started[STACK_TASKS];
    task *tasks = stack_tasks;
    pthread_t *tids = stack_tids;
    int *started = stack_started;
    if (count > STACK_TASKS) {
        tasks = malloc((size_t)count * sizeof *tasks);
        tids = malloc((size_t)count * sizeof *tids);
        started = malloc((size_t)count * sizeof *started);
        if (!tasks || !tids || !started) { /* no room to track threads: every k here, in order */
            free(tasks), free(tids), free(started);
            for (int k = 0; k < count; k++) fn(ctx, k);
            return;
        }
    }
    for (int k = 1; k < count; k++) {
        tasks[k] = (task){fn, ctx, k};
        started[k] = pthread_create(&tids[k], NULL, task_main, &tasks[k]) == 0;
    }
    fn(ctx, 0);
    for (int k = 1; k < count; k++) {
        if (started[k]) pthread_join(tids[k], NULL);
        else fn(ctx, k);
    }
    if (tasks != stack_tasks) free(tasks), free(tids), free(started);
}
