/* Energy compensation over its whole domain, checked independently of the tables: ggx_energy_create
 * (ggx_bsdf_energy_create) accepts every shape, and its table is never more than GAIN_PROMISE below ggx_albedo
 * (ggx_bsdf_albedo) at views dense in the azimuth up to 89.9 degrees, so that the compensation never adds energy; where
 * it is above E by more than that (the guarded cells of a feature narrower than the nodes: the compensation loses
 * some multiple scattering there), the loss is reported. The white furnace, by stratified Monte Carlo over the
 * library's own compensated sampler, is 1 + (E - E_table)(wi) to its sampling error and never above 1 + 1e-3. The
 * shapes: the hostile reports' reproducers (a table 0.21 below E and a furnace of 1.21 for a sharp skewed lobe at 89
 * degrees, before the guard; shapes refused before it) and a random search over the shapes ggx_shape_ellipsoid
 * accepts: alpha 1e-3 to 10, anisotropy to 1:200, skews to pi / 2, any rotation.
 * Argument: 1 the reported BRDF cases, 2 the random BRDF search, 3 the BSDF cases. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "testlib.h"

#define GAIN_PROMISE 1e-3 /* the table never below E by more than this: the furnace never above 1 + 1e-3 */
#define EXACT_MU 0.0175   /* cos 89 degrees: the accuracy's promise (ggx.h); beyond it the table only bounds E */

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

static double worst_gain_table, worst_gain, worst_loss;
static int shapes;

/* The furnace's checks at one view: the compensated albedo is 1 + (E - E_table) (ggx.h) to 4 sigma plus the
 * lobe's normalisation by the table's cell quadrature, and never a gain beyond 1e-3. */
static void check_furnace(const char *what, double f, double sigma, double e_true, double e_tab)
{
    double tol = 4 * sigma + 2e-4;
    CHECK(fabs(f - (1 + (e_true - e_tab))) <= tol, "%s: furnace %.6f, 1 + (E - E_table) = %.6f (sigma %.1e)", what, f,
          1 + (e_true - e_tab), sigma);
    CHECK(f <= 1 + GAIN_PROMISE + 4 * sigma, "%s: the compensation adds energy: furnace %.6f (sigma %.1e)", what, f,
          sigma);
    if (f - 1 > worst_gain) worst_gain = f - 1;
}

/* One BRDF shape: accepted, its table never below E by more than GAIN_PROMISE at the views of the scan (nphi azimuths
 * at each elevation to 89.9 degrees) and at the given view, within GAIN_PROMISE of E up to 89 degrees where
 * expect_exact (a shape with no feature finer than the nodes), and its furnace checked at the views where the table is furthest below E
 * and where it loses most. */
static void brdf_shape(const char *name, shape_params p, view_case vc, int nphi, int nfurnace, int expect_exact)
{
    ggx_shape s;
    make_shape(&s, p);
    ggx_energy *e = (ggx_energy *)&s;
    ggx_status st = ggx_energy_create(&s, &e);
    CHECK(st == GGX_OK && e != NULL, "%s: status %s", name, ggx_status_str(st));
    if (st != GGX_OK) return;
    shapes++;
    static const double thetas[] = {30, 60, 75, 80, 84, 86, 87, 88, 88.5, 89, 89.5, 89.9};
    enum { NT = sizeof thetas / sizeof thetas[0], KEEP = 8 };
    struct {
        double err;
        ggx_vec3 v;
    } worst[KEEP] = {{0}};
    double gain = 0, loss = 0, loss_sum = 0;
    int nv = NT * nphi + (vc.phi >= 0), n = 0, lossy = 0;
    /* the quick tier: every fourth azimuth of the full tier's scan, so that its views are a subset of those */
    int stride = test_quick() ? 4 : 1;
    for (int k = 0; k < nv; k++) {
        if (k < NT * nphi && (k % nphi) % stride) continue;
        ggx_vec3 v = k < NT * nphi ? view_deg(thetas[k / nphi], 2 * GGX_PI * ((k % nphi) + 0.37) / nphi)
                                   : view_deg(vc.theta_deg, vc.phi);
        double want = ggx_albedo(&s, v), got = ggx_energy_albedo(e, v);
        CHECK(want - got <= GAIN_PROMISE, "%s: table E %.6f below ggx_albedo %.6f at (%.5f, %.5f, %.5f)", name, got,
              want, v.x, v.y, v.z);
        if (expect_exact && v.z >= EXACT_MU) /* beyond 89 degrees the grazing band may lie above E */
            CHECK(got - want <= GAIN_PROMISE, "%s: table E %.6f above ggx_albedo %.6f at (%.5f, %.5f, %.5f)", name, got,
                  want, v.x, v.y, v.z);
        n++;
        gain = fmax(gain, want - got);
        loss = fmax(loss, got - want);
        loss_sum += fmax(0.0, got - want);
        lossy += got - want > GAIN_PROMISE;
        /* keep the views where the table is furthest off either way, and the given view, for the furnace */
        double err = fabs(got - want);
        if (k == nv - 1 && vc.phi >= 0) err = 1.0;
        int m = 0;
        for (int q = 1; q < KEEP; q++)
            if (worst[q].err < worst[m].err) m = q;
        if (err >= worst[m].err) worst[m].err = err, worst[m].v = v;
    }
    worst_gain_table = fmax(worst_gain_table, gain);
    worst_loss = fmax(worst_loss, loss);
    double fmax_dev = 0;
    for (int q = 0; q < KEEP && q < nfurnace; q++) {
        if (!(worst[q].v.z > 0)) continue;
        double sigma, f = furnace(draw_brdf, e, worst[q].v, 400, 7919u, &sigma);
        char what[160];
        snprintf(what, sizeof what, "%s at (%.5f, %.5f, %.5f)", name, worst[q].v.x, worst[q].v.y, worst[q].v.z);
        check_furnace(what, f, sigma, ggx_albedo(&s, worst[q].v), ggx_energy_albedo(e, worst[q].v));
        if (fabs(f - 1) > fmax_dev) fmax_dev = fabs(f - 1);
    }
    printf("%-44s E_table - E: at most %.2e below, %.2e above (above by more than 1e-3 at %d of %d views, mean "
           "loss %.1e); max |furnace - 1| %.2e\n",
           name, gain, loss, lossy, n, loss_sum / n, fmax_dev);
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
        int exact;
    } cases[] = {
        {"(0.002, 0.004, 0.3, 0.2) at 89, phi 3.70", {0.002, 0.004, 0.3, 0.2, 0}, {89, 3.70}, 0},
        {"(0.02, 0.04, 0.3, 0.2) at 88.5", {0.02, 0.04, 0.3, 0.2, 0}, {88.5, -1}, 0},
        {"(0.05, 0.05, theta_x 0.3)", {0.05, 0.05, 0.3, 0, 0}, {87, 0.076}, 0},
        {"aniso (0.002, 0.004) at 89", {0.002, 0.004, 0, 0, 0}, {89, 0.0}, 0},
        {"aniso (0.01, 2) at 89, phi 0.012", {0.01, 2, 0, 0, 0}, {89, 0.012}, 0},
        {"(0.3, 0.6, 0.4, -0.3), rotated 0.7", {0.3, 0.6, 0.4, -0.3, 0.7}, {89, 1.0}, 1},
        {"skewed (0.05, 0.3, -0.5, 0.5)", {0.05, 0.3, -0.5, 0.5, 0}, {89, 2.68}, 0},
        {"(0.03, 0.03, theta_x 1.0)", {0.03, 0.03, 1.0, 0, 0}, {87, 0.07}, 0},
    };
    worst_gain_table = worst_gain = worst_loss = 0;
    shapes = 0;
    /* the quick tier: the sharp unskewed lobe (quadrature nodes) and the rough skewed one (the guard's checks), the
     * two whose tables cost least; the full tier runs them all */
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++)
        if (!test_quick() || i == 3 || i == 5)
            brdf_shape(cases[i].name, cases[i].p, cases[i].v, nphi(), 4, cases[i].exact);
    printf("reported cases: %d shapes; table at most %.2e below E, at most %.2e above; largest furnace gain %.2e\n",
           shapes, worst_gain_table, worst_loss, worst_gain);
}

static void random_brdf(void **state)
{
    (void)state;
    rng r = {3301};
    int n = test_quick() ? 2 : (int)(4 * test_scale()) + 2;
    worst_gain_table = worst_gain = worst_loss = 0;
    shapes = 0;
    for (int k = 0; k < n; k++) {
        /* alpha 1e-3 to 10, log-uniform; anisotropy to 1:200; skews to pi / 2 on every other shape. The quick tier
         * draws alpha from 0.05 (a sharp skewed lobe's table is most of a minute of quadrature; the reported cases
         * and the full tier have them) */
        double amin = test_quick() ? 0.05 : 1e-3, ax = amin * pow(10.0 / amin, rng_uniform(&r));
        double ay = fmin(10.0, fmax(1e-3, ax * pow(200.0, rng_range(&r, -1, 1))));
        double tx = 0, ty = 0;
        if (k % 2 == 0) tx = rng_range(&r, -0.5, 0.5) * GGX_PI, ty = rng_range(&r, -0.5, 0.5) * GGX_PI;
        shape_params p = {ax, ay, tx, ty, rng_range(&r, 0, GGX_PI)};
        char name[96];
        snprintf(name, sizeof name, "(%.4g, %.4g, %.3g, %.3g, %.3g)", p.ax, p.ay, p.tx, p.ty, p.tz);
        brdf_shape(name, p, (view_case){0, -1}, nphi() / 2, 2, 0);
    }
    printf("random search: %d shapes; table at most %.2e below E, at most %.2e above; largest furnace gain %.2e\n",
           shapes, worst_gain_table, worst_loss, worst_gain);
}

/* The rough dielectric, from both sides at each of the elevations: accepted, its tables never below E by more than
 * GAIN_PROMISE, and the furnace at four azimuths of each. */
static void bsdf_shape(const char *name, shape_params p, double eta, int nphi_)
{
    ggx_shape s;
    make_shape(&s, p);
    ggx_bsdf_energy *e = (ggx_bsdf_energy *)&s;
    ggx_status st = ggx_bsdf_energy_create(&s, eta, &e);
    CHECK(st == GGX_OK && e != NULL, "%s: status %s", name, ggx_status_str(st));
    if (st != GGX_OK) return;
    static const double thetas[] = {60, 88.5, 89.9};
    double gain = 0, loss = 0, fdev = 0;
    for (int side = 0; side < 2; side++)
        for (unsigned a = 0; a < sizeof thetas / sizeof thetas[0]; a++)
            for (int k = 0; k < nphi_; k++) {
                double theta = side ? 180 - thetas[a] : thetas[a], phi = 2 * GGX_PI * (k + 0.37) / nphi_;
                ggx_vec3 v = view_deg(theta, phi);
                double want = ggx_bsdf_albedo(&s, eta, v, NULL, NULL), got = ggx_bsdf_energy_albedo(e, v);
                CHECK(want - got <= GAIN_PROMISE, "%s: table %.6f below ggx_bsdf_albedo %.6f at (%.4f, %.4f, %.4f)",
                      name, got, want, v.x, v.y, v.z);
                gain = fmax(gain, want - got);
                loss = fmax(loss, got - want);
                if (k % (nphi_ / 4) == 0) {
                    double sigma, f = furnace(draw_bsdf, e, v, 600, 104729u, &sigma);
                    char what[160];
                    snprintf(what, sizeof what, "%s, theta %.1f, phi %.3f", name, theta, phi);
                    check_furnace(what, f, sigma, want, got);
                    if (fabs(f - 1) > fdev) fdev = fabs(f - 1);
                }
            }
    printf("%-44s E_table - E: at most %.2e below, %.2e above; max |furnace - 1| %.2e\n", name, gain, loss, fdev);
    ggx_bsdf_energy_free(e);
}

static void bsdf_cases(void **state)
{
    (void)state;
    worst_gain = 0;
    /* the quick tier: the reported lobe's roughness, unskewed and rotated (a quarter of the skewed table's quadrature;
     * energy_bsdf_3 checks a skewed table's lookups) */
    if (test_quick()) {
        bsdf_shape("BSDF (0.02, 0.04) rotated 0.3, eta 1.5", (shape_params){0.02, 0.04, 0, 0, 0.3}, 1.5, 8);
        return;
    }
    bsdf_shape("BSDF (0.02, 0.04, 0.3, 0.2), eta 1.5", (shape_params){0.02, 0.04, 0.3, 0.2, 0}, 1.5, 8);
    bsdf_shape("BSDF (0.1, 0.8, 0.5, 0.3, 1), eta 1.33", (shape_params){0.1, 0.8, 0.5, 0.3, 1}, 1.33, 8);
    /* random shapes as the BRDF's search draws them, eta from 1.05 to 2.5 or its inverse */
    rng r = {7411};
    for (int k = 0; k < 2; k++) {
        double ax = 1e-3 * pow(1e4, rng_uniform(&r)),
               ay = fmin(10.0, fmax(1e-3, ax * pow(200.0, rng_range(&r, -1, 1))));
        shape_params p = {ax, ay, rng_range(&r, -0.5, 0.5) * GGX_PI, rng_range(&r, -0.5, 0.5) * GGX_PI,
                          rng_range(&r, 0, GGX_PI)};
        double eta = rng_range(&r, 1.05, 2.5);
        if (k % 2) eta = 1 / eta;
        char name[96];
        snprintf(name, sizeof name, "BSDF (%.4g, %.4g, %.3g, %.3g, %.3g), eta %.3g", p.ax, p.ay, p.tx, p.ty, p.tz, eta);
        bsdf_shape(name, p, eta, 8);
    }
    printf("BSDF: largest furnace gain %.2e\n", worst_gain);
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
