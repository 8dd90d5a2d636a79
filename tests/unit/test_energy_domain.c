/* Energy compensation over its whole domain, checked independently of the tables: every shape that
 * ggx_energy_create (ggx_bsdf_energy_create) accepts has a table within TABLE_PROMISE of ggx_albedo (ggx_bsdf_albedo)
 * at views dense in the azimuth up to 89 degrees (those to 89.9 reported), and a white furnace, by stratified Monte Carlo over the
 * library's own compensated sampler, that is 1 + (E - E_table)(wi) to its sampling error, never above 1 + 1e-3 and
 * within 1e-3 of 1; a shape it refuses gets GGX_ERR_RANGE and *out NULL. The shapes: the hostile report's
 * reproducers (on 660888d a table 0.21 below E and a furnace of 1.21 for a sharp skewed lobe at 89 degrees) and a
 * random search from the smallest alpha to 2, anisotropy to 1:200, skews to 1.2 rad.
 * Argument: 1 the reported BRDF cases, 2 the random BRDF search, 3 the BSDF cases. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "testlib.h"

#define TABLE_PROMISE 1e-3
#define THETA_MAX_DEG 89.0 /* the promise's views (wi.z >= 0.0175); beyond, the errors are reported */

typedef struct view_case {
    double theta_deg, phi; /* phi < 0: no particular view */
} view_case;

static ggx_vec3 view_deg(double theta_deg, double phi)
{
    double t = theta_deg * GGX_PI / 180;
    return t_vec(sin(t) * cos(phi), sin(t) * sin(phi), cos(t));
}

/* The compensated samplers in one signature: the BRDF with F = 1, the BSDF in GGX_IMPORTANCE mode. */
typedef ggx_sample (*draw_fn)(const void *e, ggx_vec3 v, double u1, double u2, double u3);
static ggx_sample draw_brdf(const void *e, ggx_vec3 v, double u1, double u2, double u3)
{
    return ggx_sample_brdf_compensated(e, NULL, v, u1, u2, u3);
}
static ggx_sample draw_bsdf(const void *e, ggx_vec3 v, double u1, double u2, double u3)
{
    return ggx_sample_bsdf_compensated(e, v, u1, u2, u3, GGX_IMPORTANCE);
}

/* The white furnace at v: the average weight of a compensated sampler over an n x n jittered stratified grid of
 * (u1, u2) (a uniform point in each cell; the cells' centres are a midpoint rule, biased where the weight jumps at
 * the edge of the invalid draws: 5.6 sigma off at a grazing view of a skewed shape), u3 random (a golden-ratio
 * sequence for u3 correlated with the strata: 5.7 sigma off at n = 300 for one view), and its standard error from
 * the spread of the weights (an upper bound for a jittered stratified estimate). seed: the stream's
 * multiplier of n. */
static double furnace(draw_fn draw, const void *e, ggx_vec3 v, int n, uint64_t seed, double *sigma)
{
    double sum = 0, sum2 = 0;
    int k = 0;
    rng r = {(uint64_t)n * seed + (uint64_t)(1e6 * fabs(v.x + 2 * v.y))};
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++, k++) {
            double u1 = (a + rng_uniform(&r)) / n, u2 = (b + rng_uniform(&r)) / n, u3 = rng_uniform(&r);
            ggx_sample s = draw(e, v, u1, u2, u3);
            double w = s.event == GGX_EVENT_INVALID ? 0.0 : s.weight;
            sum += w;
            sum2 += w * w;
        }
    double mean = sum / k;
    *sigma = sqrt(fmax(0.0, sum2 / k - mean * mean) / k);
    return mean;
}

static double worst_table, worst_gain, worst_furnace_dev;
static int accepted, refused;

/* The furnace's checks at one view: the compensated albedo is 1 + (E - E_table) (ggx.h) to 4 sigma plus the
 * lobe's normalisation by the table's cell quadrature, never a gain beyond 1e-3, and within 1e-3 of 1. */
static void check_furnace(const char *what, double f, double sigma, double e_true, double e_tab)
{
    double tol = 4 * sigma + 2e-4;
    CHECK(fabs(f - (1 + (e_true - e_tab))) <= tol, "%s: furnace %.6f, 1 + (E - E_table) = %.6f (sigma %.1e)", what, f,
          1 + (e_true - e_tab), sigma);
    CHECK(f <= 1 + TABLE_PROMISE + 4 * sigma, "%s: the compensation adds energy: furnace %.6f (sigma %.1e)", what, f,
          sigma);
    CHECK(fabs(f - 1) <= TABLE_PROMISE + 4 * sigma, "%s: furnace %.6f (sigma %.1e)", what, f, sigma);
    if (f - 1 > worst_gain) worst_gain = f - 1;
    if (fabs(f - 1) > worst_furnace_dev) worst_furnace_dev = fabs(f - 1);
}

/* One BRDF shape: refused with GGX_ERR_RANGE, or its table and furnace within the promise at the views of the scan
 * (nphi azimuths at each elevation) and at the given view. */
static void brdf_shape(const char *name, shape_params p, view_case vc, int nphi, int nfurnace)
{
    ggx_shape s;
    make_shape(&s, p);
    ggx_energy *e = (ggx_energy *)&s;
    ggx_status st = ggx_energy_create(&s, &e);
    if (st != GGX_OK) {
        CHECK(st == GGX_ERR_RANGE && e == NULL, "%s: status %s", name, ggx_status_str(st));
        printf("%-44s refused: %s\n", name, ggx_status_str(st));
        refused++;
        return;
    }
    accepted++;
    static const double thetas[] = {30, 60, 75, 80, 84, 86, 87, 88, 88.5, THETA_MAX_DEG, 89.5, 89.9};
    enum { NT = sizeof thetas / sizeof thetas[0], KEEP = 8 };
    struct {
        double err;
        ggx_vec3 v;
    } worst[KEEP] = {{0}};
    double shape_worst = 0, beyond = 0, beyond_gain = 0;
    int nv = NT * nphi + (vc.phi >= 0);
    /* the quick tier: every fourth azimuth of the full tier's scan, so that its views are a subset of those */
    int stride = test_quick() ? 4 : 1;
    for (int k = 0; k < nv; k++) {
        if (k < NT * nphi && (k % nphi) % stride) continue;
        ggx_vec3 v = k < NT * nphi ? view_deg(thetas[k / nphi], 2 * GGX_PI * ((k % nphi) + 0.37) / nphi)
                                   : view_deg(vc.theta_deg, vc.phi);
        double want = ggx_albedo(&s, v), got = ggx_energy_albedo(e, v), err = fabs(got - want);
        if (acos(v.z) > THETA_MAX_DEG * GGX_PI / 180 + 1e-9) { /* beyond the promise: reported */
            if (err > beyond) beyond = err;
            if (want - got > beyond_gain) beyond_gain = want - got;
            continue;
        }
        CHECK(err <= TABLE_PROMISE, "%s: table E %.6f, ggx_albedo %.6f at (%.5f, %.5f, %.5f)", name, got, want, v.x,
              v.y, v.z);
        if (err > shape_worst) shape_worst = err;
        /* keep the views where the table is furthest off, and the given view, for the furnace */
        if (k == nv - 1 && vc.phi >= 0) err = 1.0;
        int m = 0;
        for (int q = 1; q < KEEP; q++)
            if (worst[q].err < worst[m].err) m = q;
        if (err >= worst[m].err) worst[m].err = err, worst[m].v = v;
    }
    if (shape_worst > worst_table) worst_table = shape_worst;
    double fmax_dev = 0;
    for (int q = 0; q < KEEP && q < nfurnace; q++) {
        if (!(worst[q].v.z > 0)) continue;
        double sigma, f = furnace(draw_brdf, e, worst[q].v, 400, 7919u, &sigma);
        char what[160];
        snprintf(what, sizeof what, "%s at (%.5f, %.5f, %.5f)", name, worst[q].v.x, worst[q].v.y, worst[q].v.z);
        check_furnace(what, f, sigma, ggx_albedo(&s, worst[q].v), ggx_energy_albedo(e, worst[q].v));
        if (fabs(f - 1) > fmax_dev) fmax_dev = fabs(f - 1);
    }
    printf("%-44s accepted: max |E_table - E| %.2e over %d views, max |furnace - 1| %.2e; beyond 89 degrees "
           "%.2e (underestimate %.2e)\n",
           name, shape_worst, nv, fmax_dev, beyond, beyond_gain);
    ggx_energy_free(e);
}

static int nphi(void) { return (int)(36 * test_scale()) < 36 ? 36 : (int)(36 * test_scale()); }

static void reported_brdf(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        shape_params p;
        view_case v;
    } cases[] = {
        {"(0.002, 0.004, 0.3, 0.2) at 89, phi 3.70", {0.002, 0.004, 0.3, 0.2, 0}, {89, 3.70}},
        {"(0.02, 0.04, 0.3, 0.2) at 88.5", {0.02, 0.04, 0.3, 0.2, 0}, {88.5, -1}},
        {"(0.05, 0.05, theta_x 0.3)", {0.05, 0.05, 0.3, 0, 0}, {87, 0.076}},
        {"aniso (0.002, 0.004) at 89", {0.002, 0.004, 0, 0, 0}, {89, 0.0}},
        {"aniso (0.01, 2) at 89, phi 0.012", {0.01, 2, 0, 0, 0}, {89, 0.012}},
        {"aniso (0.01, 0.5), 1:50", {0.01, 0.5, 0, 0, 0}, {89, 0.012}},
        {"skewed (0.05, 0.3, -0.5, 0.5)", {0.05, 0.3, -0.5, 0.5, 0}, {89, 2.68}},
        {"skewed (0.15, 0.15, 0.3)", {0.15, 0.15, 0.3, 0, 0}, {87, 0.07}},
    };
    worst_table = worst_gain = worst_furnace_dev = 0;
    /* the quick tier: every other case (the sharp skewed lobe at 89, theta_x 0.3, aniso 1:200, skewed 0.05:0.3) */
    int step = test_quick() ? 2 : 1;
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i += step)
        brdf_shape(cases[i].name, cases[i].p, cases[i].v, nphi(), 4);
    printf("reported cases: %d accepted, %d refused; largest table error %.2e, largest furnace gain %.2e, "
           "largest |furnace - 1| %.2e\n",
           accepted, refused, worst_table, worst_gain, worst_furnace_dev);
}

static void random_brdf(void **state)
{
    (void)state;
    rng r = {3301};
    int n = test_quick() ? 2 : (int)(4 * test_scale()) + 2;
    worst_table = worst_gain = worst_furnace_dev = 0;
    accepted = refused = 0;
    for (int k = 0; k < n; k++) {
        /* alpha from the smallest accepted (GGX_ALPHA_MIN) to 2, log-uniform; anisotropy to 1:200; skews to 1.2 */
        double ax = GGX_ALPHA_MIN * pow(2.0 / GGX_ALPHA_MIN, rng_uniform(&r));
        double ay = fmin(2.0, fmax(GGX_ALPHA_MIN, ax * pow(200.0, rng_range(&r, -1, 1))));
        double tx = 0, ty = 0;
        if (k % 2 == 0) tx = rng_range(&r, -1.2, 1.2), ty = rng_range(&r, -1.2, 1.2);
        shape_params p = {ax, ay, tx, ty, rng_range(&r, 0, GGX_PI)};
        char name[96];
        snprintf(name, sizeof name, "(%.4g, %.4g, %.3g, %.3g, %.3g)", p.ax, p.ay, p.tx, p.ty, p.tz);
        brdf_shape(name, p, (view_case){0, -1}, nphi() / 2, 2);
    }
    printf("random search: %d shapes, %d accepted, %d refused; largest table error %.2e, largest furnace gain "
           "%.2e\n",
           n, accepted, refused, worst_table, worst_gain);
}

/* The rough dielectric: the reported skewed shape from both sides, and an accepted skewed one. */
static void bsdf_shape(const char *name, shape_params p, double eta, double theta_deg, int nphi_)
{
    ggx_shape s;
    make_shape(&s, p);
    ggx_bsdf_energy *e = (ggx_bsdf_energy *)&s;
    ggx_status st = ggx_bsdf_energy_create(&s, eta, &e);
    if (st != GGX_OK) {
        CHECK(st == GGX_ERR_RANGE && e == NULL, "%s: status %s", name, ggx_status_str(st));
        printf("%-44s refused: %s\n", name, ggx_status_str(st));
        return;
    }
    double worst = 0, fdev = 0;
    for (int side = 0; side < 2; side++)
        for (int k = 0; k < nphi_; k++) {
            ggx_vec3 v = view_deg(side ? 180 - theta_deg : theta_deg, 2 * GGX_PI * (k + 0.37) / nphi_);
            double want = ggx_bsdf_albedo(&s, eta, v, NULL, NULL), got = ggx_bsdf_energy_albedo(e, v);
            CHECK(fabs(got - want) <= TABLE_PROMISE, "%s: table %.6f, ggx_bsdf_albedo %.6f at (%.4f, %.4f, %.4f)", name,
                  got, want, v.x, v.y, v.z);
            if (fabs(got - want) > worst) worst = fabs(got - want);
            if (k % (nphi_ / 4) == 0) {
                double sigma, f = furnace(draw_bsdf, e, v, 600, 104729u, &sigma);
                char what[160];
                snprintf(what, sizeof what, "%s, side %d, phi %.3f", name, side, 2 * GGX_PI * (k + 0.37) / nphi_);
                check_furnace(what, f, sigma, want, got);
                if (fabs(f - 1) > fdev) fdev = fabs(f - 1);
            }
        }
    printf("%-44s accepted: max |E_table - E| %.2e, max |furnace - 1| %.2e\n", name, worst, fdev);
    ggx_bsdf_energy_free(e);
}

static void bsdf_cases(void **state)
{
    (void)state;
    bsdf_shape("BSDF (0.02, 0.04, 0.3, 0.2), eta 1.5, 88.5", (shape_params){0.02, 0.04, 0.3, 0.2, 0}, 1.5, 88.5, 8);
    if (!test_quick()) /* the quick tier: the reported shape */
        bsdf_shape("BSDF (0.1, 0.8, 0.5, 0.3, 1), eta 1.33, 88.5", (shape_params){0.1, 0.8, 0.5, 0.3, 1}, 1.33, 88.5,
                   8);
}

int main(int argc, char **argv)
{
    int part = argc > 1 ? atoi(argv[1]) : 0;
    const struct CMUnitTest t1[] = {cmocka_unit_test(reported_brdf)};
    const struct CMUnitTest t2[] = {cmocka_unit_test(random_brdf)};
    const struct CMUnitTest t3[] = {cmocka_unit_test(bsdf_cases)};
    int rc = 0;
    if (part == 0 || part == 1) rc |= cmocka_run_group_tests_name("energy domain: reported", t1, NULL, NULL);
    if (part == 0 || part == 2) rc |= cmocka_run_group_tests_name("energy domain: random", t2, NULL, NULL);
    if (part == 0 || part == 3) rc |= cmocka_run_group_tests_name("energy domain: BSDF", t3, NULL, NULL);
    return rc;
}
