/* Self-test of the quadrature used by every integral test: a quadrature that is wrong would make those tests
 * meaningless. SPDX-License-Identifier: MIT */
#include <math.h>

#include "testlib.h"

static double poly(double x, void *ctx)
{
    int k = *(int *)ctx;
    return pow(x, k);
}

/* One n-point Gauss-Legendre panel integrates x^k exactly for k <= 2n - 1, and not for k = 2n. */
static void gl_exactness(void **state)
{
    (void)state;
    int n = quad_gl_order();
    for (int k = 0; k <= 2 * n - 1; k++) {
        double want = (k % 2) ? 0.0 : 2.0 / (k + 1);
        CHECK_CLOSE(quad_gl(poly, &k, -1.0, 1.0), want, 1e-14, 1e-15, "k = %d", k);
    }
    int k = 2 * n;
    CHECK(fabs(quad_gl(poly, &k, -1.0, 1.0) - 2.0 / (k + 1)) > 1e-10, "degree 2n must not be exact");
}

static double sqrt_abs(double x, void *ctx)
{
    (void)ctx;
    return sqrt(fabs(x - 0.3));
}

/* The adaptive rule reaches the tolerance on a kink with an infinite derivative. */
static void adaptive_kink(void **state)
{
    (void)state;
    double want = (2.0 / 3.0) * (pow(1.3, 1.5) + pow(0.7, 1.5));
    CHECK_CLOSE(quad_adapt(sqrt_abs, NULL, -1.0, 1.0, 1e-11), want, 1e-10, 0.0, "int sqrt|x-0.3|");
}

static double one(ggx_vec3 m, void *ctx)
{
    (void)m, (void)ctx;
    return 1.0;
}
static double cos_n(ggx_vec3 m, void *ctx)
{
    (void)ctx;
    return m.z;
}
static double cos_u(ggx_vec3 m, void *ctx) { return t_dot(m, *(ggx_vec3 *)ctx); }

/* Known integrals over the hemisphere of m and over lunes, computed through the sphere space of skewed, sharp
 * shapes: checks the change of variables (Jacobian |A| / ||A^T m'||^3) and the cut break points. */
static void sphere_space_integrals(void **state)
{
    (void)state;
    rng r = {11};
    for (int i = 0; i < 12; i++) {
        shape_params p = random_shape(&r, 0.6);
        ggx_shape s;
        make_shape(&s, p);
        CHECK_CLOSE(quad_hemisphere(&s, one, NULL, NULL, 0, 1e-10, NULL), 2.0 * GGX_PI, 1e-8, 0.0, "shape %d", i);
        CHECK_CLOSE(quad_hemisphere(&s, cos_n, NULL, NULL, 0, 1e-10, NULL), GGX_PI, 1e-8, 0.0, "shape %d", i);
        ggx_vec3 u = t_dir(rng_range(&r, 0.0, GGX_PI), rng_range(&r, 0.0, 2.0 * GGX_PI));
        /* Area of the lune {m.n >= 0, m.u >= 0} is 2 (pi - angle(n, u)). */
        double lune = 2.0 * (GGX_PI - acos(u.z));
        CHECK_CLOSE(quad_hemisphere(&s, one, NULL, &u, 1, 1e-10, NULL), lune, 1e-7, 0.0, "shape %d u.z %g", i, u.z);
        /* Projected area of that lune seen from u: (1 + u.n) pi / 2. */
        CHECK_CLOSE(quad_hemisphere(&s, cos_u, &u, &u, 1, 1e-10, NULL), 0.5 * GGX_PI * (1.0 + u.z), 1e-7, 1e-12,
                    "shape %d u.z %g", i, u.z);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gl_exactness),
        cmocka_unit_test(adaptive_kink),
        cmocka_unit_test(sphere_space_integrals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
