/* The variant table of variants.h. SPDX-License-Identifier: MIT */
#include "variants.h"

#include "ggx/ggx_inline.h"
#include "testlib.h"

static const ggx_sampler_info *info_of(ggx_sampler_id id)
{
    const ggx_sampler_info *info = ggx_sampler_get(id);
    CHECK(info != NULL, "no registry entry for sampler id %d", (int)id);
    return info;
}

static int is_normal_family(ggx_sampler_family f) { return f == GGX_FAMILY_NDF || f == GGX_FAMILY_VNDF; }

/* ---- exported: ggx.h, the samplers through the registry ---- */

static int exported_has(const variant *vr, ggx_sampler_id id)
{
    (void)vr;
    const ggx_sampler_info *info = info_of(id);
    if (is_normal_family(info->family)) return info->sample ? 1 : 0;
    if (info->family == GGX_FAMILY_REJECTION) return info->sample_reject ? 2 : 0;
    return info->family == GGX_FAMILY_DIRECTION && info->sample_direction && info->pdf_direction ? 3 : 0;
}
static void exported_sample(const variant *vr, ggx_sampler_id id, const ggx_shape *s, size_t n, const ggx_vec3 *v,
                            const double *u1, const double *u2, ggx_vec3 *m)
{
    (void)vr;
    const ggx_sampler_info *info = info_of(id);
    for (size_t i = 0; i < n; i++) m[i] = info->sample(s, v[i], u1[i], u2[i]);
}
static ggx_vec3 exported_reject(const variant *vr, ggx_sampler_id id, const ggx_shape *s, ggx_vec3 v,
                                ggx_uniform_fn next, void *state, unsigned *trials)
{
    (void)vr;
    return info_of(id)->sample_reject(s, v, next, state, trials);
}
static void exported_sampler_pdf(const variant *vr, ggx_sampler_id id, const ggx_shape *s, size_t n, const ggx_vec3 *v,
                                 const ggx_vec3 *m, double *pdf)
{
    (void)vr;
    const ggx_sampler_info *info = info_of(id);
    for (size_t i = 0; i < n; i++) pdf[i] = info->pdf(s, v[i], m[i]);
}
static void exported_ndf(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *m, double *d)
{
    (void)vr;
    for (size_t i = 0; i < n; i++) d[i] = ggx_ndf(s, m[i]);
}
static void exported_g1(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *u, const ggx_vec3 *m,
                        double *g)
{
    (void)vr;
    for (size_t i = 0; i < n; i++) g[i] = ggx_g1(s, u[i], m[i]);
}
static void exported_pdf_vndf(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *v, const ggx_vec3 *m,
                              double *pdf)
{
    (void)vr;
    for (size_t i = 0; i < n; i++) pdf[i] = ggx_pdf_vndf(s, v[i], m[i]);
}
static void exported_brdf(const variant *vr, const ggx_shape *s, const ggx_fresnel *f, size_t n, const ggx_vec3 *wi,
                          const ggx_vec3 *wo, double *fr)
{
    (void)vr;
    for (size_t i = 0; i < n; i++) fr[i] = ggx_brdf_eval(s, f, wi[i], wo[i]);
}
static void exported_sample_vndf(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *v, const double *u1,
                                 const double *u2, ggx_vec3 *m)
{
    (void)vr;
    for (size_t i = 0; i < n; i++) m[i] = ggx_sample_vndf(s, v[i], u1[i], u2[i]);
}
static void exported_sample_ndf(const variant *vr, const ggx_shape *s, size_t n, const double *u1, const double *u2,
                                ggx_vec3 *m)
{
    (void)vr;
    for (size_t i = 0; i < n; i++) m[i] = ggx_sample_ndf(s, u1[i], u2[i]);
}
static void exported_sample_brdf(const variant *vr, int bounded, const ggx_shape *s, const ggx_fresnel *f, size_t n,
                                 const ggx_vec3 *wi, const double *u1, const double *u2, ggx_sample *out)
{
    (void)vr;
    for (size_t i = 0; i < n; i++)
        out[i] = bounded ? ggx_sample_brdf_bounded(s, f, wi[i], u1[i], u2[i])
                         : ggx_sample_brdf(s, f, wi[i], u1[i], u2[i]);
}

/* ---- inline: the kernels of ggx_inline.h, double (_d) and float (_f) ---- */

static ggx_vec3f down3(ggx_vec3 a)
{
    ggx_vec3f b = {(float)a.x, (float)a.y, (float)a.z};
    return b;
}
static ggx_vec3 up3(ggx_vec3f a) { return t_vec(a.x, a.y, a.z); }

/* Every registry sampler's kernels in one signature per precision (NDF samplers ignore v), generated from
 * GGX_SAMPLER_LIST: a family without a case here fails to compile, so a new family cannot be left out silently. */
typedef ggx_vec3 (*normal_d_fn)(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
typedef ggx_vec3 (*normal_f_fn)(const ggx_shapef *s, ggx_vec3 v, double u1, double u2);
typedef ggx_vec3 (*reject_d_fn)(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state, unsigned *trials);
typedef ggx_vec3 (*reject_f_fn)(const ggx_shapef *s, ggx_vec3 v, ggx_uniform_fn next, void *state, unsigned *trials);

#define KERNELS_NDF(ID, stem)                                                                                          \
    static ggx_vec3 d_##ID(const ggx_shape *s, ggx_vec3 v, double u1, double u2)                                       \
    {                                                                                                                  \
        (void)v;                                                                                                       \
        return ggx_##stem##_d(s, u1, u2);                                                                              \
    }                                                                                                                  \
    static ggx_vec3 f_##ID(const ggx_shapef *s, ggx_vec3 v, double u1, double u2)                                      \
    {                                                                                                                  \
        (void)v;                                                                                                       \
        return up3(ggx_##stem##_f(s, (float)u1, (float)u2));                                                           \
    }
#define KERNELS_VNDF(ID, stem)                                                                                         \
    static ggx_vec3 d_##ID(const ggx_shape *s, ggx_vec3 v, double u1, double u2)                                       \
    {                                                                                                                  \
        return ggx_##stem##_d(s, v, u1, u2);                                                                           \
    }                                                                                                                  \
    static ggx_vec3 f_##ID(const ggx_shapef *s, ggx_vec3 v, double u1, double u2)                                      \
    {                                                                                                                  \
        return up3(ggx_##stem##_f(s, down3(v), (float)u1, (float)u2));                                                 \
    }
#define KERNELS_REJECTION(ID, stem)                                                                                    \
    static ggx_vec3 rd_##ID(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state, unsigned *trials)        \
    {                                                                                                                  \
        return ggx_##stem##_d(s, v, next, state, trials);                                                              \
    }                                                                                                                  \
    static ggx_vec3 rf_##ID(const ggx_shapef *s, ggx_vec3 v, ggx_uniform_fn next, void *state, unsigned *trials)       \
    {                                                                                                                  \
        return up3(ggx_##stem##_f(s, down3(v), next, state, trials));                                                  \
    }
#define KERNELS_DIRECTION(ID, stem) /* directions are not samplers of normals (sample_brdf below) */
#define KERNELS(ID, name, stem, family, domain, inverse, batch, help) KERNELS_##family(ID, stem)
GGX_SAMPLER_LIST(KERNELS)

#define NORMAL_NDF(fn) fn
#define NORMAL_VNDF(fn) fn
#define NORMAL_REJECTION(fn) NULL
#define NORMAL_DIRECTION(fn) NULL
#define REJECT_NDF(fn) NULL
#define REJECT_VNDF(fn) NULL
#define REJECT_REJECTION(fn) fn
#define REJECT_DIRECTION(fn) NULL
#define ROW_ND(ID, name, stem, family, domain, inverse, batch, help) [GGX_SAMPLER_##ID] = NORMAL_##family(d_##ID),
#define ROW_NF(ID, name, stem, family, domain, inverse, batch, help) [GGX_SAMPLER_##ID] = NORMAL_##family(f_##ID),
#define ROW_RD(ID, name, stem, family, domain, inverse, batch, help) [GGX_SAMPLER_##ID] = REJECT_##family(rd_##ID),
#define ROW_RF(ID, name, stem, family, domain, inverse, batch, help) [GGX_SAMPLER_##ID] = REJECT_##family(rf_##ID),
static const normal_d_fn NORMAL_D[GGX_SAMPLER_COUNT] = {GGX_SAMPLER_LIST(ROW_ND)};
static const normal_f_fn NORMAL_F[GGX_SAMPLER_COUNT] = {GGX_SAMPLER_LIST(ROW_NF)};
static const reject_d_fn REJECT_D[GGX_SAMPLER_COUNT] = {GGX_SAMPLER_LIST(ROW_RD)};
static const reject_f_fn REJECT_F[GGX_SAMPLER_COUNT] = {GGX_SAMPLER_LIST(ROW_RF)};

static int is_f(const variant *vr) { return vr->precision == 32; }

static int inline_has(const variant *vr, ggx_sampler_id id)
{
    if (id < 0 || id >= GGX_SAMPLER_COUNT) return 0;
    if (is_f(vr) ? NORMAL_F[id] != NULL : NORMAL_D[id] != NULL) return 1;
    return (is_f(vr) ? REJECT_F[id] != NULL : REJECT_D[id] != NULL) ? 2 : 0;
}
static void inline_sample(const variant *vr, ggx_sampler_id id, const ggx_shape *s, size_t n, const ggx_vec3 *v,
                          const double *u1, const double *u2, ggx_vec3 *m)
{
    CHECK(inline_has(vr, id) == 1, "%s has no sampler of normals %d", vr->name, (int)id);
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    for (size_t i = 0; i < n; i++)
        m[i] = is_f(vr) ? NORMAL_F[id](&sf, v[i], u1[i], u2[i]) : NORMAL_D[id](s, v[i], u1[i], u2[i]);
}
static ggx_vec3 inline_reject(const variant *vr, ggx_sampler_id id, const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next,
                              void *state, unsigned *trials)
{
    CHECK(inline_has(vr, id) == 2, "%s has no rejection sampler %d", vr->name, (int)id);
    if (!is_f(vr)) return REJECT_D[id](s, v, next, state, trials);
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    return REJECT_F[id](&sf, v, next, state, trials);
}

/* One loop per evaluation: EVAL_LOOP(expr_d, expr_f) with the element's inputs named by the caller. */
#define EVAL_LOOP(out, expr_d, expr_f)                                                                                 \
    do {                                                                                                               \
        ggx_shapef sf;                                                                                                 \
        ggx_shapef_from(&sf, s);                                                                                       \
        for (size_t i = 0; i < n; i++) out[i] = is_f(vr) ? (double)(expr_f) : (expr_d);                                \
    } while (0)

static void inline_sampler_pdf(const variant *vr, ggx_sampler_id id, const ggx_shape *s, size_t n, const ggx_vec3 *v,
                               const ggx_vec3 *m, double *pdf)
{
    if (info_of(id)->family == GGX_FAMILY_NDF) EVAL_LOOP(pdf, ggx_pdf_ndf_d(s, m[i]), ggx_pdf_ndf_f(&sf, down3(m[i])));
    else EVAL_LOOP(pdf, ggx_pdf_vndf_d(s, v[i], m[i]), ggx_pdf_vndf_f(&sf, down3(v[i]), down3(m[i])));
}
static void inline_ndf(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *m, double *d)
{
    EVAL_LOOP(d, ggx_ndf_d(s, m[i]), ggx_ndf_f(&sf, down3(m[i])));
}
static void inline_g1(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *u, const ggx_vec3 *m, double *g)
{
    EVAL_LOOP(g, ggx_g1_d(s, u[i], m[i]), ggx_g1_f(&sf, down3(u[i]), down3(m[i])));
}
static void inline_pdf_vndf(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *v, const ggx_vec3 *m,
                            double *pdf)
{
    EVAL_LOOP(pdf, ggx_pdf_vndf_d(s, v[i], m[i]), ggx_pdf_vndf_f(&sf, down3(v[i]), down3(m[i])));
}
static void inline_brdf(const variant *vr, const ggx_shape *s, const ggx_fresnel *f, size_t n, const ggx_vec3 *wi,
                        const ggx_vec3 *wo, double *fr)
{
    ggx_fresnelf ff;
    ggx_fresnelf_from(&ff, f);
    EVAL_LOOP(fr, ggx_brdf_eval_d(s, f, wi[i], wo[i]), ggx_brdf_eval_f(&sf, &ff, down3(wi[i]), down3(wo[i])));
}
static void inline_sample_vndf(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *v, const double *u1,
                               const double *u2, ggx_vec3 *m)
{
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    for (size_t i = 0; i < n; i++)
        m[i] = is_f(vr) ? up3(ggx_sample_vndf_f(&sf, down3(v[i]), (float)u1[i], (float)u2[i]))
                        : ggx_sample_vndf_d(s, v[i], u1[i], u2[i]);
}
static void inline_sample_ndf(const variant *vr, const ggx_shape *s, size_t n, const double *u1, const double *u2,
                              ggx_vec3 *m)
{
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    for (size_t i = 0; i < n; i++)
        m[i] = is_f(vr) ? up3(ggx_sample_ndf_f(&sf, (float)u1[i], (float)u2[i])) : ggx_sample_ndf_d(s, u1[i], u2[i]);
}
static void inline_sample_brdf(const variant *vr, int bounded, const ggx_shape *s, const ggx_fresnel *f, size_t n,
                               const ggx_vec3 *wi, const double *u1, const double *u2, ggx_sample *out)
{
    ggx_shapef sf;
    ggx_fresnelf ff;
    ggx_shapef_from(&sf, s);
    ggx_fresnelf_from(&ff, f);
    for (size_t i = 0; i < n; i++) {
        if (!is_f(vr)) {
            out[i] = bounded ? ggx_sample_brdf_bounded_d(s, f, wi[i], u1[i], u2[i])
                             : ggx_sample_brdf_d(s, f, wi[i], u1[i], u2[i]);
            continue;
        }
        ggx_vec3f w = down3(wi[i]);
        float a = (float)u1[i], b = (float)u2[i];
        ggx_samplef x = bounded ? ggx_sample_brdf_bounded_f(&sf, &ff, w, a, b) : ggx_sample_brdf_f(&sf, &ff, w, a, b);
        out[i].w = up3(x.w), out[i].pdf = x.pdf, out[i].weight = x.weight, out[i].event = x.event;
    }
}

/* ---- batch: ggx_batch.h on the variant's instruction set, in chunks of float arrays ---- */

/* One call of a batch function over n elements: double inputs (NULL where unused) converted chunk by chunk to the
 * float arrays of ggx_batch.h, float outputs widened into value (one per element), m (normals and directions) and
 * smp (direction samples). */
typedef enum batch_fn {
    B_NDF,
    B_G1,
    B_PDF_VNDF,
    B_BRDF,
    B_NORMALS,
    B_SAMPLE_VNDF,
    B_SAMPLE_NDF,
    B_SAMPLE_BRDF,
    B_ANISO
} batch_fn;
typedef struct batch_call {
    batch_fn fn;
    ggx_sampler_id id; /* B_NORMALS */
    const ggx_shape *s;
    const ggx_fresnel *f;
    const ggx_vec3 *a, *b; /* the first and second direction of the function */
    const double *u1, *u2, *ax, *ay;
    double *value;
    ggx_vec3 *m;
    ggx_sample *smp;
} batch_call;
enum { CHUNK = 256 };

static void floats_of_vecs(float x[3][CHUNK], const ggx_vec3 *v, size_t k)
{
    for (size_t i = 0; v && i < k; i++) x[0][i] = (float)v[i].x, x[1][i] = (float)v[i].y, x[2][i] = (float)v[i].z;
}
static void floats_of(float *f, const double *d, size_t k)
{
    for (size_t i = 0; d && i < k; i++) f[i] = (float)d[i];
}

/* The path is process-wide: set it on every call, so that variants can be interleaved. */
static void batch_run(const variant *vr, const batch_call *c, size_t n)
{
    CHECK(ggx_batch_set_isa(vr->isa) == GGX_OK, "%s: ggx_batch_set_isa refused", vr->name);
    for (size_t i0 = 0; i0 < n; i0 += CHUNK) {
        size_t k = n - i0 < CHUNK ? n - i0 : CHUNK;
        float a[3][CHUNK], b[3][CHUNK], u1[CHUNK], u2[CHUNK], ax[CHUNK], ay[CHUNK], o[5][CHUNK];
        floats_of_vecs(a, c->a ? c->a + i0 : NULL, k), floats_of_vecs(b, c->b ? c->b + i0 : NULL, k);
        floats_of(u1, c->u1 ? c->u1 + i0 : NULL, k), floats_of(u2, c->u2 ? c->u2 + i0 : NULL, k);
        floats_of(ax, c->ax ? c->ax + i0 : NULL, k), floats_of(ay, c->ay ? c->ay + i0 : NULL, k);
        ggx_status st = GGX_OK;
        switch (c->fn) {
        case B_NDF: ggx_batch_ndf(o[0], k, c->s, a[0], a[1], a[2]); break;
        case B_G1: ggx_batch_g1(o[0], k, c->s, a[0], a[1], a[2], b[0], b[1], b[2]); break;
        case B_PDF_VNDF: ggx_batch_pdf_vndf(o[0], k, c->s, a[0], a[1], a[2], b[0], b[1], b[2]); break;
        case B_BRDF: ggx_batch_brdf(o[0], k, c->s, c->f, a[0], a[1], a[2], b[0], b[1], b[2]); break;
        case B_NORMALS:
            st = ggx_batch_sample_normals(c->id, o[0], o[1], o[2], k, c->s, a[0], a[1], a[2], u1, u2);
            break;
        case B_SAMPLE_VNDF: ggx_batch_sample_vndf(o[0], o[1], o[2], k, c->s, a[0], a[1], a[2], u1, u2); break;
        case B_SAMPLE_NDF: ggx_batch_sample_ndf(o[0], o[1], o[2], k, c->s, u1, u2); break;
        case B_SAMPLE_BRDF:
            st = ggx_batch_sample_directions(c->id, o[0], o[1], o[2], o[3], o[4], k, c->s, c->f, a[0], a[1], a[2], u1,
                                             u2);
            break;
        case B_ANISO: ggx_batch_sample_vndf_aniso(o[0], o[1], o[2], k, ax, ay, a[0], a[1], a[2], u1, u2); break;
        }
        CHECK(st == GGX_OK, "%s: batch function %d: %s", vr->name, (int)c->fn, ggx_status_str(st));
        for (size_t i = 0; i < k; i++) {
            if (c->value) c->value[i0 + i] = o[0][i];
            if (c->m) c->m[i0 + i] = t_vec(o[0][i], o[1][i], o[2][i]);
            if (c->smp) { /* invalid samples are written as w = 0, pdf 0, weight 0; valid ones are reflections */
                ggx_sample *x = &c->smp[i0 + i];
                x->w = t_vec(o[0][i], o[1][i], o[2][i]), x->pdf = o[3][i], x->weight = o[4][i];
                x->event = o[3][i] > 0 ? GGX_EVENT_REFLECT : GGX_EVENT_INVALID;
            }
        }
    }
}

static int batch_has(const variant *vr, ggx_sampler_id id)
{
    (void)vr;
    const ggx_sampler_info *info = ggx_sampler_get(id);
    return info && info->batch && is_normal_family(info->family) ? 1 : 0;
}
static void batch_sample(const variant *vr, ggx_sampler_id id, const ggx_shape *s, size_t n, const ggx_vec3 *v,
                         const double *u1, const double *u2, ggx_vec3 *m)
{
    batch_call c = {B_NORMALS, id, s, NULL, v, NULL, u1, u2, NULL, NULL, NULL, m, NULL};
    batch_run(vr, &c, n);
}
static void batch_ndf(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *m, double *d)
{
    batch_call c = {B_NDF, 0, s, NULL, m, NULL, NULL, NULL, NULL, NULL, d, NULL, NULL};
    batch_run(vr, &c, n);
}
static void batch_g1(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *u, const ggx_vec3 *m, double *g)
{
    batch_call c = {B_G1, 0, s, NULL, u, m, NULL, NULL, NULL, NULL, g, NULL, NULL};
    batch_run(vr, &c, n);
}
static void batch_pdf_vndf(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *v, const ggx_vec3 *m,
                           double *pdf)
{
    batch_call c = {B_PDF_VNDF, 0, s, NULL, v, m, NULL, NULL, NULL, NULL, pdf, NULL, NULL};
    batch_run(vr, &c, n);
}
/* The batch API has no pdf_ndf: D(m) from ggx_batch_ndf times m.z. */
static void batch_sampler_pdf(const variant *vr, ggx_sampler_id id, const ggx_shape *s, size_t n, const ggx_vec3 *v,
                              const ggx_vec3 *m, double *pdf)
{
    if (info_of(id)->family != GGX_FAMILY_NDF) {
        batch_pdf_vndf(vr, s, n, v, m, pdf);
        return;
    }
    batch_ndf(vr, s, n, m, pdf);
    for (size_t i = 0; i < n; i++) pdf[i] = m[i].z > 0 ? pdf[i] * (float)m[i].z : 0.0;
}
static void batch_brdf(const variant *vr, const ggx_shape *s, const ggx_fresnel *f, size_t n, const ggx_vec3 *wi,
                       const ggx_vec3 *wo, double *fr)
{
    batch_call c = {B_BRDF, 0, s, f, wi, wo, NULL, NULL, NULL, NULL, fr, NULL, NULL};
    batch_run(vr, &c, n);
}
static void batch_sample_vndf(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *v, const double *u1,
                              const double *u2, ggx_vec3 *m)
{
    batch_call c = {B_SAMPLE_VNDF, 0, s, NULL, v, NULL, u1, u2, NULL, NULL, NULL, m, NULL};
    batch_run(vr, &c, n);
}
static void batch_sample_ndf(const variant *vr, const ggx_shape *s, size_t n, const double *u1, const double *u2,
                             ggx_vec3 *m)
{
    batch_call c = {B_SAMPLE_NDF, 0, s, NULL, NULL, NULL, u1, u2, NULL, NULL, NULL, m, NULL};
    batch_run(vr, &c, n);
}
static void batch_sample_brdf(const variant *vr, int bounded, const ggx_shape *s, const ggx_fresnel *f, size_t n,
                              const ggx_vec3 *wi, const double *u1, const double *u2, ggx_sample *out)
{
    batch_call c = {B_SAMPLE_BRDF,
                    bounded ? GGX_SAMPLER_BRDF_BOUNDED : GGX_SAMPLER_BRDF,
                    s,
                    f,
                    wi,
                    NULL,
                    u1,
                    u2,
                    NULL,
                    NULL,
                    NULL,
                    NULL,
                    out};
    batch_run(vr, &c, n);
}
static void batch_sample_vndf_aniso(const variant *vr, size_t n, const double *alpha_x, const double *alpha_y,
                                    const ggx_vec3 *v, const double *u1, const double *u2, ggx_vec3 *m)
{
    batch_call c = {B_ANISO, 0, NULL, NULL, v, NULL, u1, u2, alpha_x, alpha_y, NULL, m, NULL};
    batch_run(vr, &c, n);
}

#define EXPORTED_FNS                                                                                                   \
    exported_has, exported_sample, exported_reject, exported_sampler_pdf, exported_ndf, exported_g1,                   \
        exported_pdf_vndf, exported_brdf, exported_sample_vndf, exported_sample_ndf, exported_sample_brdf, NULL
#define INLINE_FNS                                                                                                     \
    inline_has, inline_sample, inline_reject, inline_sampler_pdf, inline_ndf, inline_g1, inline_pdf_vndf, inline_brdf, \
        inline_sample_vndf, inline_sample_ndf, inline_sample_brdf, NULL
#define BATCH_FNS                                                                                                      \
    batch_has, batch_sample, NULL, batch_sampler_pdf, batch_ndf, batch_g1, batch_pdf_vndf, batch_brdf,                 \
        batch_sample_vndf, batch_sample_ndf, batch_sample_brdf, batch_sample_vndf_aniso

const variant VARIANTS[VARIANT_COUNT] = {
    {"exported", 64, GGX_ISA_AUTO, 0, EXPORTED_FNS}, {"inline-d", 64, GGX_ISA_AUTO, 0, INLINE_FNS},
    {"inline-f", 32, GGX_ISA_AUTO, 0, INLINE_FNS},   {"batch-scalar", 32, GGX_ISA_SCALAR, 1, BATCH_FNS},
    {"batch-avx2", 32, GGX_ISA_AVX2, 1, BATCH_FNS},  {"batch-avx512", 32, GGX_ISA_AVX512, 1, BATCH_FNS},
};

int variant_available(const variant *vr) { return vr->isa == GGX_ISA_AUTO || ggx_batch_isa_available(vr->isa); }

int variant_index(const variant *vr) { return (int)(vr - VARIANTS); }
