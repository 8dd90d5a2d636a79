/* Benchmark of the microsurfaces (libs/microsurface): the time to make a Gaussian field (n = 1024 to 4096), the
 * tracer's build, and first-hit rays per second from a 45 degree view on 1 and 2 threads, from random origins over
 * the tile, from a jittered grid of origins taken row by row (coherent rays), one ray at a time and in streams, and
 * from one origin a cell in streams, with the process's peak memory. Prints; never fails.
 * SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>

#include "common/parallel.h"
#include "microsurface.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct job {
    const ms_tracer *t;
    size_t n;
    long rays, hits;
    uint64_t seed;
    int coherent; /* origins on a jittered 1000 x 1000 grid over the tile, row by row (this job's rows) */
    int row0, rows;
    long g; /* shoot_rows: the grid's side */
} job;

/* rows of origins through ms_trace_coherent: a jittered grid of g x g origins over the tile (this job's rows) */
static void *shoot_rows(void *p)
{
    job *j = p;
    double zmin, zmax, d[3] = {-sin(0.785398), 0.0, -cos(0.785398)};
    ms_tracer_bounds(j->t, &zmin, &zmax);
    uint64_t s = j->seed;
    long g = j->g;
    double *o = malloc(3 * (size_t)g * sizeof *o), step = (double)j->n / (double)g;
    ms_hit *hits = malloc((size_t)g * sizeof *hits);
    int *res = malloc((size_t)g * sizeof *res);
    for (long r = j->row0; o && hits && res && r < j->row0 + j->rows; r++) {
        for (long c = 0; c < g; c++) {
            s ^= s << 13, s ^= s >> 7, s ^= s << 17;
            double u = (double)(s >> 11) * 0x1p-53;
            s ^= s << 13, s ^= s >> 7, s ^= s << 17;
            double v = (double)(s >> 11) * 0x1p-53;
            o[3 * c] = ((double)c + u) * step, o[3 * c + 1] = ((double)r + v) * step, o[3 * c + 2] = zmax + 1.0;
        }
        ms_trace_coherent(j->t, (size_t)g, o, d, hits, res);
        for (long c = 0; c < g; c++) j->hits += res[c] == 1;
    }
    free(o), free(hits), free(res);
    return NULL;
}

static void *shoot(void *p)
{
    job *j = p;
    double zmin, zmax, d[3] = {-sin(0.785398), 0.0, -cos(0.785398)};
    ms_tracer_bounds(j->t, &zmin, &zmax);
    uint64_t s = j->seed;
    for (long i = 0; i < j->rays; i++) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        double u = (double)(s >> 11) * 0x1p-53;
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        double v = (double)(s >> 11) * 0x1p-53;
        double o[3] = {u * (double)j->n, v * (double)j->n, zmax + 1.0};
        if (j->coherent) {
            long cell = (long)j->row0 * 1000 + i;
            o[0] = ((double)(cell % 1000) + u) * (double)j->n / 1000.0;
            o[1] = ((double)(cell / 1000) + v) * (double)j->n / 1000.0;
        }
        ms_hit hit;
        j->hits += ms_trace(j->t, o, d, &hit) == 1;
    }
    return NULL;
}

/* share k of a timed run: job k, by rows of streams or ray by ray */
typedef struct bench_run {
    job *jobs;
    int stream;
} bench_run;

static void bench_share(void *ctx, int k)
{
    const bench_run *b = ctx;
    if (b->stream) shoot_rows(&b->jobs[k]);
    else shoot(&b->jobs[k]);
}

int main(void)
{
    printf("libggx microsurface benchmark: Gaussian fields (alpha 0.3, correlation length 16) and first hits\n\n");
    printf("Mrays/s: 10^6 rays from random origins over the tile; (scan) from a jittered 1000 x 1000 grid of origins\n"
           "row by row; (stream) the same rows through ms_trace_coherent (Embree's streams of coherent rays); (dense)\n"
           "n x n origins, one a cell, row by row through ms_trace_coherent\n");
    printf("%-6s %9s %9s %8s %8s %8s %8s %8s %8s %8s %8s %8s\n", "n", "gen, s", "build, s", "1 thr", "2 thr", "scan 1",
           "scan 2", "strm 1", "strm 2", "dense 1", "dense 2", "peak MB");
    const size_t sizes[] = {1024, 2048, 4096};
    for (int k = 0; k < 3; k++) {
        size_t n = sizes[k];
        double *h = malloc(n * n * sizeof *h);
        char err[300];
        ms_gauss_spec sp = {n, 0.3, 0.3, 0.0, 16.0, 1};
        double t0 = now();
        if (!h || ms_gauss(&sp, h, NULL, err, sizeof err) != 0) {
            printf("%-6zu %s\n", n, h ? err : "out of memory");
            free(h);
            continue;
        }
        double t1 = now();
        ms_tracer *t = ms_tracer_new(h, n, NULL, err, sizeof err);
        double t2 = now();
        free(h);
        if (!t) {
            printf("%-6zu %12.2f %s\n", n, t1 - t0, err);
            continue;
        }
        double rate[8];
        for (int mode = 0; mode < 8; mode++) {
            int threads = 1 + mode % 2, coherent = mode / 2 >= 1, stream = mode / 2 >= 2;
            long g = mode / 2 == 3 ? (long)n : 1000, rays = stream ? g * g : 1000000;
            job jobs[2];
            double s0 = now();
            for (int i = 0; i < threads; i++) {
                int r0 = (int)(g * i / threads), r1 = (int)(g * (i + 1) / threads);
                jobs[i] = (job){t,
                                n,
                                1000000 / threads,
                                0,
                                99u + (uint64_t)i,
                                coherent,
                                stream ? r0 : 1000 / threads * i,
                                stream ? r1 - r0 : 1000 / threads,
                                g};
            }
            bench_run run = {jobs, stream};
            ggx_internal_parallel_for(threads, bench_share, &run);
            rate[mode] = (double)rays / (now() - s0) / 1e6;
        }
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        printf("%-6zu %9.2f %9.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.0f\n", n, t1 - t0, t2 - t1,
               rate[0], rate[1], rate[2], rate[3], rate[4], rate[5], rate[6], rate[7], (double)ru.ru_maxrss / 1024.0);
        ms_tracer_free(t);
    }
    return 0;
}
