/* The ellipsoid NDF, its areas, masking and the visible-normal density (Walter et al. 2014).
 * SPDX-License-Identifier: MIT */
#include <float.h>

#include "internal.h"

/* ||A^{-T} m||^2: the quadric whose square is in the denominator of D (eq 1) and in Kg (eq 20). */
static double quad_form(const ggx_shape *s, ggx_vec3 m)
{
    ggx_vec3 q = mat_mul(s->ainv_t, m);
    return v3_dot(q, q);
}

double ggx_ndf(const ggx_shape *s, ggx_vec3 m)
{
    if (!(m.z >= 0.0)) return 0.0; /* X+(m.n); also rejects NaN */
    double q = quad_form(s, m);
    return finite_or_zero(s->ndf_scale / (q * q)); /* zero m: q = 0 gives Inf, mapped to 0 */
}

double ggx_ndf_spherical(const ggx_shape *s, double theta, double phi)
{
    if (!(theta >= 0.0 && theta <= 0.5 * GGX_PI)) return 0.0;
    double st = sin(theta);
    return finite_or_zero(ggx_ndf(s, v3(st * cos(phi), st * sin(phi), cos(theta))) * st);
}

double ggx_p22(const ggx_shape *s, double slope_x, double slope_y)
{
    /* D cos^4 with m = (-x~, -y~, 1) / sqrt(1 + x~^2 + y~^2): the normalisations cancel in ||A^{-T} m||^4 cos^4. */
    double q = quad_form(s, v3(-slope_x, -slope_y, 1.0));
    return finite_or_zero(s->ndf_scale / (q * q));
}

double ggx_gaussian_curvature(const ggx_shape *s, ggx_vec3 m)
{
    double q = quad_form(s, m);
    return finite_or_zero(s->det * s->det * q * q);
}

double ggx_projected_area(const ggx_shape *s, ggx_vec3 u)
{
    return finite_or_zero(GGX_PI * v3_len(mat_mul(s->a, u)) / s->det);
}

/* ||Au|| ||Av|| + Au.Av written as ||Au|| ||Av|| ||a^ + b^||^2 / 2 with a^, b^ the unit vectors: no cancellation
 * when Au and Av are nearly opposite (a lune that is almost empty). */
static double lune_numerator(ggx_vec3 au, ggx_vec3 av, double *av_len)
{
    double lu = v3_len(au), lv = v3_len(av);
    *av_len = lv;
    ggx_vec3 h = v3_add(v3_scale(au, 1.0 / lu), v3_scale(av, 1.0 / lv));
    return 0.5 * lu * lv * v3_dot(h, h);
}

double ggx_lune_area(const ggx_shape *s, ggx_vec3 u, ggx_vec3 v)
{
    double lv;
    double num = lune_numerator(mat_mul(s->a, u), mat_mul(s->a, v), &lv);
    return finite_or_zero(GGX_PI * num / (2.0 * s->det * lv)); /* eq 28 */
}

/* A_perp_l(u, n) / (A_perp_e(n) u.n) for u.z > 0: the reciprocal of the unclamped masking ratio of eq 32.
 * With eq 26 and 28: (||Au|| ||An|| + Au.An) / (2 ||An||^2 u.z). Returns NaN/Inf for bad u; callers filter. */
static double visible_ratio(const ggx_shape *s, ggx_vec3 u)
{
    double lv;
    double num = lune_numerator(mat_mul(s->a, u), s->an, &lv);
    return num / (2.0 * s->an_len * s->an_len * u.z);
}

double ggx_lambda(const ggx_shape *s, ggx_vec3 u)
{
    if (!(u.z > 0.0)) return 0.0;
    double r = visible_ratio(s, u) - 1.0;
    /* Negative Lambda is legitimate for skewed shapes. It overflows only for u.z a denormal above the horizon,
     * where the true value is beyond any double: the largest finite one is returned. */
    if (r == HUGE_VAL) return DBL_MAX;
    return isfinite(r) ? r : 0.0;
}

double ggx_g1_smith(const ggx_shape *s, ggx_vec3 u)
{
    if (!(u.z > 0.0)) return 0.0;
    return finite_or_zero(1.0 / visible_ratio(s, u));
}

/* min(1, A_perp_e(n) u.n / A_perp_l(u, n)) for u.z > 0, else 0: eq 32 without the back-facing test. */
static double g1_dir(const ggx_shape *s, ggx_vec3 u)
{
    if (!(u.z > 0.0)) return 0.0;
    double g = finite_or_zero(1.0 / visible_ratio(s, u));
    return g < 1.0 ? g : 1.0;
}

double ggx_g1(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m)
{
    if (!(v3_dot(u, m) >= 0.0)) return 0.0; /* X+(u.m) */
    double mm = v3_dot(m, m);
    if (!(mm > 0.0 && mm < HUGE_VAL)) return 0.0; /* u.m = 0 for a zero m passes X+; no facet has it */
    return g1_dir(s, u);
}

double ggx_g2(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 m)
{
    return ggx_g1(s, wi, m) * ggx_g1(s, wo, m);
}

double ggx_g2_height_correlated(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 m)
{
    if (!(wi.z > 0.0 && wo.z > 0.0 && v3_dot(wi, m) >= 0.0 && v3_dot(wo, m) >= 0.0)) return 0.0;
    double li = visible_ratio(s, wi) - 1.0, lo = visible_ratio(s, wo) - 1.0;
    if (!isfinite(li) || !isfinite(lo)) return 0.0; /* a non-finite direction is outside the domain */
    li = li > 0.0 ? li : 0.0;
    lo = lo > 0.0 ? lo : 0.0;
    return 1.0 / (1.0 + li + lo);
}

double ggx_pdf_vndf(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    if (!(v.z > 0.0)) return 0.0;
    double mv = v3_dot(m, v);
    if (!(mv >= 0.0)) return 0.0; /* X+(m.v) */
    /* eq 33 with eq 26 and 28: A_e(n) / A_l(v, n) = 2 ||An||^2 / (||Av|| ||An|| + Av.An). No division by v.z, so a
     * view a denormal above the horizon still gets its (finite) pdf. */
    double lv;
    double num = lune_numerator(mat_mul(s->a, v), s->an, &lv);
    return finite_or_zero(ggx_ndf(s, m) * mv * 2.0 * s->an_len * s->an_len / num);
}
