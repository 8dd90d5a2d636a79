/* The ellipsoid in slope space (ggx_shape_slopes, ggx_shape_from_slopes, ggx_shape_ellipsoid_params): the Student-t
 * form of P22 against ggx_ndf, the round trips, and the sampled slopes' distribution. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "chi2.h"
#include "testlib.h"

/* A shape of the widest family: alpha log-uniform in [1e-3, 10] each, |theta_x|, |theta_y| up to the largest
 * accepted (pi / 2), theta_z any. Returns 0 for the rare draws that ggx_shape_ellipsoid refuses as singular. */
static int wide_shape(rng *r, ggx_shape *s, shape_params *p)
{
    p->ax = exp(rng_range(r, log(1e-3), log(10.0)));
    p->ay = exp(rng_range(r, log(1e-3), log(10.0)));
    p->tx = rng_range(r, -GGX_SKEW_MAX, GGX_SKEW_MAX);
    p->ty = rng_range(r, -GGX_SKEW_MAX, GGX_SKEW_MAX);
    p->tz = rng_range(r, -GGX_PI, GGX_PI);
    return ggx_shape_ellipsoid(s, p->ax, p->ay, p->tx, p->ty, p->tz) == GGX_OK;
}

/* D(m) from (t, Sigma) alone, in long double: P22(x~) / m.z^4 with the Student-t P22 of ggx.h. */
static long double ndf_from_slopes(const double t[2], const double sg[3], ggx_vec3 m)
{
    long double x = -(long double)m.x / m.z - t[0], y = -(long double)m.y / m.z - t[1];
    long double det = (long double)sg[0] * sg[2] - (long double)sg[1] * sg[1];
    long double delta = (sg[2] * x * x - 2.0L * sg[1] * x * y + sg[0] * y * y) / det;
    long double mz2 = (long double)m.z * m.z;
    return 1.0L / (3.14159265358979323846264338327950288L * sqrtl(det) * (1 + delta) * (1 + delta) * mz2 * mz2);
}

/* A normal for the comparisons: from the NDF (where D matters) or uniform over the upper hemisphere (the tails). */
static ggx_vec3 test_normal(rng *r, const ggx_shape *s, int i)
{
    if (i % 2 == 0) return ggx_sample_ndf(s, rng_uniform(r), rng_uniform(r));
    double z = rng_range(r, 1e-3, 1.0), ph = rng_range(r, 0.0, 2.0 * GGX_PI), q = sqrt(1.0 - z * z);
    return (ggx_vec3){q * cos(ph), q * sin(ph), z};
}

/* ggx.h's bound on D rebuilt from (t, Sigma) (slopes_bound, tests/support/testlib.h), measured against D of the user's A in
 * __float128 on these shapes: 5.9e-16 kappa^2 at most; ggx_ndf itself 8.3e-16 kappa^2. */
static double kappa_of(shape_params p) { return shape_kappa(p.ax, p.ay); }
static double slopes_tol(shape_params p) { return slopes_bound(p.ax, p.ay); }

/* The key fact: for 10^4 random A over all five degrees of freedom, D built from (t, Sigma) equals ggx_ndf at 8 normals
 * each, within slopes_tol. A sign error in t (t = +b / a33) or Sigma from A A^T instead of A^T A fails by orders of
 * magnitude at the first skewed shape. */
static void student_t_form(void **state)
{
    (void)state;
    rng r = {35};
    double worst = 0.0, within_1e12 = 0.0;
    int shapes = 0, skipped = 0;
    while (shapes < 10000) {
        ggx_shape s;
        shape_params p;
        if (!wide_shape(&r, &s, &p)) {
            skipped++;
            continue;
        }
        shapes++;
        double t[2], sg[3];
        assert_int_equal(ggx_shape_slopes(&s, t, sg), GGX_OK);
        for (int i = 0; i < 8; i++) {
            ggx_vec3 m = test_normal(&r, &s, i);
            if (!(m.z > 0.0)) continue;
            double want = ggx_ndf(&s, m);
            long double got = ndf_from_slopes(t, sg, m);
            if (want < 1e-280) continue; /* underflowed tails carry no relative information */
            double e = (double)fabsl(got / want - 1.0L);
            if (e > worst) worst = e;
            if (kappa_of(p) <= 20.0) within_1e12 = fmax(within_1e12, e);
            CHECK(e <= slopes_tol(p),
                  "shape (%g, %g, %g, %g, %g), m (%.17g, %.17g, %.17g): D %.17g, from slopes %.17Lg", p.ax, p.ay, p.tx,
                  p.ty, p.tz, m.x, m.y, m.z, want, got);
        }
    }
    CHECK(within_1e12 <= 1e-12, "kappa <= 20: %g", within_1e12);
    printf("student_t_form: %d shapes (%d refused as singular), largest relative difference %.3g (%.3g where "
           "kappa <= 20)\n",
           shapes, skipped, worst, within_1e12);
}

/* t = 0 exactly for unskewed shapes, Sigma = alpha^2 I for isotropic GGX and Rz^T diag(ax^2, ay^2) Rz when rotated;
 * t is the slope of the mean normal A^T A n. */
static void slopes_closed_forms(void **state)
{
    (void)state;
    ggx_shape s;
    double t[2], sg[3];
    assert_int_equal(ggx_shape_iso(&s, 0.3), GGX_OK);
    assert_int_equal(ggx_shape_slopes(&s, t, sg), GGX_OK);
    CHECK(t[0] == 0.0 && t[1] == 0.0 && sg[1] == 0.0, "iso: t (%g, %g), sxy %g", t[0], t[1], sg[1]);
    CHECK_CLOSE(sg[0], 0.09, 1e-15, 0.0, "iso sxx");
    CHECK_CLOSE(sg[2], 0.09, 1e-15, 0.0, "iso syy");
    double c = cos(0.7), sn = sin(0.7);
    assert_int_equal(ggx_shape_ellipsoid(&s, 0.5, 0.1, 0.0, 0.0, 0.7), GGX_OK);
    assert_int_equal(ggx_shape_slopes(&s, t, sg), GGX_OK);
    CHECK(fabs(t[0]) <= 1e-16 && fabs(t[1]) <= 1e-16, "rotated: t (%g, %g)", t[0], t[1]);
    CHECK_CLOSE(sg[0], 0.25 * c * c + 0.01 * sn * sn, 1e-14, 0.0, "rotated sxx");
    CHECK_CLOSE(sg[1], -(0.25 - 0.01) * c * sn, 1e-14, 0.0, "rotated sxy");
    CHECK_CLOSE(sg[2], 0.25 * sn * sn + 0.01 * c * c, 1e-14, 0.0, "rotated syy");
    /* Skewed: the mean normal A^T A n of the user's A, its slope. */
    rng r = {7};
    for (int k = 0; k < 200; k++) {
        shape_params p;
        if (!wide_shape(&r, &s, &p)) continue;
        double A[3][3];
        assert_int_equal(ggx_ellipsoid_matrix(A, p.ax, p.ay, p.tx, p.ty, p.tz), GGX_OK);
        double mn[3];
        for (int i = 0; i < 3; i++) mn[i] = A[0][i] * A[0][2] + A[1][i] * A[1][2] + A[2][i] * A[2][2];
        assert_int_equal(ggx_shape_slopes(&s, t, sg), GGX_OK);
        double scale = 1.0 + hypot(mn[0], mn[1]) / fabs(mn[2]);
        CHECK_CLOSE(t[0], -mn[0] / mn[2], 0.0, 1e-11 * scale * scale, "shape %d t_x", k);
        CHECK_CLOSE(t[1], -mn[1] / mn[2], 0.0, 1e-11 * scale * scale, "shape %d t_y", k);
        CHECK(sg[0] > 0 && sg[2] > 0 && sg[0] * sg[2] > sg[1] * sg[1], "shape %d: Sigma not positive", k);
    }
}

/* A -> (t, Sigma) -> A: the same distribution (D equal within slopes_tol at 8 normals) and the same (t, Sigma). */
static void slopes_round_trip(void **state)
{
    (void)state;
    rng r = {36};
    double worst = 0.0;
    for (int k = 0; k < 2000; k++) {
        ggx_shape s, b;
        shape_params p;
        if (!wide_shape(&r, &s, &p)) continue;
        double t[2], sg[3], t2[2], sg2[3];
        assert_int_equal(ggx_shape_slopes(&s, t, sg), GGX_OK);
        ggx_status st = ggx_shape_from_slopes(&b, t[0], t[1], sg[0], sg[1], sg[2]);
        CHECK(st == GGX_OK, "shape (%g, %g, %g, %g, %g): from_slopes %d", p.ax, p.ay, p.tx, p.ty, p.tz, (int)st);
        assert_int_equal(ggx_shape_slopes(&b, t2, sg2), GGX_OK);
        double sc = sqrt(sg[0] * sg[2] - sg[1] * sg[1]) > 0 ? fmax(sg[0], sg[2]) : 1.0;
        for (int i = 0; i < 2; i++) CHECK_CLOSE(t2[i], t[i], 1e-13, 1e-13 * sqrt(sc), "shape %d t[%d]", k, i);
        for (int i = 0; i < 3; i++) CHECK_CLOSE(sg2[i], sg[i], 1e-12, 1e-13 * sc, "shape %d sigma[%d]", k, i);
        for (int i = 0; i < 8; i++) {
            ggx_vec3 m = test_normal(&r, &s, i);
            double d0 = ggx_ndf(&s, m), d1 = ggx_ndf(&b, m);
            if (d0 < 1e-280) continue;
            double e = fabs(d1 / d0 - 1.0);
            if (e > worst) worst = e;
            CHECK(e <= slopes_tol(p), "shape (%g, %g, %g, %g, %g): D %.17g, round trip %.17g", p.ax, p.ay, p.tx, p.ty,
                  p.tz, d0, d1);
        }
    }
    printf("slopes_round_trip: largest relative difference of D %.3g\n", worst);
}

/* Slopes of normals drawn by the library's NDF sampler, standardised by the shape's own (t, Sigma), are isotropic
 * P22 with alpha 1: u = r^2 / (1 + r^2) and the angle are independent and uniform. A 20 x 20 chi-square on (u, angle)
 * for 12 shapes, each at the Sidak level for 12 runs; the negative control (Sigma scaled by 1.1 in the
 * standardisation) must be rejected. */
static double standardised_chi2(const ggx_shape *s, double scale, long n, rng *r)
{
    double t[2], sg[3];
    assert_int_equal(ggx_shape_slopes(s, t, sg), GGX_OK);
    for (int i = 0; i < 3; i++) sg[i] *= scale;
    double l00 = sqrt(sg[0]), l10 = sg[1] / l00, l11 = sqrt(sg[2] - l10 * l10); /* Sigma = L L^T */
    enum { K = 20 };
    long cnt[K][K] = {{0}};
    for (long i = 0; i < n; i++) {
        ggx_vec3 m = ggx_sample_ndf(s, rng_uniform(r), rng_uniform(r));
        double x = -m.x / m.z - t[0], y = -m.y / m.z - t[1];
        double z0 = x / l00, z1 = (y - l10 * z0) / l11, r2 = z0 * z0 + z1 * z1;
        double u = r2 / (1.0 + r2), a = atan2(z1, z0) / (2.0 * GGX_PI) + 0.5;
        int iu = (int)(u * K), ia = (int)(a * K);
        cnt[iu < K ? iu : K - 1][ia < K ? ia : K - 1]++;
    }
    double e = (double)n / (K * K), x2 = 0.0;
    for (int i = 0; i < K; i++)
        for (int j = 0; j < K; j++) x2 += ((double)cnt[i][j] - e) * ((double)cnt[i][j] - e) / e;
    return chi2_pvalue(x2, K * K - 1);
}

static void sampled_slopes_are_student_t(void **state)
{
    (void)state;
    rng r = {37};
    /* 2e5 normals at every scale (0.2 s): the negative control needs them (at 4e4 a 10 % error in Sigma gives
     * p ~ 4e-3 only) */
    long n = (long)(2e5 * fmax(1.0, test_scale()));
    double lowest = 1.0;
    for (int k = 0; k < 12; k++) {
        ggx_shape s;
        shape_params p;
        while (!wide_shape(&r, &s, &p)) {}
        double pv = standardised_chi2(&s, 1.0, n, &r);
        if (pv < lowest) lowest = pv;
        CHECK(chi2_accepts(pv), "shape (%g, %g, %g, %g, %g): p = %g", p.ax, p.ay, p.tx, p.ty, p.tz, pv);
        double neg = standardised_chi2(&s, 1.1, n, &r);
        CHECK(neg < 1e-6, "negative control accepted: p = %g", neg);
    }
    printf("sampled_slopes_are_student_t: 12 shapes, %ld normals each, lowest p = %.3g\n", n, lowest);
}

/* ggx_shape_ellipsoid_params: the parameters give the same distribution for every shape, and the shape's own
 * parameters back where they are the canonical choice (third axis nearest n, |theta_z| < pi / 4). */
static void ellipsoid_params_round_trip(void **state)
{
    (void)state;
    rng r = {38};
    int recovered = 0;
    double worst = 0.0;
    for (int k = 0; k < 3000; k++) {
        ggx_shape s, b;
        shape_params p;
        if (!wide_shape(&r, &s, &p)) continue;
        if (k % 2) p.tz = rng_range(&r, -0.5, 0.5), p.tx *= 0.28, p.ty *= 0.28; /* the canonical half */
        if (ggx_shape_ellipsoid(&s, p.ax, p.ay, p.tx, p.ty, p.tz) != GGX_OK) continue;
        double ax, ay, tx, ty, tz;
        assert_int_equal(ggx_shape_ellipsoid_params(&s, &ax, &ay, &tx, &ty, &tz), GGX_OK);
        CHECK(fabs(tx) < GGX_PI / 2 && fabs(ty) < GGX_PI / 2 && fabs(tz) < GGX_PI / 2, "angles out of range: %g %g %g",
              tx, ty, tz);
        assert_int_equal(ggx_shape_ellipsoid(&b, ax, ay, tx, ty, tz), GGX_OK);
        double kappa = kappa_of(p);
        for (int i = 0; i < 8; i++) {
            ggx_vec3 m = test_normal(&r, &s, i);
            double d0 = ggx_ndf(&s, m), d1 = ggx_ndf(&b, m);
            if (d0 < 1e-280) continue;
            double e = fabs(d1 / d0 - 1.0) / kappa;
            if (e > worst) worst = e;
            CHECK(e <= 1e-12, "shape (%g, %g, %g, %g, %g) -> (%g, %g, %g, %g, %g): D %.17g vs %.17g", p.ax, p.ay, p.tx,
                  p.ty, p.tz, ax, ay, tx, ty, tz, d0, d1);
        }
        int canonical = fabs(p.tx) <= 0.45 && fabs(p.ty) <= 0.45 && fabs(p.tz) <= 0.5 && fabs(log(p.ax / p.ay)) > 1e-3;
        if (canonical) {
            recovered++;
            double tol = 1e-13 * kappa * kappa;
            CHECK_CLOSE(ax, p.ax, tol, 0.0, "alpha_x of (%g, %g, %g, %g, %g)", p.ax, p.ay, p.tx, p.ty, p.tz);
            CHECK_CLOSE(ay, p.ay, tol, 0.0, "alpha_y");
            CHECK_CLOSE(tx, p.tx, 0.0, tol, "theta_x");
            CHECK_CLOSE(ty, p.ty, 0.0, tol, "theta_y");
            CHECK_CLOSE(tz, p.tz, 0.0, tol, "theta_z");
        }
    }
    CHECK(recovered > 1000, "only %d canonical shapes", recovered);
    /* Isotropic: theta_z = 0. */
    ggx_shape s;
    double ax, ay, tx, ty, tz;
    assert_int_equal(ggx_shape_ellipsoid(&s, 0.2, 0.2, 0.3, -0.2, 1.1), GGX_OK);
    assert_int_equal(ggx_shape_ellipsoid_params(&s, &ax, &ay, &tx, &ty, &tz), GGX_OK);
    CHECK(fabs(tz) < 1e-12 && fabs(ax - 0.2) < 1e-12 && fabs(ay - 0.2) < 1e-12, "iso: %g %g %g", ax, ay, tz);
    assert_int_equal(ggx_shape_ellipsoid_params(&s, NULL, NULL, NULL, NULL, NULL), GGX_OK);
    assert_int_equal(ggx_shape_ellipsoid_params(NULL, &ax, NULL, NULL, NULL, NULL), GGX_ERR_NULL);
    printf("ellipsoid_params_round_trip: %d shapes recovered exactly; largest D difference / kappa %.3g\n", recovered,
           worst);
}

/* ggx_shape_from_slopes at the edges of its domain. */
static void from_slopes_domain(void **state)
{
    (void)state;
    ggx_shape s, keep;
    double t[2], sg[3];
    assert_int_equal(ggx_shape_iso(&keep, 0.5), GGX_OK);
    s = keep;
    assert_int_equal(ggx_shape_from_slopes(NULL, 0, 0, 1, 0, 1), GGX_ERR_NULL);
    assert_int_equal(ggx_shape_from_slopes(&s, NAN, 0, 1, 0, 1), GGX_ERR_NONFINITE);
    assert_int_equal(ggx_shape_from_slopes(&s, 0, 0, INFINITY, 0, 1), GGX_ERR_NONFINITE);
    assert_int_equal(ggx_shape_from_slopes(&s, 0, 0, -1, 0, 1), GGX_ERR_ALPHA);
    assert_int_equal(ggx_shape_from_slopes(&s, 0, 0, 1, 2, 1), GGX_ERR_ALPHA);   /* indefinite */
    assert_int_equal(ggx_shape_from_slopes(&s, 0, 0, 1e9, 0, 1), GGX_ERR_ALPHA); /* alpha above 1e4 */
    CHECK(memcmp(&s, &keep, sizeof s) == 0, "s changed on error");
    /* Sigma = 0 and a singular Sigma: the eigenvalues are raised to GGX_ALPHA_MIN^2. */
    assert_int_equal(ggx_shape_from_slopes(&s, 0.2, -0.1, 0, 0, 0), GGX_OK);
    assert_int_equal(ggx_shape_slopes(&s, t, sg), GGX_OK);
    CHECK_CLOSE(sg[0], 1e-8, 1e-12, 0.0, "sxx of Sigma = 0");
    CHECK_CLOSE(sg[2], 1e-8, 1e-12, 0.0, "syy of Sigma = 0");
    CHECK_CLOSE(t[0], 0.2, 1e-15, 0.0, "t kept");
    assert_int_equal(ggx_shape_from_slopes(&s, 0, 0, 0.25, 0.25, 0.25), GGX_OK); /* rank 1 */
    assert_int_equal(ggx_shape_slopes(&s, t, sg), GGX_OK);
    double det = sg[0] * sg[2] - sg[1] * sg[1];
    CHECK_CLOSE(det, 0.5 * 1e-8, 1e-6, 0.0, "rank-1 Sigma: det = lambda_max * alpha_min^2");
    /* Large skews: slopes of the mean normal up to 1e3 are shapes; A n nearly horizontal. */
    assert_int_equal(ggx_shape_from_slopes(&s, 1e3, 0, 0.01, 0, 0.01), GGX_OK);
    CHECK(ggx_ndf(&s, (ggx_vec3){-1e3 / sqrt(1e6 + 1), 0, 1 / sqrt(1e6 + 1)}) > 0, "the mode's D");
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(student_t_form),
        cmocka_unit_test(slopes_closed_forms),
        cmocka_unit_test(slopes_round_trip),
        cmocka_unit_test(sampled_slopes_are_student_t),
        cmocka_unit_test(ellipsoid_params_round_trip),
        cmocka_unit_test(from_slopes_domain),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    return rc | chi2_budget_end("slopes", argc, argv);
}
