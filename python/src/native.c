/* The native half of the Python package `ggx` (python/ggx/_native.py loads it with ctypes): one element loop per
 * signature of the double API, each calling the library function it is given by pointer (the samplers' loops: the
 * registry's sampler of an id), so an array result is bit for bit what the C API returns for each element; beside
 * them, what Python needs of the C structs, and the entry points of the fits, the surfaces' readers and the
 * renderer. The module links libggx (a static build links the library's objects into it instead), so Python finds
 * every ggx_* function through it: the float batch functions are called directly from Python.
 *
 * Every loop reads its inputs through ggxpy_in: a pointer, a step in elements from one item to the next (3 for a
 * contiguous array of directions, 1 for scalars, 0 for one value broadcast over all items) and whether the elements
 * are floats or doubles, so broadcasting one direction or one number costs no copy and float32 arrays are read in
 * place. Outputs are contiguous. The float32 path (ggxpy_f32, at the end) runs the float batch API. SPDX-License-Identifier: MIT */
#include <float.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "ggx/ggx.h"
#include "ggx/ggx_samplers.h"

#define EXPORT __attribute__((visibility("default")))

typedef struct ggxpy_in {
    const void *p;
    ptrdiff_t step; /* in elements from one item to the next: 3, 1, or 0 for one item broadcast */
    int f32;        /* the elements are floats (numpy float32), else doubles */
} ggxpy_in;

static ggx_vec3 vec(const ggxpy_in *a, size_t i)
{
    ptrdiff_t k = (ptrdiff_t)i * a->step;
    if (a->f32) {
        const float *p = (const float *)a->p + k;
        return (ggx_vec3){p[0], p[1], p[2]};
    }
    const double *p = (const double *)a->p + k;
    return (ggx_vec3){p[0], p[1], p[2]};
}
static double num(const ggxpy_in *a, size_t i)
{
    ptrdiff_t k = (ptrdiff_t)i * a->step;
    return a->f32 ? (double)((const float *)a->p)[k] : ((const double *)a->p)[k];
}
static void put(double *out, size_t i, ggx_vec3 v) { out[3 * i] = v.x, out[3 * i + 1] = v.y, out[3 * i + 2] = v.z; }

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

EXPORT void ggxpy_s_dd(double (*f)(const ggx_shape *, double, double), const ggx_shape *s, size_t n, const ggxpy_in *in,
                       double *out)
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
    ggx_vec3 (*f)(const ggx_shape *, ggx_vec3, ggx_uniform_fn, void *,
                  unsigned *) = ggx_sampler_get((ggx_sampler_id)id)->sample_reject;
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
    ggx_sample (*f)(const ggx_shape *, const ggx_fresnel *, double, ggx_vec3, double, double, double,
                    ggx_transport) = ggx_sampler_get((ggx_sampler_id)id)->sample_direction;
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

/* ---- SGGX flakes (ggx/ggx_sggx.h): the same loops over a ggx_sggx in place of the shape ---- */

EXPORT size_t ggxpy_sizeof_sggx(void) { return sizeof(ggx_sggx); }
/* S, its eigenvalues (ascending) and unit eigenvectors (rows), for the Python object's properties. */
EXPORT void ggxpy_sggx_fields(const ggx_sggx *g, double s[9], double eig[3], double axes[9])
{
    memcpy(s, g->s, sizeof g->s);
    memcpy(eig, g->eig, sizeof g->eig);
    memcpy(axes, g->axes, sizeof g->axes);
}

/* Evaluations: f(g, w) (ndf, sigma) and f(g, wi, wo) (the phase functions). */
EXPORT void ggxpy_sggx_v(double (*f)(const ggx_sggx *, ggx_vec3), const ggx_sggx *g, size_t n, const ggxpy_in *in,
                         double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = f(g, vec(&in[0], i));
}
EXPORT void ggxpy_sggx_vv(double (*f)(const ggx_sggx *, ggx_vec3, ggx_vec3), const ggx_sggx *g, size_t n,
                          const ggxpy_in *in, double *out)
{
    for (size_t i = 0; i < n; i++) out[i] = f(g, vec(&in[0], i), vec(&in[1], i));
}

/* Samplers: w = f(g, wi, u1, u2) (VNDF, specular), inputs wi, u1, u2; and the diffuse one, inputs wi, u1 to u4. */
EXPORT void ggxpy_sggx_sample2(ggx_vec3 (*f)(const ggx_sggx *, ggx_vec3, double, double), const ggx_sggx *g, size_t n,
                               const ggxpy_in *in, double *w)
{
    for (size_t i = 0; i < n; i++) put(w, i, f(g, vec(&in[0], i), num(&in[1], i), num(&in[2], i)));
}
EXPORT void ggxpy_sggx_sample4(const ggx_sggx *g, size_t n, const ggxpy_in *in, double *w)
{
    for (size_t i = 0; i < n; i++)
        put(w, i,
            ggx_sggx_sample_diffuse(g, vec(&in[0], i), num(&in[1], i), num(&in[2], i), num(&in[3], i), num(&in[4], i)));
}

/* ---- fits (ggx/ggx_fit.h) and measured surfaces (libs/surface/surface.h) ----
 * ggx_fit_info reaches Python as one flat array of doubles whose fields are listed once, here: FIT_FIELDS gives each
 * field's name and length, ggxpy_fit_fields() the names as "name:length,..." for the Python side to unpack. */
#include <stdlib.h>

#include "ggx/ggx_fit.h"
#include "surface.h"

#define FIT_FIELDS(X)                                                                                                  \
    X(iterations, 1, (double)i->iterations)                                                                            \
    X(converged, 1, (double)i->converged)                                                                              \
    X(stationarity, 1, i->stationarity)                                                                                \
    X(log_likelihood, 1, i->log_likelihood)                                                                            \
    X(t, 2, i->t[k])                                                                                                   \
    X(sigma, 3, i->sigma[k])                                                                                           \
    X(std_error, 5, i->std_error[k])                                                                                   \
    X(covariance, 25, i->covariance[k / 5][k % 5])                                                                     \
    X(gof_chi2, 1, i->gof_chi2)                                                                                        \
    X(gof_pvalue, 1, i->gof_pvalue)                                                                                    \
    X(gof_cells, 1, (double)i->gof_cells)                                                                              \
    X(gof_dof, 1, (double)i->gof_dof)                                                                                  \
    X(used, 1, (double)i->used)                                                                                        \
    X(ignored_horizon, 1, (double)i->ignored_horizon)                                                                  \
    X(ignored_nonfinite, 1, (double)i->ignored_nonfinite)                                                              \
    X(ignored_weight, 1, (double)i->ignored_weight)                                                                    \
    X(effective_n, 1, i->effective_n)                                                                                  \
    X(clamped, 1, (double)i->clamped)                                                                                  \
    X(best, 1, (double)i->best)                                                                                        \
    X(model_log_likelihood, 4, i->models[k].log_likelihood)                                                            \
    X(model_bic, 4, i->models[k].bic)                                                                                  \
    X(model_parameters, 4, (double)i->models[k].parameters)                                                            \
    X(model_iterations, 4, (double)i->models[k].iterations)                                                            \
    X(model_t, 8, i->models[k / 2].t[k % 2])                                                                           \
    X(model_sigma, 12, i->models[k / 3].sigma[k % 3])                                                                  \
    X(tails_nu, 1, i->tails.nu)                                                                                        \
    X(tails_nu_std_error, 1, i->tails.nu_std_error)                                                                    \
    X(tails_log_likelihood, 1, i->tails.log_likelihood)                                                                \
    X(tails_bic, 1, i->tails.bic)                                                                                      \
    X(tails_t, 2, i->tails.t[k])                                                                                       \
    X(tails_sigma, 3, i->tails.sigma[k])                                                                               \
    X(tails_iterations, 1, (double)i->tails.iterations)                                                                \
    X(tails_converged, 1, (double)i->tails.converged)                                                                  \
    X(tails_subsample, 1, (double)i->tails.subsample)

EXPORT const char *ggxpy_fit_fields(void)
{
#define NAME(f, len, e) #f ":" #len ","
    return FIT_FIELDS(NAME);
#undef NAME
}

static void flatten(const ggx_fit_info *i, double *out)
{
#define PUT(f, len, e)                                                                                                 \
    for (int k = 0; k < len; k++) *out++ = (e);
    FIT_FIELDS(PUT)
#undef PUT
}

EXPORT int ggxpy_fit_normals(ggx_shape *out, const double *m, const double *w, size_t n, int model, int threads,
                             int max_iterations, double tolerance, double *info)
{
    ggx_fit_options o = {(ggx_fit_model)model, max_iterations, tolerance, threads, NULL, NULL, 0};
    ggx_fit_info fi;
    int st = ggx_fit_normals(out, (const ggx_vec3 *)m, w, n, &o, &fi);
    flatten(&fi, info);
    return st;
}

EXPORT int ggxpy_fit_normal_cells(ggx_shape *out, const double *uv, const double *w, size_t n, double q, int model,
                                  int threads, int max_iterations, double tolerance, double *info)
{
    ggx_fit_options o = {(ggx_fit_model)model, max_iterations, tolerance, threads, NULL, NULL, 0};
    ggx_fit_info fi;
    int st = ggx_fit_normal_cells(out, uv, w, n, q, &o, &fi);
    flatten(&fi, info);
    return st;
}

EXPORT int ggxpy_fit_heightfield(ggx_shape *out, const double *h, size_t nx, size_t ny, double dx, double dy,
                                 int keep_tilt, int downsample, int model, int threads, int max_iterations,
                                 double tolerance, double *info)
{
    ggx_fit_options o = {(ggx_fit_model)model, max_iterations, tolerance, threads, NULL, NULL, 0};
    ggx_heightfield_options ho = {keep_tilt, downsample};
    ggx_fit_info fi;
    int st = ggx_fit_heightfield(out, h, nx, ny, dx, dy, &ho, &o, &fi);
    flatten(&fi, info);
    return st;
}

EXPORT size_t ggxpy_sizeof_vec3(void) { return sizeof(ggx_vec3); }

/* A surface read by the readers of the command, held for the Python side to copy: ggxpy_surface_read returns it (or
 * NULL with err), meta = nx, ny, dx, dy, z_scale, bits, channels, is_normals, has_weights; ggxpy_surface_copy fills
 * arrays of nx * ny heights, or 3 nx * ny normal components and nx * ny weights; ggxpy_surface_close frees it. */
EXPORT void *ggxpy_surface_read(const char *path, int normals, int y_down, double meta[9], char *err, size_t errn)
{
    surface *s = malloc(sizeof *s);
    if (!s) {
        snprintf(err, errn, "out of memory");
        return NULL;
    }
    surface_read_options o = {normals ? SURFACE_NORMALS : SURFACE_HEIGHTS, y_down};
    if (surface_read(path, &o, s, err, errn) != 0) {
        free(s);
        return NULL;
    }
    const double v[9] = {(double)s->nx, (double)s->ny, s->dx,       s->dy,
                         s->z_scale,    s->bits,       s->channels, s->kind == SURFACE_NORMALS,
                         s->w != NULL};
    memcpy(meta, v, sizeof v);
    return s;
}

EXPORT void ggxpy_surface_copy(const void *handle, double *values, double *weights)
{
    const surface *s = handle;
    size_t n = s->nx * s->ny;
    if (s->kind == SURFACE_HEIGHTS) memcpy(values, s->h, n * sizeof *values);
    else
        for (size_t i = 0; i < n; i++)
            values[3 * i] = s->m[i].x, values[3 * i + 1] = s->m[i].y, values[3 * i + 2] = s->m[i].z;
    if (weights && s->w) memcpy(weights, s->w, n * sizeof *weights);
}

/* Whether the surface has its texels' decoded red and green (surface.uv); copies them into uv (2 nx * ny) when not
 * NULL. */
EXPORT int ggxpy_surface_uv(const void *handle, double *uv)
{
    const surface *s = handle;
    if (s->uv && uv) memcpy(uv, s->uv, 2 * s->nx * s->ny * sizeof *uv);
    return s->uv != NULL;
}

EXPORT void ggxpy_surface_close(void *handle)
{
    if (!handle) return;
    surface_free(handle);
    free(handle);
}

/* ---- images of the material (libs/render/render.h) ----
 * ggx.render: light 0 the built-in sky, 1 the white furnace, 2 the environment file at path, 3 a distant light from
 * dir (unit, world frame) of irradiance E; sampler a registry name or NULL. Fills rgb (and var unless NULL) with
 * 3 w h floats; returns 0, or -1 with a one-line reason in err. */
#include "render.h"

EXPORT int ggxpy_render(const ggx_shape *s, const ggx_fresnel *f, const char *sampler, int compensate, int scene,
                        int light, const char *path, const double dir[3], double irradiance, int strategy, int w, int h,
                        int spp, int depth, unsigned long long seed, int threads, int jitter, float *rgb, float *var,
                        char *err, size_t errn)
{
    render_spec r;
    render_spec_defaults(&r);
    r.shape = *s, r.fresnel = *f, r.compensate = compensate, r.scene = scene ? RENDER_PLANE : RENDER_SPHERE;
    r.strategy = (render_strategy)strategy, r.width = w, r.height = h, r.spp = spp, r.depth = depth, r.seed = seed;
    r.threads = threads, r.jitter = jitter;
    if (sampler && !(r.sampler = ggx_sampler_find(sampler)))
        return surface_fail(err, errn, "unknown sampler '%s'", sampler);
    render_env env;
    memset(&env, 0, sizeof env);
    int rc = 0;
    if (light == 0) rc = render_env_default_sky(&env, err, errn);
    else if (light == 1) rc = render_env_white(&env, 1.0, err, errn);
    else if (light == 2) {
        surface m;
        surface_read_options o = {SURFACE_RADIANCE, 0};
        rc = surface_read(path, &o, &m, err, errn);
        if (rc == 0 && (m.nx > 65536 || m.ny > 65536)) rc = surface_fail(err, errn, "'%s': too large", path);
        if (rc == 0) {
            float *px = m.rgb;
            m.rgb = NULL;
            rc = render_env_init(&env, (int)m.nx, (int)m.ny, px, NULL, err, errn);
        }
        surface_free(&m);
    } else {
        r.light = RENDER_LIGHT_DIRECTIONAL;
        r.light_dir = (ggx_vec3){dir[0], dir[1], dir[2]};
        r.light_irradiance = irradiance;
    }
    if (rc == 0 && light <= 2) r.env = &env;
    if (rc == 0) rc = render_prepare(&r, err, errn);
    if (rc == 0) {
        long over = render_image(&r, rgb, var);
        if (over)
            rc = surface_fail(err, errn,
                              "the image does not fit single precision: %ld pixel values exceed the largest float "
                              "(%g) with this light; lower its radiance or irradiance",
                              over, (double)FLT_MAX);
    }
    render_release(&r);
    render_env_free(&env);
    return rc;
}

/* ---- The float32 path: the float batch API (ggx/ggx_batch.h) over the Python layout ----
 * ggxpy_f32 runs one batch function over n items whose inputs are ggxpy_in (floats or doubles, directions
 * interleaved (n, 3) or broadcast) and whose outputs are the caller's contiguous float arrays ((n, 3) for directions,
 * (n,) for numbers). It works in chunks of CHUNK items held on the stack: each chunk's inputs are gathered into the
 * struct-of-arrays the batch API takes (a float input of numbers is passed in place), the batch function runs on the
 * chunk and its directions are interleaved into the output. No array of n items is made, and each chunk stays in
 * the cache. A sampler's view is normalised here, in double (the samplers depend on its direction only, and float
 * cannot hold a view of length 1e-50 or 1e300): a zero, NaN or infinite view becomes the zero vector (no sample).
 * A sampler's u read from a double below 1 that rounds to 1 becomes the largest float below 1 (the batch samplers
 * take u in [0, 1)). threads > 1 splits [0, n) into as many contiguous ranges, run by ggx_internal_parallel_for;
 * the results do not depend on it. */
#include <math.h>

#include "common/parallel.h"
#include "ggx/ggx_batch.h"
#include "ggx/ggx_inline.h"

enum { CHUNK = 512 };

/* What ggxpy_f32 runs; inputs and outputs in this order. */
enum {
    F32_NDF,         /* m -> D */
    F32_G1,          /* u, m -> G1 */
    F32_PDF_VNDF,    /* v, m -> pdf */
    F32_BRDF,        /* wi, wo -> f_r (fresnel) */
    F32_NORMALS,     /* view v, u1, u2 -> m (ggx_batch_sample_normals) */
    F32_DIRECTIONS,  /* view wi, u1, u2 -> w, pdf, weight, event (ggx_batch_sample_directions) */
    F32_SAMPLE_EVAL, /* view wi, u1, u2 -> w, pdf, weight, event, f_r (ggx_batch_brdf of the sampled w) */
    F32_PDF_BRDF     /* wi, wo -> pdf of the direction sampler (its float kernel: no batch function has it) */
};

typedef struct f32job {
    int op, sampler;
    const ggx_shape *s;
    const ggx_fresnel *f;
    ggx_shapef sf;
    const ggxpy_in *in;
    void *out[5];
    size_t n, per;
    ggx_status status;
} f32job;

typedef struct soa3 {
    float x[CHUNK], y[CHUNK], z[CHUNK];
} soa3;

/* Directions [b, b + c) of a as floats. */
static void gather(const ggxpy_in *a, size_t b, size_t c, soa3 *o)
{
    if (a->f32) {
        const float *p = (const float *)a->p + (ptrdiff_t)b * a->step;
        for (size_t i = 0; i < c; i++, p += a->step) o->x[i] = p[0], o->y[i] = p[1], o->z[i] = p[2];
    } else {
        const double *p = (const double *)a->p + (ptrdiff_t)b * a->step;
        for (size_t i = 0; i < c; i++, p += a->step)
            o->x[i] = (float)p[0], o->y[i] = (float)p[1], o->z[i] = (float)p[2];
    }
}

/* A view: unit in double, then rounded; the zero vector where it has no direction. */
static void unit_view(double x, double y, double z, float *ox, float *oy, float *oz)
{
    double big = fmax(fabs(x), fmax(fabs(y), fabs(z)));
    x /= big, y /= big, z /= big;
    double l = sqrt(x * x + y * y + z * z);
    x /= l, y /= l, z /= l;
    int ok = isfinite(x) && isfinite(y) && isfinite(z);
    *ox = ok ? (float)x : 0.0f, *oy = ok ? (float)y : 0.0f, *oz = ok ? (float)z : 0.0f;
}

static void gather_view(const ggxpy_in *a, size_t b, size_t c, soa3 *o)
{
    if (a->step == 0) { /* one view: normalised once */
        ggx_vec3 v = vec(a, 0);
        float x, y, z;
        unit_view(v.x, v.y, v.z, &x, &y, &z);
        for (size_t i = 0; i < c; i++) o->x[i] = x, o->y[i] = y, o->z[i] = z;
        return;
    }
    if (a->f32) { /* a float's square neither overflows nor underflows in double: no scaling needed */
        const float *p = (const float *)a->p + (ptrdiff_t)b * a->step;
        for (size_t i = 0; i < c; i++, p += a->step) {
            double x = p[0], y = p[1], z = p[2], r = 1.0 / sqrt(x * x + y * y + z * z);
            int ok = r > 0 && r < INFINITY; /* NaN, zero and infinite views fail */
            o->x[i] = ok ? (float)(x * r) : 0.0f, o->y[i] = ok ? (float)(y * r) : 0.0f;
            o->z[i] = ok ? (float)(z * r) : 0.0f;
        }
        return;
    }
    const double *p = (const double *)a->p + (ptrdiff_t)b * a->step;
    for (size_t i = 0; i < c; i++, p += a->step) unit_view(p[0], p[1], p[2], &o->x[i], &o->y[i], &o->z[i]);
}

/* Numbers [b, b + c) of a as floats: in place for a contiguous float input, else copied into buf. For u (is_u), a
 * double below 1 that rounds to 1 becomes the largest float below 1. */
static const float *gather_num(const ggxpy_in *a, size_t b, size_t c, float *buf, int is_u)
{
    if (a->f32 && a->step == 1) return (const float *)a->p + b;
    if (a->f32) {
        float v = *(const float *)a->p;
        for (size_t i = 0; i < c; i++) buf[i] = v;
        return buf;
    }
    const double *p = (const double *)a->p + (ptrdiff_t)b * a->step;
    const float below_one = 0x1.fffffep-1f;
    for (size_t i = 0; i < c; i++, p += a->step) {
        float v = (float)*p;
        buf[i] = is_u && v >= 1.0f && *p < 1.0 ? below_one : v;
    }
    return buf;
}

static void scatter(float *out, size_t b, size_t c, const soa3 *o)
{
    float *q = out + 3 * b;
    for (size_t i = 0; i < c; i++, q += 3) q[0] = o->x[i], q[1] = o->y[i], q[2] = o->z[i];
}

/* The pdf of a direction sampler from its float kernel. */
static float pdf_direction_f(int sampler, const ggx_shapef *s, ggx_vec3f wi, ggx_vec3f wo)
{
    return sampler == GGX_SAMPLER_BRDF_BOUNDED ? ggx_pdf_brdf_bounded_f(s, wi, wo) : ggx_pdf_brdf_f(s, wi, wo);
}

static void f32_range(f32job *j, size_t begin, size_t end)
{
    soa3 a, m;
    float u1b[CHUNK], u2b[CHUNK], pdf[CHUNK], weight[CHUNK];
    const ggx_shape *s = j->s;
    for (size_t b = begin; b < end; b += CHUNK) {
        size_t c = end - b < CHUNK ? end - b : CHUNK;
        float *o0 = j->out[0], *o1 = j->out[1], *o2 = j->out[2], *o4 = j->out[4];
        int8_t *ev = j->out[3];
        switch (j->op) {
        case F32_NDF:
            gather(&j->in[0], b, c, &m);
            ggx_batch_ndf(o0 + b, c, s, m.x, m.y, m.z);
            break;
        case F32_G1:
        case F32_PDF_VNDF:
        case F32_BRDF:
            gather(&j->in[0], b, c, &a);
            gather(&j->in[1], b, c, &m);
            if (j->op == F32_G1) ggx_batch_g1(o0 + b, c, s, a.x, a.y, a.z, m.x, m.y, m.z);
            else if (j->op == F32_PDF_VNDF) ggx_batch_pdf_vndf(o0 + b, c, s, a.x, a.y, a.z, m.x, m.y, m.z);
            else ggx_batch_brdf(o0 + b, c, s, j->f, a.x, a.y, a.z, m.x, m.y, m.z);
            break;
        case F32_PDF_BRDF:
            gather(&j->in[0], b, c, &a);
            gather(&j->in[1], b, c, &m);
            for (size_t i = 0; i < c; i++)
                o0[b + i] = pdf_direction_f(j->sampler, &j->sf, (ggx_vec3f){a.x[i], a.y[i], a.z[i]},
                                            (ggx_vec3f){m.x[i], m.y[i], m.z[i]});
            break;
        default: { /* the samplers */
            gather_view(&j->in[0], b, c, &a);
            const float *u1 = gather_num(&j->in[1], b, c, u1b, 1), *u2 = gather_num(&j->in[2], b, c, u2b, 1);
            if (j->op == F32_NORMALS) {
                j->status = ggx_batch_sample_normals((ggx_sampler_id)j->sampler, m.x, m.y, m.z, c, s, a.x, a.y, a.z, u1,
                                                     u2);
                scatter(o0, b, c, &m);
                break;
            }
            float *p = o1 ? o1 + b : pdf, *w = o2 ? o2 + b : weight;
            j->status = ggx_batch_sample_directions((ggx_sampler_id)j->sampler, m.x, m.y, m.z, p, w, c, s, j->f, a.x,
                                                    a.y, a.z, u1, u2);
            scatter(o0, b, c, &m);
            if (ev)
                for (size_t i = 0; i < c; i++) ev[b + i] = (int8_t)(p[i] > 0);
            if (j->op == F32_SAMPLE_EVAL) ggx_batch_brdf(o4 + b, c, s, j->f, a.x, a.y, a.z, m.x, m.y, m.z);
        }
        }
        if (j->status != GGX_OK) return;
    }
}

/* Range k of [0, n), run by thread k with its own copy of the job (its own status). */
static void f32_part(void *ctx, int k)
{
    f32job *j = (f32job *)ctx + k;
    size_t begin = (size_t)k * j->per < j->n ? (size_t)k * j->per : j->n;
    size_t end = begin + j->per < j->n ? begin + j->per : j->n;
    f32_range(j, begin, end);
}

enum { THREAD_MIN = 65536 };

/* out: outputs in the op's order (pdf, weight and event may be NULL for the samplers). Returns a ggx_status. */
EXPORT int ggxpy_f32(int op, int sampler, const ggx_shape *s, const ggx_fresnel *f, size_t n, const ggxpy_in *in,
                     void *out0, void *out1, void *out2, void *out3, void *out4, int threads)
{
    f32job j;
    memset(&j, 0, sizeof j);
    j.op = op, j.sampler = sampler, j.s = s, j.f = f, j.in = in, j.n = j.per = n, j.status = GGX_OK;
    j.out[0] = out0, j.out[1] = out1, j.out[2] = out2, j.out[3] = out3, j.out[4] = out4;
    ggx_shapef_from(&j.sf, s);
    if (threads <= 1 || n < THREAD_MIN) {
        f32_range(&j, 0, n);
        return j.status;
    }
    f32job parts[256];
    threads = threads < 256 ? threads : 256;
    /* whole chunks per thread: the chunks (whose bounds decide which elements a vectorised loop's tail takes) are
     * the same for every count of threads */
    size_t per = ((n + (size_t)threads - 1) / (size_t)threads + CHUNK - 1) / CHUNK * CHUNK;
    for (int k = 0; k < threads; k++) parts[k] = j, parts[k].per = per;
    ggx_internal_parallel_for(threads, f32_part, parts);
    for (int k = 0; k < threads; k++)
        if (parts[k].status != GGX_OK) return parts[k].status;
    return GGX_OK;
}

/* The fused step of a renderer in double: the sample of a direction sampler (w, pdf, weight, event) and the BRDF of
 * the sampled direction, f_r(wi, w) (ggx_brdf_eval), per item. Inputs wi, u1, u2. */
EXPORT void ggxpy_sample_eval(int id, const ggx_shape *s, const ggx_fresnel *fr, size_t n, const ggxpy_in *in,
                              double *w, double *pdf, double *weight, int8_t *event, double *f_r)
{
    ggx_sample (*f)(const ggx_shape *, const ggx_fresnel *, double, ggx_vec3, double, double, double,
                    ggx_transport) = ggx_sampler_get((ggx_sampler_id)id)->sample_direction;
    for (size_t i = 0; i < n; i++) {
        ggx_vec3 wi = vec(&in[0], i);
        ggx_sample r = f(s, fr, 1.5, wi, num(&in[1], i), num(&in[2], i), 0.0, GGX_RADIANCE);
        put(w, i, r.w);
        pdf[i] = r.pdf, weight[i] = r.weight, event[i] = (int8_t)r.event;
        f_r[i] = ggx_brdf_eval(s, fr, wi, r.w);
    }
}
