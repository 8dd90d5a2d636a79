/* SPDX-License-Identifier: MIT */
#include "verify.h"

#include "ggx/ggx_inline.h"

#include "common/gauss.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>

double rng_uniform(rng *r)
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-53;
}

double rng_range(rng *r, double a, double b) { return a + (b - a) * rng_uniform(r); }

/* The vector helpers are the kernel's (include/ggx/kernel/vec.inc) in double. */
ggx_vec3 t_vec(double x, double y, double z) { return ggx_k_v3_d(x, y, z); }
ggx_vec3 t_dir(double theta, double phi) { return t_vec(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)); }
double t_dot(ggx_vec3 a, ggx_vec3 b) { return ggx_k_dot_d(a, b); }
ggx_vec3 t_scale(ggx_vec3 a, double k) { return ggx_k_scale_d(a, k); }
ggx_vec3 t_add(ggx_vec3 a, ggx_vec3 b) { return ggx_k_add_d(a, b); }
ggx_vec3 t_normalize(ggx_vec3 v) { return t_scale(v, 1.0 / sqrt(t_dot(v, v))); } /* NaN for the zero vector */
ggx_vec3 t_cross(ggx_vec3 a, ggx_vec3 b) { return ggx_k_cross_d(a, b); }
ggx_vec3 t_matvec(const double M[3][3], ggx_vec3 v) { return ggx_k_mul_d(M, v); }
ggx_vec3 t_mattvec(const double M[3][3], ggx_vec3 v) { return ggx_k_tmul_d(M, v); }
void t_frame(ggx_vec3 n, ggx_vec3 *e1, ggx_vec3 *e2)
{
    ggx_vec3 a = fabs(n.x) < 0.6 ? t_vec(1, 0, 0) : t_vec(0, 1, 0);
    *e1 = t_normalize(t_cross(a, n));
    *e2 = t_cross(n, *e1);
}

/* ---- quadrature ---- */

/* The rule tables are computed once per process; pthread_once makes the first quadratures of concurrent threads
 * wait for them instead of racing on the tables. */
static gq_rule rule;
static pthread_once_t gl_once = PTHREAD_ONCE_INIT;
static void gl_compute(void) { gq_rule_init(&rule); }
static void gl_init(void) { pthread_once(&gl_once, gl_compute); }

int quad_gl_order(void) { return GQ_N; }

double quad_gl(t_fn1 f, void *ctx, double a, double b)
{
    gl_init();
    double c = 0.5 * (a + b), h = 0.5 * (b - a), sum = 0.0;
    for (int i = 0; i < GQ_N; i++) sum += rule.w[i] * f(c + h * rule.x[i], ctx);
    return sum * h;
}

enum { MAX_PANELS = 2000 };
double quad_adapt(t_fn1 f, void *ctx, double a, double b, double abs_tol)
{
    if (!(b > a)) return 0.0;
    gl_init();
    gq_panel ps[MAX_PANELS]; /* on the stack: calls nest (the 2D rules call this inside their integrand) */
    const double br[2] = {a, b};
    return gq_adapt(&rule, f, ctx, br, 2, abs_tol, ps, MAX_PANELS);
}

typedef struct hemi_ctx {
    const ggx_shape *s;
    t_integrand f;
    void *ctx;
    ggx_vec3 p, e1, e2; /* sphere-space pole normalize(A n) and frame */
    ggx_vec3 w[8];      /* cut normals in sphere space, A u_k, in frame coordinates */
    int ncuts;
    double theta, inner_tol;
    long calls;
} hemi_ctx;

static double hemi_phi(double phi, void *vc)
{
    hemi_ctx *c = vc;
    double st = sin(c->theta), ct = cos(c->theta), cp = cos(phi), sp = sin(phi);
    ggx_vec3 loc = t_vec(st * cp, st * sp, ct); /* in (e1, e2, p) coordinates */
    for (int k = 0; k < c->ncuts; k++)
        if (t_dot(loc, c->w[k]) < 0.0) return 0.0;
    ggx_vec3 ms = t_add(t_add(t_scale(c->e1, loc.x), t_scale(c->e2, loc.y)), t_scale(c->p, loc.z));
    ggx_vec3 at = t_mattvec(c->s->a, ms);
    double l = sqrt(t_dot(at, at));
    ggx_vec3 m = t_scale(at, 1.0 / l);
    c->calls++;
    return c->f(m, c->ctx) * c->s->det / (l * l * l) * st;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Break points of the inner (phi) integral at the current theta: where the cut great circles cross. */
static double hemi_theta(double theta, void *vc)
{
    hemi_ctx *c = vc;
    c->theta = theta;
    double br[2 + 2 * 8];
    int nb = 0;
    br[nb++] = 0.0;
    br[nb++] = 2.0 * GGX_PI;
    for (int k = 0; k < c->ncuts; k++) {
        double R = hypot(c->w[k].x, c->w[k].y);
        if (!(R > 0.0)) continue;
        double rhs = -c->w[k].z * cos(theta) / (R * sin(theta));
        if (!(fabs(rhs) < 1.0)) continue;
        double phi0 = atan2(c->w[k].y, c->w[k].x), d = acos(rhs);
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            double ph = fmod(phi0 + sgn * d + 4.0 * GGX_PI, 2.0 * GGX_PI);
            br[nb++] = ph;
        }
    }
    qsort(br, (size_t)nb, sizeof br[0], cmp_double);
    double sum = 0.0;
    for (int i = 0; i + 1 < nb; i++) sum += quad_adapt(hemi_phi, c, br[i], br[i + 1], c->inner_tol / nb);
    return sum;
}

double quad_hemisphere(const ggx_shape *s, t_integrand f, void *ctx, const ggx_vec3 *cuts, int ncuts, double rel_tol,
                       long *calls)
{
    hemi_ctx c;
    c.s = s;
    c.f = f;
    c.ctx = ctx;
    c.p = t_normalize(s->an);
    t_frame(c.p, &c.e1, &c.e2);
    c.ncuts = ncuts;
    c.calls = 0;
    double br[2 + 8];
    int nb = 0;
    br[nb++] = 0.0;
    br[nb++] = 0.5 * GGX_PI;
    for (int k = 0; k < ncuts && k < 8; k++) {
        ggx_vec3 w = t_matvec(s->a, cuts[k]);
        c.w[k] = t_vec(t_dot(w, c.e1), t_dot(w, c.e2), t_dot(w, c.p));
        double R = hypot(c.w[k].x, c.w[k].y);
        double tb = atan2(fabs(c.w[k].z), R); /* the cut reaches polar angle tb */
        if (tb > 0.0 && tb < 0.5 * GGX_PI) br[nb++] = tb;
    }
    qsort(br, (size_t)nb, sizeof br[0], cmp_double);
    /* A first pass at a loose tolerance sets the scale for the absolute tolerance of the real pass. */
    c.inner_tol = 1e-3;
    double est = 0.0;
    for (int i = 0; i + 1 < nb; i++) est += quad_gl(hemi_theta, &c, br[i], br[i + 1]);
    double abs_tol = rel_tol * fabs(est) + 1e-300;
    c.inner_tol = 0.1 * abs_tol;
    double sum = 0.0;
    for (int i = 0; i + 1 < nb; i++) sum += quad_adapt(hemi_theta, &c, br[i], br[i + 1], 0.5 * abs_tol / nb);
    if (calls) *calls = c.calls;
    return sum;
}

ggx_vec3 key_of_normal(const ggx_shape *s, ggx_vec3 m) { return t_normalize(t_matvec(s->ainv_t, m)); }

ggx_vec3 normal_of_key(const ggx_shape *s, ggx_vec3 k, double *jacobian)
{
    ggx_vec3 at = t_mattvec(s->a, k);
    double l = sqrt(t_dot(at, at));
    if (jacobian) *jacobian = s->det / (l * l * l);
    return t_scale(at, 1.0 / l);
}
