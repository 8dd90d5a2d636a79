/* Gaussian random fields with Beckmann facets, by FFT with KISS FFT (microsurface.h; docs/design/microsurface.md).
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "microsurface.h"

#ifdef GGX_HAVE_KISSFFT
#include <kiss_fftnd.h>
#endif

static const double PI = 3.14159265358979323846;

/* splitmix64: the seed's stream of 64-bit words */
static uint64_t next_u64(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* a pair of independent standard normals (Box-Muller, u in (0, 1]) */
static void normals(uint64_t *s, double *a, double *b)
{
    double u = ((double)(next_u64(s) >> 11) + 1.0) * 0x1p-53, v = (double)(next_u64(s) >> 11) * 0x1p-53;
    double r = sqrt(-2.0 * log(u));
    *a = r * cos(2.0 * PI * v), *b = r * sin(2.0 * PI * v);
}

/* the lattice's wave number of index i: 2 pi i / n folded into (-pi, pi] */
static double wave(size_t i, size_t n)
{
    return 2.0 * PI * (double)(i <= n / 2 ? (double)i : (double)i - (double)n) / (double)n;
}

/* S(k) = exp(-k^T M^-1 k / 4), the Gaussian autocorrelation's spectrum up to a constant, and from it the variance of
 * the heights, the covariance of the slopes of the four facets of a cell (both triangulations) and the mixed
 * difference's share, for Re sum_k A(k) W(k) e^{i k.x}, A = sqrt(c S), E|W|^2 = 1: var = c/2 sum S; the diagonal
 * c/2 sum S |e^{i k_a} - 1|^2 = c/2 sum S 4 sin^2(k_a/2); the off-diagonal, the mean of the cut from (x+1, y) to
 * (x, y+1) (Re[(e^{i kx} - 1) conj(e^{i ky} - 1)]) and of the other cut (Re[(1 - e^{-i kx}) conj(e^{i ky} - 1)]),
 * c/2 sum S sin kx sin ky; mixed = E[D^2] / 4 = c/2 sum S 4 sin^2(kx/2) sin^2(ky/2), D = h(x+1, y+1) - h(x+1, y) -
 * h(x, y+1) + h(x, y), by which the first cut's off-diagonal exceeds that mean and the second's falls short of it. */
static void moments(size_t n, const double M[3], double *var, double cov[3], double *mixed)
{
    double det = M[0] * M[2] - M[1] * M[1], ixx = M[2] / det, ixy = -M[1] / det, iyy = M[0] / det;
    double *t = malloc(4 * n * sizeof *t); /* per index: k, sin(k/2)^2, cos k, sin k */
    if (!t) {
        *var = NAN;
        return;
    }
    for (size_t i = 0; i < n; i++) {
        double k = wave(i, n), h = sin(0.5 * k);
        t[4 * i] = k, t[4 * i + 1] = h * h, t[4 * i + 2] = cos(k), t[4 * i + 3] = sin(k);
    }
    double sv = 0.0, sxx = 0.0, sxy = 0.0, syy = 0.0, sm = 0.0;
    for (size_t j = 0; j < n; j++) {
        const double *b = t + 4 * j;
        for (size_t i = 0; i < n; i++) {
            const double *a = t + 4 * i;
            double S = exp(-0.25 * (ixx * a[0] * a[0] + 2.0 * ixy * a[0] * b[0] + iyy * b[0] * b[0]));
            /* the two cuts' off-diagonals, cos(a - b) - cos a - cos b + 1 and cos a + cos b - cos(a + b) - 1, average
             * to sin a sin b; their difference is 2 (1 - cos a)(1 - cos b) = 8 sin^2(a/2) sin^2(b/2) */
            sv += S, sxx += S * 4.0 * a[1], syy += S * 4.0 * b[1];
            sxy += S * a[3] * b[3], sm += S * 4.0 * a[1] * b[1];
        }
    }
    free(t);
    *var = 0.5 * sv, cov[0] = 0.5 * sxx, cov[1] = 0.5 * sxy, cov[2] = 0.5 * syy, *mixed = 0.5 * sm;
}

static int fail(char *err, size_t errn, const char *what)
{
    snprintf(err, errn, "%s", what);
    return -1;
}

int ms_gauss(const ms_gauss_spec *sp, double *h, ms_gauss_info *info, char *err, size_t errn)
{
    size_t n = sp->n;
    if (n < 8 || n > 16384 || n % 2 != 0) return fail(err, errn, "Gaussian surface: the size must be even, 8 to 16384");
    if (!(sp->alpha_x >= 1e-3 && sp->alpha_x <= 10.0 && sp->alpha_y >= 1e-3 && sp->alpha_y <= 10.0))
        return fail(err, errn, "Gaussian surface: the alphas must be in [0.001, 10]");
    if (!isfinite(sp->phi)) return fail(err, errn, "Gaussian surface: the rotation must be finite");
    if (!(sp->corr_len >= 4.0 && sp->corr_len <= (double)n / 4.0))
        return fail(err, errn, "Gaussian surface: the correlation length must be in [4, size / 4] grid spacings");
#ifndef GGX_HAVE_KISSFFT
    (void)h, (void)info;
    return fail(err, errn, "Gaussian surfaces are not built (KISS FFT not found: apt-get install libkissfft-dev)");
#else
    double c = cos(sp->phi), s = sin(sp->phi), ax2 = 0.5 * sp->alpha_x * sp->alpha_x,
           ay2 = 0.5 * sp->alpha_y * sp->alpha_y;
    /* the roughness axes turned as ggx_shape_ellipsoid's theta_z turns them: Sigma_xy = (ay^2 - ax^2) c s / 2 */
    const double target[3] = {ax2 * c * c + ay2 * s * s, (ay2 - ax2) * c * s, ax2 * s * s + ay2 * c * c};
    double det_t = target[0] * target[2] - target[1] * target[1];
    double sigma2 = sp->corr_len * sp->corr_len * sqrt(det_t) / 2.0;
    double M[3] = {target[0] / (2.0 * sigma2), target[1] / (2.0 * sigma2), target[2] / (2.0 * sigma2)};
    /* correct M until the four facets of the lattice's cells have Sigma_s together (the continuous field's slopes
     * would have 2 sigma^2 M); the spectrum's constant keeps the heights' variance sigma^2 */
    double var, cov[3], mixed = 0.0, scale = 1.0;
    int it = 0;
    for (; it < 50; it++) {
        moments(n, M, &var, cov, &mixed);
        if (!(var > 0.0)) return fail(err, errn, "Gaussian surface: out of memory");
        scale = sigma2 / var, mixed *= scale;
        double e = 0.0;
        for (int k = 0; k < 3; k++) {
            cov[k] *= scale;
            e = fmax(e, fabs(cov[k] - target[k]) / sqrt(target[0] * target[2]));
        }
        if (e < 1e-10) break;
        for (int k = 0; k < 3; k++) M[k] += (target[k] - cov[k]) / (2.0 * sigma2);
        if (!(M[0] > 0.0 && M[2] > 0.0 && M[0] * M[2] > M[1] * M[1]))
            return fail(err, errn,
                        "Gaussian surface: no spectrum of this size gives these slopes at this correlation "
                        "length (too anisotropic for it: give a larger size or correlation length)");
    }
    size_t count = n * n;
    kiss_fft_cpx *buf = malloc(count * sizeof *buf), *out = malloc(count * sizeof *out);
    int dims[2] = {(int)n, (int)n};
    kiss_fftnd_cfg cfg = kiss_fftnd_alloc(dims, 2, 1, NULL, NULL);
    if (!buf || !out || !cfg) {
        free(buf), free(out), free(cfg);
        return fail(err, errn, "Gaussian surface: out of memory");
    }
    double det = M[0] * M[2] - M[1] * M[1], ixx = M[2] / det, ixy = -M[1] / det, iyy = M[0] / det;
    uint64_t state = sp->seed;
    for (size_t j = 0; j < n; j++) {
        double ky = wave(j, n);
        for (size_t i = 0; i < n; i++) {
            double kx = wave(i, n), a, b;
            double A = sqrt(scale * exp(-0.25 * (ixx * kx * kx + 2.0 * ixy * kx * ky + iyy * ky * ky)));
            normals(&state, &a, &b); /* W = (a + i b) / sqrt(2): E|W|^2 = 1 */
            buf[j * n + i].r = (float)(A * a * 0.70710678118654752);
            buf[j * n + i].i = (float)(A * b * 0.70710678118654752);
        }
    }
    kiss_fftnd(cfg, buf, out); /* the inverse transform, unscaled: sum_k A W e^{+i k.x} */
    for (size_t i = 0; i < count; i++) h[i] = out[i].r;
    free(buf), free(out);
    kiss_fft_free(cfg);
    if (info) {
        info->sigma = sqrt(sigma2), info->iterations = it;
        memcpy(info->metric, M, sizeof M), memcpy(info->slope_cov, cov, sizeof cov);
        info->cut_xy = mixed;
    }
    return 0;
#endif
}
