/* libFuzzer target: the shape constructors and every hot function fed from raw bytes (any double, NaN and
 * infinities included), checking the numerical contract of include/ggx/ggx.h; a violation aborts. The samplers are
 * every entry of the registry (ggx_samplers.h), so a new registry line is fuzzed too; and the energy compensation
 * of the conductor and of the rough dielectric.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ggx/ggx.h"
#include "ggx/ggx_samplers.h"

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

#define REQUIRE(cond, ...)                                                                                             \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            fprintf(stderr, "contract violated: %s: ", #cond);                                                         \
            fprintf(stderr, __VA_ARGS__);                                                                              \
            fputc('\n', stderr);                                                                                       \
            abort();                                                                                                   \
        }                                                                                                              \
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

/* Random numbers of a rejection sampler: the input's remaining doubles (any value: NaN reads as 0, others clamp),
 * then splitmix64, so that a sampler that rejects them still ends well within its budget. */
typedef struct stream {
    bytes b;
    uint64_t state;
} stream;
static double stream_next(void *vs)
{
    stream *st = vs;
    if (st->b.n >= 8) return next_double(&st->b);
    uint64_t z = (st->state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

/* A direction sampler, in both transport modes: a valid sample or an invalid one zeroed. Reflection sampling (a
 * sampler whose pdf is 0 for transmitted directions: here, for alpha 0.3, the one refracted through n from 30
 * degrees with eta 1.5) has weight <= 1 exactly (eq 52). */
static void check_directions(const ggx_sampler_info *e, const ggx_shape *s, const ggx_fresnel *f, double eta,
                             ggx_vec3 vu, double u1, double u2, double u3)
{
    const ggx_vec3 probe_v = {0.5, 0.0, 0.8660254037844386}, probe_w = {-0.3333333333333333, 0.0, -0.9428090415820634};
    ggx_shape probe_s;
    REQUIRE(ggx_shape_iso(&probe_s, 0.3) == GGX_OK, "probe shape");
    int reflects_only = e->pdf_direction(&probe_s, 1.5, probe_v, probe_w) == 0;
    const ggx_transport modes[2] = {GGX_RADIANCE, GGX_IMPORTANCE};
    for (int k = 0; k < 2; k++) {
        ggx_sample x = e->sample_direction(s, f, eta, vu, u1, u2, u3, modes[k]);
        if (x.event == GGX_EVENT_INVALID) {
            REQUIRE(x.pdf == 0 && x.weight == 0 && is_zero(x.w), "%s: invalid sample not zeroed", e->name);
            continue;
        }
        REQUIRE(is_unit(x.w) && isfinite(x.pdf) && x.pdf > 0 && isfinite(x.weight) && x.weight >= 0,
                "%s: pdf %g weight %g", e->name, x.pdf, x.weight);
        if (reflects_only) REQUIRE(x.weight <= 1.0, "%s: weight %.17g > 1", e->name, x.weight);
    }
}

/* Energy compensation: tables built once (an isotropic and a rotated anisotropic shape; a skewed table takes
 * seconds), fed raw directions, numbers and any Fresnel term its setup functions accept. */
static ggx_energy *energy_tables[2];
static void check_energy(bytes *b)
{
    if (!energy_tables[0]) {
        ggx_shape a, c;
        REQUIRE(ggx_shape_iso(&a, 0.05) == GGX_OK && ggx_shape_ellipsoid(&c, 0.1, 0.6, 0, 0, 0.4) == GGX_OK, "shapes");
        REQUIRE(ggx_energy_create(&a, &energy_tables[0]) == GGX_OK &&
                    ggx_energy_create(&c, &energy_tables[1]) == GGX_OK,
                "energy tables");
    }
    const ggx_energy *e = energy_tables[next_byte(b) & 1];
    ggx_fresnel f;
    uint8_t kind = next_byte(b) % 4;
    double p1 = next_double(b), p2 = next_double(b);
    ggx_status st = kind == 0   ? ggx_fresnel_one(&f)
                    : kind == 1 ? ggx_fresnel_dielectric(&f, p1)
                    : kind == 2 ? ggx_fresnel_conductor(&f, p1, p2)
                                : ggx_fresnel_schlick(&f, p1);
    const ggx_fresnel *fp = st == GGX_OK ? &f : NULL;
    ggx_vec3 wi = vec(b), wo = vec(b);
    double u1 = next_double(b), u2 = next_double(b), u3 = next_double(b);
    double fa = ggx_fresnel_avg(fp);
    REQUIRE(fa >= 0 && fa <= 1 + 1e-12, "F_avg %g", fa);
    double r[] = {ggx_energy_albedo(e, wi), ggx_brdf_ms_eval(e, fp, wi, wo), ggx_pdf_brdf_ms(e, wi, wo),
                  ggx_brdf_compensated_eval(e, fp, wi, wo), ggx_pdf_brdf_compensated(e, fp, wi, wo)};
    for (unsigned i = 0; i < sizeof r / sizeof r[0]; i++)
        REQUIRE(isfinite(r[i]) && r[i] >= 0, "energy function %u = %g", i, r[i]);
    REQUIRE(r[0] <= 1, "E %g", r[0]);
    ggx_sample xs[2] = {ggx_sample_brdf_ms(e, fp, wi, u1, u2), ggx_sample_brdf_compensated(e, fp, wi, u1, u2, u3)};
    for (int k = 0; k < 2; k++) {
        if (xs[k].event == GGX_EVENT_INVALID) {
            REQUIRE(xs[k].pdf == 0 && xs[k].weight == 0 && is_zero(xs[k].w), "energy sampler %d: invalid not zeroed",
                    k);
            continue;
        }
        REQUIRE(is_unit(xs[k].w) && xs[k].w.z > 0 && isfinite(xs[k].pdf) && xs[k].pdf > 0 && isfinite(xs[k].weight) &&
                    xs[k].weight >= 0,
                "energy sampler %d: pdf %g weight %g", k, xs[k].pdf, xs[k].weight);
    }
}

/* The rough dielectric's compensation: one isotropic table (eta 1.5; it holds both sides, so light from above and
 * from below, the denser side; a table takes half a second, several under the sanitizers, and an anisotropic one
 * seconds), fed raw directions on either side, numbers and both transport modes. */
static ggx_bsdf_energy *bsdf_table;
static void check_bsdf_energy(bytes *b)
{
    if (!bsdf_table) {
        ggx_shape a;
        REQUIRE(ggx_shape_iso(&a, 0.2) == GGX_OK && ggx_bsdf_energy_create(&a, 1.5, &bsdf_table) == GGX_OK,
                "dielectric energy table");
    }
    const ggx_bsdf_energy *e = bsdf_table;
    ggx_transport mode = (next_byte(b) & 1) ? GGX_IMPORTANCE : GGX_RADIANCE;
    ggx_vec3 wi = vec(b), wo = vec(b);
    double u1 = next_double(b), u2 = next_double(b), u3 = next_double(b);
    double r[] = {ggx_bsdf_energy_albedo(e, wi), ggx_bsdf_ms_eval(e, wi, wo, mode), ggx_pdf_bsdf_ms(e, wi, wo),
                  ggx_bsdf_compensated_eval(e, wi, wo, mode), ggx_pdf_bsdf_compensated(e, wi, wo)};
    for (unsigned i = 0; i < sizeof r / sizeof r[0]; i++)
        REQUIRE(isfinite(r[i]) && r[i] >= 0, "dielectric energy function %u = %g", i, r[i]);
    REQUIRE(r[0] <= 1, "E %g", r[0]);
    ggx_sample xs[2] = {ggx_sample_bsdf_ms(e, wi, u1, u2, u3, mode),
                        ggx_sample_bsdf_compensated(e, wi, u1, u2, u3, mode)};
    for (int k = 0; k < 2; k++) {
        if (xs[k].event == GGX_EVENT_INVALID) {
            REQUIRE(xs[k].pdf == 0 && xs[k].weight == 0 && is_zero(xs[k].w),
                    "dielectric sampler %d: invalid not zeroed", k);
            continue;
        }
        REQUIRE(is_unit(xs[k].w) && xs[k].w.z != 0 && isfinite(xs[k].pdf) && xs[k].pdf > 0 && isfinite(xs[k].weight) &&
                    xs[k].weight >= 0,
                "dielectric sampler %d: pdf %g weight %g", k, xs[k].pdf, xs[k].weight);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    {
        bytes eb = {data, size};
        check_energy(&eb);
        bytes db = {data, size};
        check_bsdf_energy(&db);
    }
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
    double r[] = {ggx_ndf(&s, m),
                  ggx_gaussian_curvature(&s, m),
                  ggx_projected_area(&s, v),
                  ggx_lune_area(&s, v, m),
                  ggx_g1(&s, v, m),
                  ggx_g1_smith(&s, v),
                  ggx_g1_tilted(&s, v, m),
                  ggx_g1_risers(&s, v, m),
                  ggx_g2(&s, v, m, m),
                  ggx_g2_height_correlated(&s, v, m, m),
                  ggx_pdf_vndf(&s, v, m),
                  ggx_pdf_ndf(&s, m),
                  ggx_brdf_eval(&s, &f, v, m),
                  ggx_pdf_brdf(&s, v, m),
                  ggx_bsdf_eval(&s, eta, v, m, GGX_RADIANCE),
                  ggx_bsdf_eval(&s, eta, m, v, GGX_IMPORTANCE),
                  ggx_pdf_bsdf(&s, eta, v, m),
                  ggx_p22(&s, m.x, m.y),
                  ggx_ndf_spherical(&s, v.x, v.y),
                  ggx_fresnel_dielectric_eval(v.x, eta),
                  ggx_fresnel_conductor_eval(v.x, eta, m.x),
                  ggx_fresnel_schlick_eval(v.x, m.x),
                  ggx_jacobian_reflect(v, m),
                  ggx_jacobian_refract(v, m, v, eta, m.x)};
    for (unsigned i = 0; i < sizeof r / sizeof r[0]; i++)
        REQUIRE(isfinite(r[i]) && r[i] >= 0, "function %u = %g", i, r[i]);
    REQUIRE(isfinite(ggx_lambda(&s, v)), "lambda");

    /* samplers: the view as a direction (normalised when finite and non-zero) */
    ggx_vec3 vu = unit_or_raw(&b, 1);
    double u1 = next_double(&b), u2 = next_double(&b), u3 = next_double(&b);
    int in_domain = vu.z > 0 && is_unit(vu);
    /* rejection samplers read the rest of the input as their random numbers, then a fixed generator */
    stream rs = {b, 0x9e3779b97f4a7c15u};
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
        if (e->family == GGX_FAMILY_DIRECTION) {
            check_directions(e, &s, &f, eta, vu, u1, u2, u3);
            continue;
        }
        int ndf = e->family == GGX_FAMILY_NDF;
        ggx_vec3 x;
        if (e->family == GGX_FAMILY_REJECTION) {
            unsigned trials;
            x = e->sample_reject(&s, vu, stream_next, &rs, &trials);
        } else {
            x = e->sample(&s, vu, u1, u2);
        }
        if (e->domain == GGX_DOMAIN_UNSKEWED && s.kind == GGX_SHAPE_SKEWED) {
            REQUIRE(is_zero(x), "%s on a skewed shape", e->name);
            continue;
        }
        if (!ndf && !in_domain) {
            REQUIRE(is_zero(x) || vu.z > 0, "%s: outside the domain", e->name);
            continue;
        }
        if (is_zero(x)) { /* a rejection budget exhausted, or a visible part below 1e-9 of the silhouette */
            ggx_vec3 n = {0, 0, 1};
            REQUIRE(e->family == GGX_FAMILY_REJECTION ||
                        (!ndf && ggx_lune_area(&s, vu, n) < 1e-9 * ggx_projected_area(&s, vu)),
                    "%s: no sample (visible fraction %g)", e->name,
                    ndf ? 1.0 : ggx_lune_area(&s, vu, n) / ggx_projected_area(&s, vu));
            continue;
        }
        double pdf = e->pdf(&s, vu, x);
        REQUIRE(is_unit(x) && isfinite(pdf) && pdf > 0, "%s: m (%g,%g,%g) pdf %g", e->name, x.x, x.y, x.z, pdf);
        if (e->inverse) {
            ggx_vec2 inv = e->inverse(&s, vu, x);
            REQUIRE(inv.x >= 0 && inv.x <= 1 && inv.y >= 0 && inv.y <= 1, "%s: inverse map (%g, %g) outside [0, 1]",
                    e->name, inv.x, inv.y);
        }
    }
    if (next_byte(&b) == 0x5a) { /* the dielectric's albedo: milliseconds per call, so for one input in 256 */
        double rr = -1, tt = -1, e = ggx_bsdf_albedo(&s, eta, v, &rr, &tt);
        REQUIRE(isfinite(e) && rr >= 0 && tt >= 0 && e == rr + tt && e <= 1 + 1e-12, "bsdf albedo R %g T %g", rr, tt);
    }
    return 0;
}
