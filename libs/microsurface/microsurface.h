/* Microsurfaces with a chosen NDF, for checking the model against geometry (docs/design/microsurface.md): periodic
 * height fields on an n x n grid of unit spacing, heights h[y n + x]. SPDX-License-Identifier: MIT */
#ifndef GGX_LAB_MICROSURFACE_H
#define GGX_LAB_MICROSURFACE_H

#include <stddef.h>
#include <stdint.h>

#include "ggx/ggx.h"

/* A Gaussian random field whose facets have Beckmann slopes: the facets of a cell are the four triangles of its two
 * triangulations (as ggx_fit_heightfield reads them), whose slopes pair the forward differences a = h(x+1, y) -
 * h(x, y), b = h(x+1, y+1) - h(x, y+1) with c = h(x, y+1) - h(x, y), d = h(x+1, y+1) - h(x+1, y): (a, c), (b, d)
 * for the cut from (x+1, y) to (x, y+1), the tracer's, and (a, d), (b, c) for the other. The four together are
 * Gaussian with covariance Sigma_s = half the slope scale of ggx_shape_ellipsoid(alpha_x, alpha_y, 0, 0, phi)
 * (ggx_shape_slopes: Sigma_xx = (ax^2 c^2 + ay^2 s^2) / 2, Sigma_xy = (ay^2 - ax^2) c s / 2, c = cos phi, s = sin phi:
 * the same axes as the library's shape of that rotation), over the ensemble of fields (a field's own covariance
 * scatters about it by about corr_len / n). Each cut alone has Sigma_s's diagonal, but no height field can give both
 * cuts its off-diagonal: a c + b d - a d - b c = D^2, D = b - a the cell's mixed difference, so the tracer's cut has
 * Sigma_xy + cut_xy and the other Sigma_xy - cut_xy (ms_gauss_info). Its autocorrelation is Gaussian, C(r) = sigma^2
 * exp(-r^T M r) sampled on the periodic lattice, sigma^2 = corr_len^2 sqrt(det Sigma_s) / 2 (corr_len in grid
 * spacings): the continuous field of M0 = Sigma_s / (2 sigma^2), det(M0)^(-1/4) = corr_len, would have slopes of
 * covariance Sigma_s; M is M0 corrected so that the four facets have it (det(M)^(-1/4) within 2 % of corr_len for
 * isotropic shapes and for corr_len >= 16; 9 % off at 8 for alphas 0.1, 0.4). Periodic: h(n, y) = h(0, y). */
typedef struct ms_gauss_spec {
    size_t n;                     /* even, 8 to 16384 */
    double alpha_x, alpha_y, phi; /* alphas in [1e-3, 10], phi any finite angle (radians) */
    double corr_len;              /* in [4, n / 4]; refused where the lattice cannot carry the slopes (an axis'
                                   * correlation length below about 3 spacings, or above about n / 4) */
    uint64_t seed;
} ms_gauss_spec;

typedef struct ms_gauss_info {
    double sigma;        /* the heights' standard deviation */
    double metric[3];    /* M: M_xx, M_xy, M_yy */
    double slope_cov[3]; /* the four facets' covariance by the spectrum: Sigma_s to 1e-9 relative */
    double cut_xy;       /* E[D^2] / 4 by the spectrum: what the tracer's cut adds to Sigma_xy and the other cut
                          * takes from it (about 0.05 sqrt(det Sigma_s) at corr_len 4, 0.013 at 8) */
    int iterations;      /* the corrections of M */
} ms_gauss_info;

/* Fills h (n * n doubles); info may be NULL. Returns 0, or -1 with a one-line reason in err (a bad spec, no memory,
 * KISS FFT missing from the build). */
int ms_gauss(const ms_gauss_spec *spec, double *h, ms_gauss_info *info, char *err, size_t errn);

/* A field of GGX slopes: h = G / sqrt(W(x)), G an ms_gauss field of slope covariance Sigma (the scale of GGX's
 * P22, ggx.h) and W(x) the chi^2_2 quantile of the rank of an independent
 * Gaussian field of correlation length mix_len at x among the tile's points (Sigma that of ggx_shape_ellipsoid(alpha_x,
 * alpha_y, 0, 0, phi)). Over the tile's area W is chi^2_2
 * exactly (to the ranks' 1/n^2), and conditional on W the slopes are N(0, Sigma / W), whose mixture is GGX's
 * P22(s) = 1 / (pi sqrt(det Sigma) (1 + s^T Sigma^-1 s)^2); where W varies slowly against G the facets follow it,
 * the gradient's cross term G grad(W^-1/2) adding about corr_len / mix_len. mix_len 0: 8 corr_len, which
 * measured best (docs/design/microsurface.md). Alphas in [1e-3, 7]; mix_len in [corr_len, n / 4]. */
typedef struct ms_ggx_spec {
    size_t n;
    double alpha_x, alpha_y, phi, corr_len, mix_len;
    uint64_t seed;
} ms_ggx_spec;
int ms_ggx(const ms_ggx_spec *spec, double *h, char *err, size_t errn);

/* V-grooves (Torrance-Sparrow's V-cavities): grooves along y of period p texels (even, >= 2, dividing n) and slope
 * +-s along x (0 < s <= 100), h(x, y) = s * (distance from x to the nearest multiple of p), so every facet has the
 * normal (-s, 0, 1) / sqrt(1 + s^2) or (s, 0, 1) / sqrt(1 + s^2), each on half the area. Returns 0 or -1 with err. */
int ms_vgroove(size_t n, size_t p, double s, double *h, char *err, size_t errn);

/* ---- the tracer (trace.c, Embree) ----
 * A height field of ms_gauss or ms_vgroove as Embree grid geometry (two triangles per cell), tiled periodically:
 * a ray that leaves the tile's side enters the opposite side, so the surface is infinite. Directions are unit
 * vectors of the tangent frame (z up); a ray goes from its origin along d. */
typedef struct ms_tracer ms_tracer;
typedef struct ms_hit {
    double p[3]; /* the hit point, x and y within the tile [0, n) (a patch: within [0, nx - 1] x [0, ny - 1]) */
    double m[3]; /* the facet's unit normal, m.z > 0 */
    size_t cell; /* the cell hit: y n + x (a patch: y nx + x) */
} ms_hit;

/* The tracer of h (n x n, kept by copy in single precision); NULL with err where Embree is not built or fails.
 * tilt NULL: the tile repeats as it is; else an infinite tilted patch: the tile repeats raised by tilt[0] n a tile
 * along x and tilt[1] n along y (h(x + n, y) = h(x, y) + tilt[0] n), finite, at most 100 in size. */
ms_tracer *ms_tracer_new(const double *h, size_t n, const double tilt[2], char *err, size_t errn);
void ms_tracer_free(ms_tracer *t);
/* A measured patch: h (nx x ny heights, x fastest, h[y nx + x], in grid spacings; NaN marks a missing point) as
 * Embree grid geometry, finite: no wrap, rays that leave its side are not continued. Cell (x, y), x < nx - 1,
 * y < ny - 1, is present where its four corners are, else absent: hits in it are discarded (an intersection filter)
 * so rays pass through missing regions. nx, ny from 3 to 16384; at least one present cell; the present heights
 * within 1e6 of 0 (single precision carries them to about 0.06 there; take the mean off first). NULL with err.
 * The tracer keeps its own copy of h (doubles, for the facets' slopes) and works with the functions below; a patch
 * has no tilt, ms_tracer_crossings is 1 for it, its hits' cells are y nx + x. */
ms_tracer *ms_patch_new(const double *h, size_t nx, size_t ny, char *err, size_t errn);
/* 1 for a patch, with its size, its heights (the tracer's copy) and its missing points and absent cells (any
 * pointer may be NULL); 0 for a periodic tile. */
int ms_tracer_patch(const ms_tracer *t, size_t *nx, size_t *ny, const double **h, size_t *missing, size_t *absent);
/* 1 where cell (x, y) of a patch is present (all its corners are), 0 where it is absent or outside. */
int ms_patch_present(const ms_tracer *t, size_t x, size_t y);
/* ms_trace's results beyond 1, 0 and -1 for a patch: -1 (below the band) is a ray that fell through a missing region
 * (a hole); MS_LEFT a ray that left the patch through its side within the heights' band, or passed beside it. */
#define MS_LEFT (-2)
/* The edge treatment of a patch (docs/design/microsurface.md, "Measured patches"): rays along -v start at the band's
 * top z_top = zmax + pad (ms_patch_top) over the window w = [w[0], w[2]] x [w[1], w[3]], the points whose ray crosses
 * the whole band (down to the lowest height) over the patch: the patch [0, nx - 1] x [0, ny - 1] less (z_top - zmin)
 * tan(theta_v) on the side the rays travel towards (none upstream: a ray from above never meets the surface behind its
 * start). No ray along -v from the window leaves the patch before it hits or passes below every height. reflect 1 (the
 * BRDF's window): twice that margin downstream (the specular path down and back up) and (z_top - zmin)
 * max(tan(theta_v), 1) on every side, so that rays reflected up at the view's angle (or 45 degrees) reach the band's
 * top over the patch; more grazing ones may leave (MS_LEFT, counted). Returns 0, or -1 with err where the window is
 * empty or under a cell wide (the view too grazing for the patch's band). */
int ms_patch_window(const ms_tracer *t, const double v[3], int reflect, double w[4], char *err, size_t errn);
/* The height rays start from over a patch: the present heights' top plus the tracer's single-precision pad. */
double ms_patch_top(const ms_tracer *t);
/* The heights' range over the tile's column, for rays that start above the surface there (a patch: over its present
 * heights). */
void ms_tracer_bounds(const ms_tracer *t, double *zmin, double *zmax);
/* The tilt it was made with (0, 0 for none). */
void ms_tracer_tilt(const ms_tracer *t, double tilt[2]);
/* The tiles a ray along d (not along the plane) crosses while it passes through the heights' band, about: 1 + the
 * band's thickness times the ray's run over its fall, over the tile's size (the tracer's work per ray grows with
 * it: a tile with one tall spike makes every ray walk through many tiles). HUGE_VAL along the plane. */
double ms_tracer_crossings(const ms_tracer *t, const double d[3]);
/* The most tile crossings ms_measure_g1 and ms_measure_brdf take on (rays times ms_tracer_crossings, for the BRDF
 * twice that: in and out): seconds of tracing; more is refused with the estimate. */
#define MS_MAX_CROSSINGS 67108864.0
/* The first hit of the ray (o, d) on the tiled surface (or the patch) beyond a distance of 1e-4 (so that a ray leaving
 * a hit point does not hit its own facet): 1 and *hit (its height that of the tile's copy at x, y in [0, n)), or 0
 * where the ray escapes (it is above the surface's top going up from the mean plane, or along it), or -1 where it
 * leaves below the surface's bottom (which a tracer that works never does; on a patch, through a missing region), or on
 * a patch MS_LEFT where it leaves the patch's side within the band. The tracer may be used from any number of threads
 * at once. */
int ms_trace(const ms_tracer *t, const double o[3], const double d[3], ms_hit *hit);
/* ms_trace of count rays of one direction d from the origins o[3 i .. 3 i + 2], into hits[i] and result[i]: the
 * same hits, their first segments traced in streams of 64 (Embree's coherent rays), which is faster where
 * neighbouring origins are near (a row of a jittered grid). */
void ms_trace_coherent(const ms_tracer *t, size_t count, const double *o, const double d[3], ms_hit *hits, int *result);

/* ---- masking measured (measure.c) ----
 * The facets of h (n x n, periodic): in each cell (x, y) the triangles Embree makes, split along the diagonal from
 * (x + 1, y) to (x, y + 1), whose slopes are forward differences: the lower-left one (h(x+1, y) - h(x, y),
 * h(x, y+1) - h(x, y)), the upper-right one (h(x+1, y+1) - h(x, y+1), h(x+1, y+1) - h(x+1, y)). Each has projected
 * area 1/2 and projected area (v.z - s.v_xy) / 2 towards v where that is positive (front-facing).
 * Normals are binned into rings of equal sin^2(theta_m) (rings of them in [0, 1]) times sectors of equal azimuth. */
typedef struct ms_g1 {
    double g1;            /* G1(v) of all the facets: n^2 f / (their projected area towards v), exact for a height
                           * field, f = v.z - tilt . (v.x, v.y) the footprint's projected area per unit tile area */
    double g1_off_risers; /* G1(v) of the facets off a sawtooth's risers: their visible share by the rays (g1 to
                           * Monte Carlo error where there are none) */
    double riser_area, riser_visible; /* the risers' projected area towards v, and the part of it the rays see first,
                                       * per unit tile area (0 where there are none) */
    size_t risers[2];                 /* the sawtooth's period along x and y where that axis has risers, else 0 */
    double slope_mean[2]; /* the slopes' mean of the facets off the risers (the tilted patch's or ramp's tilt) */
    double slope_cov[3];  /* and their covariance (the mean removed), for Beckmann's Smith form */
    long rays, missed;    /* rays traced from above on a jittered grid, and those that hit nothing (0 if it works) */
    long left, holes;     /* a patch's misses: rays that left its side within the band, and those that fell through a
                           * missing region (missed = left + holes; 0 for a tile) */
    double window[4];     /* where the rays started (at the band's top): x0, y0, x1, y1; a tile: 0, 0, n, n */
    int rings, sectors;
    double *area;    /* per bin: the facets' projected area towards v (front-facing), per unit tile area */
    double *visible; /* per bin: the area of it that the rays see first, per unit tile area */
} ms_g1;

/* Traces about rays rays (a jittered grid of g x g origins, g = ceil(sqrt(rays))) from above along -v on threads
 * threads and fills r (ms_g1_free releases it); the tracer's tilt applies (the tile's differences across its sides
 * raised by it). risers (may be NULL: none): ms_find_risers' periods, whose cells' facets are counted apart from the
 * others' (bins, covariance, g1_off_risers). Each row of the grid draws its jitter from its own stream and the
 * threads' counts are summed as integers, so the result is the same for any number of threads. Returns 0 or -1
 * with err: the view not clear of the plane (ms_view_clear), more work than MS_MAX_CROSSINGS. */
int ms_measure_g1(const ms_tracer *t, const double *h, size_t n, const double v[3], long rays, int rings, int sectors,
                  const size_t risers[2], int threads, ms_g1 *r, char *err, size_t errn);
/* On a patch (ms_patch_new) ms_measure_g1 is ms_patch_g1 with the window of ms_patch_window (h, n ignored: NULL, 0 will
 * do; risers must be NULL). ms_patch_g1 takes the window w (NULL: ms_patch_window's, reflect 0; any other rectangle
 * inside the patch, for the edge treatment's own tests): g x g rays (g = ceil(sqrt(rays))) on a jittered grid over w at
 * ms_patch_top. The facets are those of the present cells whose centres lie in w: area per bin over the count of all
 * the cells (present or absent) whose centres lie in w, g1 their present count times f over their projected area (exact
 * for the surface they sample; f = v.z - slope_mean . (v.x, v.y), the footprint of their mean slope, which a scan keeps
 * where it was not levelled); visible per bin f times the bin's share of the rays, so a ray that left (left) or fell
 * through a hole (holes) lowers the visible share (g1_off_risers, the traced G1), never silently. Each row draws its
 * own stream (not the tile's), the result the same for any number of threads. Returns 0 or -1 with err (a view along
 * the plane, a window outside the patch or empty). */
int ms_patch_g1(const ms_tracer *t, const double v[3], const double w[4], long rays, int rings, int sectors,
                int threads, ms_g1 *r, char *err, size_t errn);
/* The risers of a sawtooth of period P (P divides n, 2 <= P <= n / 2; ms_ramp's): along x, the columns x = P - 1
 * mod P where the median of their differences (which a steep pit does not move) steps from the other columns' by
 * more than 1 (a step steeper than 45 degrees), and likewise the rows along y. risers[0] and risers[1] receive P
 * for an axis with risers, else 0; P 0: none (0, 0). Returns 0, or -1 with err: P out of range, a tile that is no
 * sawtooth of period P (other columns step, or only some of those), one that has no risers of it, no memory. */
int ms_find_risers(const double *h, size_t n, size_t P, size_t risers[2], char *err, size_t errn);
void ms_g1_free(ms_g1 *r);
/* The BRDF of the tiled surface with F = 1, traced: rays from wi (a jittered grid of origins) reflect specularly at
 * every facet they meet until they escape, at most max_bounces times. Outgoing directions are binned in rings of
 * equal sin^2(theta_o) times sectors of equal azimuth, bins of equal projected solid angle pi / bins, so a bin's
 * BRDF is its share of the rays times bins / pi. The same for any number of threads (as ms_measure_g1); more work
 * than MS_MAX_CROSSINGS is refused. */
typedef struct ms_brdf {
    int rings, sectors;
    long rays, lost, capped; /* lost: left below the surface (none if the tracer works; on a patch, fell through a
                              * missing region); capped: still bouncing */
    long left;               /* a patch's rays that left its side within the heights' band (0 for a tile): not in
                              * any bin, so the albedo falls short of 1 by left / rays */
    double window[4];        /* where the rays started, as ms_g1's */
    double *single;          /* per bin: the share of the rays that leave into it after one reflection */
    double *all;             /* and after any number */
} ms_brdf;
int ms_measure_brdf(const ms_tracer *t, size_t n, const double wi[3], long rays, int rings, int sectors,
                    int max_bounces, int threads, ms_brdf *r, char *err, size_t errn);
/* On a patch ms_measure_brdf is ms_patch_brdf with ms_patch_window's window (reflect 1; n ignored). ms_patch_brdf: g x
 * g rays on a jittered grid over w (NULL: ms_patch_window(t, wi, 1)) at ms_patch_top along -wi, reflected as on a tile;
 * a ray that leaves the patch's side within the band is counted in left, one that falls through a hole in lost, neither
 * binned. ms_measure_brdf_from_bin refuses a patch (the window depends on each ray's wi). */
int ms_patch_brdf(const ms_tracer *t, const double wi[3], const double w[4], long rays, int rings, int sectors,
                  int max_bounces, int threads, ms_brdf *r, char *err, size_t errn);
/* ms_measure_brdf with each ray's wi drawn uniformly in projected solid angle over the outgoing bin `bin`: share
 * b of the result is then (1 / pi) times the double integral of f over bin x bin b in projected solid angles, times
 * the bins' count; by reciprocity the same as share bin from bin b (the traced BRDF's reciprocity test). */
int ms_measure_brdf_from_bin(const ms_tracer *t, size_t n, int bin, long rays, int rings, int sectors, int max_bounces,
                             int threads, ms_brdf *r, char *err, size_t errn);
void ms_brdf_free(ms_brdf *r);

/* G1(v) of the facets alone (ms_g1's g1, no rays): n^2 f over their projected area towards v, f the footprint's as
 * in ms_g1 (tilt as for ms_tracer_new, may be NULL). */
double ms_facets_g1(const double *h, size_t n, const double tilt[2], const double v[3]);
/* Smith's G1(v) for Beckmann slopes of covariance cov (Sxx, Sxy, Syy, the mean removed): 1 / (1 + Lambda(a)),
 * Lambda(a) = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)), a = 1 / (alpha_phi tan theta), alpha_phi^2 = 2 u^T cov u
 * for the unit azimuth u of v. */
double ms_beckmann_g1(const double cov[3], const double v[3]);
/* ---- skewed surfaces (skew.c) ----
 * A skewed ellipsoid's slopes have a location t (ggx_shape_slopes), the mean slope of its facets, which no periodic
 * height field has. Two surfaces carry it: a tilted patch, a field g plus the plane t . (x, y), repeated as an
 * infinite tilted surface (ms_tracer_new's tilt); and a sawtooth, the ramp t . (x mod P, y mod P) over g, periodic,
 * whose steps back down at x = P - 1 mod P (and y) are risers: near-vertical facets on 1 / P of the cells (Walter's
 * remedy, section 5.1 of the seed: vertical area that brings the mean normal back to n).
 * ms_ramp adds tx (x mod P) + ty (y mod P) to h; period 0: P = n, the tilted patch's plane over the tile. Returns 0,
 * or -1 with err (slopes not finite or above 100, P below 2 or not dividing n). */
int ms_ramp(double *h, size_t n, double tx, double ty, size_t period, char *err, size_t errn);
/* The GGX surface of a skewed shape s: ms_ggx of its scale Sigma (as the alphas and rotation of the unskewed shape of
 * (0, Sigma), written into spec) under ms_ramp of its location t (into t) and period. Returns 0 or -1 with err. */
int ms_ggx_skewed(const ggx_shape *s, ms_ggx_spec *spec, size_t period, double *h, double t[2], char *err, size_t errn);

/* Walter's remedy with Smith's masking, for a skewed shape s (slopes of location t and scale Sigma), unit v above the
 * plane (else 0): the facets of D and vertical facets of area |t| per unit area facing along t, all masked alike,
 * so that the visible projected area is v.z: G1 = v.z / (v.z (1 + ggx_lambda(s, v)) + max(t . v_xy, 0)). The
 * tracer rejects it where the risers face v (they are seen unmasked there); the library's forms for skewed surfaces
 * are ggx_g1_tilted (a tilted patch) and ggx_g1_risers (the sawtooth). */
double ms_g1_vertical_facets(const ggx_shape *s, const double v[3]);

/* 1 where the view v is at least 1e-3 in cosine (0.06 degrees) above the plane of slope tilt (may be NULL: the
 * horizontal plane), the views ms_measure_g1 takes: rays nearer the plane cross tiles without end. */
int ms_view_clear(const double tilt[2], const double v[3]);
/* 1 where cell (y n + x) of an n x n tile is one of the risers of ms_find_risers' periods, else 0. */
int ms_riser_cell(const size_t risers[2], size_t n, size_t cell);
/* The unit normals of the four triangles of each inner cell off the risers (both triangulations, as
 * ggx_fit_heightfield takes them) into m (room for 4 (n - 1)^2); returns how many. */
size_t ms_facet_normals(const double *h, size_t n, const size_t risers[2], ggx_vec3 *m);
/* The bin of a unit normal m (m.z > 0). */
int ms_bin(const double m[3], int rings, int sectors);

/* ---- a caller's binning of outgoing directions ----
 * bin(ctx, wo) gives the bin of a unit direction wo above the plane, in [0, bins), or -1 to count it in none. The
 * measures that take one (ms_patch_brdf_binned, ms_kirchhoff_binned) fill bins shares. */
typedef struct ms_binning {
    int bins;
    int (*bin)(const void *ctx, const double wo[3]);
    const void *ctx;
} ms_binning;

/* The tracer's bins (ms_bin: rings of equal sin^2 theta times sectors of equal azimuth) as a binning: rb holds its
 * counts and must outlive it. */
typedef struct ms_ring_bins {
    int rings, sectors;
} ms_ring_bins;
int ms_ring_bin(const void *ctx, const double wo[3]);
ms_binning ms_ring_binning(ms_ring_bins *rb, int rings, int sectors);
/* ms_patch_brdf into the caller's bins: r->single and r->all have out->bins shares (r->rings = out->bins,
 * r->sectors = 1); a ray whose final direction out gives -1 is counted in no bin. */
int ms_patch_brdf_binned(const ms_tracer *t, const double wi[3], const double w[4], long rays, const ms_binning *out,
                         int max_bounces, int threads, ms_brdf *r, char *err, size_t errn);

/* ---- levelling (level.c) ----
 * Removes from h (nx x ny, x fastest; non-finite values are missing points, left as they are) the least-squares plane
 * of its finite points, in place (keep_tilt: their mean only; where the finite points lie on one line, their mean
 * only). plane (may be NULL) receives the plane taken off: its slopes along x and y per grid step and its height at the
 * grid's centre ((nx - 1) / 2, (ny - 1) / 2). Returns how many points are finite (0: nothing changed). */
size_t ms_level(double *h, size_t nx, size_t ny, int keep_tilt, double plane[3]);

#endif
