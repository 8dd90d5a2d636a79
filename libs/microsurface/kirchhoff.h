/* Wave optics for a measured height field: the scalar Kirchhoff (Beckmann-Kirchhoff) BRDF with F = 1, by FFT
 * (docs/design/kirchhoff.md derives it and states its measured accuracy). SPDX-License-Identifier: MIT */
#ifndef GGX_LAB_KIRCHHOFF_H
#define GGX_LAB_KIRCHHOFF_H

#include <stddef.h>

#include "microsurface.h"

/* The BRDF of a patch of heights h(x, y) lit by a plane wave of wavelength lambda from the unit direction wi (local
 * frame, z up, pointing away from the surface), scalar field, perfect reflector (F = 1), single scattering, no
 * shadowing or masking, Kirchhoff's tangent plane, far field:
 *     f(wi, wo) = (1 + wi.wo)^2 / ((wi.z + wo.z)^2 lambda^2 cos(theta_i) cos(theta_o) sum W^2 dx^2)
 *                 |dx^2 sum_x W(x) exp(-i k ((wi + wo)_xy . x + (wi.z + wo.z) h(x)))|^2,   k = 2 pi / lambda,
 * W a Tukey window over the patch (the patch is not periodic; the window keeps its edges from diffracting).
 * The FFT evaluates the sum on a grid of p = (wi + wo)_xy / (wi.z + wo.z) (the facet slope that reflects wi into
 * wo) with the phase's wi.z + wo.z held at one value per level; a direction wo takes the level nearest its wo.z.
 * That is exact for the specular spike, for the geometric-optics limit (the sum's stationary phase) and for every
 * wo.z on a level; between levels a direction's diffuse halo is computed as at the wavelength lambda v_l / v (v
 * its wi.z + wo.z, v_l the level's). Missing points (NaN) are filled from their neighbours. Every length (heights,
 * spacing, wavelength) in one unit. */

/* The wavelengths of ms_kirchhoff_rgb, micrometres: red 0.630, green 0.532, blue 0.465 (near the dominant
 * wavelengths of the sRGB primaries; three lines, not a spectrum: a speckle or grating pattern shows its colour
 * fringes at these three wavelengths only). */
extern const double ms_kirchhoff_rgb_um[3];

typedef struct ms_kirchhoff_spec {
    const double *h;   /* nx * ny heights, row-major h[y nx + x]; NaN (or any non-finite) for a missing point */
    size_t nx, ny;     /* at least 2 x 2 valid points */
    double dx;         /* the grid's spacing, equal along x and y, > 0 */
    double wavelength; /* > 0, in the unit of dx and h */
    double wi[3];      /* unit (normalised here), wi.z >= 1e-3 */
    int levels;        /* 1 to 64 levels of wo.z with their own FFT; 0: 1 (the specular wo.z) */
    int upsample;      /* 1 to 16: the heights interpolated bilinearly onto a grid U times finer before the FFT;
                        * 0: the least U (within max_points, or on crop's window) that keeps 1 - alias of the
                        * windowed points' phase step between neighbours below pi at wi.z + 1 (the grid's Nyquist
                        * limit; beyond it a slope's light folds back: `aliased`) */
    double taper;      /* the Tukey window's cosine taper as a share of each side, (0, 1]; 0: 1 (Hann). A smaller
                        * taper keeps more of the patch at full weight (finer angular resolution, lambda over the
                        * flat width) and diffracts more from the steeper edges */
    int keep_tilt;     /* 0: the least-squares plane of the valid points is removed first (a scan's mounting
                        * tilt); 1: heights as given */
    size_t max_points; /* the most FFT points times levels (memory: 12 bytes each and 8 per height); 0: 2^23 */
    int threads;       /* 1 or more; 0: 1. The result is the same for any count */
    double alias;      /* with upsample 0: the windowed share of the points whose phase step may pass pi on the
                        * chosen grid, [0, 1); 0: 1e-3 */
    int crop;          /* where the upsampling (given or chosen) does not fit max_points, 1 computes it on the largest
                        * centred window of the patch that fits (at least 16 x 16 points; the levelling and the
                        * missing points' filling are the whole patch's); 0 lowers a chosen upsampling instead (a
                        * given one is refused) */
} ms_kirchhoff_spec;

typedef struct ms_kirchhoff {
    double wi[3], wavelength;
    double dx;             /* the spacing of the grid the FFT used: spec dx / upsample */
    size_t nx, ny;         /* that grid's points */
    size_t fft_nx, fft_ny; /* the FFT's size (the grid zero-padded to a product of 2, 3, 5) */
    int upsample, levels, threads;
    double coherent;      /* the specular (coherent) share: |sum W^2 e^(-2 i k wi.z h)|^2 / (sum W^2)^2, the
                               * power in the spike's shape; 1 for a plane, exp(-(2 k wi.z sigma_h)^2) in
                               * expectation for Gaussian heights */
    double aliased;       /* the windowed share of the points whose phase step to a neighbour exceeds pi at
                               * wi.z + (the highest level's wo.z): light the grid cannot place */
    double missing;       /* the share of the points that were missing (filled) */
    double sigma_h;       /* the RMS height after levelling, over the valid points */
    size_t crop[4];       /* the window of the given grid computed: first x, first y, points along x and y */
    double *level_woz;    /* the levels' wo.z (levels of them) */
    float *power;         /* per level, fft_ny x fft_nx: |FFT|^2 / (fft_nx fft_ny sum W^2), which sums to 1 */
    double *hp, *wx, *wy; /* the prepared heights (nx * ny) and the window's factors along x and y */
} ms_kirchhoff;

/* Validates spec and computes the levels' FFTs into k (ms_kirchhoff_free releases it). Returns 0, or -1 with a
 * one-line reason in err: no heights or no valid points, fewer than 2 x 2 valid, dx or the wavelength not finite
 * or <= 0, wi not finite or below 1e-3 in cosine, heights times k not finite or above 1e12 rad, levels, upsample
 * or taper out of range, a grid beyond max_points at upsample 1 (too large for memory), no memory. */
int ms_kirchhoff_setup(const ms_kirchhoff_spec *spec, ms_kirchhoff *k, char *err, size_t errn);
void ms_kirchhoff_free(ms_kirchhoff *k);
/* 1 where the build has KISS FFT (ms_kirchhoff_setup works), else 0 (it refuses every spec, saying so). */
int ms_kirchhoff_built(void);

/* The BRDF binned as the tracer's ms_brdf (ms_bin: rings of equal sin^2(theta_o) times sectors of equal azimuth, of
 * equal projected solid angle pi / bins): share[b] (rings * sectors of them) receives the share of the incident
 * power that leaves into bin b, so its mean BRDF is share[b] bins / pi. Each FFT cell is the facet slope p, whose
 * normal n = (p, 1) / |(p, 1)| reflects wi into wo, and carries its power times (wi.n) / (n.z wi.z) (cells whose n
 * faces away from wi or whose wo is below the plane carry none). Returns the total share (about 1 - the share
 * lost below the plane by the steepest slopes), or NaN for rings or sectors below 1. */
double ms_kirchhoff_bin(const ms_kirchhoff *k, int rings, int sectors, double *share);

/* ms_kirchhoff_bin into the caller's bins (microsurface.h's ms_binning; a direction it gives -1 is counted in none):
 * share[b] for b < bins. Returns the total of the shares binned, or NaN for no bins. */
double ms_kirchhoff_binned(const ms_kirchhoff *k, const ms_binning *b, double *share);

/* The same binning for geometric optics on the same prepared heights and window: each point's slope (central
 * differences) carries W^2 / sum W^2 times (wi.n) / (n.z wi.z) into the bin of wi reflected about its normal: the
 * single-scattering microfacet BRDF D(h) / (4 cos_i cos_o) of the heights' own (windowed) slopes without masking
 * or Fresnel, which ms_kirchhoff_bin approaches as sigma_h / lambda grows. Returns the total share. */
double ms_kirchhoff_geometric(const ms_kirchhoff *k, int rings, int sectors, double *share);

/* f(wi, wo) at a unit wo (wo.z > 0), from the level nearest wo.z, bilinear between its grid's points (the speckle
 * is resolved at the grid's step lambda / (fft_n dx) in (wi + wo)_xy, no finer); 0 where wo is beyond the grid's
 * Nyquist limit or below the plane. */
double ms_kirchhoff_brdf(const ms_kirchhoff *k, const double wo[3]);
/* f(wi, wo) by the formula above summed directly over the prepared points in double precision, the phase at wo's
 * own wi.z + wo.z (no level, no grid): the reference for ms_kirchhoff_brdf, O(nx ny) a direction. */
double ms_kirchhoff_brdf_exact(const ms_kirchhoff *k, const double wo[3]);

/* ms_kirchhoff_setup and ms_kirchhoff_bin at the three wavelengths ms_kirchhoff_rgb_um times um (the length of a
 * micrometre in the spec's unit: 1 for heights in micrometres, 1e-6 for metres), spec->wavelength ignored:
 * share[3 b + c] for bin b and colour c, total[c], coherent[c] (may be NULL). Returns 0 or -1 with err. */
int ms_kirchhoff_rgb(const ms_kirchhoff_spec *spec, double um, int rings, int sectors, double *share, double total[3],
                     double coherent[3], char *err, size_t errn);

#endif
