/* SGGX flake distributions (ggx_sggx.h): S = A^T A against ggx_ndf with a control that catches the transposed and
 * inverted matrices, the normalisations of D and both phase functions, reciprocity, the chi-square of every sampler
 * with negative controls, the diffuse phase function against an independent quadrature and against Monte Carlo, and
 * the edge cases of the contract. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "chi2.h"
#include "testlib.h"

/* A random rotation's rows (a uniform axis and angle is enough here). */
static void random_rotation(rng *r, double R[3][3])
{
    ggx_vec3 a = t_dir(acos(rng_range(r, -1.0, 1.0)), rng_range(r, 0.0, 2.0 * GGX_PI)), e1, e2;
    t_frame(a, &e1, &e2);
    double t = rng_range(r, 0.0, 2.0 * GGX_PI), c = cos(t), s = sin(t);
    ggx_vec3 rows[3] = {t_add(t_scale(e1, c), t_scale(e2, s)), t_add(t_scale(e1, -s), t_scale(e2, c)), a};
    for (int i = 0; i < 3; i++) R[i][0] = rows[i].x, R[i][1] = rows[i].y, R[i][2] = rows[i].z;
}

/* S = R^T diag(l) R, eigenvalues log-uniform over [lmin, 1]. */
static void random_spd(rng *r, double lmin, double S[3][3])
{
    double R[3][3], l[3];
    random_rotation(r, R);
    for (int k = 0; k < 3; k++) l[k] = exp(rng_range(r, log(lmin), 0.0));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            S[i][j] = R[0][i] * l[0] * R[0][j] + R[1][i] * l[1] * R[1][j] + R[2][i] * l[2] * R[2][j];
}

static ggx_vec3 random_dir(rng *r) { return t_dir(acos(rng_range(r, -1.0, 1.0)), rng_range(r, 0.0, 2.0 * GGX_PI)); }

static void make_sggx(ggx_sggx *f, const double S[3][3]) { assert_int_equal(ggx_sggx_from_matrix(f, S), GGX_OK); }

/* A shape whose ggx_ndf is proportional to the distribution's D on the upper hemisphere (A = S^(1/2)): the lobe-aware
 * quadrature of the verify library integrates in its sphere space. */
static void shape_of(const ggx_sggx *f, ggx_shape *s) { assert_int_equal(ggx_shape_matrix(s, f->half), GGX_OK); }

/* ---- S from A ---- */

/* The spread max/min - 1 of D_candidate(m) / ggx_ndf(m) over normals of the upper hemisphere: 0 (to rounding) when the
 * candidate's D is the shape's up to a constant. */
static double ratio_spread(const ggx_sggx *f, const ggx_shape *s, rng *r, double *ratio)
{
    double lo = INFINITY, hi = 0.0;
    for (int i = 0; i < 64; i++) {
        ggx_vec3 m = i % 2 ? ggx_sample_ndf(s, rng_uniform(r), rng_uniform(r))
                           : t_dir(acos(rng_range(r, 1e-3, 1.0)), rng_range(r, 0.0, 2.0 * GGX_PI));
        double d = ggx_ndf(s, m);
        if (!(d > 1e-200)) continue;
        double q = ggx_sggx_ndf(f, m) / d;
        lo = fmin(lo, q), hi = fmax(hi, q);
    }
    *ratio = hi;
    return hi / lo - 1.0;
}

/* The decision of docs/design/sggx.md: of A^T A, A A^T, (A^T A)^-1 and (A A^T)^-1, only A^T A gives D proportional
 * to ggx_ndf on skewed and rotated shapes (A non-symmetric, A^T A != A A^T), with the factor sigma(n) = ||A n||;
 * ggx_sggx_from_shape is that matrix. Each wrong candidate must be caught on every such shape. */
static void s_from_a(void **state)
{
    (void)state;
    rng r = {531};
    const double params[][5] = {{0.3, 0.6, 0.4, -0.3, 0.7},
                                {0.05, 0.2, 1.0, 0.5, -2.0},
                                {1.0, 0.1, -0.8, 1.2, 0.3},
                                {0.5, 0.5, 0.6, 0.0, 0.0},
                                {2.0, 0.3, 0.2, -0.9, 1.4}};
    double worst_right = 0.0, least_wrong = INFINITY;
    for (int k = 0; k < 5; k++) {
        const double *p = params[k];
        double A[3][3], M[4][3][3];
        ggx_shape s;
        assert_int_equal(ggx_ellipsoid_matrix(A, p[0], p[1], p[2], p[3], p[4]), GGX_OK);
        assert_int_equal(ggx_shape_matrix(&s, (const double(*)[3])A), GGX_OK);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                M[0][i][j] = M[1][i][j] = 0.0;
                for (int l = 0; l < 3; l++) M[0][i][j] += A[l][i] * A[l][j], M[1][i][j] += A[i][l] * A[j][l];
            }
        for (int c = 0; c < 2; c++) { /* the inverses, by the adjugate */
            double(*X)[3] = M[c], (*Y)[3] = M[c + 2];
            double det = X[0][0] * (X[1][1] * X[2][2] - X[1][2] * X[2][1]) -
                         X[0][1] * (X[1][0] * X[2][2] - X[1][2] * X[2][0]) +
                         X[0][2] * (X[1][0] * X[2][1] - X[1][1] * X[2][0]);
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                    Y[i][j] = (X[i1][j1] * X[i2][j2] - X[i1][j2] * X[i2][j1]) / det;
                }
        }
        const char *names[4] = {"A^T A", "A A^T", "(A^T A)^-1", "(A A^T)^-1"};
        for (int c = 0; c < 4; c++) {
            ggx_sggx f;
            make_sggx(&f, (const double(*)[3])M[c]);
            double ratio, spread = ratio_spread(&f, &s, &r, &ratio);
            printf("  shape %d, S = %-11s: D / ggx_ndf spread %.3g\n", k, names[c], spread);
            if (c == 0) {
                worst_right = fmax(worst_right, spread);
                CHECK(spread < 1e-12, "S = A^T A, shape %d: spread %g", k, spread);
                CHECK_CLOSE(ratio, s.an_len, 1e-12, 0.0, "the factor is sigma(n) = ||A n||");
            } else {
                least_wrong = fmin(least_wrong, spread);
                CHECK(spread > 1e-2, "S = %s not caught on shape %d: spread %g", names[c], k, spread);
            }
        }
        /* the constructor from the shape is A^T A, and sigma is the projected area times |A| / pi */
        ggx_sggx f;
        assert_int_equal(ggx_sggx_from_shape(&f, &s), GGX_OK);
        double ratio, spread = ratio_spread(&f, &s, &r, &ratio);
        CHECK(spread < 1e-12 && fabs(ratio / s.an_len - 1.0) < 1e-12, "from_shape %d: %g %g", k, spread, ratio);
        for (int i = 0; i < 8; i++) {
            ggx_vec3 w = random_dir(&r);
            CHECK_CLOSE(ggx_sggx_sigma(&f, w), s.det * ggx_projected_area(&s, w) / GGX_PI, 1e-13, 0.0, "sigma(w)");
        }
    }
    printf("s_from_a: A^T A spread <= %.3g; the wrong candidates >= %.3g\n", worst_right, least_wrong);
}

/* ---- normalisations ---- */

typedef struct dctx {
    const ggx_sggx *f;
    ggx_vec3 w, wo;
    double sign; /* the lower hemisphere, as m -> -m of the upper one */
} dctx;

/* D(m) max(0, w.m) at sign * m, for m on the upper hemisphere. */
static double d_proj(ggx_vec3 m, void *ctx)
{
    const dctx *c = ctx;
    ggx_vec3 x = t_scale(m, c->sign);
    return ggx_sggx_ndf(c->f, x) * fmax(0.0, t_dot(c->w, x));
}
/* (1/pi) ||H u||: the integrand of the integral of D over the sphere in sphere space (docs/design/sggx.md). */
static double area_term(const ggx_sggx *f, ggx_vec3 u) { return ggx_sggx_sigma(f, u) / GGX_PI; }

/* Product midpoint rule over the sphere (n slices of z, 2n of phi): for smooth integrands. */
static double sphere_sum(double (*g)(ggx_vec3 w, void *ctx), void *ctx, int n)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        double z = -1.0 + (i + 0.5) * 2.0 / n, q = sqrt(1.0 - z * z);
        for (int j = 0; j < 2 * n; j++) {
            double ph = (j + 0.5) * GGX_PI / n;
            sum += g(t_vec(q * cos(ph), q * sin(ph), z), ctx);
        }
    }
    return sum * (2.0 / n) * (GGX_PI / n);
}
static double area_fn(ggx_vec3 u, void *ctx) { return area_term(((const dctx *)ctx)->f, u); }
static double d_fn(ggx_vec3 m, void *ctx) { return 2.0 * ggx_sggx_ndf(((const dctx *)ctx)->f, m) * (m.z >= 0); }

/* sigma(w) = integral of D(m) max(0, w.m) dm = sqrt(w^T S w), and the integral of D over the sphere is the
 * ellipsoid's area times sqrt(|S|) / pi, computed in sphere space as (1/pi) integral of ||H u|| du. */
static void normalisation(void **state)
{
    (void)state;
    rng r = {532};
    double worst = 0.0, worst_area = 0.0;
    for (int k = 0; k < 6; k++) {
        double S[3][3];
        random_spd(&r, k < 3 ? 1e-2 : 1e-4, S);
        ggx_sggx f;
        ggx_shape s;
        make_sggx(&f, (const double(*)[3])S);
        shape_of(&f, &s);
        for (int i = 0; i < 3; i++) {
            ggx_vec3 w = random_dir(&r);
            dctx up = {&f, w, w, 1.0}, down = {&f, w, w, -1.0};
            ggx_vec3 cw = w, cn = t_scale(w, -1.0);
            double I = quad_hemisphere(&s, d_proj, &up, &cw, 1, 1e-10, NULL) +
                       quad_hemisphere(&s, d_proj, &down, &cn, 1, 1e-10, NULL);
            double sig = ggx_sggx_sigma(&f, w);
            double direct = sqrt(w.x * (S[0][0] * w.x + S[0][1] * w.y + S[0][2] * w.z) +
                                 w.y * (S[1][0] * w.x + S[1][1] * w.y + S[1][2] * w.z) +
                                 w.z * (S[2][0] * w.x + S[2][1] * w.y + S[2][2] * w.z));
            worst = fmax(worst, fabs(I / sig - 1.0));
            CHECK_CLOSE(I, sig, 1e-8, 0.0, "integral of D (w.m)+ vs sigma, S %d", k);
            CHECK_CLOSE(sig, direct, 1e-13, 0.0, "sigma vs sqrt(w^T S w)");
        }
        if (k < 3) { /* the integral of D, in m (lobe-aware) and in sphere space */
            dctx c = {&f, {0, 0, 1}, {0, 0, 1}, 1.0};
            double Dm = quad_hemisphere(&s, d_fn, &c, NULL, 0, 1e-10, NULL);
            double Du = sphere_sum(area_fn, &c, 400);
            worst_area = fmax(worst_area, fabs(Dm / Du - 1.0));
            CHECK_CLOSE(Dm, Du, 1e-5, 0.0, "integral of D, S %d", k);
        }
    }
    /* S = I: D = 1 / pi, sigma = 1, the integral of D is 4 */
    double I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    ggx_sggx f;
    make_sggx(&f, (const double(*)[3])I3);
    CHECK_CLOSE(ggx_sggx_ndf(&f, t_vec(0.6, 0, 0.8)), 1.0 / GGX_PI, 1e-15, 0.0, "D of S = I");
    CHECK_CLOSE(ggx_sggx_sigma(&f, t_vec(0, 0.6, -0.8)), 1.0, 1e-15, 0.0, "sigma of S = I");
    printf("normalisation: sigma identity to %.3g, the integral of D in m vs in sphere space to %.3g\n", worst,
           worst_area);
}

/* ---- phase functions ---- */

typedef struct pctx {
    const ggx_sggx *f;
    ggx_vec3 wi;
    int diffuse;
} pctx;
static double phase_fn(ggx_vec3 wo, void *ctx)
{
    const pctx *c = ctx;
    return c->diffuse ? ggx_sggx_phase_diffuse(c->f, c->wi, wo) : ggx_sggx_phase_specular(c->f, c->wi, wo);
}

/* Both phase functions integrate to 1 over the sphere and are reciprocal: sigma(wi) f(wi, wo) = sigma(wo) f(wo, wi). */
static void phases(void **state)
{
    (void)state;
    rng r = {533};
    double worst_spec = 0.0, worst_diff = 0.0, worst_recip = 0.0;
    for (int k = 0; k < 3; k++) {
        double S[3][3];
        random_spd(&r, 0.1, S);
        ggx_sggx f;
        make_sggx(&f, (const double(*)[3])S);
        ggx_vec3 wi = random_dir(&r);
        pctx ps = {&f, wi, 0}, pd = {&f, wi, 1};
        double is = sphere_sum(phase_fn, &ps, 600), id = sphere_sum(phase_fn, &pd, test_quick() ? 48 : 96);
        worst_spec = fmax(worst_spec, fabs(is - 1.0)), worst_diff = fmax(worst_diff, fabs(id - 1.0));
        CHECK_CLOSE(is, 1.0, 2e-5, 0.0, "specular phase integral, S %d", k);
        CHECK_CLOSE(id, 1.0, 1e-3, 0.0, "diffuse phase integral, S %d", k);
        for (int i = 0; i < 20; i++) {
            ggx_vec3 a = random_dir(&r), b = random_dir(&r);
            double sa = ggx_sggx_sigma(&f, a), sb = ggx_sggx_sigma(&f, b);
            double s1 = sa * ggx_sggx_phase_specular(&f, a, b), s2 = sb * ggx_sggx_phase_specular(&f, b, a);
            double d1 = sa * ggx_sggx_phase_diffuse(&f, a, b), d2 = sb * ggx_sggx_phase_diffuse(&f, b, a);
            worst_recip = fmax(worst_recip, fabs(d1 / d2 - 1.0));
            CHECK_CLOSE(s1, s2, 1e-13, 0.0, "specular reciprocity");
            CHECK_CLOSE(d1, d2, 1e-7, 0.0, "diffuse reciprocity");
        }
    }
    printf("phases: integral of the specular phase - 1 <= %.3g, of the diffuse <= %.3g (midpoint rules); diffuse "
           "reciprocity to %.3g\n",
           worst_spec, worst_diff, worst_recip);
}

/* ---- the diffuse phase function: exact evaluation ---- */

typedef struct fctx {
    const ggx_sggx *f;
    ggx_vec3 wi, wo;
} fctx;
static double dd_fn(ggx_vec3 m, void *ctx)
{
    const fctx *c = ctx;
    return ggx_sggx_ndf(c->f, m) * t_dot(c->wi, m) * t_dot(c->wo, m);
}
/* pi sigma(wi) f(wi, wo) = the integral of D (wi.m)+ (wo.m)+ over the sphere: on the upper hemisphere cut by wi and
 * wo, plus (m -> -m) the one cut by -wi and -wo; by the verify library's lobe-aware quadrature. */
static double diffuse_reference(const ggx_sggx *f, const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo)
{
    fctx c = {f, wi, wo};
    ggx_vec3 up[2] = {wi, wo}, down[2] = {t_scale(wi, -1.0), t_scale(wo, -1.0)};
    double I = quad_hemisphere(s, dd_fn, &c, up, 2, 1e-10, NULL) + quad_hemisphere(s, dd_fn, &c, down, 2, 1e-10, NULL);
    return I / (GGX_PI * ggx_sggx_sigma(f, wi));
}

/* Against the independent quadrature, for random S with eigenvalue ratios to 1e4 and shapes to alpha = 1e-3 (ratio
 * 1e6), skewed and rotated; pairs in general position and in a common plane with an axis of S; within the header's
 * 1e-4. */
static void diffuse_vs_quadrature(void **state)
{
    (void)state;
    rng r = {534};
    double worst = 0.0;
    int cases = test_quick() ? 6 : 40;
    for (int k = 0; k < cases; k++) {
        ggx_sggx f;
        ggx_shape s;
        if (k % 2 == 0) {
            double S[3][3];
            random_spd(&r, 1e-4, S);
            make_sggx(&f, (const double(*)[3])S);
        } else {
            double al = k == 1 ? 1e-3 : exp(rng_range(&r, log(1e-3), 0.0));
            assert_int_equal(ggx_shape_ellipsoid(&s, al, al * (k == 3 ? 3.0 : 1.0), 0.4, -0.3, 0.7), GGX_OK);
            assert_int_equal(ggx_sggx_from_shape(&f, &s), GGX_OK);
        }
        shape_of(&f, &s);
        for (int i = 0; i < 4; i++) {
            ggx_vec3 wi = random_dir(&r), wo = random_dir(&r);
            if (i == 3) { /* both in the plane of the flattest and the longest axes */
                ggx_vec3 e1 = {f.axes[0][0], f.axes[0][1], f.axes[0][2]},
                         e3 = {f.axes[2][0], f.axes[2][1], f.axes[2][2]};
                wi = t_normalize(t_add(e1, t_scale(e3, 0.7))), wo = t_normalize(t_add(e1, t_scale(e3, -0.4)));
            }
            double got = ggx_sggx_phase_diffuse(&f, wi, wo), want = diffuse_reference(&f, &s, wi, wo);
            double e = fabs(got - want) / want;
            worst = fmax(worst, e);
            CHECK(e < 1e-4, "case %d pair %d: %.12g vs quadrature %.12g (eigenvalues %g %g %g)", k, i, got, want,
                  f.eig[0], f.eig[1], f.eig[2]);
        }
    }
    printf("diffuse_vs_quadrature: %d distributions, largest relative difference %.3g\n", cases, worst);
}

/* Against Monte Carlo: the mean of max(0, wo.m) / pi over visible normals m drawn by ggx_sggx_sample_vndf (1e6
 * samples at the quick tier, 1e8 at the full one), within 5 standard errors plus the stated 1e-4. */
static void diffuse_vs_monte_carlo(void **state)
{
    (void)state;
    rng r = {535};
    long n = test_quick() ? 1000000L : 100000000L;
    double worst = 0.0;
    for (int k = 0; k < 3; k++) {
        ggx_shape s;
        ggx_sggx f;
        assert_int_equal(ggx_shape_ellipsoid(&s, k == 0 ? 0.05 : 0.4, 0.2, 0.5, -0.2, 1.0), GGX_OK);
        assert_int_equal(ggx_sggx_from_shape(&f, &s), GGX_OK);
        ggx_vec3 wi = random_dir(&r), wo = k == 2 ? t_normalize(t_vec(-wi.x, -wi.y, wi.z)) : random_dir(&r);
        double sum = 0.0, sum2 = 0.0;
        for (long i = 0; i < n; i++) {
            ggx_vec3 m = ggx_sggx_sample_vndf(&f, wi, rng_uniform(&r), rng_uniform(&r));
            double x = fmax(0.0, t_dot(wo, m)) / GGX_PI;
            sum += x, sum2 += x * x;
        }
        double dn = (double)n, mean = sum / dn, se = sqrt(fmax(0.0, sum2 / dn - mean * mean) / dn);
        double got = ggx_sggx_phase_diffuse(&f, wi, wo);
        worst = fmax(worst, fabs(got - mean) / se);
        CHECK(fabs(got - mean) <= 5.0 * se + 1e-4 * got, "case %d: exact %.9g, Monte Carlo %.9g +- %.3g", k, got, mean,
              se);
    }
    printf("diffuse_vs_monte_carlo: %ld samples each, largest difference %.2f standard errors\n", n, worst);
}

/* ---- samplers: chi-square ---- */

typedef enum { SAMP_VNDF, SAMP_SPECULAR, SAMP_DIFFUSE } samp_kind;
typedef struct sctx {
    const ggx_sggx *f;   /* the sampler's distribution */
    const ggx_sggx *pdf; /* the density's (another one for the negative controls) */
    ggx_vec3 wi;
    samp_kind kind;
} sctx;

static int s_draw(void *ctx, rng *r, ggx_vec3 *w)
{
    const sctx *c = ctx;
    double u1 = rng_uniform(r), u2 = rng_uniform(r);
    if (c->kind == SAMP_VNDF) *w = ggx_sggx_sample_vndf(c->f, c->wi, u1, u2);
    if (c->kind == SAMP_SPECULAR) *w = ggx_sggx_sample_specular(c->f, c->wi, u1, u2);
    if (c->kind == SAMP_DIFFUSE) *w = ggx_sggx_sample_diffuse(c->f, c->wi, u1, u2, rng_uniform(r), rng_uniform(r));
    return !(w->x == 0 && w->y == 0 && w->z == 0);
}
static int s_key(void *ctx, ggx_vec3 w, int *region, ggx_vec3 *k)
{
    (void)ctx;
    *region = 0, *k = w;
    return 1;
}
static double s_density(void *ctx, int region, ggx_vec3 w)
{
    const sctx *c = ctx;
    (void)region;
    if (c->kind == SAMP_VNDF)
        return fmax(0.0, t_dot(c->wi, w)) * ggx_sggx_ndf(c->pdf, w) / ggx_sggx_sigma(c->pdf, c->wi);
    if (c->kind == SAMP_SPECULAR) return ggx_sggx_phase_specular(c->pdf, c->wi, w);
    return ggx_sggx_phase_diffuse(c->pdf, c->wi, w);
}

static double run_chi2(const sctx *c, const char *name, uint64_t seed)
{
    chi2_problem p = {name, 1, s_draw, s_key, s_density, (void *)c};
    /* the diffuse density costs microseconds and the harness integrates it over each cell: a coarser grid for it
     * (cells expect ~400 samples) */
    long n = c->kind == SAMP_DIFFUSE ? 200000 : chi2_samples();
    int nt = 16, np = 32;
    if (c->kind != SAMP_DIFFUSE) chi2_grid(n, &nt, &np);
    chi2_result res = chi2_run(&p, n, nt, np, seed, test_chi2_level());
    return res.zero_cell_hits ? 0.0 : res.pvalue;
}

/* Every sampler against its density on three distributions (a skewed and rotated shape, a fibre-like S with one small
 * eigenvalue, a random S), and each negative control (the density of S stretched by 1.15 along one axis) rejected. */
static void samplers_chi2(void **state)
{
    (void)state;
    rng r = {536};
    ggx_sggx fs[3];
    ggx_shape s;
    assert_int_equal(ggx_shape_ellipsoid(&s, 0.3, 0.6, 0.4, -0.3, 0.7), GGX_OK);
    assert_int_equal(ggx_sggx_from_shape(&fs[0], &s), GGX_OK);
    double fibre[3][3] = {{1.0, 0.0, 0.0}, {0.0, 0.9, 0.1}, {0.0, 0.1, 0.06}}, S[3][3];
    make_sggx(&fs[1], (const double(*)[3])fibre);
    random_spd(&r, 0.05, S);
    make_sggx(&fs[2], (const double(*)[3])S);
    const char *kinds[3] = {"vndf", "specular", "diffuse"};
    double lowest = 1.0, highest_neg = 0.0;
    for (int k = 0; k < 3; k++)
        for (int d = 0; d < 3; d++) {
            ggx_vec3 wi = random_dir(&r);
            sctx c = {&fs[d], &fs[d], wi, (samp_kind)k};
            char name[64];
            snprintf(name, sizeof name, "sggx_%s_%d", kinds[k], d);
            double pv = run_chi2(&c, name, 5360 + 10 * k + d);
            lowest = fmin(lowest, pv);
            CHECK(chi2_accepts(pv), "%s: p = %g", name, pv);
            if (d == 0) { /* the negative control */
                ggx_sggx wrong;
                double W[3][3];
                memcpy(W, fs[d].s, sizeof W);
                for (int i = 0; i < 3; i++) W[0][i] *= 1.15, W[i][0] *= 1.15;
                make_sggx(&wrong, (const double(*)[3])W);
                sctx n = {&fs[d], &wrong, wi, (samp_kind)k};
                chi2_problem p = {"neg", 1, s_draw, s_key, s_density, &n};
                long ns = k == SAMP_DIFFUSE ? 200000 : chi2_samples();
                int nt = 16, np = 32;
                if (k != SAMP_DIFFUSE) chi2_grid(ns, &nt, &np);
                chi2_result res = chi2_run_quiet(&p, ns, nt, np, 5460 + k, test_chi2_level());
                highest_neg = fmax(highest_neg, res.pvalue);
                CHECK(res.pvalue < 1e-6, "negative control of %s accepted: p = %g", kinds[k], res.pvalue);
            }
        }
    printf("samplers_chi2: 9 runs, lowest p = %.3g; negative controls p <= %.3g\n", lowest, highest_neg);
}

/* ---- the contract's edges ---- */

static void edges(void **state)
{
    (void)state;
    ggx_sggx f, keep;
    double I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    make_sggx(&keep, (const double(*)[3])I3);
    f = keep;
    double bad[3][3];
    memcpy(bad, I3, sizeof bad);
    assert_int_equal(ggx_sggx_from_matrix(NULL, (const double(*)[3])I3), GGX_ERR_NULL);
    assert_int_equal(ggx_sggx_from_matrix(&f, NULL), GGX_ERR_NULL);
    bad[1][2] = NAN;
    assert_int_equal(ggx_sggx_from_matrix(&f, (const double(*)[3])bad), GGX_ERR_NONFINITE);
    bad[1][2] = 0.5; /* not symmetric */
    assert_int_equal(ggx_sggx_from_matrix(&f, (const double(*)[3])bad), GGX_ERR_RANGE);
    bad[2][1] = 2.0, bad[1][2] = 2.0; /* symmetric, indefinite */
    assert_int_equal(ggx_sggx_from_matrix(&f, (const double(*)[3])bad), GGX_ERR_SINGULAR);
    double zero[3][3] = {{0}};
    assert_int_equal(ggx_sggx_from_matrix(&f, (const double(*)[3])zero), GGX_ERR_SINGULAR);
    double flat[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1e-13}};
    assert_int_equal(ggx_sggx_from_matrix(&f, (const double(*)[3])flat), GGX_ERR_SINGULAR);
    double huge[3][3] = {{1e120, 0, 0}, {0, 1e120, 0}, {0, 0, 1e120}};
    assert_int_equal(ggx_sggx_from_matrix(&f, (const double(*)[3])huge), GGX_ERR_RANGE);
    CHECK(memcmp(&f, &keep, sizeof f) == 0, "f changed on error");
    ggx_shape s;
    assert_int_equal(ggx_shape_aniso(&s, 1e-4, 1.0), GGX_OK);
    assert_int_equal(ggx_sggx_from_shape(&f, &s), GGX_OK);
    assert_int_equal(ggx_sggx_from_shape(NULL, &s), GGX_ERR_NULL);
    assert_int_equal(ggx_sggx_from_shape(&f, NULL), GGX_ERR_NULL);
    assert_int_equal(ggx_shape_aniso(&s, 1e-4, 1e3), GGX_OK);
    assert_int_equal(ggx_sggx_from_shape(&f, &s), GGX_ERR_SINGULAR);

    /* evaluations: NaN and zero directions give 0 */
    ggx_shape sk;
    assert_int_equal(ggx_shape_ellipsoid(&sk, 0.2, 0.5, 0.3, 0.2, 0.1), GGX_OK);
    assert_int_equal(ggx_sggx_from_shape(&f, &sk), GGX_OK);
    ggx_vec3 z = {0, 0, 0}, nan = {NAN, 0, 1}, w = t_normalize(t_vec(0.3, -0.2, 0.9));
    CHECK(ggx_sggx_ndf(&f, z) == 0 && ggx_sggx_ndf(&f, nan) == 0, "ndf of zero / NaN");
    CHECK(ggx_sggx_sigma(&f, z) == 0 && ggx_sggx_sigma(&f, nan) == 0, "sigma of zero / NaN");
    CHECK(ggx_sggx_phase_specular(&f, w, z) == 0 && ggx_sggx_phase_specular(&f, nan, w) == 0, "specular phase");
    CHECK(ggx_sggx_phase_diffuse(&f, w, z) == 0 && ggx_sggx_phase_diffuse(&f, nan, w) == 0, "diffuse phase");
    CHECK(ggx_sggx_phase_specular(&f, w, t_scale(w, -1.0)) == 0, "specular phase at wo = -wi");
    CHECK(ggx_sggx_phase_diffuse(&f, w, t_scale(w, -1.0)) == 0, "diffuse phase at wo = -wi");
    CHECK(ggx_sggx_phase_diffuse(&f, w, w) > 0, "diffuse phase at wo = wi");
    CHECK_CLOSE(ggx_sggx_sigma(&f, t_scale(w, 3.0)), 3.0 * ggx_sggx_sigma(&f, w), 1e-15, 0.0, "sigma homogeneous");
    /* samplers: the zero vector for zero or NaN wi; unit vectors for u at 0, 1 - 2^-24, 1, NaN and out of range */
    ggx_vec3 m = ggx_sggx_sample_vndf(&f, z, 0.5, 0.5);
    CHECK(m.x == 0 && m.y == 0 && m.z == 0, "vndf of a zero wi");
    m = ggx_sggx_sample_diffuse(&f, nan, 0.5, 0.5, 0.5, 0.5);
    CHECK(m.x == 0 && m.y == 0 && m.z == 0, "diffuse of a NaN wi");
    const double us[] = {0.0, 1.0 - 0x1p-24, 1.0, NAN, -3.0, 7.0};
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            ggx_vec3 o[3] = {ggx_sggx_sample_vndf(&f, w, us[i], us[j]), ggx_sggx_sample_specular(&f, w, us[i], us[j]),
                             ggx_sggx_sample_diffuse(&f, w, us[i], us[j], us[j], us[i])};
            for (int k = 0; k < 3; k++)
                CHECK(fabs(sqrt(t_dot(o[k], o[k])) - 1.0) <= 1e-12, "sampler %d at u = (%g, %g): |w| = %.17g", k, us[i],
                      us[j], sqrt(t_dot(o[k], o[k])));
            CHECK(t_dot(o[0], w) > 0, "visible normal at u = (%g, %g)", us[i], us[j]);
        }
    /* the sphere point antipodal to the sphere-space view (a + s = 0 exactly: S diagonal, wi and s along z) */
    double D3[3][3] = {{0.3, 0, 0}, {0, 0.05, 0}, {0, 0, 2.0}};
    ggx_sggx fd;
    make_sggx(&fd, (const double(*)[3])D3);
    ggx_vec3 zi = t_vec(0, 0, 1), mz = ggx_sggx_sample_vndf(&fd, zi, 1.0, 0.0);
    ggx_vec3 wz = ggx_sggx_sample_diffuse(&fd, zi, 1.0, 0.0, 1.0, 0.0);
    CHECK(fabs(t_dot(mz, mz) - 1.0) <= 1e-12 && t_dot(mz, zi) > 0, "vndf at the antipode: (%g, %g, %g)", mz.x, mz.y,
          mz.z);
    CHECK(fabs(t_dot(wz, wz) - 1.0) <= 1e-12 && t_dot(wz, zi) > 0, "diffuse at the antipodes: (%g, %g, %g)", wz.x, wz.y,
          wz.z);
    /* the samplers depend on wi's direction only */
    ggx_vec3 a = ggx_sggx_sample_vndf(&f, w, 0.3, 0.8), b = ggx_sggx_sample_vndf(&f, t_scale(w, 1e-3), 0.3, 0.8);
    CHECK(fabs(a.x - b.x) + fabs(a.y - b.y) + fabs(a.z - b.z) < 1e-15, "vndf of a scaled wi");
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(s_from_a),
        cmocka_unit_test(normalisation),
        cmocka_unit_test(phases),
        cmocka_unit_test(diffuse_vs_quadrature),
        cmocka_unit_test(diffuse_vs_monte_carlo),
        cmocka_unit_test(samplers_chi2),
        cmocka_unit_test(edges),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    return rc | chi2_budget_end("sggx", argc, argv);
}
