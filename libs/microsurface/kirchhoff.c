/* The scalar Kirchhoff BRDF of a height field by FFT (kirchhoff.h; docs/design/kirchhoff.md). SPDX-License-Identifier:
 * MIT */
#include "kirchhoff.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/parallel.h"
#include "microsurface.h"

#ifdef GGX_HAVE_KISSFFT
#include <kiss_fft.h>
#endif

static const double PI = 3.14159265358979323846;
const double ms_kirchhoff_rgb_um[3] = {0.630, 0.532, 0.465};

enum { CHUNKS = 32 }; /* the fixed split of the binning passes: partial sums added in chunk order */

static int fail(char *err, size_t errn, const char *fmt, ...)
{
    if (err && errn) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errn, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* fail() for the functions that return a pointer */
static double *fail_null(char *err, size_t errn, const char *fmt, ...)
{
    if (err && errn) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errn, fmt, ap);
        va_end(ap);
    }
    return NULL;
}

/* The share a facet of unit normal n carries from wi into its mirror direction (written to wo): its projected area
 * towards wi over its projected area on the plane, over wi.z; 0 where n faces away from wi or wo is below the
 * plane. The one weight of both the wave binning (n from the FFT cell's slope) and the geometric one. */
static double facet_share(const double wi[3], const double n[3], double wo[3])
{
    double c = wi[0] * n[0] + wi[1] * n[1] + wi[2] * n[2];
    if (c <= 0.0) return 0.0;
    for (int j = 0; j < 3; j++) wo[j] = 2.0 * c * n[j] - wi[j];
    if (wo[2] <= 0.0) return 0.0;
    return c / (n[2] * wi[2]);
}

/* The obliquity factor of the Kirchhoff integral with the cosines of the BRDF's definition,
 * (1 + wi.wo)^2 / ((wi.z + wo.z)^2 cos_i cos_o) (docs/design/kirchhoff.md, eq. 3). */
static double obliquity(const double wi[3], const double wo[3])
{
    double d = 1.0 + wi[0] * wo[0] + wi[1] * wo[1] + wi[2] * wo[2], v = wi[2] + wo[2];
    return d * d / (v * v * wi[2] * wo[2]);
}

/* the least n >= m whose only prime factors are 2, 3 and 5 (KISS FFT's fast radices) */
static size_t fast_size(size_t m)
{
    for (size_t n = m;; n++) {
        size_t r = n;
        while (r % 2 == 0) r /= 2;
        while (r % 3 == 0) r /= 3;
        while (r % 5 == 0) r /= 5;
        if (r == 1) return n;
    }
}

/* the Tukey window at i of n points, taper a (share of the whole length in cosine ramps, half at each end) */
static double tukey(size_t i, size_t n, double a)
{
    double t = (double)i / (double)(n - 1), e = fmin(t, 1.0 - t);
    return e >= 0.5 * a ? 1.0 : 0.5 * (1.0 - cos(2.0 * PI * e / a));
}

/* Missing points (valid[i] = 0) filled layer by layer from the known ones (each takes the mean of its known
 * 8-neighbours as its layer is reached), then 16 Gauss-Seidel sweeps of the 4-neighbour mean over the filled ones
 * alone: holes become smooth patches that meet their rims. */
static int fill_missing(double *h, unsigned char *valid, size_t nx, size_t ny)
{
    size_t n = nx * ny, nf = 0;
    size_t *front = malloc(n * sizeof *front), *next = malloc(n * sizeof *next), *filled = malloc(n * sizeof *filled);
    unsigned char *known = malloc(n), *queued = calloc(n, 1);
    if (!front || !next || !filled || !known || !queued) {
        free(front), free(next), free(filled), free(known), free(queued);
        return -1;
    }
    memcpy(known, valid, n);
    size_t nfront = 0;
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            if (known[y * nx + x]) continue;
            int near = 0;
            for (int dy = -1; dy <= 1 && !near; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    long xx = (long)x + dx, yy = (long)y + dy;
                    if (xx >= 0 && yy >= 0 && xx < (long)nx && yy < (long)ny && known[yy * (long)nx + xx]) near = 1;
                }
            if (near) front[nfront++] = y * nx + x, queued[y * nx + x] = 1;
        }
    while (nfront) {
        size_t nnext = 0;
        for (size_t f = 0; f < nfront; f++) { /* the layer's values from the points known before it */
            size_t i = front[f], x = i % nx, y = i / nx;
            double s = 0.0;
            int c = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    long xx = (long)x + dx, yy = (long)y + dy;
                    if (xx >= 0 && yy >= 0 && xx < (long)nx && yy < (long)ny && known[yy * (long)nx + xx])
                        s += h[yy * (long)nx + xx], c++;
                }
            h[i] = s / c;
        }
        for (size_t f = 0; f < nfront; f++) known[front[f]] = 1, filled[nf++] = front[f];
        for (size_t f = 0; f < nfront; f++) {
            size_t i = front[f], x = i % nx, y = i / nx;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    long xx = (long)x + dx, yy = (long)y + dy;
                    if (xx < 0 || yy < 0 || xx >= (long)nx || yy >= (long)ny) continue;
                    size_t j = (size_t)(yy * (long)nx + xx);
                    if (!known[j] && !queued[j]) queued[j] = 1, next[nnext++] = j;
                }
        }
        size_t *t = front;
        front = next, next = t, nfront = nnext;
    }
    for (int sweep = 0; sweep < 16; sweep++)
        for (size_t f = 0; f < nf; f++) {
            size_t i = filled[f], x = i % nx, y = i / nx;
            double s = 0.0;
            int c = 0;
            if (x > 0) s += h[i - 1], c++;
            if (x + 1 < nx) s += h[i + 1], c++;
            if (y > 0) s += h[i - nx], c++;
            if (y + 1 < ny) s += h[i + nx], c++;
            h[i] = s / c;
        }
    free(front), free(next), free(filled), free(known), free(queued);
    return 0;
}

/* Windowed shares of the points by the upsampling factor their steepest step to a neighbour needs to stay below pi
 * of phase at wavenumber kv: need[u] for u = 1 .. 16, need[17] beyond. */
static void phase_needs(const double *h, size_t nx, size_t ny, const double *wx, const double *wy, double kv,
                        double need[18])
{
    double tot = 0.0;
    memset(need, 0, 18 * sizeof *need);
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            double d = 0.0, w = wx[x] * wx[x] * wy[y] * wy[y];
            size_t i = y * nx + x;
            if (x + 1 < nx) d = fabs(h[i + 1] - h[i]);
            if (y + 1 < ny) d = fmax(d, fabs(h[i + nx] - h[i]));
            double u = ceil(kv * d / PI);
            need[u <= 1.0 ? 1 : u >= 17.0 ? 17 : (int)u] += w, tot += w;
        }
    for (int u = 0; u < 18; u++) need[u] /= tot;
}

/* the level (index into the ascending level_woz) nearest wo.z */
static int level_of(const ms_kirchhoff *k, double woz)
{
    int lo = 0, hi = k->levels - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (woz > 0.5 * (k->level_woz[mid] + k->level_woz[mid + 1])) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

#ifdef GGX_HAVE_KISSFFT
typedef struct fft_job {
    ms_kirchhoff *k;
    kiss_fft_cfg cx, cy;
    kiss_fft_cpx *buf;
    float *power;
    double kv, norm;
    int threads, pass;
    kiss_fft_cpx *tmp[64];
} fft_job;

/* pass 0: rows y = t mod threads of the windowed phase field, transformed along x; pass 1: columns x = t mod threads
 * transformed along y into the power */
static void fft_pass(void *ctx, int t)
{
    fft_job *j = ctx;
    const ms_kirchhoff *k = j->k;
    size_t Nx = k->fft_nx, Ny = k->fft_ny;
    kiss_fft_cpx *tmp = j->tmp[t];
    if (j->pass == 0) {
        for (size_t y = (size_t)t; y < k->ny; y += (size_t)j->threads) {
            const double *h = k->hp + y * k->nx;
            for (size_t x = 0; x < Nx; x++) {
                if (x < k->nx) {
                    double w = k->wx[x] * k->wy[y], a = -j->kv * h[x];
                    tmp[x].r = (float)(w * cos(a)), tmp[x].i = (float)(w * sin(a));
                } else tmp[x].r = tmp[x].i = 0.0f;
            }
            kiss_fft(j->cx, tmp, j->buf + y * Nx);
        }
    } else {
        kiss_fft_cpx *col = tmp + Ny;
        for (size_t x = (size_t)t; x < Nx; x += (size_t)j->threads) {
            for (size_t y = 0; y < Ny; y++) col[y] = y < k->ny ? j->buf[y * Nx + x] : (kiss_fft_cpx){0.0f, 0.0f};
            kiss_fft(j->cy, col, tmp);
            for (size_t y = 0; y < Ny; y++)
                j->power[y * Nx + x] = (float)(((double)tmp[y].r * tmp[y].r + (double)tmp[y].i * tmp[y].i) * j->norm);
        }
    }
}
#endif

void ms_kirchhoff_free(ms_kirchhoff *k)
{
    if (!k) return;
    free(k->level_woz), free(k->power), free(k->hp), free(k->wx), free(k->wy);
    k->level_woz = NULL, k->power = NULL, k->hp = k->wx = k->wy = NULL;
}

/* The heights of s: the valid points levelled (unless keep_tilt), checked against the wavenumber, the missing ones
 * filled; into k their RMS and the missing share. NULL with err on bad heights or no memory. */
static double *prepared_heights(const ms_kirchhoff_spec *s, ms_kirchhoff *k, char *err, size_t errn)
{
    size_t nx = s->nx, ny = s->ny;
    size_t n = nx * ny, nvalid = 0;
    double *h = malloc(n * sizeof *h);
    unsigned char *valid = malloc(n);
    if (!h || !valid) {
        free(h), free(valid);
        return fail_null(err, errn, "kirchhoff: no memory for %zu heights", n);
    }
    for (size_t i = 0; i < n; i++) {
        valid[i] = isfinite(s->h[i]) ? 1 : 0;
        h[i] = s->h[i];
        nvalid += valid[i];
    }
    if (nvalid == 0) {
        free(h), free(valid);
        return fail_null(err, errn, "kirchhoff: all %zu points are missing", n);
    }
    size_t rows = 0, cols = 0; /* a 2 x 2 block of valid points must exist somewhere: rows and columns with two */
    for (size_t y = 0; y < ny; y++) {
        size_t c = 0;
        for (size_t x = 0; x < nx; x++) c += valid[y * nx + x];
        rows += c >= 2;
    }
    for (size_t x = 0; x < nx; x++) {
        size_t c = 0;
        for (size_t y = 0; y < ny; y++) c += valid[y * nx + x];
        cols += c >= 2;
    }
    if (nvalid < 4 || rows < 2 || cols < 2) {
        free(h), free(valid);
        return fail_null(err, errn, "kirchhoff: %zu valid points: fewer than 2 x 2", nvalid);
    }
    ms_level(h, nx, ny, s->keep_tilt, NULL);
    double ss = 0.0, hmax = 0.0;
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            size_t i = y * nx + x;
            if (!valid[i]) continue;
            ss += h[i] * h[i], hmax = fmax(hmax, fabs(h[i]));
        }
    double wave_k = 2.0 * PI / s->wavelength;
    if (!isfinite(hmax) || !isfinite(ss) || !(2.0 * wave_k * hmax <= 1e12)) {
        free(h), free(valid);
        return fail_null(err, errn,
                         "kirchhoff: heights up to %g against wavelength %g: phases beyond 1e12 rad (an absurd scale)",
                         hmax, s->wavelength);
    }
    k->sigma_h = sqrt(ss / (double)nvalid);
    k->missing = (double)(n - nvalid) / (double)n;
    if (nvalid < n && fill_missing(h, valid, nx, ny) != 0) {
        free(h), free(valid);
        return fail_null(err, errn, "kirchhoff: no memory to fill the missing points");
    }
    free(valid);
    return h;
}

int ms_kirchhoff_setup(const ms_kirchhoff_spec *s, ms_kirchhoff *k, char *err, size_t errn)
{
    memset(k, 0, sizeof *k);
    if (!s || !s->h) return fail(err, errn, "kirchhoff: no heights");
    size_t nx = s->nx, ny = s->ny;
    if (nx < 2 || ny < 2) return fail(err, errn, "kirchhoff: %zu x %zu heights: at least 2 x 2", nx, ny);
    if (nx > ((size_t)1 << 20) || ny > ((size_t)1 << 20) || nx * ny > ((size_t)1 << 28))
        return fail(err, errn, "kirchhoff: %zu x %zu heights: too large for memory (at most 2^28 points)", nx, ny);
    if (!isfinite(s->dx) || !(s->dx > 0.0)) return fail(err, errn, "kirchhoff: spacing %g: finite and > 0", s->dx);
    if (!isfinite(s->wavelength) || !(s->wavelength > 0.0))
        return fail(err, errn, "kirchhoff: wavelength %g: finite and > 0", s->wavelength);
    double wl = sqrt(s->wi[0] * s->wi[0] + s->wi[1] * s->wi[1] + s->wi[2] * s->wi[2]);
    if (!isfinite(wl) || !(wl > 0.0) || !(s->wi[2] / wl >= 1e-3))
        return fail(err, errn, "kirchhoff: wi (%g, %g, %g): finite and at least 1e-3 above the plane in cosine",
                    s->wi[0], s->wi[1], s->wi[2]);
    int levels = s->levels ? s->levels : 1, U = s->upsample;
    double taper = s->taper > 0.0 ? s->taper : 1.0;
    if (levels < 1 || levels > 64) return fail(err, errn, "kirchhoff: %d levels: 1 to 64", s->levels);
    if (U < 0 || U > 16) return fail(err, errn, "kirchhoff: upsample %d: 1 to 16 (0: chosen)", U);
    if (!(s->taper >= 0.0 && s->taper <= 1.0)) return fail(err, errn, "kirchhoff: taper %g: in (0, 1]", s->taper);
    if (!(s->alias >= 0.0 && s->alias < 1.0)) return fail(err, errn, "kirchhoff: alias %g: in [0, 1)", s->alias);
    size_t max_points = s->max_points ? s->max_points : (size_t)1 << 23;
    int threads = s->threads > 0 ? (s->threads > 64 ? 64 : s->threads) : 1;
    double *h = prepared_heights(s, k, err, errn), wave_k = 2.0 * PI / s->wavelength;
    if (!h) return -1;
    /* the levels of wo.z: 1: the specular one; L: (l + 1/2) / L with the nearest to wi.z moved onto it */
    for (int j = 0; j < 3; j++) k->wi[j] = s->wi[j] / wl;
    k->wavelength = s->wavelength, k->levels = levels, k->threads = threads;
    k->level_woz = malloc((size_t)levels * sizeof *k->level_woz);
    if (!k->level_woz) {
        free(h);
        return fail(err, errn, "kirchhoff: no memory");
    }
    int near = 0;
    for (int l = 0; l < levels; l++) {
        k->level_woz[l] = levels == 1 ? k->wi[2] : (l + 0.5) / levels;
        if (fabs(k->level_woz[l] - k->wi[2]) < fabs(k->level_woz[near] - k->wi[2])) near = l;
    }
    k->level_woz[near] = k->wi[2];
    double kv_max = wave_k * (k->wi[2] + k->level_woz[levels - 1]);
    /* the window on the given grid, and the upsampling factor */
    double *wx0 = malloc(nx * sizeof *wx0), *wy0 = malloc(ny * sizeof *wy0), need[18];
    if (!wx0 || !wy0) {
        free(wx0), free(wy0), free(h), ms_kirchhoff_free(k);
        return fail(err, errn, "kirchhoff: no memory");
    }
    for (size_t x = 0; x < nx; x++) wx0[x] = tukey(x, nx, taper);
    for (size_t y = 0; y < ny; y++) wy0[y] = tukey(y, ny, taper);
    phase_needs(h, nx, ny, wx0, wy0, kv_max, need);
    free(wx0), free(wy0);
    if (!s->crop && fast_size(nx) * fast_size(ny) * (size_t)levels > max_points) {
        free(h), ms_kirchhoff_free(k);
        return fail(err, errn, "kirchhoff: %zu x %zu points at %d levels: beyond %zu FFT points (too large for memory)",
                    nx, ny, levels, max_points);
    }
    if (U == 0) {
        double cum = 0.0;
        double keep = 1.0 - (s->alias > 0.0 ? s->alias : 1e-3);
        for (U = 1; U < 16; U++) {
            cum += need[U];
            if (cum >= keep) break;
        }
    }
    /* crop: the largest centred window (at least 16 x 16 points) whose upsampled grid fits, shrunk 2 % a step */
    size_t cx = nx, cy = ny;
    while (s->crop && cx >= 16 && cy >= 16 &&
           fast_size((cx - 1) * (size_t)U + 1) * fast_size((cy - 1) * (size_t)U + 1) * (size_t)levels > max_points)
        cx = (size_t)(0.98 * (double)cx), cy = (size_t)(0.98 * (double)cy);
    if (cx >= 16 && cy >= 16 && (cx < nx || cy < ny)) {
        size_t x0 = (nx - cx) / 2, y0 = (ny - cy) / 2;
        for (size_t y = 0; y < cy; y++) memmove(h + y * cx, h + (y0 + y) * nx + x0, cx * sizeof *h);
        k->crop[0] = x0, k->crop[1] = y0, nx = cx, ny = cy;
    }
    /* else (or a window under 16 x 16): the chosen upsampling lowered until it fits */
    while (s->upsample == 0 && U > 1 &&
           fast_size((nx - 1) * (size_t)U + 1) * fast_size((ny - 1) * (size_t)U + 1) * (size_t)levels > max_points)
        U--;
    k->crop[2] = nx, k->crop[3] = ny;
    k->aliased = 0.0;
    for (int u = U + 1; u < 18; u++) k->aliased += need[u];
    k->upsample = U, k->dx = s->dx / U;
    k->nx = (nx - 1) * (size_t)U + 1, k->ny = (ny - 1) * (size_t)U + 1;
    k->fft_nx = fast_size(k->nx), k->fft_ny = fast_size(k->ny);
    size_t N = k->fft_nx * k->fft_ny;
    if (N * (size_t)levels > max_points) {
        free(h), ms_kirchhoff_free(k);
        return fail(err, errn, "kirchhoff: upsample %d gives %zu x %zu FFT points at %d levels: beyond %zu", U,
                    k->fft_nx, k->fft_ny, levels, max_points);
    }
    k->hp = malloc(k->nx * k->ny * sizeof *k->hp);
    k->wx = malloc(k->nx * sizeof *k->wx), k->wy = malloc(k->ny * sizeof *k->wy);
    k->power = malloc(N * (size_t)levels * sizeof *k->power);
    if (!k->hp || !k->wx || !k->wy || !k->power) {
        free(h), ms_kirchhoff_free(k);
        return fail(err, errn, "kirchhoff: no memory for %zu x %zu FFT points", k->fft_nx, k->fft_ny);
    }
    for (size_t Y = 0; Y < k->ny; Y++) { /* bilinear between the given points */
        size_t y0 = Y / (size_t)U, y1 = y0 + 1 < ny ? y0 + 1 : y0;
        double ty = (double)(Y % (size_t)U) / U;
        for (size_t X = 0; X < k->nx; X++) {
            size_t x0 = X / (size_t)U, x1 = x0 + 1 < nx ? x0 + 1 : x0;
            double tx = (double)(X % (size_t)U) / U;
            k->hp[Y * k->nx + X] = (1.0 - ty) * ((1.0 - tx) * h[y0 * nx + x0] + tx * h[y0 * nx + x1]) +
                                   ty * ((1.0 - tx) * h[y1 * nx + x0] + tx * h[y1 * nx + x1]);
        }
    }
    free(h);
    double sw2x = 0.0, sw2y = 0.0;
    for (size_t x = 0; x < k->nx; x++) k->wx[x] = tukey(x, k->nx, taper), sw2x += k->wx[x] * k->wx[x];
    for (size_t y = 0; y < k->ny; y++) k->wy[y] = tukey(y, k->ny, taper), sw2y += k->wy[y] * k->wy[y];
    /* the coherent share: the field's projection on the window's, at the specular wi.z + wo.z */
    double cr = 0.0, ci = 0.0, kv_spec = 2.0 * wave_k * k->wi[2];
    for (size_t y = 0; y < k->ny; y++)
        for (size_t x = 0; x < k->nx; x++) {
            double w = k->wx[x] * k->wx[x] * k->wy[y] * k->wy[y], a = -kv_spec * k->hp[y * k->nx + x];
            cr += w * cos(a), ci += w * sin(a);
        }
    k->coherent = (cr * cr + ci * ci) / (sw2x * sw2y * sw2x * sw2y);
#ifdef GGX_HAVE_KISSFFT
    fft_job j = {0};
    j.k = k, j.threads = threads, j.norm = 1.0 / ((double)N * sw2x * sw2y);
    j.cx = kiss_fft_alloc((int)k->fft_nx, 0, NULL, NULL);
    j.cy = kiss_fft_alloc((int)k->fft_ny, 0, NULL, NULL);
    j.buf = malloc(k->fft_nx * k->ny * sizeof *j.buf);
    int ok = j.cx && j.cy && j.buf;
    size_t tn = k->fft_nx > 2 * k->fft_ny ? k->fft_nx : 2 * k->fft_ny;
    for (int t = 0; t < threads; t++) ok = ok && (j.tmp[t] = malloc(tn * sizeof *j.tmp[t])) != NULL;
    for (int l = 0; ok && l < levels; l++) {
        j.kv = wave_k * (k->wi[2] + k->level_woz[l]), j.power = k->power + (size_t)l * N;
        j.pass = 0;
        ggx_internal_parallel_for(threads, fft_pass, &j);
        j.pass = 1;
        ggx_internal_parallel_for(threads, fft_pass, &j);
    }
    for (int t = 0; t < threads; t++) free(j.tmp[t]);
    free(j.buf), kiss_fft_free(j.cx), kiss_fft_free(j.cy);
    if (!ok) {
        ms_kirchhoff_free(k);
        return fail(err, errn, "kirchhoff: no memory for the FFT of %zu x %zu points", k->fft_nx, k->fft_ny);
    }
    return 0;
#else
    (void)threads;
    ms_kirchhoff_free(k);
    return fail(err, errn, "kirchhoff: not built (KISS FFT missing: apt-get install libkissfft-dev)");
#endif
}

int ms_kirchhoff_built(void)
{
#ifdef GGX_HAVE_KISSFFT
    return 1;
#else
    return 0;
#endif
}

typedef struct bin_job {
    const ms_kirchhoff *k;
    const ms_binning *b;
    int threads, geometric;
    double *part; /* CHUNKS x bins */
} bin_job;

/* the bin of wo, or -1 (the caller's binning may count a direction in none) */
static int bin_of(const ms_binning *b, const double wo[3])
{
    int i = b->bin(b->ctx, wo);
    return i >= 0 && i < b->bins ? i : -1;
}

static void bin_pass(void *ctx, int t)
{
    bin_job *j = ctx;
    const ms_kirchhoff *k = j->k;
    size_t bins = (size_t)j->b->bins;
    for (int c = t; c < CHUNKS; c += j->threads) {
        double *part = j->part + (size_t)c * bins, n[3], wo[3];
        if (j->geometric) { /* the points' own slopes, weighted by W^2 */
            size_t nx = k->nx, ny = k->ny;
            for (size_t y = (size_t)c * ny / CHUNKS; y < (size_t)(c + 1) * ny / CHUNKS; y++)
                for (size_t x = 0; x < nx; x++) {
                    const double *h = k->hp + y * nx;
                    size_t xa = x ? x - 1 : 0, xb = x + 1 < nx ? x + 1 : x, ya = y ? y - 1 : 0,
                           yb = y + 1 < ny ? y + 1 : y;
                    double sx = (h[xb] - h[xa]) / ((double)(xb - xa) * k->dx),
                           sy = (k->hp[yb * nx + x] - k->hp[ya * nx + x]) / ((double)(yb - ya) * k->dx);
                    double w = k->wx[x] * k->wx[x] * k->wy[y] * k->wy[y], l = sqrt(1.0 + sx * sx + sy * sy);
                    n[0] = -sx / l, n[1] = -sy / l, n[2] = 1.0 / l;
                    double f = facet_share(k->wi, n, wo);
                    int b = f > 0.0 && w > 0.0 ? bin_of(j->b, wo) : -1;
                    if (b >= 0) part[b] += w * f;
                }
            continue;
        }
        size_t Nx = k->fft_nx, Ny = k->fft_ny, N = Nx * Ny;
        for (int l = 0; l < k->levels; l++) {
            const float *P = k->power + (size_t)l * N;
            double v = k->wi[2] + k->level_woz[l];
            double ux = k->wavelength / ((double)Nx * k->dx * v), uy = k->wavelength / ((double)Ny * k->dx * v);
            for (size_t y = (size_t)c * Ny / CHUNKS; y < (size_t)(c + 1) * Ny / CHUNKS; y++) {
                double py = (double)(y < (Ny + 1) / 2 ? (long)y : (long)y - (long)Ny) * uy;
                for (size_t x = 0; x < Nx; x++) {
                    double p = P[y * Nx + x];
                    if (p == 0.0) continue;
                    double px = (double)(x < (Nx + 1) / 2 ? (long)x : (long)x - (long)Nx) * ux;
                    double il = 1.0 / sqrt(1.0 + px * px + py * py);
                    n[0] = px * il, n[1] = py * il, n[2] = il;
                    double f = facet_share(k->wi, n, wo);
                    int b = f > 0.0 && (k->levels == 1 || level_of(k, wo[2]) == l) ? bin_of(j->b, wo) : -1;
                    if (b >= 0) part[b] += p * f;
                }
            }
        }
    }
}

static double bin_run(const ms_kirchhoff *k, const ms_binning *bn, double *share, int geometric)
{
    if (bn->bins < 1 || !k->power) return NAN;
    size_t bins = (size_t)bn->bins;
    bin_job j = {k, bn, k->threads, geometric, calloc(CHUNKS * bins, sizeof(double))};
    if (!j.part) return NAN;
    ggx_internal_parallel_for(j.threads, bin_pass, &j);
    double tot = 0.0, wsum = 1.0;
    if (geometric) {
        double a = 0.0, b = 0.0;
        for (size_t x = 0; x < k->nx; x++) a += k->wx[x] * k->wx[x];
        for (size_t y = 0; y < k->ny; y++) b += k->wy[y] * k->wy[y];
        wsum = a * b;
    }
    for (size_t b = 0; b < bins; b++) {
        double v = 0.0;
        for (int c = 0; c < CHUNKS; c++) v += j.part[(size_t)c * bins + b];
        share[b] = v / wsum, tot += share[b];
    }
    free(j.part);
    return tot;
}

double ms_kirchhoff_bin(const ms_kirchhoff *k, int rings, int sectors, double *share)
{
    if (rings < 1 || sectors < 1) return NAN;
    ms_ring_bins r;
    ms_binning b = ms_ring_binning(&r, rings, sectors);
    return bin_run(k, &b, share, 0);
}

double ms_kirchhoff_binned(const ms_kirchhoff *k, const ms_binning *b, double *share)
{
    return bin_run(k, b, share, 0);
}

double ms_kirchhoff_geometric(const ms_kirchhoff *k, int rings, int sectors, double *share)
{
    if (rings < 1 || sectors < 1) return NAN;
    ms_ring_bins r;
    ms_binning b = ms_ring_binning(&r, rings, sectors);
    return bin_run(k, &b, share, 1);
}

double ms_kirchhoff_brdf(const ms_kirchhoff *k, const double wo[3])
{
    if (!k->power || !(wo[2] > 0.0)) return 0.0;
    int l = k->levels == 1 ? 0 : level_of(k, wo[2]);
    double v = k->wi[2] + wo[2], vl = k->wi[2] + k->level_woz[l];
    size_t Nx = k->fft_nx, Ny = k->fft_ny;
    /* the grid's fractional index of p = v_xy / v at the level: p vl Nx dx / lambda */
    double fx = (k->wi[0] + wo[0]) / v * vl * (double)Nx * k->dx / k->wavelength,
           fy = (k->wi[1] + wo[1]) / v * vl * (double)Ny * k->dx / k->wavelength;
    if (fabs(fx) > 0.5 * (double)Nx - 1.0 || fabs(fy) > 0.5 * (double)Ny - 1.0) return 0.0;
    double x0 = floor(fx), y0 = floor(fy), tx = fx - x0, ty = fy - y0;
    const float *P = k->power + (size_t)l * Nx * Ny;
    size_t xa = (size_t)(((long)x0 % (long)Nx + (long)Nx) % (long)Nx), xb = (xa + 1) % Nx;
    size_t ya = (size_t)(((long)y0 % (long)Ny + (long)Ny) % (long)Ny), yb = (ya + 1) % Ny;
    double p = (1.0 - ty) * ((1.0 - tx) * P[ya * Nx + xa] + tx * P[ya * Nx + xb]) +
               ty * ((1.0 - tx) * P[yb * Nx + xa] + tx * P[yb * Nx + xb]);
    /* power per cell over the cell's area in (wi + wo)_xy at the level, scaled to the direction's v (exact at the
     * level; the geometric limit's scaling between) */
    double cell = k->wavelength * k->wavelength / ((double)Nx * (double)Ny * k->dx * k->dx);
    return obliquity(k->wi, wo) * (vl / v) * (vl / v) * p / cell;
}

double ms_kirchhoff_brdf_exact(const ms_kirchhoff *k, const double wo[3])
{
    if (!k->hp || !(wo[2] > 0.0)) return 0.0;
    double kk = 2.0 * PI / k->wavelength;
    double vx = kk * (k->wi[0] + wo[0]) * k->dx, vy = kk * (k->wi[1] + wo[1]) * k->dx, vz = kk * (k->wi[2] + wo[2]);
    double re = 0.0, im = 0.0, sw2 = 0.0;
    for (size_t y = 0; y < k->ny; y++)
        for (size_t x = 0; x < k->nx; x++) {
            double w = k->wx[x] * k->wy[y], a = -(vx * (double)x + vy * (double)y + vz * k->hp[y * k->nx + x]);
            re += w * cos(a), im += w * sin(a), sw2 += w * w;
        }
    /* |dx^2 sum|^2 / (lambda^2 sum W^2 dx^2) */
    return obliquity(k->wi, wo) * (re * re + im * im) * k->dx * k->dx / (k->wavelength * k->wavelength * sw2);
}

int ms_kirchhoff_rgb(const ms_kirchhoff_spec *spec, double um, int rings, int sectors, double *share, double total[3],
                     double coherent[3], char *err, size_t errn)
{
    if (!(um > 0.0) || !isfinite(um)) return fail(err, errn, "kirchhoff: a micrometre of %g units", um);
    if (rings < 1 || sectors < 1) return fail(err, errn, "kirchhoff: %d x %d bins", rings, sectors);
    size_t bins = (size_t)rings * (size_t)sectors;
    double *one = malloc(bins * sizeof *one);
    if (!one) return fail(err, errn, "kirchhoff: no memory");
    for (int c = 0; c < 3; c++) {
        ms_kirchhoff_spec s = *spec;
        ms_kirchhoff k;
        s.wavelength = ms_kirchhoff_rgb_um[c] * um;
        if (ms_kirchhoff_setup(&s, &k, err, errn) != 0) {
            free(one);
            return -1;
        }
        double t = ms_kirchhoff_bin(&k, rings, sectors, one);
        if (total) total[c] = t;
        if (coherent) coherent[c] = k.coherent;
        for (size_t b = 0; b < bins; b++) share[3 * b + (size_t)c] = one[b];
        ms_kirchhoff_free(&k);
    }
    free(one);
    return 0;
}
