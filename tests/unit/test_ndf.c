/* The distribution of normals: normalisation, closed forms, slope space, curvature, areas.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "testlib.h"

static double ndf_cos(ggx_vec3 m, void *ctx) { return ggx_ndf((const ggx_shape *)ctx, m) * m.z; }

/* Walter eq 1 is normalised for any A: the integral of D(m) (m.n) over the hemisphere is 1. 60 random shapes with
 * alpha in [0.02, 2], ratios up to 1:10, theta_z any and |theta_x|, |theta_y| <= 0.6. The quadrature is asked for
 * 1e-10; the bound 1e-6 is the requirement, so a wrong normalising constant (e.g. ||A n|| dropped, off by
 * up to 20 % for these skews) or a wrong exponent fails by orders of magnitude. */
static void normalisation(void **state)
{
    (void)state;
    rng r = {1};
    double worst = 0.0;
    long calls = 0;
    for (int i = 0; i < 60; i++) {
        shape_params p = random_shape(&r, 0.6);
        ggx_shape s;
        make_shape(&s, p);
        long c;
        double v = quad_hemisphere(&s, ndf_cos, &s, NULL, 0, 1e-10, &c);
        calls += c;
        CHECK_CLOSE(v, 1.0, 1e-6, 0.0, "shape (%g, %g, %g, %g, %g)", p.ax, p.ay, p.tx, p.ty, p.tz);
        if (fabs(v - 1.0) > worst) worst = fabs(v - 1.0);
    }
    printf("normalisation: 60 shapes, largest |integral - 1| = %.3g (%ld evaluations)\n", worst, calls);
}

/* The same integral in plain (theta, phi) coordinates, without the sphere-space change of variables, for
 * moderately rough shapes: D(theta, phi) = D(m) sin(theta) integrates with cos(theta) to 1. */
typedef struct sph_ctx {
    const ggx_shape *s;
    double theta;
} sph_ctx;
static double sph_phi(double phi, void *vc)
{
    sph_ctx *c = vc;
    return ggx_ndf_spherical(c->s, c->theta, phi) * cos(c->theta);
}
static double sph_theta(double theta, void *vc)
{
    sph_ctx *c = vc;
    c->theta = theta;
    return quad_adapt(sph_phi, c, 0.0, 2.0 * GGX_PI, 1e-12);
}
static void spherical_density(void **state)
{
    (void)state;
    const shape_params ps[] = {{0.5, 0.5, 0, 0, 0}, {0.3, 0.9, 0.2, -0.3, 1.0}, {1.5, 0.4, -0.5, 0.1, 2.0}};
    for (unsigned i = 0; i < sizeof ps / sizeof ps[0]; i++) {
        ggx_shape s;
        make_shape(&s, ps[i]);
        sph_ctx c = {&s, 0.0};
        CHECK_CLOSE(quad_adapt(sph_theta, &c, 0.0, 0.5 * GGX_PI, 1e-11), 1.0, 1e-8, 0.0, "shape %u", i);
        rng r = {100 + i};
        for (int k = 0; k < 100; k++) {
            double th = rng_range(&r, 0.0, 0.5 * GGX_PI), ph = rng_range(&r, -GGX_PI, GGX_PI);
            CHECK_CLOSE(ggx_ndf_spherical(&s, th, ph), ggx_ndf(&s, t_dir(th, ph)) * sin(th), 1e-15, 0.0,
                        "theta %g phi %g", th, ph);
        }
    }
}

/* The closed-form anisotropic GGX (Burley's GTR2aniso), written independently of the library. */
static double ggx_aniso_closed(double ax, double ay, ggx_vec3 m)
{
    double q = m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay) + m.z * m.z;
    return 1.0 / (GGX_PI * ax * ay * q * q);
}

/* R = I: anisotropic GGX; alpha_x = alpha_y: the isotropic form alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2);
 * R = Rz(theta_z): anisotropic GGX in the rotated tangent frame. */
static void closed_forms(void **state)
{
    (void)state;
    rng r = {2};
    for (int i = 0; i < 200; i++) {
        shape_params p = random_shape(&r, 0.0);
        ggx_shape s, rot, iso;
        CHECK(ggx_shape_aniso(&s, p.ax, p.ay) == GGX_OK, "aniso");
        CHECK(ggx_shape_ellipsoid(&rot, p.ax, p.ay, 0, 0, p.tz) == GGX_OK, "rotated");
        CHECK(ggx_shape_iso(&iso, p.ax) == GGX_OK, "iso");
        CHECK(s.kind == GGX_SHAPE_DIAGONAL && rot.kind == GGX_SHAPE_UNSKEWED, "kinds %d %d", s.kind, rot.kind);
        double th = acos(rng_range(&r, 1e-3, 1.0)), ph = rng_range(&r, -GGX_PI, GGX_PI);
        ggx_vec3 m = t_dir(th, ph);
        CHECK_CLOSE(ggx_ndf(&s, m), ggx_aniso_closed(p.ax, p.ay, m), 1e-13, 0.0, "a=(%g,%g) m=(%g,%g,%g)", p.ax, p.ay,
                    m.x, m.y, m.z);
        /* Rz rotates the tangent plane by theta_z: A^{-T} m = S^{-1} Rz m, so D(m) = D_aniso(Rz m). */
        double c = cos(p.tz), sn = sin(p.tz);
        ggx_vec3 mr = t_vec(c * m.x - sn * m.y, sn * m.x + c * m.y, m.z);
        CHECK_CLOSE(ggx_ndf(&rot, m), ggx_aniso_closed(p.ax, p.ay, mr), 1e-12, 0.0, "tz=%g", p.tz);
        /* The stored tangent frame and alphas (from the eigen-decomposition at setup) reproduce D. */
        ggx_vec3 mt = t_vec(rot.tangent_cos * m.x + rot.tangent_sin * m.y,
                            -rot.tangent_sin * m.x + rot.tangent_cos * m.y, m.z);
        CHECK_CLOSE(ggx_ndf(&rot, m), ggx_aniso_closed(rot.alpha_x, rot.alpha_y, mt), 1e-11, 0, "tangent frame");
        double a2 = p.ax * p.ax, t2 = tan(th) * tan(th), c4 = pow(cos(th), 4);
        CHECK_CLOSE(ggx_ndf(&iso, m), a2 / (GGX_PI * c4 * (a2 + t2) * (a2 + t2)), 1e-12, 0.0, "iso alpha %g", p.ax);
    }
}

/* Slope space (blog Part 1): D(m) = P22(-mx/mz, -my/mz) / cos^4; for R = I, P22 is
 * 1 / (pi ax ay (1 + x^2/ax^2 + y^2/ay^2)^2); and P22 integrates to 1 over the plane (checked in polar
 * coordinates with r = t / (1 - t), for skewed shapes whose peak is off the origin). */
typedef struct p22_ctx {
    const ggx_shape *s;
    double t;
} p22_ctx;
static double p22_phi(double phi, void *vc)
{
    p22_ctx *c = vc;
    double r = c->t / (1.0 - c->t), dr = 1.0 / ((1.0 - c->t) * (1.0 - c->t));
    return ggx_p22(c->s, r * cos(phi), r * sin(phi)) * r * dr;
}
static double p22_t(double t, void *vc)
{
    p22_ctx *c = vc;
    c->t = t;
    return quad_adapt(p22_phi, c, 0.0, 2.0 * GGX_PI, 1e-12);
}
static void slope_space(void **state)
{
    (void)state;
    rng r = {3};
    for (int i = 0; i < 200; i++) {
        shape_params p = random_shape(&r, 0.6);
        ggx_shape s, d;
        make_shape(&s, p);
        CHECK(ggx_shape_aniso(&d, p.ax, p.ay) == GGX_OK, "aniso");
        ggx_vec3 m = t_dir(acos(rng_range(&r, 1e-3, 1.0)), rng_range(&r, -GGX_PI, GGX_PI));
        double c4 = pow(m.z, 4);
        CHECK_CLOSE(ggx_ndf(&s, m), ggx_p22(&s, -m.x / m.z, -m.y / m.z) / c4, 1e-12, 0.0, "shape %d", i);
        double x = rng_range(&r, -5, 5), y = rng_range(&r, -5, 5);
        double q = 1.0 + x * x / (p.ax * p.ax) + y * y / (p.ay * p.ay);
        CHECK_CLOSE(ggx_p22(&d, x, y), 1.0 / (GGX_PI * p.ax * p.ay * q * q), 1e-12, 0.0, "slopes %g %g", x, y);
    }
    const shape_params ps[] = {{0.5, 0.5, 0, 0, 0}, {0.4, 0.8, 0.3, -0.2, 0.7}};
    for (int i = 0; i < 2; i++) {
        ggx_shape s;
        make_shape(&s, ps[i]);
        p22_ctx c = {&s, 0.0};
        CHECK_CLOSE(quad_adapt(p22_t, &c, 0.0, 1.0, 1e-11), 1.0, 1e-7, 0.0, "P22 integral, shape %d", i);
    }
}

/* Gaussian curvature (eq 20) against the explicit ellipsoid x^T A^T A x = 1, x = A^{-1} s(theta, phi): the Gauss
 * map's area ratio |dm/dtheta x dm/dphi| / |dx/dtheta x dx/dphi| by central differences (step 1e-5: truncation
 * ~1e-10, rounding ~1e-11 relative, so 1e-7 leaves margin; a wrong power of ||A^{-T} m|| is off by O(1)). */
typedef struct ell_pt {
    ggx_vec3 x, m;
} ell_pt;
static ell_pt ellipsoid_point(const ggx_shape *s, double th, double ph)
{
    /* x = A^{-1} s: solve with A^{-1} = (A^{-T})^T. */
    ggx_vec3 sp = t_dir(th, ph);
    ell_pt e;
    e.x = t_mattvec(s->ainv_t, sp);
    e.m = t_normalize(t_mattvec(s->a, sp)); /* gradient A^T A x = A^T s */
    return e;
}
static void gaussian_curvature(void **state)
{
    (void)state;
    rng r = {4};
    const double h = 1e-5;
    for (int i = 0; i < 300; i++) {
        shape_params p = random_shape(&r, 0.6);
        ggx_shape s;
        make_shape(&s, p);
        double th = acos(rng_range(&r, -0.95, 0.95)), ph = rng_range(&r, -GGX_PI, GGX_PI);
        ell_pt t0 = ellipsoid_point(&s, th + h, ph), t1 = ellipsoid_point(&s, th - h, ph);
        ell_pt p0 = ellipsoid_point(&s, th, ph + h), p1 = ellipsoid_point(&s, th, ph - h);
        ggx_vec3 xt = t_scale(t_add(t0.x, t_scale(t1.x, -1)), 0.5 / h),
                 xp = t_scale(t_add(p0.x, t_scale(p1.x, -1)), 0.5 / h);
        ggx_vec3 mt = t_scale(t_add(t0.m, t_scale(t1.m, -1)), 0.5 / h),
                 mp = t_scale(t_add(p0.m, t_scale(p1.m, -1)), 0.5 / h);
        ggx_vec3 cx = t_cross(xt, xp), cm = t_cross(mt, mp);
        double fd = sqrt(t_dot(cm, cm) / t_dot(cx, cx));
        ell_pt c = ellipsoid_point(&s, th, ph);
        CHECK_CLOSE(ggx_gaussian_curvature(&s, c.m), fd, 1e-7, 0.0, "shape (%g,%g,%g,%g,%g) th %g ph %g", p.ax, p.ay,
                    p.tx, p.ty, p.tz, th, ph);
        /* eq 9: D = 1 / (A_e(n) Kg) on the upper hemisphere. */
        if (c.m.z > 0.0)
            CHECK_CLOSE(ggx_ndf(&s, c.m),
                        1.0 / (ggx_projected_area(&s, t_vec(0, 0, 1)) * ggx_gaussian_curvature(&s, c.m)), 1e-13, 0.0,
                        "eq 9");
    }
}

/* Projected areas: eq 26 against the silhouettes of an axis-aligned ellipsoid with semi-axes (1/ax, 1/ay, 1)
 * (pi times the product of the two semi-axes across the view), scale and orthogonal invariances, and the lune
 * identities A_l(u, u) = A_e(u) and A_l(u, v) + A_l(u, -v) = A_e(u). */
static void projected_areas(void **state)
{
    (void)state;
    ggx_shape d;
    CHECK(ggx_shape_aniso(&d, 0.3, 0.7) == GGX_OK, "aniso");
    CHECK_CLOSE(ggx_projected_area(&d, t_vec(0, 0, 1)), GGX_PI / (0.3 * 0.7), 1e-15, 0, "along z");
    CHECK_CLOSE(ggx_projected_area(&d, t_vec(1, 0, 0)), GGX_PI / 0.7, 1e-15, 0, "along x");
    CHECK_CLOSE(ggx_projected_area(&d, t_vec(0, 1, 0)), GGX_PI / 0.3, 1e-15, 0, "along y");
    rng r = {5};
    for (int i = 0; i < 200; i++) {
        shape_params p = random_shape(&r, 0.6);
        ggx_shape s;
        make_shape(&s, p);
        ggx_vec3 u = t_dir(acos(rng_range(&r, -1, 1)), rng_range(&r, -GGX_PI, GGX_PI));
        ggx_vec3 v = t_dir(acos(rng_range(&r, -1, 1)), rng_range(&r, -GGX_PI, GGX_PI));
        double ae = ggx_projected_area(&s, u);
        CHECK_CLOSE(ggx_lune_area(&s, u, u), ae, 1e-14, 0, "A_l(u,u)");
        CHECK_CLOSE(ggx_lune_area(&s, u, v) + ggx_lune_area(&s, u, t_scale(v, -1)), ae, 1e-13, 0, "halves");
        CHECK(ggx_lune_area(&s, u, v) <= ae * (1 + 1e-15), "lune within ellipsoid");
        /* 2 A scales areas by 1/4 (pi ||2Au|| / |2A| = pi 2 ||Au|| / (8 |A|)); Q A leaves them unchanged. */
        double A2[3][3], QA[3][3];
        double c = cos(0.7), sn = sin(0.7);
        for (int k = 0; k < 3; k++) {
            for (int j = 0; j < 3; j++) A2[k][j] = 2.0 * s.a[k][j];
            QA[0][k] = c * s.a[0][k] - sn * s.a[1][k];
            QA[1][k] = sn * s.a[0][k] + c * s.a[1][k];
            QA[2][k] = -s.a[2][k]; /* a reflection too: det < 0 */
        }
        ggx_shape s2, sq;
        CHECK(ggx_shape_matrix(&s2, (const double(*)[3])A2) == GGX_OK, "2A");
        CHECK(ggx_shape_matrix(&sq, (const double(*)[3])QA) == GGX_OK, "QA");
        CHECK_CLOSE(ggx_projected_area(&s2, u), 0.25 * ae, 1e-14, 0, "scale");
        /* Canonical form: A' n = ||A n|| z exactly, for the shape and for the re-rotated matrix. */
        CHECK(s.a[0][2] == 0 && s.a[1][2] == 0 && sq.a[0][2] == 0 && sq.a[1][2] == 0 && sq.a[2][2] > 0, "A' n along z");
        CHECK(s.kind == GGX_SHAPE_SKEWED || fabs(p.tx) + fabs(p.ty) == 0, "kind");
        CHECK_CLOSE(ggx_projected_area(&sq, u), ae, 1e-13, 0, "Q A");
        CHECK_CLOSE(ggx_lune_area(&sq, u, v), ggx_lune_area(&s, u, v), 1e-12, 1e-14 * ae, "Q A lune");
        ggx_vec3 m = t_dir(acos(rng_range(&r, 0, 1)), rng_range(&r, -GGX_PI, GGX_PI));
        CHECK_CLOSE(ggx_ndf(&sq, m), ggx_ndf(&s, m), 1e-12, 0, "Q A ndf");
        CHECK_CLOSE(ggx_ndf(&s2, m), ggx_ndf(&s, m), 1e-13, 0, "2A ndf");
    }
}

/* The truncated microsurface seen from u: the integral of X+(m.u) D(m) (m.u) dm equals A_l(u, n) / A_e(n)
 * (eq 27-28 with the normalisation of eq 9) for random u, a quarter of them grazing (u.z down to 1e-6), plus views
 * below the horizon, for random skewed shapes. A lune formula built with A^{-T} n (the blog's form) instead of A n
 * is off by up to ~10 % here, so 1e-7 separates them. */
static double ndf_cos_u(ggx_vec3 m, void *ctx)
{
    const void **c = ctx;
    const ggx_shape *s = c[0];
    ggx_vec3 u = *(const ggx_vec3 *)c[1];
    return ggx_ndf(s, m) * t_dot(m, u);
}
static void lune_by_quadrature(void **state)
{
    (void)state;
    rng r = {6};
    double worst = 0.0;
    for (int i = 0; i < 40; i++) {
        shape_params p = random_shape(&r, 0.6);
        ggx_shape s;
        make_shape(&s, p);
        ggx_vec3 u = i % 8 == 7 ? t_dir(rng_range(&r, 0.5 * GGX_PI, 0.9 * GGX_PI), rng_range(&r, -GGX_PI, GGX_PI))
                                : random_view(&r);
        const void *ctx[2] = {&s, &u};
        double got = quad_hemisphere(&s, ndf_cos_u, ctx, &u, 1, 1e-10, NULL);
        ggx_vec3 n = t_vec(0, 0, 1);
        double want = ggx_lune_area(&s, u, n) / ggx_projected_area(&s, n);
        CHECK_CLOSE(got, want, 1e-7, 1e-12, "shape (%g,%g,%g,%g,%g) u (%g,%g,%g)", p.ax, p.ay, p.tx, p.ty, p.tz, u.x,
                    u.y, u.z);
        if (want > 0 && fabs(got / want - 1) > worst) worst = fabs(got / want - 1);
    }
    printf("lune areas: 40 views, largest relative error %.3g\n", worst);
}

/* The sign of theta_z (docs/design/render.md, "Scene and frames"): A = S Rz(theta_z) puts the axis of alpha_x at
 * azimuth -theta_z. With alpha (0.3, 0.6) and theta_z = +30 degrees, D at a fixed tilt is smallest at azimuth -30
 * (the axis of the smaller alpha) and largest at +60; a sign error would swap them. */
static void rotation_sign(void **state)
{
    (void)state;
    const double deg = GGX_PI / 180;
    ggx_shape s;
    CHECK(ggx_shape_ellipsoid(&s, 0.3, 0.6, 0, 0, 30 * deg) == GGX_OK, "shape");
    double lo = INFINITY, hi = 0;
    int at_lo = 0, at_hi = 0;
    for (int d = -90; d < 90; d += 5) {
        ggx_vec3 m = {sin(0.3) * cos(d * deg), sin(0.3) * sin(d * deg), cos(0.3)};
        double v = ggx_ndf(&s, m);
        if (v < lo) lo = v, at_lo = d;
        if (v > hi) hi = v, at_hi = d;
    }
    CHECK(at_lo == -30 && at_hi == 60, "D smallest at azimuth %d, largest at %d (want -30 and 60)", at_lo, at_hi);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(normalisation),      cmocka_unit_test(spherical_density),  cmocka_unit_test(closed_forms),
        cmocka_unit_test(slope_space),        cmocka_unit_test(gaussian_curvature), cmocka_unit_test(projected_areas),
        cmocka_unit_test(lune_by_quadrature), cmocka_unit_test(rotation_sign),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
