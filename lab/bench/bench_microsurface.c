/* Benchmark of the microsurfaces (libs/microsurface): the time to make a Gaussian field (n = 1024 to 4096), the
 * tracer's build, and first-hit rays per second from a 45 degree view on 1 and 2 threads, from random origins over
 * the tile, from a jittered grid of origins taken row by row (coherent rays), one ray at a time and in streams, and
 * from one origin a cell in streams, with the process's peak memory. Then measured patches (ms_patch_new): a scan
 * (argv[1], e.g. tests/data/x3p/KautschukInfiniteFocus.x3p, levelled by its mean only) and a 2048 x 2048 Gaussian
 * field traced as a patch: ms_measure_g1's and ms_measure_brdf's rays per second on 1 and 2 threads, and the ceiling,
 * Embree's own first hits on the same grid from the same jittered rows (rtcIntersect1M streams of 64, and packets
 * of 16) with nothing else done. Prints; never fails. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <string.h>
#include <time.h>

#include "common/parallel.h"
#include "microsurface.h"
#include "surface.h"
#ifdef GGX_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

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

#ifdef GGX_HAVE_EMBREE
/* the ceiling: Embree alone on the patch's grid (missing points at the lowest height, no filter), first hits of a
 * g x g jittered grid of rays along d, rows [row0, row1) in streams of 64 (packet 0) or packets of 16 (packet 1) */
typedef struct ceiling_job {
    RTCScene scene;
    double w[4], z, d[3];
    long g, row0, row1, hits;
    int packet;
} ceiling_job;

static void ceiling_rows(void *p)
{
    ceiling_job *j = p;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    uint64_t s = 7;
    double sx = (j->w[2] - j->w[0]) / (double)j->g, sy = (j->w[3] - j->w[1]) / (double)j->g;
    for (long r = j->row0; r < j->row1; r++)
        for (long c0 = 0; c0 < j->g; c0 += 64) {
            struct RTCRayHit rh[64];
            int m = j->g - c0 < 64 ? (int)(j->g - c0) : 64;
            for (int i = 0; i < m; i++) {
                s ^= s << 13, s ^= s >> 7, s ^= s << 17;
                double u = (double)(s >> 11) * 0x1p-53;
                struct RTCRay *y = &rh[i].ray;
                y->org_x = (float)(j->w[0] + ((double)(c0 + i) + u) * sx),
                y->org_y = (float)(j->w[1] + ((double)r + u) * sy);
                y->org_z = (float)j->z, y->dir_x = (float)j->d[0], y->dir_y = (float)j->d[1], y->dir_z = (float)j->d[2];
                y->tnear = 0.0f, y->tfar = INFINITY, y->mask = 0xFFFFFFFFu, y->flags = 0, y->time = 0.0f;
                rh[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
            }
            if (!j->packet) {
                rtcIntersect1M(j->scene, &ctx, rh, (unsigned)m, sizeof rh[0]);
                for (int i = 0; i < m; i++) j->hits += rh[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
                continue;
            }
            for (int q = 0; q < m; q += 16) {
                struct RTCRayHit16 pk;
                int valid[16];
                for (int i = 0; i < 16; i++) {
                    const struct RTCRay *y = &rh[q + i < m ? q + i : q].ray;
                    valid[i] = q + i < m ? -1 : 0;
                    pk.ray.org_x[i] = y->org_x, pk.ray.org_y[i] = y->org_y, pk.ray.org_z[i] = y->org_z;
                    pk.ray.dir_x[i] = y->dir_x, pk.ray.dir_y[i] = y->dir_y, pk.ray.dir_z[i] = y->dir_z;
                    pk.ray.tnear[i] = 0.0f, pk.ray.tfar[i] = INFINITY, pk.ray.mask[i] = 0xFFFFFFFFu;
                    pk.ray.flags[i] = 0, pk.ray.time[i] = 0.0f, pk.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
                }
                rtcIntersect16(valid, j->scene, &ctx, &pk);
                for (int i = 0; i < 16; i++) j->hits += valid[i] && pk.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
            }
        }
}

static void ceiling_share(void *ctx, int k) { ceiling_rows((ceiling_job *)ctx + k); }

/* Embree's first hits per second (millions) on the grid of h (nx x ny) for the window w at height z along d */
static double ceiling(const double *h, size_t nx, size_t ny, const double w[4], double z, const double d[3],
                      int threads, int packet)
{
    RTCDevice dev = rtcNewDevice(NULL);
    RTCScene sc = rtcNewScene(dev);
    rtcSetSceneBuildQuality(sc, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(sc, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_GRID);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nx * ny);
    struct RTCGrid *gr = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, sizeof *gr, 1);
    double lo = HUGE_VAL;
    for (size_t i = 0; i < nx * ny; i++)
        if (!isnan(h[i])) lo = fmin(lo, h[i]);
    for (size_t i = 0; i < nx * ny; i++)
        v[3 * i] = (float)(i % nx), v[3 * i + 1] = (float)(i / nx), v[3 * i + 2] = (float)(isnan(h[i]) ? lo : h[i]);
    gr->startVertexID = 0, gr->stride = (unsigned)nx, gr->width = (unsigned short)nx, gr->height = (unsigned short)ny;
    rtcCommitGeometry(g);
    rtcAttachGeometry(sc, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(sc);
    long side = 2000;
    ceiling_job jobs[2];
    for (int k = 0; k < threads; k++)
        jobs[k] = (ceiling_job){sc,
                                {w[0], w[1], w[2], w[3]},
                                z,
                                {d[0], d[1], d[2]},
                                side,
                                side * k / threads,
                                side * (k + 1) / threads,
                                0,
                                packet};
    double t0 = now();
    ggx_internal_parallel_for(threads, ceiling_share, jobs);
    double rate = (double)(side * side) / (now() - t0) / 1e6;
    rtcReleaseScene(sc);
    rtcReleaseDevice(dev);
    return rate;
}
#endif

/* A patch's rates: ms_measure_g1 (4 million rays) and ms_measure_brdf (1 million rays, up to 100 bounces) per
 * second from 60 degrees, on 1 and 2 threads, and the ceiling */
static void bench_patch(const char *name, const double *h, size_t nx, size_t ny)
{
    char err[400];
    double t0 = now();
    ms_tracer *t = ms_patch_new(h, nx, ny, err, sizeof err);
    double t1 = now();
    if (!t) {
        printf("%-28s %s\n", name, err);
        return;
    }
    double v[3] = {sin(1.0471976), 0.0, cos(1.0471976)}, r[4];
    for (int k = 0; k < 4; k++) {
        int threads = 1 + k % 2;
        ms_g1 g;
        ms_brdf b;
        double s0 = now();
        long rays = k < 2 ? 4000000 : 1000000;
        int ok = k < 2 ? ms_measure_g1(t, NULL, 0, v, rays, 4, 8, NULL, threads, &g, err, sizeof err)
                       : ms_measure_brdf(t, 0, v, rays, 8, 16, 100, threads, &b, err, sizeof err);
        r[k] = ok == 0 ? (double)(k < 2 ? g.rays : b.rays) / (now() - s0) / 1e6 : NAN;
        if (ok == 0 && k < 2) ms_g1_free(&g);
        if (ok == 0 && k >= 2) ms_brdf_free(&b);
    }
    double c[4] = {NAN, NAN, NAN, NAN};
#ifdef GGX_HAVE_EMBREE
    double w[4], d[3] = {-v[0], -v[1], -v[2]};
    if (ms_patch_window(t, v, 0, w, err, sizeof err) == 0)
        for (int k = 0; k < 4; k++) c[k] = ceiling(h, nx, ny, w, ms_patch_top(t), d, 1 + k % 2, k / 2);
#endif
    printf("%-28s %5zu x %-5zu %7.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f\n", name, nx, ny, t1 - t0, r[0],
           r[1], r[2], r[3], c[0], c[1], c[2], c[3]);
    ms_tracer_free(t);
}

/* the measured patches: the scan at path (if it reads) and a 2048 x 2048 Gaussian field */
static void patches(const char *path)
{
    printf("\nmeasured patches (ms_patch_new), view 60 degrees: Mrays/s of ms_measure_g1 (4e6 first hits: binning and "
           "the facets' pass included) and ms_measure_brdf (1e6 paths, each up to 100 bounces), on 1 and 2 threads; "
           "the ceiling: Embree alone, first hits of 4e6 rays from the same window in streams of 64 (strm) and "
           "packets of 16 (pk16)\n");
    printf("%-28s %-13s %7s %8s %8s %8s %8s %8s %8s %8s %8s\n", "surface", "size", "build s", "G1 1", "G1 2", "BRDF 1",
           "BRDF 2", "strm 1", "strm 2", "pk16 1", "pk16 2");
    surface s;
    surface_read_options ro = {SURFACE_HEIGHTS, 0};
    char err[400];
    if (path && surface_read(path, &ro, &s, err, sizeof err) == 0) {
        double scale = (s.z_scale > 0 ? s.z_scale : 1.0) / (s.dx > 0 ? s.dx : 1.0), sum = 0.0, cnt = 0.0;
        for (size_t i = 0; i < s.nx * s.ny; i++)
            if (isfinite(s.h[i])) sum += s.h[i] * scale, cnt += 1.0;
        for (size_t i = 0; i < s.nx * s.ny; i++) s.h[i] = isfinite(s.h[i]) ? s.h[i] * scale - sum / cnt : NAN;
        const char *base = strrchr(path, '/');
        bench_patch(base ? base + 1 : path, s.h, s.nx, s.ny);
        surface_free(&s);
    } else if (path) {
        printf("%s: %s\n", path, err);
    }
    size_t n = 2048;
    double *h = malloc(n * n * sizeof *h);
    ms_gauss_spec sp = {n, 0.3, 0.3, 0.0, 16.0, 1};
    if (h && ms_gauss(&sp, h, NULL, err, sizeof err) == 0) bench_patch("Gaussian field (a patch)", h, n, n);
    else printf("Gaussian field: %s\n", h ? err : "out of memory");
    free(h);
}

int main(int argc, char **argv)
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
    patches(argc > 1 ? argv[1] : NULL);
    return 0;
}
