/* libFuzzer target: the shape constructors and every hot function fed from raw bytes (any double, NaN and
 * infinities included), checking the numerical contract of include/ggx/ggx.h; a violation aborts.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ggx/ggx.h"

typedef struct bytes {
    const uint8_t *p;
    size_t n;
} bytes;

static double next_double(bytes *b)
{
    double d = 0.5;
    if (b->n >= 8) {
        memcpy(&d, b->p, 8);
        b->p += 8, b->n -= 8;
    } else if (b->n > 0) { /* a short tail: a small fraction */
        d = b->p[0] / 256.0;
        b->p++, b->n--;
    }
    return d;
}

static uint8_t next_byte(bytes *b)
{
    if (!b->n) return 0;
    b->n--;
    return *b->p++;
}

#define REQUIRE(cond, ...)                                                                                          \
    do {                                                                                                            \
        if (!(cond)) {                                                                                              \
            fprintf(stderr, "contract violated: %s: ", #cond);                                                      \
            fprintf(stderr, __VA_ARGS__);                                                                           \
            fputc('\n', stderr);                                                                                    \
            abort();                                                                                                \
        }                                                                                                           \
    } while (0)

static ggx_vec3 vec(bytes *b)
{
    ggx_vec3 v;
    v.x = next_double(b), v.y = next_double(b), v.z = next_double(b);
    return v;
}

static ggx_vec3 unit_or_raw(bytes *b, int unit)
{
    ggx_vec3 v = vec(b);
    double l = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (unit && l > 0 && isfinite(l)) v.x /= l, v.y /= l, v.z /= l;
    return v;
}

static int is_zero(ggx_vec3 v) { return v.x == 0 && v.y == 0 && v.z == 0; }
static int is_unit(ggx_vec3 v) { return fabs(sqrt(v.x * v.x + v.y * v.y + v.z * v.z) - 1) <= 1e-12; }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes b = {data, size};
    ggx_shape s;
    ggx_status st;
    uint8_t ctor = next_byte(&b) % 4;
    if (ctor == 0) {
        st = ggx_shape_iso(&s, next_double(&b));
    } else if (ctor == 1) {
        double ax = next_double(&b);
        st = ggx_shape_aniso(&s, ax, next_double(&b));
    } else if (ctor == 2) {
        double p[5];
        for (int i = 0; i < 5; i++) p[i] = next_double(&b);
        st = ggx_shape_ellipsoid(&s, p[0], p[1], p[2], p[3], p[4]);
    } else {
        double A[3][3];
        for (int i = 0; i < 9; i++) A[i / 3][i % 3] = next_double(&b);
        st = ggx_shape_matrix(&s, (const double(*)[3])A);
    }
    REQUIRE(ggx_status_str(st) != NULL, "status %d", st);
    if (st != GGX_OK) return 0;
    REQUIRE(s.det > 0 && isfinite(s.ndf_scale) && s.ndf_scale > 0, "shape terms");

    int unit = next_byte(&b) & 1;
    ggx_vec3 v = unit_or_raw(&b, unit), m = unit_or_raw(&b, unit);
    ggx_fresnel f;
    ggx_fresnel_conductor(&f, 0.2, 3.9);
    double eta = next_double(&b);
    double r[] = {ggx_ndf(&s, m),          ggx_gaussian_curvature(&s, m), ggx_projected_area(&s, v),
                  ggx_lune_area(&s, v, m), ggx_g1(&s, v, m),              ggx_g1_smith(&s, v),
                  ggx_g2(&s, v, m, m),     ggx_g2_height_correlated(&s, v, m, m),
                  ggx_pdf_vndf(&s, v, m),  ggx_pdf_ndf(&s, m),            ggx_brdf_eval(&s, &f, v, m),
                  ggx_pdf_brdf(&s, v, m),  ggx_bsdf_eval(&s, eta, v, m, GGX_RADIANCE),
                  ggx_bsdf_eval(&s, eta, m, v, GGX_IMPORTANCE), ggx_pdf_bsdf(&s, eta, v, m),
                  ggx_p22(&s, m.x, m.y),   ggx_ndf_spherical(&s, v.x, v.y),
                  ggx_fresnel_dielectric_eval(v.x, eta), ggx_fresnel_conductor_eval(v.x, eta, m.x),
                  ggx_fresnel_schlick_eval(v.x, m.x),   ggx_jacobian_reflect(v, m),
                  ggx_jacobian_refract(v, m, v, eta, m.x)};
    for (unsigned i = 0; i < sizeof r / sizeof r[0]; i++) REQUIRE(isfinite(r[i]) && r[i] >= 0, "function %u = %g", i, r[i]);
    REQUIRE(isfinite(ggx_lambda(&s, v)), "lambda");

    /* samplers: the view as a direction (normalised when finite and non-zero) */
    ggx_vec3 vu = unit_or_raw(&b, 1);
    double u1 = next_double(&b), u2 = next_double(&b), u3 = next_double(&b);
    int in_domain = vu.z > 0 && is_unit(vu);
    ggx_vec3 (*vndf[])(const ggx_shape *, ggx_vec3, double, double) = {
        ggx_sample_vndf_caps, ggx_sample_vndf_crescent, ggx_sample_vndf_crescent_polar, ggx_sample_vndf_heitz};
    for (unsigned k = 0; k < 4; k++) {
        ggx_vec3 x = vndf[k](&s, vu, u1, u2);
        if (!in_domain) {
            REQUIRE(is_zero(x) || vu.z > 0, "vndf %u: outside the domain", k);
            continue;
        }
        if (is_zero(x)) { /* allowed only where the visible part is a sliver below 1e-9 of the silhouette */
            ggx_vec3 n = {0, 0, 1};
            REQUIRE(ggx_lune_area(&s, vu, n) < 1e-9 * ggx_projected_area(&s, vu), "vndf %u: no sample for a view"
                    " with visible fraction %g", k, ggx_lune_area(&s, vu, n) / ggx_projected_area(&s, vu));
            continue;
        }
        double pdf = ggx_pdf_vndf(&s, vu, x);
        REQUIRE(is_unit(x) && isfinite(pdf) && pdf > 0, "vndf %u: m (%g,%g,%g) pdf %g", k, x.x, x.y, x.z, pdf);
        ggx_vec2 inv = k == 0 ? ggx_sample_vndf_caps_inv(&s, vu, x) : ggx_sample_vndf_heitz_inv(&s, vu, x);
        REQUIRE(inv.x >= 0 && inv.x <= 1 && inv.y >= 0 && inv.y <= 1, "inverse map in [0, 1]");
    }
    ggx_vec3 (*ndf[])(const ggx_shape *, double, double) = {ggx_sample_ndf_stretch, ggx_sample_ndf_ellipse,
                                                            ggx_sample_ndf_inversion, ggx_sample_ndf_visible};
    for (unsigned k = 0; k < 4; k++) {
        ggx_vec3 x = ndf[k](&s, u1, u2);
        if (k == 2 && s.kind == GGX_SHAPE_SKEWED) {
            REQUIRE(is_zero(x), "inversion on a skewed shape");
            continue;
        }
        double pdf = ggx_pdf_ndf(&s, x);
        REQUIRE(is_unit(x) && isfinite(pdf) && pdf > 0, "ndf %u: m (%g,%g,%g) pdf %g", k, x.x, x.y, x.z, pdf);
    }
    ggx_sample smp[3] = {ggx_sample_brdf(&s, &f, vu, u1, u2), ggx_sample_bsdf(&s, eta, vu, u1, u2, u3, GGX_RADIANCE),
                         ggx_sample_bsdf(&s, eta, vu, u1, u2, u3, GGX_IMPORTANCE)};
    for (int k = 0; k < 3; k++) {
        if (smp[k].event == GGX_EVENT_INVALID)
            REQUIRE(smp[k].pdf == 0 && smp[k].weight == 0 && is_zero(smp[k].w), "invalid sample %d not zeroed", k);
        else
            REQUIRE(is_unit(smp[k].w) && isfinite(smp[k].pdf) && smp[k].pdf > 0 && isfinite(smp[k].weight) && smp[k].weight >= 0,
                    "sample %d: pdf %g weight %g", k, smp[k].pdf, smp[k].weight);
    }
    if (smp[0].event != GGX_EVENT_INVALID) REQUIRE(smp[0].weight <= 1.0, "brdf weight %.17g > 1", smp[0].weight);
    return 0;
}
