/* SPDX-License-Identifier: MIT */
#include "testlib.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

double test_scale(void)
{
    const char *e = getenv("GGX_TEST_SCALE");
    double v = e ? atof(e) : 1.0;
    return v > 0 ? v : 1.0;
}

int test_quick(void) { return test_scale() < 1.0; }

long chi2_samples(void) { return (long)(1e6 * test_scale()); }

void chi2_grid(long n, int *ntheta, int *nphi)
{
    int nt = (int)floor(sqrt((double)n / 100.0));
    *ntheta = nt < 4 ? 4 : (nt > 100 ? 100 : nt);
    *nphi = 2 * *ntheta;
}

double shape_kappa(double ax, double ay) { return fmax(fmax(ax, ay), 1.0) / fmin(fmin(ax, ay), 1.0); }
double slopes_bound(double ax, double ay) { return 1e-12 + 2e-15 * shape_kappa(ax, ay) * shape_kappa(ax, ay); }

shape_params random_shape(rng *r, double max_skew)
{
    shape_params p;
    p.ax = exp(rng_range(r, log(0.02), log(2.0)));
    double ratio = exp(rng_range(r, log(0.1), log(10.0)));
    p.ay = p.ax * ratio;
    if (p.ay < 0.02 || p.ay > 2.0) p.ay = p.ax / ratio; /* keep both in [0.02, 2] with the same ratio */
    if (p.ay < 0.02) p.ay = 0.02;
    if (p.ay > 2.0) p.ay = 2.0;
    p.tx = rng_range(r, -max_skew, max_skew);
    p.ty = rng_range(r, -max_skew, max_skew);
    p.tz = rng_range(r, -GGX_PI, GGX_PI);
    return p;
}

void make_shape(ggx_shape *s, shape_params p)
{
    ggx_status st = ggx_shape_ellipsoid(s, p.ax, p.ay, p.tx, p.ty, p.tz);
    CHECK(st == GGX_OK, "shape (%g, %g, %g, %g, %g): %s", p.ax, p.ay, p.tx, p.ty, p.tz, ggx_status_str(st));
}

ggx_vec3 random_view(rng *r)
{
    double phi = rng_range(r, 0.0, 2.0 * GGX_PI);
    double c = rng_uniform(r) < 0.25 ? exp(rng_range(r, log(1e-6), log(1e-2))) : rng_range(r, 1e-2, 1.0);
    double sn = sqrt(1.0 - c * c);
    return t_vec(sn * cos(phi), sn * sin(phi), c);
}

/* ---- checks ---- */

static void vfail(const char *file, int line, const char *what, const char *fmt, va_list ap)
{
    char msg[1024];
    vsnprintf(msg, sizeof msg, fmt, ap);
    print_error("%s:%d: %s\n    inputs: %s\n", file, line, what, msg);
    _fail(file, line);
}

void check_close_impl(double got, double want, double rel_tol, double abs_tol, const char *file, int line,
                      const char *fmt, ...)
{
    double err = fabs(got - want);
    if (err <= abs_tol + rel_tol * fabs(want)) return; /* NaN fails here */
    char what[256];
    snprintf(what, sizeof what, "got %.17g, want %.17g (abs err %.3g, rel err %.3g; tol rel %.3g abs %.3g)", got, want,
             err, want != 0.0 ? err / fabs(want) : err, rel_tol, abs_tol);
    va_list ap;
    va_start(ap, fmt);
    vfail(file, line, what, fmt, ap);
    va_end(ap);
}

void check_impl(int ok, const char *expr, const char *file, int line, const char *fmt, ...)
{
    if (ok) return;
    char what[256];
    snprintf(what, sizeof what, "check failed: %s", expr);
    va_list ap;
    va_start(ap, fmt);
    vfail(file, line, what, fmt, ap);
    va_end(ap);
}

double rng_gauss(rng *r)
{
    double u = rng_uniform(r), v = rng_uniform(r);
    return sqrt(-2.0 * log(1.0 - u)) * cos(2.0 * GGX_PI * v);
}

double rng_gamma(rng *r, double a)
{
    if (a < 1.0) return rng_gamma(r, a + 1.0) * pow(1.0 - rng_uniform(r), 1.0 / a);
    double d = a - 1.0 / 3.0, c = 1.0 / sqrt(9.0 * d);
    for (;;) {
        double x = rng_gauss(r), v = 1.0 + c * x;
        if (v <= 0.0) continue;
        v = v * v * v;
        if (log(1.0 - rng_uniform(r)) < 0.5 * x * x + d - d * v + d * log(v)) return d * v;
    }
}

ggx_vec3 student_t_normal(rng *r, const double t[2], const double sg[3], double nu)
{
    double l00 = sqrt(sg[0]), l10 = sg[1] / l00, l11 = sqrt(sg[2] - l10 * l10);
    double k = sqrt(nu / (4.0 * rng_gamma(r, 0.5 * nu))), g0 = rng_gauss(r) * k, g1 = rng_gauss(r) * k;
    double x = t[0] + l00 * g0, y = t[1] + l10 * g0 + l11 * g1, n = 1.0 / sqrt(1.0 + x * x + y * y);
    return (ggx_vec3){-x * n, -y * n, n};
}
