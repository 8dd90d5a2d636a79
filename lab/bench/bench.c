/* libggx benchmarks: ns per call (median of 9 runs after a warm-up) for the scalar double API and for every batch
 * kernel on every instruction-set path, at an n that fits in L1 and at 64 MiB of data, with 1 and 2 threads; ratios
 * within the same run; instructions per sample where perf counters are available; and the two floors of the batch
 * VNDF sampler: arithmetic (its operations at the measured peak) and memory (its bytes at the measured copy
 * bandwidth); and plain transcriptions of the same formulas (lab/bench/reference.c) timed beside the library on the same
 * inputs, with checks that they compute the same values. Never part of the test suite. SPDX-License-Identifier: MIT */
#define _GNU_SOURCE
#include <immintrin.h>
#include <linux/perf_event.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include "ggx/ggx.h"
#include "ggx/ggx_batch.h"
#include "ggx/ggx_inline.h"
#include "reference.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Instructions retired, or -1 when the machine has no counters (virtual machines often don't). */
static int perf_fd = -2;
static long long instr_begin(void)
{
    if (perf_fd == -2) {
        struct perf_event_attr a;
        memset(&a, 0, sizeof a);
        a.size = sizeof a;
        a.type = PERF_TYPE_HARDWARE;
        a.config = PERF_COUNT_HW_INSTRUCTIONS;
        a.exclude_kernel = 1;
        a.exclude_hv = 1;
        perf_fd = (int)syscall(SYS_perf_event_open, &a, 0, -1, -1, 0);
    }
    if (perf_fd < 0) return -1;
    long long v;
    if (read(perf_fd, &v, sizeof v) != sizeof v) return -1;
    return v;
}

static volatile double sink;

typedef void (*bench_fn)(void *ctx, long n);

/* Median ns per call of fn over 9 runs of n calls after one warm-up run; *ipc_out instructions per call or -1. */
static double time_it(bench_fn fn, void *ctx, long n, double *instr)
{
    double t[9];
    fn(ctx, n);
    long long i0 = instr_begin();
    for (int r = 0; r < 9; r++) {
        double a = now();
        fn(ctx, n);
        t[r] = (now() - a) / n * 1e9;
    }
    long long i1 = instr_begin();
    if (instr) *instr = (i0 >= 0 && i1 >= 0) ? (double)(i1 - i0) / (9.0 * n) : -1;
    qsort(t, 9, sizeof t[0], cmp);
    return t[4];
}

/* A library function against its reference: the two are timed alternately, 9 rounds, and the ratio is the median
 * of the per-round ratios, so that a drift of the machine's speed between the two timings (a shared host) does not
 * enter the ratio. *tr and *tl get the medians of each. */
static double time_pair(bench_fn ref, const ggx_shape *ref_s, bench_fn lib, const ggx_shape *lib_s,
                        const ggx_shape **slot, void *ctx, long n, double *tr, double *tl)
{
    double a[9], b[9], q[9];
    *slot = ref_s, ref(ctx, n);
    *slot = lib_s, lib(ctx, n);
    for (int r = 0; r < 9; r++) {
        double t0 = now();
        *slot = ref_s, ref(ctx, n);
        double t1 = now();
        *slot = lib_s, lib(ctx, n);
        double t2 = now();
        a[r] = (t1 - t0) / n * 1e9, b[r] = (t2 - t1) / n * 1e9, q[r] = b[r] / a[r];
    }
    qsort(a, 9, sizeof a[0], cmp), qsort(b, 9, sizeof b[0], cmp), qsort(q, 9, sizeof q[0], cmp);
    *tr = a[4], *tl = b[4];
    return q[4];
}

/* ---------------------------------------------------------------- scalar double */

enum { NS = 4096 };
typedef struct sctx {
    const ggx_shape *s;
    ggx_fresnel f;
    ggx_vec3 v[NS], m[NS];
    double u1[NS], u2[NS];
    float ax, ay, fv[NS][3], fu1[NS], fu2[NS]; /* the same inputs in float, for the float reference */
    ggx_shapef sf;                             /* s in float, for the inline float kernels */
    const ggx_sggx *g;                         /* a flake distribution, for the SGGX table */
} sctx;

#define SCALAR_BENCH(name, expr)                                                                                       \
    static void name(void *vc, long n)                                                                                 \
    {                                                                                                                  \
        sctx *c = vc;                                                                                                  \
        double acc = 0;                                                                                                \
        for (long i = 0; i < n; i++) {                                                                                 \
            long k = i & (NS - 1);                                                                                     \
            (void)k;                                                                                                   \
            acc += expr;                                                                                               \
        }                                                                                                              \
        sink = acc;                                                                                                    \
    }
SCALAR_BENCH(b_ndf, ggx_ndf(c->s, c->m[k]))
SCALAR_BENCH(b_g1, ggx_g1(c->s, c->v[k], c->m[k]))
SCALAR_BENCH(b_pdf, ggx_pdf_vndf(c->s, c->v[k], c->m[k]))
SCALAR_BENCH(b_brdf, ggx_brdf_eval(c->s, &c->f, c->v[k], c->m[k]))
SCALAR_BENCH(b_caps, ggx_sample_vndf_caps(c->s, c->v[k], c->u1[k], c->u2[k]).z)
SCALAR_BENCH(b_crescent, ggx_sample_vndf_crescent(c->s, c->v[k], c->u1[k], c->u2[k]).z)
SCALAR_BENCH(b_heitz, ggx_sample_vndf_heitz(c->s, c->v[k], c->u1[k], c->u2[k]).z)
SCALAR_BENCH(b_stretch, ggx_sample_ndf_stretch(c->s, c->u1[k], c->u2[k]).z)
SCALAR_BENCH(b_sbrdf, ggx_sample_brdf(c->s, &c->f, c->v[k], c->u1[k], c->u2[k]).weight)
SCALAR_BENCH(b_vndf, ggx_sample_vndf(c->s, c->v[k], c->u1[k], c->u2[k]).z)
SCALAR_BENCH(b_sbrdfb, ggx_sample_brdf_bounded(c->s, &c->f, c->v[k], c->u1[k], c->u2[k]).weight)
SCALAR_BENCH(b_sbrdfa, ggx_sample_brdf_bounded_azimuth(c->s, &c->f, c->v[k], c->u1[k], c->u2[k]).weight)
SCALAR_BENCH(b_sggx_ndf, ggx_sggx_ndf(c->g, c->m[k]))
SCALAR_BENCH(b_sggx_vndf, ggx_sggx_sample_vndf(c->g, c->v[k], c->u1[k], c->u2[k]).z)
SCALAR_BENCH(b_sggx_spec, ggx_sggx_phase_specular(c->g, c->v[k], c->m[k]))
SCALAR_BENCH(b_sggx_diff, ggx_sggx_phase_diffuse(c->g, c->v[k], c->m[k]))
SCALAR_BENCH(b_sggx_sdiff, ggx_sggx_sample_diffuse(c->g, c->v[k], c->u1[k], c->u2[k], c->u2[k], c->u1[k]).z)

/* The SGGX functions on flake distributions of three shapes (S = A^T A): the skewed A of the scalar table, isotropic
 * alpha = 1 (S = I) and alpha = 0.01 (eigenvalue ratio 1e4); the surface's VNDF sampler beside the flakes'. */
static void sggx_table(sctx *c, const ggx_shape *skew, long ns)
{
    ggx_shape iso1, iso01;
    ggx_sggx g[3];
    ggx_shape_iso(&iso1, 1.0);
    ggx_shape_iso(&iso01, 0.01);
    ggx_sggx_from_shape(&g[0], skew);
    ggx_sggx_from_shape(&g[1], &iso1);
    ggx_sggx_from_shape(&g[2], &iso01);
    struct {
        const char *name;
        bench_fn f;
        long n;
    } sb[] = {{"ggx_sggx_ndf", b_sggx_ndf, ns},
              {"ggx_sggx_sample_vndf", b_sggx_vndf, ns},
              {"ggx_sggx_phase_specular", b_sggx_spec, ns},
              {"ggx_sggx_sample_diffuse", b_sggx_sdiff, ns},
              {"ggx_sggx_phase_diffuse", b_sggx_diff, ns / 200}};
    printf("\nSGGX (double)                  skewed A   alpha = 1   alpha = 0.01\n");
    for (unsigned k = 0; k < sizeof sb / sizeof sb[0]; k++) {
        printf("%-28s", sb[k].name);
        for (int i = 0; i < 3; i++) {
            c->g = &g[i];
            printf(" %10.2f", time_it(sb[k].f, c, sb[k].n, NULL));
        }
        printf("\n");
    }
    c->s = skew;
    printf("%-28s %10.2f   (the surface's sampler, ggx_sample_vndf)\n", "ggx_sample_vndf",
           time_it(b_vndf, c, ns, NULL));
}
/* energy compensation: the table of c->s is bench_energy */
static const ggx_energy *bench_energy;
SCALAR_BENCH(b_ealb, ggx_energy_albedo(bench_energy, c->v[k]))
SCALAR_BENCH(b_ms, ggx_brdf_ms_eval(bench_energy, &c->f, c->v[k], c->m[k]))
SCALAR_BENCH(b_comp, ggx_brdf_compensated_eval(bench_energy, &c->f, c->v[k], c->m[k]))
SCALAR_BENCH(
    b_scomp,
    ggx_sample_brdf_compensated(bench_energy, &c->f, c->v[k], c->u1[k], c->u2[k], c->u1[(k + 1) & (NS - 1)]).weight)
SCALAR_BENCH(b_isotab, ggx_albedo_iso_table(0.05 + c->u1[k], c->v[k].z, GGX_MASKING_SEPARABLE))
SCALAR_BENCH(b_fresnel_avg, ggx_fresnel_avg(&c->f))
/* the dielectric's table from both sides (v.z of either sign), eta 1.2 to 2.2 */
SCALAR_BENCH(b_anitab, ggx_albedo_aniso_table(0.05 + c->u1[k], 0.05 + 0.9 * c->u2[k], c->v[k]))
SCALAR_BENCH(b_bsdftab,
             ggx_bsdf_albedo_iso_table(0.05 + c->u1[k], 1.2 + c->u2[k], c->u2[k] < 0.5 ? c->v[k].z : -c->v[k].z))

/* Energy compensation against the single-scattering functions it adds to, same run; the setup it needs; the shipped
 * isotropic table against the quadrature it replaces. */
static void energy_table(sctx *sc, const ggx_shape *diag, const ggx_shape *skew, long ns)
{
    printf("\nenergy compensation (docs/design/energy.md), ns per call   diagonal A    skewed A\n");
    const ggx_shape *sh[2] = {diag, skew};
    ggx_energy *e[2];
    double setup[2], r[8][2];
    for (int k = 0; k < 2; k++) {
        double t0 = now();
        ggx_status st = ggx_energy_create(sh[k], &e[k]);
        if (st != GGX_OK) {
            printf("ggx_energy_create: %s for the %s shape; energy benchmarks left out\n", ggx_status_str(st),
                   k ? "skewed" : "diagonal");
            if (k) ggx_energy_free(e[0]);
            return;
        }
        setup[k] = now() - t0;
    }
    struct {
        const char *name;
        bench_fn f;
    } eb[] = {{"ggx_brdf_eval", b_brdf},
              {"ggx_brdf_compensated_eval", b_comp},
              {"ggx_brdf_ms_eval", b_ms},
              {"ggx_energy_albedo", b_ealb},
              {"ggx_sample_brdf_bounded", b_sbrdfb},
              {"ggx_sample_brdf_compensated", b_scomp},
              {"ggx_fresnel_avg (conductor)", b_fresnel_avg}};
    for (unsigned i = 0; i < sizeof eb / sizeof eb[0]; i++) {
        for (int k = 0; k < 2; k++) {
            sc->s = sh[k];
            bench_energy = e[k];
            r[i][k] = time_it(eb[i].f, sc, ns / 4, NULL);
        }
        printf("%-44s %10.2f %11.2f\n", eb[i].name, r[i][0], r[i][1]);
    }
    printf("compensated / single-scattering: eval %.2f, %.2f; sampling %.2f, %.2f\n", r[1][0] / r[0][0],
           r[1][1] / r[0][1], r[5][0] / r[4][0], r[5][1] / r[4][1]);
    printf("ggx_energy_create: %.2f s (diagonal), %.2f s (skewed)\n", setup[0], setup[1]);
    double tl = time_it(b_isotab, sc, ns / 4, NULL);
    ggx_shape iso;
    ggx_shape_iso(&iso, 0.3);
    double t0 = now();
    for (int i = 0; i < 20; i++) sink = ggx_albedo(&iso, sc->v[i]);
    double tq = (now() - t0) / 20 * 1e9;
    printf("ggx_albedo_iso_table %.1f ns, ggx_albedo (quadrature, alpha 0.3) %.0f ns: %.0fx\n", tl, tq, tq / tl);
    double ta = time_it(b_anitab, sc, ns / 4, NULL);
    ggx_shape an;
    ggx_shape_aniso(&an, 0.15, 0.5);
    t0 = now();
    for (int i = 0; i < 20; i++) sink = ggx_albedo(&an, sc->v[i]);
    tq = (now() - t0) / 20 * 1e9;
    printf("ggx_albedo_aniso_table %.1f ns, ggx_albedo (quadrature, alpha (0.15, 0.5)) %.0f ns: %.0fx\n", ta, tq,
           tq / ta);
    double tb = time_it(b_bsdftab, sc, ns / 4, NULL);
    t0 = now();
    for (int i = 0; i < 20; i++) sink = ggx_bsdf_albedo(&iso, 1.5, sc->v[i], NULL, NULL);
    tq = (now() - t0) / 20 * 1e9;
    printf("ggx_bsdf_albedo_iso_table %.1f ns, ggx_bsdf_albedo (quadrature, alpha 0.3, eta 1.5) %.0f ns: %.0fx\n", tb,
           tq, tq / tb);
    for (int k = 0; k < 2; k++) ggx_energy_free(e[k]);
}

static double rnd(uint64_t *s);

/* The best any sampler of the bounded form can do (docs/design/bounded-vndf.md, "What no bound of this form can do"): such
 * a sampler keeps the caps' azimuth 2 pi u1 and draws u2 uniformly in [0, u2*(u1)) (c.z uniform above a bound), and
 * no removed point may reflect above the horizon, so on each meridian it keeps at least [0, u2*] with u2* the largest
 * u2 whose plain sample (ggx_sample_brdf, the same cap point) is valid. On a grid of np meridians and nz heights,
 * *meridian is the wasted fraction with u2* per meridian and *plane with the largest u2* of all (the best single
 * plane c.z >= b). A kept sliver thinner than the grid is missed, which makes both look better than they are, never
 * worse: a case they cannot halve cannot be halved. np <= 512, nz <= 2048 (the static grid). */
static void bound_ceiling(const ggx_shape *s, ggx_vec3 v, int np, int nz, double *meridian, double *plane)
{
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    static unsigned char bad[512][2048];
    int first[512], top = 0; /* first[p]: number of heights kept by the bound (u2 index of the last valid + 1) */
    for (int p = 0; p < np; p++) {
        first[p] = 0;
        for (int k = 0; k < nz; k++) {
            ggx_sample x = ggx_sample_brdf(s, &one, v, (p + 0.5) / np, (k + 0.5) / nz);
            bad[p][k] = x.event == GGX_EVENT_INVALID;
            if (!bad[p][k]) first[p] = k + 1;
        }
        if (first[p] > top) top = first[p];
    }
    double wm = 0, wp = 0;
    for (int p = 0; p < np; p++) {
        int nm = 0, npl = 0;
        for (int k = 0; k < top; k++) npl += bad[p][k], nm += k < first[p] && bad[p][k];
        wm += first[p] ? (double)nm / first[p] : 0;
        wp += top ? (double)npl / top : 0;
    }
    *meridian = wm / np, *plane = wp / np;
}

/* Bounded reflection sampling against reflection sampling: per shape and view, the fraction of samples
 * wasted (reflected below the horizon) and the variance of the one-sample albedo estimator (F = 1: its weight),
 * n samples each with the same random numbers. */
static void bounded_table(long n, int np, int nz)
{
    static const struct {
        const char *name;
        double ax, ay, tx, ty, tz;
    } shapes[] = {{"iso 0.05", 0.05, 0.05, 0, 0, 0},
                  {"iso 0.1", 0.1, 0.1, 0, 0, 0},
                  {"iso 0.3", 0.3, 0.3, 0, 0, 0},
                  {"iso 0.6", 0.6, 0.6, 0, 0, 0},
                  {"iso 1", 1, 1, 0, 0, 0},
                  {"aniso 0.15:0.5", 0.15, 0.5, 0, 0, 0},
                  {"aniso 0.3:1 rot", 0.3, 1, 0, 0, 0.6},
                  {"skew 0.3:0.6", 0.3, 0.6, 0.4, -0.3, 0.5},
                  {"skew 0.6:0.6", 0.6, 0.6, 0.3, 0.2, 0},
                  {"skew 1:1", 1, 1, 0.4, -0.3, 0.5},
                  {"aniso 0.1:1", 0.1, 1, 0, 0, 0},
                  {"aniso 0.05:0.5", 0.05, 0.5, 0, 0, 0},
                  {"skew 0.1:1", 0.1, 1, 0.5, 0.5, 0.3},
                  {"skew 0.05:0.3", 0.05, 0.3, -0.5, 0.5, 1.2}};
    static const double views[] = {0, 30, 45, 60, 70, 80, 89};
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    printf("\nbounded reflection sampling against ggx_sample_brdf (plain), F = 1, %ld samples each: wasted = samples\n"
           "below the horizon, plain, ggx_sample_brdf_bounded (plane), ggx_sample_brdf_bounded_azimuth (azimuth);\n"
           "var = variance of the albedo estimate per sample over plain's; halved: whether azimuth wastes at most\n"
           "half of plain's where plain wastes more than 5%%; best: the waste of the best per-meridian bound and of\n"
           "the best plane (bound_ceiling, %d x %d grid), which no sampler of this form can beat\n",
           n, np, nz);
    printf("%-16s %5s %8s %8s %8s %8s %8s %8s %8s %8s %7s\n", "shape", "view", "plain", "plane", "azimuth", "best mer",
           "best pl", "var pl", "var az", "albedo", "halved");
    double worst_var = 0;
    int misses = 0, cases = 0, plane_halved = 0, best_halved = 0, best_plane_halved = 0;
    for (unsigned i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
        ggx_shape s;
        ggx_shape_ellipsoid(&s, shapes[i].ax, shapes[i].ay, shapes[i].tx, shapes[i].ty, shapes[i].tz);
        for (unsigned j = 0; j < sizeof views / sizeof views[0]; j++) {
            double t = views[j] * GGX_PI / 180, ph = 0.7;
            ggx_vec3 v = {sin(t) * cos(ph), sin(t) * sin(ph), cos(t)};
            uint64_t seed = 99;
            double sw[3] = {0, 0, 0}, sw2[3] = {0, 0, 0};
            long bad[3] = {0, 0, 0};
            for (long k = 0; k < n; k++) {
                double u1 = rnd(&seed), u2 = rnd(&seed);
                ggx_sample x[3] = {ggx_sample_brdf(&s, &one, v, u1, u2), ggx_sample_brdf_bounded(&s, &one, v, u1, u2),
                                   ggx_sample_brdf_bounded_azimuth(&s, &one, v, u1, u2)};
                for (int q = 0; q < 3; q++) {
                    bad[q] += x[q].event == GGX_EVENT_INVALID;
                    sw[q] += x[q].weight, sw2[q] += x[q].weight * x[q].weight;
                }
            }
            double var[3], w[3];
            for (int q = 0; q < 3; q++) {
                var[q] = sw2[q] / (double)n - (sw[q] / (double)n) * (sw[q] / (double)n);
                w[q] = (double)bad[q] / (double)n;
            }
            double r1 = var[0] > 0 ? var[1] / var[0] : 1.0, r2 = var[0] > 0 ? var[2] / var[0] : 1.0;
            if (r1 > worst_var) worst_var = r1;
            if (r2 > worst_var) worst_var = r2;
            const char *halved = w[0] > 0.05 ? (w[2] <= 0.5 * w[0] ? "yes" : "NO") : "-";
            cases += w[0] > 0.05, misses += w[0] > 0.05 && !(w[2] <= 0.5 * w[0]);
            plane_halved += w[0] > 0.05 && w[1] <= 0.5 * w[0];
            double bm, bp;
            bound_ceiling(&s, v, np, nz, &bm, &bp);
            best_halved += w[0] > 0.05 && bm <= 0.5 * w[0];
            best_plane_halved += w[0] > 0.05 && bp <= 0.5 * w[0];
            printf("%-16s %5.0f %8.4f %8.4f %8.4f %8.4f %8.4f %8.3f %8.3f %8.4f %7s\n", shapes[i].name, views[j], w[0],
                   w[1], w[2], bm, bp, r1, r2, sw[2] / (double)n, halved);
        }
    }
    printf("largest variance ratio bounded / plain: %.3f; waste halved by the per-azimuth bound in %d of %d cases "
           "where plain wastes more than 5%%, by the plane bound in %d\n",
           worst_var, cases - misses, cases, plane_halved);
    printf("at best (bound_ceiling): a per-meridian bound could halve it in %d of %d cases, a plane in %d\n",
           best_halved, cases, best_plane_halved);
}

/* The inline float sampler of ggx_inline.h behind one call, as the float reference is (a renderer would inline
 * both). */
__attribute__((noinline)) static float vndf_f_z(const sctx *c, long k)
{
    ggx_vec3f v = {c->fv[k][0], c->fv[k][1], c->fv[k][2]};
    return ggx_sample_vndf_f(&c->sf, v, c->fu1[k], c->fu2[k]).z;
}
SCALAR_BENCH(b_vndf_f, vndf_f_z(c, k))

/* The plain transcriptions, through the same loop. They live in another translation unit, as the library does, so
 * neither side is inlined into the loop and both pay one call. */
static float ref_caps_f_z(const sctx *c, long k)
{
    float m[3];
    ref_caps_vndf_f_diag(c->ax, c->ay, c->fv[k][0], c->fv[k][1], c->fv[k][2], c->fu1[k], c->fu2[k], m);
    return m[2];
}
SCALAR_BENCH(r_caps, ref_caps_vndf_d(c->s->a, c->v[k], c->u1[k], c->u2[k]).z)
SCALAR_BENCH(r_caps_f, ref_caps_f_z(c, k))
#ifdef GGX_BENCH_V3
#include "isa_v3.h"
SCALAR_BENCH(b_vndf_f_v3, bench_v3_vndf_f_z(&c->sf, c->fv[k], c->fu1[k], c->fu2[k]))
SCALAR_BENCH(r_caps_f_v3, bench_v3_listing_z(c->ax, c->ay, c->fv[k], c->fu1[k], c->fu2[k]))
#endif
SCALAR_BENCH(r_g1, ref_g1_eq6(c->s->a, c->v[k], c->m[k]))
SCALAR_BENCH(r_pdf, ref_pdf_vndf_eq33(c->s->a, c->s->ainv_t, c->s->det, c->v[k], c->m[k]))
SCALAR_BENCH(r_floor, ref_sqrt_sincos_f(c->fu1[k], c->fu2[k]))

static double rel_diff(double a, double b)
{
    double d = fabs(a - b), l = fmax(fabs(a), fabs(b));
    return d > 0.0 ? d / l : 0.0;
}

/* Max difference over the NS inputs between each reference and the library function it transcribes: the proof that
 * the timed pairs compute the same thing. Printed, never fatal. */
static void reference_checks(const sctx *c, const ggx_shape *diag, const ggx_shape *skew)
{
    double caps = 0, caps_f = 0, g1 = 0, pdf = 0;
    for (int k = 0; k < NS; k++) {
        ggx_vec3 a = ref_caps_vndf_d(skew->a, c->v[k], c->u1[k], c->u2[k]);
        ggx_vec3 b = ggx_sample_vndf_caps(skew, c->v[k], c->u1[k], c->u2[k]);
        caps = fmax(caps, fmax(fabs(a.x - b.x), fmax(fabs(a.y - b.y), fabs(a.z - b.z))));
        float f[3];
        ref_caps_vndf_f_diag(c->ax, c->ay, c->fv[k][0], c->fv[k][1], c->fv[k][2], c->fu1[k], c->fu2[k], f);
        b = ggx_sample_vndf_caps(diag, c->v[k], c->u1[k], c->u2[k]);
        caps_f = fmax(caps_f, fmax(fabs(f[0] - b.x), fmax(fabs(f[1] - b.y), fabs(f[2] - b.z))));
        g1 = fmax(g1, rel_diff(ref_g1_eq6(skew->a, c->v[k], c->m[k]), ggx_g1(skew, c->v[k], c->m[k])));
        pdf = fmax(pdf, rel_diff(ref_pdf_vndf_eq33(skew->a, skew->ainv_t, skew->det, c->v[k], c->m[k]),
                                 ggx_pdf_vndf(skew, c->v[k], c->m[k])));
    }
    printf("agreement over the same %d inputs:\n", NS);
    printf("  caps plain double vs ggx_sample_vndf_caps (skewed):   max abs diff %.2e (%s 1e-6)\n", caps,
           caps <= 1e-6 ? "within" : "NOT within");
    printf("  Dupuy-Benyoub float vs ggx_sample_vndf_caps (diag):   max abs diff %.2e (float rounding)\n", caps_f);
    printf("  eq 6 plain vs ggx_g1 (skewed):                        max rel diff %.2e (%s 1e-12)\n", g1,
           g1 <= 1e-12 ? "within" : "NOT within");
    printf("  eq 33 plain vs ggx_pdf_vndf (skewed):                 max rel diff %.2e (%s 1e-12)\n", pdf,
           pdf <= 1e-12 ? "within" : "NOT within");
}

/* ---------------------------------------------------------------- batch */

typedef struct bctx {
    const ggx_shape *s;
    ggx_fresnel f;
    size_t n;
    float *in[7], *out[5];
    int op;
} bctx;

static void b_batch(void *vc, long reps)
{
    bctx *c = vc;
    for (long r = 0; r < reps; r += (long)c->n) {
        switch (c->op) {
        case 0:
            ggx_batch_sample_vndf(c->out[0], c->out[1], c->out[2], c->n, c->s, c->in[0], c->in[1], c->in[2], c->in[3],
                                  c->in[4]);
            break;
        case 1:
            ggx_batch_pdf_vndf(c->out[0], c->n, c->s, c->in[0], c->in[1], c->in[2], c->in[5], c->in[6], c->in[2]);
            break;
        case 2: ggx_batch_ndf(c->out[0], c->n, c->s, c->in[5], c->in[6], c->in[2]); break;
        case 3: ggx_batch_g1(c->out[0], c->n, c->s, c->in[0], c->in[1], c->in[2], c->in[5], c->in[6], c->in[2]); break;
        case 4: ggx_batch_sample_ndf(c->out[0], c->out[1], c->out[2], c->n, c->s, c->in[3], c->in[4]); break;
        case 5:
            ggx_batch_brdf(c->out[0], c->n, c->s, &c->f, c->in[0], c->in[1], c->in[2], c->in[5], c->in[6], c->in[2]);
            break;
        case 6:
            ggx_batch_sample_brdf(c->out[0], c->out[1], c->out[2], c->out[3], c->out[4], c->n, c->s, &c->f, c->in[0],
                                  c->in[1], c->in[2], c->in[3], c->in[4]);
            break;
        case 7:
            ggx_batch_sample_directions(GGX_SAMPLER_BRDF_BOUNDED, c->out[0], c->out[1], c->out[2], c->out[3], c->out[4],
                                        c->n, c->s, &c->f, c->in[0], c->in[1], c->in[2], c->in[3], c->in[4]);
            break;
        }
    }
}
static const char *BATCH_NAMES[] = {"sample_vndf", "pdf_vndf", "ndf",         "g1",
                                    "sample_ndf",  "brdf",     "sample_brdf", "brdf_bounded"};
static const int BATCH_BYTES[] = {32, 28, 16, 28, 20, 28, 40, 40}; /* floats read + written per element, x 4 */
enum { BATCH_OPS = sizeof BATCH_NAMES / sizeof BATCH_NAMES[0] };

/* ---------------------------------------------------------------- machine limits */

/* Peak FMA throughput of this core in flops per ns (8 independent AVX2 FMA chains; each FMA is 16 flops). */
__attribute__((target("avx2,fma"))) static double peak_flops(void)
{
    __m256 a[8], b = _mm256_set1_ps(0.999999f), c = _mm256_set1_ps(1e-7f);
    for (int i = 0; i < 8; i++) a[i] = _mm256_set1_ps((float)i);
    long n = 20000000;
    double t0 = now();
    for (long i = 0; i < n; i++)
        for (int k = 0; k < 8; k++) a[k] = _mm256_fmadd_ps(a[k], b, c);
    double t = now() - t0;
    float out[8];
    __m256 s = a[0];
    for (int k = 1; k < 8; k++) s = _mm256_add_ps(s, a[k]);
    _mm256_storeu_ps(out, s);
    sink = out[0];
    return (double)n * 8 * 16 / (t * 1e9);
}

/* ns per 8-wide sqrt and per 8-wide division, independent (throughput). */
__attribute__((target("avx2,fma"))) static void sqrt_div_cost(double *ns_sqrt, double *ns_div)
{
    __m256 a[4], b[4], x = _mm256_set1_ps(1.0001f);
    for (int i = 0; i < 4; i++) a[i] = b[i] = _mm256_set1_ps(2.0f + (float)i);
    long n = 10000000;
    double t0 = now();
    for (long i = 0; i < n; i++)
        for (int k = 0; k < 4; k++) a[k] = _mm256_sqrt_ps(_mm256_add_ps(a[k], x));
    double t1 = now();
    for (long i = 0; i < n; i++)
        for (int k = 0; k < 4; k++) b[k] = _mm256_div_ps(x, _mm256_add_ps(b[k], x));
    double t2 = now();
    float o[8];
    _mm256_storeu_ps(o, _mm256_add_ps(a[0], b[0]));
    sink = o[0];
    *ns_sqrt = (t1 - t0) * 1e9 / (n * 4.0);
    *ns_div = (t2 - t1) * 1e9 / (n * 4.0);
}

/* Copy bandwidth in bytes per ns (read + write counted), from memcpy of 256 MiB. */
static double copy_bandwidth(void)
{
    size_t n = 256u << 20;
    char *a = malloc(n), *b = malloc(n);
    memset(a, 1, n);
    memset(b, 2, n);
    double best = 0;
    for (int r = 0; r < 5; r++) {
        double t0 = now();
        memcpy(b, a, n);
        double t = now() - t0;
        double bw = 2.0 * (double)n / (t * 1e9);
        if (bw > best) best = bw;
    }
    sink = b[12345];
    free(a);
    free(b);
    return best;
}

static double rnd(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1.0p-53;
}

int main(int argc, char **argv)
{
    int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    int sggx_only = argc > 1 && strcmp(argv[1], "--sggx") == 0; /* the SGGX table alone, at the quick size */
    quick |= sggx_only;
    uint64_t seed = 1;
    ggx_shape diag, skew;
    ggx_shape_aniso(&diag, 0.15, 0.5);
    ggx_shape_ellipsoid(&skew, 0.15, 0.5, 0.3, -0.2, 0.5);
    static sctx sc;
    ggx_fresnel_conductor(&sc.f, 0.2, 3.9);
    for (int i = 0; i < NS; i++) {
        double ct = 0.05 + 0.95 * rnd(&seed), ph = 6.283185307 * rnd(&seed), st = sqrt(1 - ct * ct);
        sc.v[i] = (ggx_vec3){st * cos(ph), st * sin(ph), ct};
        ct = 0.3 + 0.7 * rnd(&seed), ph = 6.283185307 * rnd(&seed), st = sqrt(1 - ct * ct);
        sc.m[i] = (ggx_vec3){st * cos(ph), st * sin(ph), ct};
        sc.u1[i] = rnd(&seed), sc.u2[i] = rnd(&seed);
        sc.fv[i][0] = (float)sc.v[i].x, sc.fv[i][1] = (float)sc.v[i].y, sc.fv[i][2] = (float)sc.v[i].z;
        sc.fu1[i] = (float)sc.u1[i], sc.fu2[i] = (float)sc.u2[i];
    }
    sc.ax = 0.15f, sc.ay = 0.5f; /* diag's alphas */
    long ns = quick ? 200000 : 2000000;
    printf("libggx benchmark (%s); ns per call, median of 9 runs\n\n", quick ? "quick" : "full");
    if (sggx_only) {
        sggx_table(&sc, &skew, ns);
        return 0;
    }
    printf("scalar double API              diagonal A    skewed A   skewed/diag\n");
    struct {
        const char *name;
        bench_fn f;
    } sb[] = {{"ggx_ndf", b_ndf},
              {"ggx_g1", b_g1},
              {"ggx_pdf_vndf", b_pdf},
              {"ggx_brdf_eval", b_brdf},
              {"ggx_sample_vndf_caps", b_caps},
              {"ggx_sample_vndf_crescent", b_crescent},
              {"ggx_sample_vndf_heitz", b_heitz},
              {"ggx_sample_ndf_stretch", b_stretch},
              {"ggx_sample_brdf", b_sbrdf},
              {"ggx_sample_brdf_bounded", b_sbrdfb},
              {"ggx_sample_brdf_bounded_azimuth", b_sbrdfa}};
    double caps_diag = 0, caps_skew = 0, res[11][2];
    for (unsigned k = 0; k < sizeof sb / sizeof sb[0]; k++) {
        sc.s = &diag;
        res[k][0] = time_it(sb[k].f, &sc, ns, NULL);
        sc.s = &skew;
        res[k][1] = time_it(sb[k].f, &sc, ns, NULL);
        printf("%-28s %10.2f %11.2f %11.2f\n", sb[k].name, res[k][0], res[k][1], res[k][1] / res[k][0]);
    }
    caps_diag = res[4][0], caps_skew = res[4][1];
    printf("\nsamplers relative to caps      diagonal A    skewed A\n");
    for (int k = 5; k <= 6; k++)
        printf("%-28s %10.2f %11.2f\n", sb[k].name, res[k][0] / res[4][0], res[k][1] / res[4][1]);
    printf("skewed caps / diagonal caps: %.2f (target <= 1.2)\n", caps_skew / caps_diag);
    /* the ratios timed alternately (time_pair), as the reference table's */
    double q[2][2], t0, t1;
    for (int b = 0; b < 2; b++) {
        q[b][0] = time_pair(b_sbrdf, &diag, b ? b_sbrdfa : b_sbrdfb, &diag, &sc.s, &sc, ns, &t0, &t1);
        q[b][1] = time_pair(b_sbrdf, &skew, b ? b_sbrdfa : b_sbrdfb, &skew, &sc.s, &sc, ns, &t0, &t1);
    }
    printf(
        "ggx_sample_brdf_bounded / ggx_sample_brdf: %.2f diagonal, %.2f skewed (target <= 1.15; timed alternately)\n",
        q[0][0], q[0][1]);
    printf("ggx_sample_brdf_bounded_azimuth / ggx_sample_brdf: %.2f diagonal, %.2f skewed (target <= 1.15)\n", q[1][0],
           q[1][1]);
    bounded_table(quick ? 100000 : 400000, quick ? 128 : 512, quick ? 500 : 2000);
    energy_table(&sc, &diag, &skew, ns);

    /* Each reference is timed right after the library function it transcribes, on the same shape and inputs. */
    printf("\nreference transcriptions (same run; lab/bench/reference.c), ns per call\n");
    printf("timed alternately, 9 rounds; the ratio is the median of the per-round ratios\n");
    printf("%-32s %8s   %-28s %8s   %s\n", "reference", "ns/call", "library", "ns/call", "library/reference");
    struct {
        const char *name, *lib_name;
        bench_fn ref, lib;
        const ggx_shape *s, *lib_s; /* the reference's shape and the library's */
    } rb[] = {
        {"caps plain double (skewed)", "ggx_sample_vndf", r_caps, b_vndf, &skew, &skew},
        {"Dupuy-Benyoub float (diagonal)", "ggx_sample_vndf", r_caps_f, b_vndf, &diag, &diag},
        {"Dupuy-Benyoub float (diagonal)", "ggx_sample_vndf_f (diagonal)", r_caps_f, b_vndf_f, &diag, &diag},
        {"Dupuy-Benyoub float (diagonal)", "ggx_sample_vndf_f (skewed)", r_caps_f, b_vndf_f, &diag, &skew},
#ifdef GGX_BENCH_V3
        {"Dupuy-Benyoub float, v3 (diag)", "ggx_sample_vndf_f, v3 (diag)", r_caps_f_v3, b_vndf_f_v3, &diag, &diag},
        {"Dupuy-Benyoub float, v3 (diag)", "ggx_sample_vndf_f, v3 (skewed)", r_caps_f_v3, b_vndf_f_v3, &diag, &skew},
#endif
        {"eq 6 plain (skewed)", "ggx_g1", r_g1, b_g1, &skew, &skew},
        {"eq 33 plain (skewed)", "ggx_pdf_vndf", r_pdf, b_pdf, &skew, &skew},
        {"sqrtf + sinf/cosf", NULL, r_floor, NULL, &diag, &diag}};
    for (unsigned k = 0; k < sizeof rb / sizeof rb[0]; k++) {
#ifdef GGX_BENCH_V3
        if ((rb[k].ref == r_caps_f_v3) && !bench_v3_supported()) continue;
#endif
        sc.s = rb[k].s;
        if (!rb[k].lib) {
            printf("%-32s %8.2f   %-28s %8s   %s\n", rb[k].name, time_it(rb[k].ref, &sc, ns, NULL), "-", "-", "-");
            continue;
        }
        ggx_shapef_from(&sc.sf, rb[k].lib_s); /* the float references read ax, ay, not sf */
        double tr, tl, q = time_pair(rb[k].ref, rb[k].s, rb[k].lib, rb[k].lib_s, &sc.s, &sc, ns, &tr, &tl);
        printf("%-32s %8.2f   %-28s %8.2f   %.2f\n", rb[k].name, tr, rb[k].lib_name, tl, q);
    }
    reference_checks(&sc, &diag, &skew);

    /* batch */
    double peak = peak_flops(), ns_sqrt, ns_div;
    sqrt_div_cost(&ns_sqrt, &ns_div);
    double bw = copy_bandwidth();
    printf("\nmachine: FMA peak %.1f GFLOP/s per core; 8-wide sqrt %.2f ns, 8-wide div %.2f ns (throughput); "
           "copy bandwidth %.1f GB/s\n",
           peak, ns_sqrt, ns_div, bw);
    size_t big = (64u << 20) / 32; /* 64 MiB of sample_vndf data (5 inputs + 3 outputs) */
    size_t sizes[2] = {512, big};
    float *in[7], *out[5];
    for (int k = 0; k < 7; k++) in[k] = malloc(sizeof(float) * big);
    for (int k = 0; k < 5; k++) out[k] = malloc(sizeof(float) * big);
    for (size_t i = 0; i < big; i++) {
        double ct = 0.05 + 0.95 * rnd(&seed), ph = 6.283185307 * rnd(&seed), st = sqrt(1 - ct * ct);
        in[0][i] = (float)(st * cos(ph)), in[1][i] = (float)(st * sin(ph)), in[2][i] = (float)ct;
        in[3][i] = (float)rnd(&seed), in[4][i] = (float)rnd(&seed);
        in[5][i] = (float)(0.3 * st * cos(ph)), in[6][i] = (float)(0.3 * st * sin(ph));
    }
    const ggx_batch_isa isas[3] = {GGX_ISA_SCALAR, GGX_ISA_AVX2, GGX_ISA_AVX512};
    double vndf_best = 1e9, vndf_scalar_isa = 0;
    printf("\nbatch float API, ns per element      n = 512 (L1)        n = %zu (64 MiB)\n", big);
    printf("%-14s %-8s %18s %12s %12s   instr/elem\n", "kernel", "isa", "1 thread", "1 thread", "2 threads");
    for (int op = 0; op < BATCH_OPS; op++) {
        for (int k = 0; k < 3; k++) {
            if (ggx_batch_set_isa(isas[k]) != GGX_OK) continue;
            bctx c = {op == 0 || op == 1 ? &skew : &skew, sc.f, 0, {0}, {0}, op};
            memcpy(c.in, in, sizeof in);
            memcpy(c.out, out, sizeof out);
            double t[3], instr = -1;
            c.n = sizes[0];
            ggx_batch_set_threads(1);
            t[0] = time_it(b_batch, &c, quick ? 200000 : 2000000, &instr);
            c.n = sizes[1];
            t[1] = time_it(b_batch, &c, (long)big * (quick ? 1 : 2), NULL);
            ggx_batch_set_threads(2);
            t[2] = time_it(b_batch, &c, (long)big * (quick ? 1 : 2), NULL);
            ggx_batch_set_threads(1);
            char ins[32];
            if (instr >= 0) snprintf(ins, sizeof ins, "%.1f", instr);
            else snprintf(ins, sizeof ins, "n/a");
            printf("%-14s %-8s %18.3f %12.3f %12.3f   %s\n", BATCH_NAMES[op], ggx_batch_isa_name(isas[k]), t[0], t[1],
                   t[2], ins);
            if (op == 0 && t[0] < vndf_best) vndf_best = t[0];
            if (op == 0 && isas[k] == GGX_ISA_SCALAR) vndf_scalar_isa = t[0];
        }
    }
    ggx_batch_set_isa(GGX_ISA_AUTO);
    /* Floors of batch sample_vndf (general A), lower bounds: its ~75 flops (two 3x3 products, two normalisations,
     * the sincos polynomials, the cap and the rim test) at the FMA peak, and its 3 sqrt + 2 div per element on the
     * divider (8 elements per vector) -- separate units, so the arithmetic floor is the larger of the two -- and the
     * 32 bytes it moves at the copy bandwidth. */
    double flop_t = 75.0 / peak, div_t = (3.0 * ns_sqrt + 2.0 * ns_div) / 8.0;
    double arith = fmax(flop_t, div_t);
    double mem = 32.0 / bw;
    printf("\nbatch sample_vndf floors per element: arithmetic %.3f ns (FMA %.3f, sqrt/div %.3f), memory %.3f ns "
           "(larger: %.3f ns)\n",
           arith, flop_t, div_t, mem, fmax(arith, mem));
    printf("best batch sample_vndf (L1, 1 thread) %.3f ns = %.2f x the larger floor\n", vndf_best,
           vndf_best / fmax(arith, mem));
    printf("speed-up over scalar double ggx_sample_vndf_caps (skewed): %.1f x (baseline-ISA batch: %.1f x)\n",
           caps_skew / vndf_best, caps_skew / vndf_scalar_isa);
    for (int k = 0; k < 7; k++) free(in[k]);
    for (int k = 0; k < 5; k++) free(out[k]);
    sggx_table(&sc, &skew, ns);
    return 0;
}
