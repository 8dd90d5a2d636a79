/* The float batch API against the double API: every instruction-set path the CPU has, every n from 0 to 300 (tails),
 * misaligned pointers, and the contract on the float path. One test body run over every variant.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ggx/ggx_batch.h"
#include "ggx/ggx_samplers.h"
#include "testlib.h"

enum { NMAX = 300, OFF = 1 }; /* OFF: every array starts one float past an aligned address */

typedef struct arrays {
    float *buf[20];
} arrays;

static float *arr(arrays *a, int i)
{
    if (!a->buf[i]) a->buf[i] = malloc(sizeof(float) * (NMAX + 16));
    return a->buf[i] + OFF;
}

typedef struct worst {
    double ndf, g1, pdf, brdf, m, mndf, w, spdf, weight, aniso;
    double normals[GGX_SAMPLER_COUNT]; /* ggx_batch_sample_normals, per registry sampler */
} worst;

static int batch_normals(const ggx_sampler_info *info)
{
    return info->batch && (info->family == GGX_FAMILY_NDF || info->family == GGX_FAMILY_VNDF);
}

static double rel(double got, double want) { return fabs(got - want) / fmax(fabs(want), 1e-30); }

/* One body for every ISA: random shapes, views and normals with z >= 0.02, all n in [0, NMAX]. */
static void compare(ggx_batch_isa isa, worst *w)
{
    CHECK(ggx_batch_set_isa(isa) == GGX_OK, "set isa %s", ggx_batch_isa_name(isa));
    arrays A;
    memset(&A, 0, sizeof A);
    float *vx = arr(&A, 0), *vy = arr(&A, 1), *vz = arr(&A, 2), *mx = arr(&A, 3), *my = arr(&A, 4), *mz = arr(&A, 5);
    float *u1 = arr(&A, 6), *u2 = arr(&A, 7), *o1 = arr(&A, 8), *o2 = arr(&A, 9), *o3 = arr(&A, 10);
    float *o4 = arr(&A, 11), *o5 = arr(&A, 12), *ax = arr(&A, 13), *ay = arr(&A, 14);
    rng r = {1234};
    for (int n = 0; n <= NMAX; n++) {
        shape_params p = random_shape(&r, n % 3 ? 0.5 : 0.0);
        if (p.ax < 0.05) p.ax = 0.05;
        if (p.ay < 0.05) p.ay = 0.05;
        ggx_shape s;
        make_shape(&s, p);
        ggx_fresnel f;
        ggx_fresnel_conductor(&f, 0.2, 3.9);
        if (n % 4 == 1) ggx_fresnel_schlick(&f, 0.04);
        if (n % 4 == 2) ggx_fresnel_dielectric(&f, 1.5);
        if (n % 4 == 3) ggx_fresnel_one(&f);
        double V[NMAX][3], M[NMAX][3];
        for (int i = 0; i < n; i++) {
            ggx_vec3 v = t_dir(acos(rng_range(&r, 0.02, 1)), rng_range(&r, -GGX_PI, GGX_PI));
            ggx_vec3 m = t_dir(acos(rng_range(&r, 0.02, 1)), rng_range(&r, -GGX_PI, GGX_PI));
            vx[i] = (float)v.x, vy[i] = (float)v.y, vz[i] = (float)v.z, mx[i] = (float)m.x, my[i] = (float)m.y,
            mz[i] = (float)m.z;
            /* the double reference sees exactly the float inputs */
            V[i][0] = vx[i], V[i][1] = vy[i], V[i][2] = vz[i], M[i][0] = mx[i], M[i][1] = my[i], M[i][2] = mz[i];
            u1[i] = (float)rng_uniform(&r), u2[i] = (float)rng_uniform(&r);
            ax[i] = (float)p.ax, ay[i] = (float)p.ay;
        }
        /* sentinels past the end must survive */
        o1[n] = o2[n] = o3[n] = o4[n] = o5[n] = -7.0f;
        ggx_batch_ndf(o1, (size_t)n, &s, mx, my, mz);
        ggx_batch_g1(o2, (size_t)n, &s, vx, vy, vz, mx, my, mz);
        ggx_batch_pdf_vndf(o3, (size_t)n, &s, vx, vy, vz, mx, my, mz);
        ggx_batch_brdf(o4, (size_t)n, &s, &f, vx, vy, vz, mx, my, mz);
        for (int i = 0; i < n; i++) {
            ggx_vec3 v = t_vec(V[i][0], V[i][1], V[i][2]), m = t_vec(M[i][0], M[i][1], M[i][2]);
            double d = ggx_ndf(&s, m), g = ggx_g1(&s, v, m), pv = ggx_pdf_vndf(&s, v, m),
                   fr = ggx_brdf_eval(&s, &f, v, m);
            w->ndf = fmax(w->ndf, rel(o1[i], d));
            w->g1 = fmax(w->g1, rel(o2[i], g));
            /* the pdf is proportional to m.v, which a float dot product resolves to ~1e-7 absolute */
            double mvd = v.x * m.x + v.y * m.y + v.z * m.z;
            double ep = mvd >= 0.01 ? rel(o3[i], pv) : 0.0;
            w->pdf = fmax(w->pdf, ep);
            w->brdf = fmax(w->brdf, rel(o4[i], fr));
            CHECK(rel(o1[i], d) <= 2e-5 && rel(o2[i], g) <= 2e-5 && ep <= 2e-5 && rel(o4[i], fr) <= 2e-5,
                  "%s n %d i %d: D %g/%g G1 %g/%g pdf %g/%g brdf %g/%g", ggx_batch_isa_name(isa), n, i, o1[i], d, o2[i],
                  g, o3[i], pv, o4[i], fr);
        }
        CHECK(o1[n] == -7.0f && o2[n] == -7.0f && o3[n] == -7.0f && o4[n] == -7.0f, "wrote past n = %d", n);
        /* samplers: same u as the double samplers */
        ggx_batch_sample_vndf(o1, o2, o3, (size_t)n, &s, vx, vy, vz, u1, u2);
        for (int i = 0; i < n; i++) {
            ggx_vec3 m = ggx_sample_vndf_caps(&s, t_vec(V[i][0], V[i][1], V[i][2]), u1[i], u2[i]);
            double e = fmax(fabs(o1[i] - m.x), fmax(fabs(o2[i] - m.y), fabs(o3[i] - m.z)));
            w->m = fmax(w->m, e);
            CHECK(e <= 1e-4, "%s vndf n %d i %d: err %g", ggx_batch_isa_name(isa), n, i, e);
        }
        ggx_batch_sample_vndf_aniso(o1, o2, o3, (size_t)n, ax, ay, vx, vy, vz, u1, u2);
        ggx_shape sa;
        CHECK(ggx_shape_aniso(&sa, (float)p.ax, (float)p.ay) == GGX_OK, "aniso");
        for (int i = 0; i < n; i++) {
            ggx_vec3 m = ggx_sample_vndf_caps(&sa, t_vec(V[i][0], V[i][1], V[i][2]), u1[i], u2[i]);
            double e = fmax(fabs(o1[i] - m.x), fmax(fabs(o2[i] - m.y), fabs(o3[i] - m.z)));
            w->aniso = fmax(w->aniso, e);
            CHECK(e <= 1e-4, "%s aniso n %d i %d: err %g", ggx_batch_isa_name(isa), n, i, e);
        }
        ggx_batch_sample_ndf(o1, o2, o3, (size_t)n, &s, u1, u2);
        for (int i = 0; i < n; i++) {
            ggx_vec3 m = ggx_sample_ndf_stretch(&s, u1[i], u2[i]);
            double e = fmax(fabs(o1[i] - m.x), fmax(fabs(o2[i] - m.y), fabs(o3[i] - m.z)));
            w->mndf = fmax(w->mndf, e);
            CHECK(e <= 1e-4, "%s ndf n %d i %d: err %g", ggx_batch_isa_name(isa), n, i, e);
        }
        /* every batch sampler of normals of the registry, against its double sampler for the same u */
        for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
            const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
            if (!batch_normals(info)) continue;
            o1[n] = o2[n] = o3[n] = -7.0f;
            ggx_status st = ggx_batch_sample_normals((ggx_sampler_id)id, o1, o2, o3, (size_t)n, &s, vx, vy, vz, u1, u2);
            CHECK(st == GGX_OK, "%s: ggx_batch_sample_normals(%s): %s", ggx_batch_isa_name(isa), info->name,
                  ggx_status_str(st));
            for (int i = 0; i < n; i++) {
                ggx_vec3 m = info->sample(&s, t_vec(V[i][0], V[i][1], V[i][2]), u1[i], u2[i]);
                double e = fmax(fabs(o1[i] - m.x), fmax(fabs(o2[i] - m.y), fabs(o3[i] - m.z)));
                w->normals[id] = fmax(w->normals[id], e);
                CHECK(e <= 1e-4, "%s %s n %d i %d: u (%.9g, %.9g), v (%.9g, %.9g, %.9g): err %g",
                      ggx_batch_isa_name(isa), info->name, n, i, u1[i], u2[i], vx[i], vy[i], vz[i], e);
            }
            CHECK(o1[n] == -7.0f && o2[n] == -7.0f && o3[n] == -7.0f, "%s wrote past n = %d", info->name, n);
        }
        /* every batch direction sampler of the registry (reflection, bounded reflection) against its double
         * sampler; ggx_batch_sample_brdf is the first of them, bit for bit */
        for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
            const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
            if (!info->batch || info->family != GGX_FAMILY_DIRECTION) continue;
            o5[n] = -7.0f;
            ggx_status st = ggx_batch_sample_directions((ggx_sampler_id)id, o1, o2, o3, o4, o5, (size_t)n, &s, &f, vx,
                                                        vy, vz, u1, u2);
            CHECK(st == GGX_OK, "%s: ggx_batch_sample_directions(%s): %s", ggx_batch_isa_name(isa), info->name,
                  ggx_status_str(st));
            CHECK(o5[n] == -7.0f, "%s wrote past n = %d", info->name, n);
            if (id == GGX_SAMPLER_BRDF) {
                float *pb[5] = {arr(&A, 15), arr(&A, 16), arr(&A, 17), arr(&A, 18), arr(&A, 19)};
                float *q[5] = {o1, o2, o3, o4, o5};
                ggx_batch_sample_brdf(pb[0], pb[1], pb[2], pb[3], pb[4], (size_t)n, &s, &f, vx, vy, vz, u1, u2);
                for (int k = 0; k < 5; k++)
                    CHECK(n == 0 || memcmp(pb[k], q[k], sizeof(float) * (size_t)n) == 0,
                          "ggx_batch_sample_brdf differs from ggx_batch_sample_directions(brdf), output %d", k);
            }
            for (int i = 0; i < n; i++) {
                ggx_sample x = info->sample_direction(&s, &f, 1.5, t_vec(V[i][0], V[i][1], V[i][2]), u1[i], u2[i], 0.5,
                                                      GGX_RADIANCE);
                if (fabs(x.w.z) < 1e-4 || (x.event == GGX_EVENT_INVALID && fabs(o3[i]) < 1e-4))
                    continue; /* the horizon */
                CHECK((x.event != GGX_EVENT_INVALID) == (o4[i] > 0), "%s %s validity n %d i %d",
                      ggx_batch_isa_name(isa), info->name, n, i);
                if (x.event == GGX_EVENT_INVALID) continue;
                double e = fmax(fabs(o1[i] - x.w.x), fmax(fabs(o2[i] - x.w.y), fabs(o3[i] - x.w.z)));
                w->w = fmax(w->w, e);
                w->spdf = fmax(w->spdf, rel(o4[i], x.pdf));
                w->weight = fmax(w->weight, fabs(o5[i] - x.weight));
                CHECK(e <= 1e-4 && rel(o4[i], x.pdf) <= 1e-4 && fabs(o5[i] - x.weight) <= 2e-4 && o5[i] <= 1.0f,
                      "%s %s sample n %d i %d: w err %g pdf %g/%g weight %g/%g", ggx_batch_isa_name(isa), info->name, n,
                      i, e, o4[i], x.pdf, o5[i], x.weight);
            }
        }
    }
    for (int i = 0; i < 20; i++) free(A.buf[i]);
}

static void every_isa(void **state)
{
    (void)state;
    const ggx_batch_isa isas[] = {GGX_ISA_SCALAR, GGX_ISA_AVX2, GGX_ISA_AVX512};
    int tested = 0;
    for (unsigned k = 0; k < 3; k++) {
        if (!ggx_batch_isa_available(isas[k])) {
            CHECK(ggx_batch_set_isa(isas[k]) == GGX_ERR_RANGE, "unavailable isa accepted");
            printf("batch %-6s: not available on this CPU or build\n", ggx_batch_isa_name(isas[k]));
            continue;
        }
        worst w = {0};
        compare(isas[k], &w);
        tested++;
        printf(
            "batch %-6s: rel err D %.1e G1 %.1e pdf %.1e brdf %.1e; abs err vndf %.1e aniso %.1e ndf %.1e brdf-w %.1e; "
            "sample pdf rel %.1e weight abs %.1e\n",
            ggx_batch_isa_name(isas[k]), w.ndf, w.g1, w.pdf, w.brdf, w.m, w.aniso, w.mndf, w.w, w.spdf, w.weight);
        for (int id = 0; id < GGX_SAMPLER_COUNT; id++)
            if (batch_normals(ggx_sampler_get((ggx_sampler_id)id)))
                printf("batch %-6s: ggx_batch_sample_normals %-15s abs err %.1e\n", ggx_batch_isa_name(isas[k]),
                       ggx_sampler_get((ggx_sampler_id)id)->name, w.normals[id]);
    }
    CHECK(tested >= 1, "no ISA tested");
    ggx_batch_set_isa(GGX_ISA_AUTO);
}

/* The registry's batch flag is the batch API's: ggx_batch_sample_normals takes exactly the samplers of normals
 * marked batch and ggx_batch_sample_directions exactly the direction samplers marked batch (GGX_ERR_RANGE for the
 * others and for ids outside the registry, writing nothing); NULL arrays give GGX_ERR_NULL when n > 0. */
static void registry_entry_points(void **state)
{
    (void)state;
    float v[3] = {0.2f, 0.1f, 0.97f}, u[2] = {0.3f, 0.6f}, m[3] = {-7.0f, -7.0f, -7.0f};
    ggx_shape s;
    make_shape(&s, (shape_params){0.2, 0.6, 0.3, -0.2, 1.0});
    int batched = 0;
    for (int id = -1; id <= GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
        ggx_status st = ggx_batch_sample_normals((ggx_sampler_id)id, &m[0], &m[1], &m[2], 1, &s, &v[0], &v[1], &v[2],
                                                 &u[0], &u[1]);
        if (info && batch_normals(info)) {
            batched++;
            CHECK(st == GGX_OK && fabsf(m[0] * m[0] + m[1] * m[1] + m[2] * m[2] - 1) < 1e-5f, "%s: %s", info->name,
                  ggx_status_str(st));
            CHECK(ggx_batch_sample_normals((ggx_sampler_id)id, NULL, &m[1], &m[2], 1, &s, &v[0], &v[1], &v[2], &u[0],
                                           &u[1]) == GGX_ERR_NULL,
                  "%s: NULL output accepted", info->name);
            m[0] = m[1] = m[2] = -7.0f;
            continue;
        }
        CHECK(st == GGX_ERR_RANGE && m[0] == -7.0f && m[1] == -7.0f && m[2] == -7.0f,
              "sampler id %d (%s), not a batch sampler of normals: status %s", id, info ? info->name : "none",
              ggx_status_str(st));
    }
    CHECK(batched > 0, "no batch sampler of normals in the registry");
    int directions = 0;
    for (int id = -1; id <= GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
        float w[5] = {-7.0f, -7.0f, -7.0f, -7.0f, -7.0f};
        ggx_status st = ggx_batch_sample_directions((ggx_sampler_id)id, &w[0], &w[1], &w[2], &w[3], &w[4], 1, &s, NULL,
                                                    &v[0], &v[1], &v[2], &u[0], &u[1]);
        if (info && info->batch && info->family == GGX_FAMILY_DIRECTION) {
            directions++;
            ggx_fresnel one;
            ggx_fresnel_one(&one); /* the batch's NULL: F = 1 */
            ggx_sample x = info->sample_direction(&s, &one, 1.5, t_vec(v[0], v[1], v[2]), u[0], u[1], 0.5,
                                                  GGX_RADIANCE);
            CHECK(st == GGX_OK && (w[3] > 0) == (x.event != GGX_EVENT_INVALID) && fabs(w[3] - x.pdf) <= 1e-4 * x.pdf,
                  "%s: %s, pdf %g against %g", info->name, ggx_status_str(st), w[3], x.pdf);
            CHECK(ggx_batch_sample_directions((ggx_sampler_id)id, &w[0], &w[1], &w[2], &w[3], NULL, 1, &s, NULL, &v[0],
                                              &v[1], &v[2], &u[0], &u[1]) == GGX_ERR_NULL,
                  "%s: NULL output accepted", info->name);
            continue;
        }
        CHECK(st == GGX_ERR_RANGE && w[0] == -7.0f && w[3] == -7.0f && w[4] == -7.0f,
              "sampler id %d (%s), not a batch direction sampler: status %s", id, info ? info->name : "none",
              ggx_status_str(st));
    }
    CHECK(directions == 2, "batch direction samplers in the registry: %d, want brdf and brdf-bounded", directions);
}

/* Views of any length the float fast path takes (squared length from GGX_L2_MIN = 1e-20 up) give the normal of the
 * unit view, within the batch bound, on every instruction set and every batch sampler of normals, for the shapes whose
 * products underflow soonest: alpha 1e-4 (skewed too) and a matrix scaled to 1e-49 (normalised by ggx_shapef_from).
 * (In float these elements reach the slow path through the other checks even without the mu.mu bound of
 * GGX_FACE_FLOOR: measured with GGX_MU2_MIN, its predecessor, set to 0. The test guards the contract, not that
 * constant.) */
static void short_views(void **state)
{
    (void)state;
    const shape_params shapes[] = {{1e-4, 1e-4, 0, 0, 0}, {1e-4, 0.5, 0.6, -0.4, 0.3}, {0.3, 0.6, 0.4, -0.3, 0.5}};
    const float lengths[] = {1e-10f, 1e-8f, 1e-5f, 1.0f, 1e2f};
    const ggx_batch_isa isas[] = {GGX_ISA_SCALAR, GGX_ISA_AVX2, GGX_ISA_AVX512};
    enum { NV = 16 };
    rng r = {77};
    for (unsigned k = 0; k < sizeof shapes / sizeof shapes[0] + 1; k++) {
        ggx_shape s;
        if (k < sizeof shapes / sizeof shapes[0]) make_shape(&s, shapes[k]);
        else { /* the skewed shape's canonical matrix scaled to 1e-49 */ ggx_shape b;
            make_shape(&b, shapes[2]);
            double A[3][3];
            for (int i = 0; i < 9; i++) A[i / 3][i % 3] = 1e-49 * b.a[i / 3][i % 3];
            CHECK(ggx_shape_matrix(&s, (const double(*)[3])A) == GGX_OK, "scaled matrix");
        }
        ggx_vec3 unit[NV];
        float u1[NV], u2[NV];
        for (int i = 0; i < NV; i++) {
            unit[i] = t_dir(acos(rng_range(&r, 0.05, 1)), rng_range(&r, -GGX_PI, GGX_PI));
            u1[i] = (float)rng_uniform(&r), u2[i] = (float)rng_uniform(&r);
        }
        for (unsigned q = 0; q < sizeof isas / sizeof isas[0]; q++) {
            if (ggx_batch_set_isa(isas[q]) != GGX_OK) continue;
            for (unsigned l = 0; l < sizeof lengths / sizeof lengths[0]; l++) {
                float vx[NV], vy[NV], vz[NV], mx[NV], my[NV], mz[NV];
                for (int i = 0; i < NV; i++)
                    vx[i] = (float)unit[i].x * lengths[l], vy[i] = (float)unit[i].y * lengths[l],
                    vz[i] = (float)unit[i].z * lengths[l];
                for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
                    const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
                    if (!info->batch || info->family != GGX_FAMILY_VNDF) continue;
                    CHECK(ggx_batch_sample_normals((ggx_sampler_id)id, mx, my, mz, NV, &s, vx, vy, vz, u1, u2) ==
                              GGX_OK,
                          "%s", info->name);
                    for (int i = 0; i < NV; i++) {
                        ggx_vec3 w = t_vec(vx[i], vy[i], vz[i]), m = info->sample(&s, t_normalize(w), u1[i], u2[i]);
                        double e = fmax(fabs(mx[i] - m.x), fmax(fabs(my[i] - m.y), fabs(mz[i] - m.z)));
                        CHECK(isfinite(e) && e <= 1e-4, "%s %s, shape %u, view length %g, element %d: err %g",
                              ggx_batch_isa_name(isas[q]), info->name, k, lengths[l], i, e);
                    }
                }
            }
        }
    }
    ggx_batch_set_isa(GGX_ISA_AUTO);
}

/* Threads: a large batch split over threads gives bit-identical results to one thread. */
static void threads_identical(void **state)
{
    (void)state;
    enum { N = 200003 };
    float *in[5], *o1[3], *o2[3];
    rng r = {5};
    for (int k = 0; k < 5; k++) in[k] = malloc(sizeof(float) * N);
    for (int k = 0; k < 3; k++) o1[k] = malloc(sizeof(float) * N), o2[k] = malloc(sizeof(float) * N);
    for (int i = 0; i < N; i++) {
        ggx_vec3 v = random_view(&r);
        in[0][i] = (float)v.x, in[1][i] = (float)v.y, in[2][i] = (float)v.z;
        in[3][i] = (float)rng_uniform(&r), in[4][i] = (float)rng_uniform(&r);
    }
    ggx_shape s;
    make_shape(&s, (shape_params){0.2, 0.6, 0.3, -0.2, 1.0});
    CHECK(ggx_batch_set_threads(0) == GGX_ERR_RANGE && ggx_batch_set_threads(1) == GGX_OK, "threads");
    ggx_batch_sample_vndf(o1[0], o1[1], o1[2], N, &s, in[0], in[1], in[2], in[3], in[4]);
    ggx_batch_set_threads(3);
    ggx_batch_sample_vndf(o2[0], o2[1], o2[2], N, &s, in[0], in[1], in[2], in[3], in[4]);
    ggx_batch_set_threads(1);
    for (int k = 0; k < 3; k++) CHECK(memcmp(o1[k], o2[k], sizeof(float) * N) == 0, "threads changed results");
    for (int k = 0; k < 5; k++) free(in[k]);
    for (int k = 0; k < 3; k++) free(o1[k]), free(o2[k]);
}

/* The contract on the float path: NaN, below the horizon, zero vectors give 0; samples are unit or zero. */
static void float_contract(void **state)
{
    (void)state;
    const float nan = NAN;
    float vx[6] = {0, 0.6f, 0, nan, 0, 1}, vy[6] = {0, 0, 0, 0, 0, 0}, vz[6] = {1, -0.8f, 0, 1, 0, 0};
    float u1[6] = {0, 0.5f, 1, nan, 0.99999994f, 0.3f}, u2[6] = {0, 0.5f, 1, 0.5f, 0.99999994f, nan};
    float o[5][6];
    ggx_shape s;
    make_shape(&s, (shape_params){GGX_ALPHA_MIN, 10, 0.4, -0.3, 0.5});
    const ggx_batch_isa isas[] = {GGX_ISA_SCALAR, GGX_ISA_AVX2, GGX_ISA_AVX512};
    for (unsigned k = 0; k < 3; k++) {
        if (ggx_batch_set_isa(isas[k]) != GGX_OK) continue;
        ggx_batch_pdf_vndf(o[0], 6, &s, vx, vy, vz, vx, vy, vz);
        for (int i = 0; i < 6; i++) CHECK(isfinite(o[0][i]) && o[0][i] >= 0, "pdf %d = %g", i, o[0][i]);
        CHECK(o[0][1] == 0 && o[0][2] == 0 && o[0][3] == 0, "outside the domain");
        ggx_batch_sample_vndf(o[0], o[1], o[2], 6, &s, vx, vy, vz, u1, u2);
        for (int i = 0; i < 6; i++) {
            float l = o[0][i] * o[0][i] + o[1][i] * o[1][i] + o[2][i] * o[2][i];
            CHECK(l == 0 || fabsf(l - 1) < 1e-5f, "sample %d length %g", i, l);
            if (!(vz[i] > 0)) CHECK(l == 0, "view %d below the horizon gave a sample", i);
        }
    }
    ggx_batch_set_isa(GGX_ISA_AUTO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(every_isa), cmocka_unit_test(registry_entry_points),
                                       cmocka_unit_test(threads_identical), cmocka_unit_test(short_views),
                                       cmocka_unit_test(float_contract)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
