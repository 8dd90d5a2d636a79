/* The native half of the Python package `ggx` (python/ggx/__init__.py loads it with ctypes): one element loop per
 * signature of the double API, each calling the library function it is given by pointer, so an array result is
 * bit for bit what the C API returns for each element. The library's objects are linked into this module, which
 * therefore exports the whole ggx_* API too (the float batch functions are called directly from Python).
 *
 * Every loop reads its inputs through ggxpy_in: a pointer and a step in doubles from one element to the next (3 for
 * a contiguous array of directions, 1 for scalars, 0 for one value broadcast over all elements), so broadcasting
 * one direction or one number costs no copy. Outputs are contiguous. SPDX-License-Identifier: MIT */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "ggx/ggx.h"
#include "ggx/ggx_samplers.h"

#define EXPORT __attribute__((visibility("default")))

typedef struct ggxpy_in {
    const double *p;
    ptrdiff_t step;
} ggxpy_in;

static ggx_vec3 vec(const ggxpy_in *a, size_t i)
{
    const double *p = a->p + (ptrdiff_t)i * a->step;
    return (ggx_vec3){p[0], p[1], p[2]};
}
static double num(const ggxpy_in *a, size_t i) { return a->p[(ptrdiff_t)i * a->step]; }
static void put(double *out, size_t i, ggx_vec3 v)
{
    out[3 * i] = v.x, out[3 * i + 1] = v.y, out[3 * i + 2] = v.z;
}

/* Sizes and fields the Python side needs without restating the C structs. */
EXPORT size_t ggxpy_sizeof_shape(void) { return sizeof(ggx_shape); }
EXPORT size_t ggxpy_sizeof_fresnel(void) { return sizeof(ggx_fresnel); }
EXPORT int ggxpy_shape_kind(const ggx_shape *s) { return (int)s->kind; }
EXPORT void ggxpy_shape_canonical(const ggx_shape *s, double a[9]) { memcpy(a, s->a, sizeof s->a); }
/* What the Python side shows of a registry entry (it lists the samplers from here, never by hand). 0 for an id
 * outside the registry. */
EXPORT int ggxpy_sampler_desc(int id, const char **name, const char **help, const char **function, int *family,
                              int *domain, int *batch, int *has_inverse)
{
    const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
    if (!e) return 0;
    *name = e->name, *help = e->help, *function = e->function, *family = (int)e->family, *domain = (int)e->domain;
    *batch = e->batch;
    *has_inverse = e->inverse != NULL;
    return 1;
}

/* --- Evaluations: double f(shape, ...) --- */

EXPORT void ggxpy_s_v(double (*f)(const ggx_shape *, ggx_vec3), const ggx_shape *s, size_t n, const ggxpy_in *in,
                      double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = f(s, vec(&in[0], i));
}

EXPORT void ggxpy_s_vv(double (*f)(const ggx_shape *, ggx_vec3, ggx_vec3), const ggx_shape *s, size_t n,
                       const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = f(s, vec(&in[0], i), vec(&in[1], i));
}

EXPORT void ggxpy_s_vvv(double (*f)(const ggx_shape *, ggx_vec3, ggx_vec3, ggx_vec3), const ggx_shape *s, size_t n,
                        const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = f(s, vec(&in[0], i), vec(&in[1], i), vec(&in[2], i));
}

EXPORT void ggxpy_s_dd(double (*f)(const ggx_shape *, double, double), const ggx_shape *s, size_t n,
                       const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = f(s, num(&in[0], i), num(&in[1], i));
}

EXPORT void ggxpy_sf_vv(double (*f)(const ggx_shape *, const ggx_fresnel *, ggx_vec3, ggx_vec3), const ggx_shape *s,
                        const ggx_fresnel *fr, size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = f(s, fr, vec(&in[0], i), vec(&in[1], i));
}

/* The registry's pdf of sampler id: pdf(shape, v, m) for normals, pdf_direction(shape, eta, v, w) for directions. */
EXPORT void ggxpy_sampler_pdf(int id, const ggx_shape *s, double eta, size_t n, const ggxpy_in *in, double *out)
{
    const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
    if (e->pdf) {
        for (size_t i = 0; i < n; i++) out[i] = e->pdf(s, vec(&in[0], i), vec(&in[1], i));
        return;
    }
    double (*f)(const ggx_shape *, double, ggx_vec3, ggx_vec3) = e->pdf_direction;
    for (size_t i = 0; i < n; i++) out[i] = f(s, eta, vec(&in[0], i), vec(&in[1], i));
}

EXPORT void ggxpy_bsdf(const ggx_shape *s, double eta, int mode, size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = ggx_bsdf_eval(s, eta, vec(&in[0], i), vec(&in[1], i), (ggx_transport)mode);
}

EXPORT void ggxpy_bsdf_albedo(const ggx_shape *s, double eta, size_t n, const ggxpy_in *in, double *r, double *t)
{
    for (size_t i = 0; i < n; i++) ggx_bsdf_albedo(s, eta, vec(&in[0], i), &r[i], &t[i]);
}

/* --- Geometry: a direction of two directions (ggx_reflect, ggx_half_reflect) --- */

EXPORT void ggxpy_vv_v(ggx_vec3 (*f)(ggx_vec3, ggx_vec3), size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) put(out, i, f(vec(&in[0], i), vec(&in[1], i)));
}

/* --- Functions of numbers --- */

EXPORT void ggxpy_fresnel(const ggx_fresnel *fr, size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = ggx_fresnel_eval(fr, num(&in[0], i));
}

EXPORT void ggxpy_albedo_iso_table(int masking, size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = ggx_albedo_iso_table(num(&in[0], i), num(&in[1], i), (ggx_masking)masking);
}

EXPORT void ggxpy_bsdf_albedo_iso_table(size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = ggx_bsdf_albedo_iso_table(num(&in[0], i), num(&in[1], i), num(&in[2], i));
}

EXPORT void ggxpy_albedo_aniso_table(size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = ggx_albedo_aniso_table(num(&in[0], i), num(&in[1], i), vec(&in[2], i));
}

/* --- Samplers, by registry id (the caller checks that the entry has the function it asks for) --- */

/* NDF and VNDF: m = f(shape, v, u1, u2). Inputs v, u1, u2. */
EXPORT void ggxpy_sample(int id, const ggx_shape *s, size_t n, const ggxpy_in *in, double *m)
{
    ggx_vec3 (*f)(const ggx_shape *, ggx_vec3, double, double) = ggx_sampler_get((ggx_sampler_id)id)->sample;
    for (size_t i = 0; i < n; i++) put(m, i, f(s, vec(&in[0], i), num(&in[1], i), num(&in[2], i)));
}

/* The (u1, u2) that give m. Inputs v, m; output n x 2. */
EXPORT void ggxpy_inverse(int id, const ggx_shape *s, size_t n, const ggxpy_in *in, double *u)
{
    ggx_vec2 (*f)(const ggx_shape *, ggx_vec3, ggx_vec3) = ggx_sampler_get((ggx_sampler_id)id)->inverse;
    for (size_t i = 0; i < n; i++) {
        ggx_vec2 r = f(s, vec(&in[0], i), vec(&in[1], i));
        u[2 * i] = r.x, u[2 * i + 1] = r.y;
    }
}

/* Rejection samplers draw their candidates from a stream of their own per element, seeded by the bits of (u1, u2):
 * splitmix64 (Steele, Lea & Flood 2014), 53-bit doubles in [0, 1). The same (u1, u2) give the same normal. */
static double next_uniform(void *state)
{
    uint64_t z = (*(uint64_t *)state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1p-53;
}

EXPORT void ggxpy_sample_reject(int id, const ggx_shape *s, size_t n, const ggxpy_in *in, double *m, double *trials)
{
    ggx_vec3 (*f)(const ggx_shape *, ggx_vec3, ggx_uniform_fn, void *, unsigned *) =
        ggx_sampler_get((ggx_sampler_id)id)->sample_reject;
    for (size_t i = 0; i < n; i++) {
        double u1 = num(&in[1], i), u2 = num(&in[2], i);
        uint64_t b1, b2;
        memcpy(&b1, &u1, sizeof b1);
        memcpy(&b2, &u2, sizeof b2);
        uint64_t state = b1 * 0x9e3779b97f4a7c15u ^ (b2 + 0x632be59bd9b4e019u);
        unsigned t = 0;
        put(m, i, f(s, vec(&in[0], i), next_uniform, &state, &t));
        trials[i] = t;
    }
}

/* DIRECTION: ggx_sample = f(shape, fresnel, eta, v, u1, u2, u3, mode). Inputs v, u1, u2, u3. */
EXPORT void ggxpy_sample_direction(int id, const ggx_shape *s, const ggx_fresnel *fr, double eta, int mode, size_t n,
                                   const ggxpy_in *in, double *w, double *pdf, double *weight, int8_t *event)
{
    ggx_sample (*f)(const ggx_shape *, const ggx_fresnel *, double, ggx_vec3, double, double, double, ggx_transport) =
        ggx_sampler_get((ggx_sampler_id)id)->sample_direction;
    for (size_t i = 0; i < n; i++) {
        ggx_sample r = f(s, fr, eta, vec(&in[0], i), num(&in[1], i), num(&in[2], i), num(&in[3], i),
                         (ggx_transport)mode);
        put(w, i, r.w);
        pdf[i] = r.pdf, weight[i] = r.weight, event[i] = (int8_t)r.event;
    }
}

/* --- Energy compensation (an energy object in place of the shape) --- */

EXPORT void ggxpy_energy_albedo(const ggx_energy *e, size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = ggx_energy_albedo(e, vec(&in[0], i));
}

EXPORT void ggxpy_energy_pdf_ms(const ggx_energy *e, size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = ggx_pdf_brdf_ms(e, vec(&in[0], i), vec(&in[1], i));
}

EXPORT void ggxpy_ef_vv(double (*f)(const ggx_energy *, const ggx_fresnel *, ggx_vec3, ggx_vec3), const ggx_energy *e,
                        const ggx_fresnel *fr, size_t n, const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = f(e, fr, vec(&in[0], i), vec(&in[1], i));
}

/* The multiple-scattering lobe's sampler (u3 unused) and the compensated BRDF's. Inputs wi, u1, u2, u3. */
EXPORT void ggxpy_energy_sample(int compensated, const ggx_energy *e, const ggx_fresnel *fr, size_t n,
                                const ggxpy_in *in, double *w, double *pdf, double *weight, int8_t *event)
{
    for (size_t i = 0; i < n; i++) {
        ggx_vec3 wi = vec(&in[0], i);
        double u1 = num(&in[1], i), u2 = num(&in[2], i);
        ggx_sample r = compensated ? ggx_sample_brdf_compensated(e, fr, wi, u1, u2, num(&in[3], i))
                                   : ggx_sample_brdf_ms(e, fr, wi, u1, u2);
        put(w, i, r.w);
        pdf[i] = r.pdf, weight[i] = r.weight, event[i] = (int8_t)r.event;
    }
}
