/* The periodic microsurface tracer over Embree (microsurface.h; docs/design/microsurface.md).
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "microsurface.h"

#ifdef GGX_HAVE_EMBREE
#include <embree3/rtcore.h>

struct ms_tracer {
    RTCDevice device;
    RTCScene scene;
    size_t n;
    double tilt[2];
    double zmin, zmax; /* the heights' range over the tile's column, its border included */
    double rmin, rmax; /* the range of z - tilt . (x, y) over the surface: the band the rays cross */
    /* a patch (ms_patch_new): nx x ny heights, no wrap; zmin, zmax (= rmin, rmax) over its present heights, padded */
    int patch;
    size_t nx, ny, missing, absent_cells;
    double *h;             /* the heights as given (NaN at missing points) */
    unsigned char *absent; /* per cell y nx + x: 1 where a corner is missing; NULL where none is */
};

/* Embree's error code in words. */
static const char *embree_error_words(enum RTCError e)
{
    switch (e) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "an invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "an invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "this processor is not supported";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "an unknown error";
    }
}

/* The grid geometry g committed into t's scene and the scene built: t, or NULL (t freed) with Embree's error. */
static ms_tracer *committed(ms_tracer *t, RTCGeometry g, const char *what, size_t nx, size_t ny, char *err, size_t errn)
{
    rtcCommitGeometry(g);
    rtcAttachGeometry(t->scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(t->scene);
    enum RTCError e = rtcGetDeviceError(t->device);
    if (e != RTC_ERROR_NONE) {
        snprintf(err, errn, "%s: Embree could not build the surface of %zu x %zu heights (%s)", what, nx, ny,
                 embree_error_words(e));
        ms_tracer_free(t);
        return NULL;
    }
    return t;
}

ms_tracer *ms_tracer_new(const double *h, size_t n, const double tilt[2], char *err, size_t errn)
{
    if (tilt && !(isfinite(tilt[0]) && isfinite(tilt[1]) && fabs(tilt[0]) <= 100.0 && fabs(tilt[1]) <= 100.0)) {
        snprintf(err, errn, "tracer: a finite tilt of at most 100");
        return NULL;
    }
    if (n < 2 || n > 16384) { /* one grid primitive: at most 32767 vertices a side */
        snprintf(err, errn, "tracer: a size from 2 to 16384");
        return NULL;
    }
    ms_tracer *t = calloc(1, sizeof *t);
    if (!t) {
        snprintf(err, errn, "tracer: out of memory");
        return NULL;
    }
    t->n = n;
    if (tilt) t->tilt[0] = tilt[0], t->tilt[1] = tilt[1];
    t->device = rtcNewDevice(NULL);
    if (!t->device) {
        snprintf(err, errn, "tracer: Embree did not start (%s)", embree_error_words(rtcGetDeviceError(NULL)));
        free(t);
        return NULL;
    }
    t->scene = rtcNewScene(t->device);
    rtcSetSceneBuildQuality(t->scene, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(t->scene, RTC_SCENE_FLAG_ROBUST); /* watertight: no ray through an edge between two triangles */
    /* Embree's grid geometry over the tile and a border of one cell around it (the periodic copies), so that the
     * tile's sides are inner edges: a ray that meets the surface exactly at a side then hits in one of the two tiles
     * (a mesh's own border edges are not watertight). Each cell is two triangles cut along the diagonal from
     * (x+1, y) to (x, y+1) (tests/unit/test_microsurface.c checks it). Embree's robust mode keeps the inner edges
     * watertight: without it a few rays in a million pass between two triangles (the test keeps two such rays). */
    RTCGeometry g = rtcNewGeometry(t->device, RTC_GEOMETRY_TYPE_GRID);
    size_t side = n + 3; /* vertices at -1 .. n + 1 */
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), side * side);
    struct RTCGrid *grid = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, sizeof(struct RTCGrid),
                                                   1);
    if (!v || !grid) {
        snprintf(err, errn, "tracer: out of memory for %zu x %zu heights", n, n);
        rtcReleaseGeometry(g);
        ms_tracer_free(t);
        return NULL;
    }
    t->zmin = t->rmin = HUGE_VAL, t->zmax = t->rmax = -HUGE_VAL;
    for (size_t y = 0; y < side; y++)
        for (size_t x = 0; x < side; x++) {
            /* vertex (x - 1, y - 1): the tile's height there, raised by the tilt times the tiles crossed */
            double X = (double)x - 1.0, Y = (double)y - 1.0;
            double wx = X < 0.0 ? -1.0 : X >= (double)n ? 1.0 : 0.0, wy = Y < 0.0 ? -1.0 : Y >= (double)n ? 1.0 : 0.0;
            double z = h[((y + n - 1) % n) * n + (x + n - 1) % n] + (t->tilt[0] * wx + t->tilt[1] * wy) * (double)n;
            float *p = v + 3 * (y * side + x);
            p[0] = (float)X, p[1] = (float)Y, p[2] = (float)z;
            double r = (double)p[2] - t->tilt[0] * X - t->tilt[1] * Y;
            t->zmin = fmin(t->zmin, (double)p[2]), t->zmax = fmax(t->zmax, (double)p[2]);
            t->rmin = fmin(t->rmin, r), t->rmax = fmax(t->rmax, r);
        }
    /* the band padded for single precision (a flat tilted plane's band is of no thickness) */
    double pad = 1e-3 + 1e-5 * fmax(fabs(t->zmin), fabs(t->zmax));
    t->rmin -= pad, t->rmax += pad;
    grid->startVertexID = 0, grid->stride = (unsigned)side;
    grid->width = (unsigned short)side, grid->height = (unsigned short)side;
    return committed(t, g, "tracer", n, n, err, errn);
}

void ms_tracer_free(ms_tracer *t)
{
    if (!t) return;
    if (t->scene) rtcReleaseScene(t->scene);
    if (t->device) rtcReleaseDevice(t->device);
    free(t->h), free(t->absent);
    free(t);
}

void ms_tracer_bounds(const ms_tracer *t, double *zmin, double *zmax) { *zmin = t->zmin, *zmax = t->zmax; }

void ms_tracer_tilt(const ms_tracer *t, double tilt[2]) { tilt[0] = t->tilt[0], tilt[1] = t->tilt[1]; }

double ms_tracer_crossings(const ms_tracer *t, const double d[3])
{
    if (t->patch) return 1.0;
    double dr = fabs(d[2] - t->tilt[0] * d[0] - t->tilt[1] * d[1]), run = hypot(d[0], d[1]);
    if (!(dr > 0.0)) return HUGE_VAL;
    return 1.0 + (t->rmax - t->rmin) * run / dr / (double)t->n;
}

/* One ray's walk through the tiles: its position in the tile's frame, the steps taken, and the end of the segment
 * being traced (where it leaves the tile's column or the heights' band). */
typedef struct walk {
    double x, y, z, dr, tx, ty, tz, tend;
    int step;
} walk;

static void walk_begin(const ms_tracer *t, const double o[3], const double d[3], walk *w)
{
    double n = (double)t->n, kx = floor(o[0] / n), ky = floor(o[1] / n);
    w->x = o[0] - n * kx, w->y = o[1] - n * ky, w->z = o[2] - (t->tilt[0] * kx + t->tilt[1] * ky) * n;
    /* the ray's height over the tilted plane z = tilt . (x, y) changes at the rate dr along the ray */
    w->dr = d[2] - t->tilt[0] * d[0] - t->tilt[1] * d[1];
    w->step = 0;
}

/* The next segment of the ray as Embree's ray: 2, or 0 (escaped) or -1 (left below) before any. */
static int walk_segment(const ms_tracer *t, const double d[3], walk *w, struct RTCRayHit *rh)
{
    double n = (double)t->n, r = w->z - t->tilt[0] * w->x - t->tilt[1] * w->y, dr = w->dr;
    if (w->step >= 1 << 20) return 0;
    if (dr >= 0.0 && r > t->rmax) return 0;
    if (dr < 0.0 && r < t->rmin) return -1;
    /* the ray's part inside this tile's column: up to where it leaves a side (or the heights' band) */
    w->tx = d[0] > 0.0 ? (n - w->x) / d[0] : d[0] < 0.0 ? -w->x / d[0] : HUGE_VAL;
    w->ty = d[1] > 0.0 ? (n - w->y) / d[1] : d[1] < 0.0 ? -w->y / d[1] : HUGE_VAL;
    w->tz = dr > 0.0 ? (t->rmax - r) / dr : dr < 0.0 ? (t->rmin - r) / dr : HUGE_VAL;
    w->tend = fmin(fmin(w->tx, w->ty), w->tz);
    if (!(w->tend < HUGE_VAL)) return 0; /* along the plane, inside the band, along no side: cannot happen */
    rh->ray.org_x = (float)w->x, rh->ray.org_y = (float)w->y, rh->ray.org_z = (float)w->z;
    rh->ray.dir_x = (float)d[0], rh->ray.dir_y = (float)d[1], rh->ray.dir_z = (float)d[2];
    rh->ray.tnear = w->step == 0 ? 1e-4f : 0.0f, rh->ray.tfar = (float)(w->tend * (1.0 + 1e-6) + 1e-6);
    rh->ray.mask = 0xFFFFFFFFu, rh->ray.flags = 0, rh->ray.time = 0.0f;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID, rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return 2;
}

/* After Embree traced the segment: 1 and *hit, 0 or -1 (escaped, left below), or 2 (into the next tile). */
static int walk_after(const ms_tracer *t, const double d[3], walk *w, const struct RTCRayHit *rh, ms_hit *hit)
{
    double n = (double)t->n, tx0 = t->tilt[0], ty0 = t->tilt[1];
    if (rh->hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        double th = rh->ray.tfar, gx = rh->hit.Ng_x, gy = rh->hit.Ng_y, gz = rh->hit.Ng_z;
        double l = sqrt(gx * gx + gy * gy + gz * gz);
        if (gz < 0.0) l = -l; /* the upward normal: a height field's facets all face up */
        hit->p[0] = w->x + th * d[0], hit->p[1] = w->y + th * d[1], hit->p[2] = w->z + th * d[2];
        /* a hit in the border (within about 1e-5 of a side) is the same facet of the next tile */
        if (hit->p[0] < 0.0) hit->p[0] += n, hit->p[2] += tx0 * n;
        if (hit->p[0] >= n) hit->p[0] -= n, hit->p[2] -= tx0 * n;
        if (hit->p[1] < 0.0) hit->p[1] += n, hit->p[2] += ty0 * n;
        if (hit->p[1] >= n) hit->p[1] -= n, hit->p[2] -= ty0 * n;
        hit->m[0] = gx / l, hit->m[1] = gy / l, hit->m[2] = gz / l;
        size_t cx = (size_t)fmin(fmax(floor(hit->p[0]), 0.0), n - 1);
        size_t cy = (size_t)fmin(fmax(floor(hit->p[1]), 0.0), n - 1);
        hit->cell = cy * t->n + cx;
        return 1;
    }
    if (w->tend == w->tz) return w->dr > 0.0 ? 0 : -1; /* left the heights' band: escaped (up), or through (down) */
    /* into the next tile: move to the side, wrap the coordinate that crossed it, and start a little before it
     * (1e-3 back along the ray, outside the new tile's geometry), so that a crossing of the surface at the side
     * itself, which single precision may give to neither tile, is inside the new segment; the tilt: the next
     * tile's surface is tilt n higher along the way the ray goes */
    double te = w->tend;
    w->x += te * d[0], w->y += te * d[1], w->z += te * d[2];
    if (te == w->tx) w->x = d[0] > 0.0 ? 0.0 : n, w->z -= (d[0] > 0.0 ? 1.0 : -1.0) * tx0 * n;
    if (te == w->ty) w->y = d[1] > 0.0 ? 0.0 : n, w->z -= (d[1] > 0.0 ? 1.0 : -1.0) * ty0 * n;
    w->x -= 1e-3 * d[0], w->y -= 1e-3 * d[1], w->z -= 1e-3 * d[2];
    w->step++;
    return 2;
}

static int walk_on(const ms_tracer *t, const double d[3], walk *w, ms_hit *hit)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (;;) {
        struct RTCRayHit rh;
        int k = walk_segment(t, d, w, &rh);
        if (k != 2) return k;
        rtcIntersect1(t->scene, &ctx, &rh);
        k = walk_after(t, d, w, &rh, hit);
        if (k != 2) return k;
    }
}

/* ---- patches: a finite grid without wrap, missing points (microsurface.h; docs/design/microsurface.md) ---- */

/* The cell of a patch that Embree's ray (single precision, as the filter sees it) meets at distance th: the one
 * computation of a hit's cell, shared by the filter and the hit, so that no accepted hit lies in an absent cell. */
static size_t patch_cell(const ms_tracer *t, const float o[3], const float d[3], double th)
{
    double x = (double)o[0] + th * (double)d[0], y = (double)o[1] + th * (double)d[1];
    size_t cx = (size_t)fmin(fmax(floor(x), 0.0), (double)(t->nx - 2));
    size_t cy = (size_t)fmin(fmax(floor(y), 0.0), (double)(t->ny - 2));
    return cy * t->nx + cx;
}

/* Embree's intersection filter: a hit in an absent cell is no hit, so the ray goes on through the hole. The rays
 * come as RTCRayN, members of N floats each (rtcore_ray.h's accessors are C++ only): org_x, org_y, org_z, tnear,
 * dir_x, dir_y, dir_z, time, tfar, which holds the candidate hit's distance. */
static void patch_filter(const struct RTCFilterFunctionNArguments *a)
{
    const ms_tracer *t = a->geometryUserPtr;
    const float *ray = (const float *)a->ray;
    unsigned N = a->N;
    for (unsigned i = 0; i < N; i++) {
        if (a->valid[i] != -1) continue;
        float o[3] = {ray[i], ray[N + i], 0.0f}, d[3] = {ray[4 * N + i], ray[5 * N + i], 0.0f};
        if (t->absent[patch_cell(t, o, d, (double)ray[8 * N + i])]) a->valid[i] = 0;
    }
}

/* the patch's checks, its copy of h, the absent cells and the band; 0 or -1 with err */
static int patch_heights(ms_tracer *t, const double *h, char *err, size_t errn)
{
    size_t nx = t->nx, ny = t->ny;
    t->h = malloc(nx * ny * sizeof *t->h);
    t->absent = calloc((nx - 1) * ny, 1);
    if (!t->h || !t->absent) {
        snprintf(err, errn, "patch: out of memory for %zu x %zu heights", nx, ny);
        return -1;
    }
    t->zmin = HUGE_VAL, t->zmax = -HUGE_VAL;
    for (size_t i = 0; i < nx * ny; i++) {
        t->h[i] = h[i];
        if (isnan(h[i])) {
            t->missing++;
            continue;
        }
        if (!(fabs(h[i]) <= 1e6)) {
            snprintf(err, errn, "patch: height %zu is %g, not within 1e6 grid spacings of 0", i, h[i]);
            return -1;
        }
        t->zmin = fmin(t->zmin, h[i]), t->zmax = fmax(t->zmax, h[i]);
    }
    for (size_t y = 0; y + 1 < ny; y++)
        for (size_t x = 0; x + 1 < nx; x++) {
            size_t i = y * nx + x;
            t->absent[i] = isnan(h[i]) || isnan(h[i + 1]) || isnan(h[i + nx]) || isnan(h[i + nx + 1]);
            t->absent_cells += t->absent[i];
        }
    if (t->absent_cells == (nx - 1) * (ny - 1)) {
        snprintf(err, errn, "patch: no cell of the %zu x %zu heights has all four corners (%zu missing points)", nx, ny,
                 t->missing);
        return -1;
    }
    if (!t->absent_cells) free(t->absent), t->absent = NULL;
    /* the band padded for single precision, as the tile's */
    double pad = 1e-3 + 1e-5 * fmax(fabs(t->zmin), fabs(t->zmax));
    t->rmin = t->zmin - pad, t->rmax = t->zmax + pad;
    return 0;
}

ms_tracer *ms_patch_new(const double *h, size_t nx, size_t ny, char *err, size_t errn)
{
    if (nx < 3 || ny < 3 || nx > 16384 || ny > 16384) { /* one grid primitive: at most 32767 vertices a side */
        snprintf(err, errn, "patch: %zu x %zu heights: a size from 3 to 16384 along each axis", nx, ny);
        return NULL;
    }
    ms_tracer *t = calloc(1, sizeof *t);
    if (!t) {
        snprintf(err, errn, "patch: out of memory");
        return NULL;
    }
    t->patch = 1, t->nx = nx, t->ny = ny, t->n = nx;
    if (patch_heights(t, h, err, errn) != 0) {
        ms_tracer_free(t);
        return NULL;
    }
    t->device = rtcNewDevice(NULL);
    if (!t->device) {
        snprintf(err, errn, "patch: Embree did not start (%s)", embree_error_words(rtcGetDeviceError(NULL)));
        ms_tracer_free(t);
        return NULL;
    }
    t->scene = rtcNewScene(t->device);
    rtcSetSceneBuildQuality(t->scene, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(t->scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry g = rtcNewGeometry(t->device, RTC_GEOMETRY_TYPE_GRID);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nx * ny);
    struct RTCGrid *grid = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, sizeof(struct RTCGrid),
                                                   1);
    if (!v || !grid) {
        snprintf(err, errn, "patch: out of memory for %zu x %zu heights", nx, ny);
        rtcReleaseGeometry(g);
        ms_tracer_free(t);
        return NULL;
    }
    /* a missing point takes the lowest height: its cells are absent (the filter), it only bounds the BVH */
    for (size_t i = 0; i < nx * ny; i++) {
        float *p = v + 3 * i;
        p[0] = (float)(i % nx), p[1] = (float)(i / nx), p[2] = (float)(isnan(h[i]) ? t->zmin : h[i]);
    }
    grid->startVertexID = 0, grid->stride = (unsigned)nx;
    grid->width = (unsigned short)nx, grid->height = (unsigned short)ny;
    if (t->absent) {
        rtcSetGeometryUserData(g, t);
        rtcSetGeometryIntersectFilterFunction(g, patch_filter);
    }
    return committed(t, g, "patch", nx, ny, err, errn);
}

int ms_tracer_patch(const ms_tracer *t, size_t *nx, size_t *ny, const double **h, size_t *missing, size_t *absent)
{
    if (!t->patch) return 0;
    if (nx) *nx = t->nx;
    if (ny) *ny = t->ny;
    if (h) *h = t->h;
    if (missing) *missing = t->missing;
    if (absent) *absent = t->absent_cells;
    return 1;
}

int ms_patch_present(const ms_tracer *t, size_t x, size_t y)
{
    if (!t->patch || x + 1 >= t->nx || y + 1 >= t->ny) return 0;
    return !t->absent || !t->absent[y * t->nx + x];
}

double ms_patch_top(const ms_tracer *t) { return t->rmax; }

int ms_patch_window(const ms_tracer *t, const double v[3], int reflect, double w[4], char *err, size_t errn)
{
    if (!t->patch || !(v[2] > 0.0)) {
        snprintf(err, errn, "patch: a window needs a patch and a view above the plane");
        return -1;
    }
    /* the rays go along -v: from z_top down to the lowest height they move (z_top - zmin) v_xy / v.z backwards */
    double fall = t->rmax - t->rmin, mx = fall * v[0] / v[2], my = fall * v[1] / v[2];
    double X = (double)(t->nx - 1), Y = (double)(t->ny - 1), k = reflect ? 2.0 : 1.0;
    /* the BRDF's: twice that downstream (down to the lowest height, and back up to the top at the mirror angle) */
    w[0] = mx > 0.0 ? k * mx : 0.0, w[2] = mx < 0.0 ? X + k * mx : X;
    w[1] = my > 0.0 ? k * my : 0.0, w[3] = my < 0.0 ? Y + k * my : Y;
    if (reflect) { /* and rays reflected up at theta_v (or 45 degrees) on every side */
        double m = fall * fmax(sqrt(v[0] * v[0] + v[1] * v[1]) / v[2], 1.0);
        w[0] = fmax(w[0], m), w[1] = fmax(w[1], m), w[2] = fmin(w[2], X - m), w[3] = fmin(w[3], Y - m);
    }
    if (!(w[2] - w[0] >= 1.0 && w[3] - w[1] >= 1.0)) {
        snprintf(err, errn,
                 "patch: at %.3g degrees from the normal the rays cross the heights' band of %.4g spacings over "
                 "%.4g x %.4g spacings, more than the %zu x %zu patch leaves a window of one cell for (a steeper view, "
                 "or the patch without its outliers)",
                 acos(fmin(v[2] / sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), 1.0)) * 180.0 / 3.14159265358979323846,
                 fall, fabs(mx), fabs(my), t->nx, t->ny);
        return -1;
    }
    return 0;
}

/* A ray over a patch, clipped to the patch's box (its column and band): the segment as Embree's ray, and the axis
 * through which it leaves the box. 2 (to trace), or the result where the ray misses the box. */
static int patch_segment(const ms_tracer *t, const double o[3], const double d[3], struct RTCRayHit *rh, int *axis)
{
    double lo[3] = {0.0, 0.0, t->rmin}, hi[3] = {(double)(t->nx - 1), (double)(t->ny - 1), t->rmax};
    double t0 = 0.0, t1 = HUGE_VAL;
    int inside = 1;
    *axis = 2;
    for (int k = 0; k < 3; k++) {
        if (k < 2 && !(o[k] >= lo[k] && o[k] <= hi[k])) inside = 0;
        if (d[k] == 0.0) {
            if (!(o[k] >= lo[k] && o[k] <= hi[k])) t1 = -1.0; /* parallel to the slab, outside it */
            continue;
        }
        double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
        if (a > b) {
            double c = a;
            a = b, b = c;
        }
        t0 = fmax(t0, a);
        if (b < t1) t1 = b, *axis = k;
    }
    if (!(t0 <= t1)) { /* it misses the box: above going up (or below going down) its column, else beside it */
        if (inside) return d[2] > 0.0 ? 0 : -1;
        return o[2] >= t->rmax && d[2] >= 0.0 ? 0 : MS_LEFT;
    }
    rh->ray.org_x = (float)o[0], rh->ray.org_y = (float)o[1], rh->ray.org_z = (float)o[2];
    rh->ray.dir_x = (float)d[0], rh->ray.dir_y = (float)d[1], rh->ray.dir_z = (float)d[2];
    rh->ray.tnear = (float)fmax(t0, 1e-4), rh->ray.tfar = (float)(t1 * (1.0 + 1e-6) + 1e-6);
    rh->ray.mask = 0xFFFFFFFFu, rh->ray.flags = 0, rh->ray.time = 0.0f;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID, rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return 2;
}

/* After Embree traced a patch's segment: 1 and *hit, or where the ray left the box: through the top (0), the
 * bottom (-1: through a hole, or a leak), a side (MS_LEFT) */
static int patch_after(const ms_tracer *t, const double o[3], const double d[3], int axis, const struct RTCRayHit *rh,
                       ms_hit *hit)
{
    if (rh->hit.geomID == RTC_INVALID_GEOMETRY_ID) return axis == 2 ? (d[2] > 0.0 ? 0 : -1) : MS_LEFT;
    double th = rh->ray.tfar, gx = rh->hit.Ng_x, gy = rh->hit.Ng_y, gz = rh->hit.Ng_z;
    double l = sqrt(gx * gx + gy * gy + gz * gz);
    if (gz < 0.0) l = -l;
    for (int k = 0; k < 3; k++) hit->p[k] = o[k] + th * d[k];
    hit->m[0] = gx / l, hit->m[1] = gy / l, hit->m[2] = gz / l;
    float fo[3] = {rh->ray.org_x, rh->ray.org_y, rh->ray.org_z}, fd[3] = {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z};
    hit->cell = patch_cell(t, fo, fd, th);
    return 1;
}

static int patch_trace(const ms_tracer *t, const double o[3], const double d[3], ms_hit *hit)
{
    struct RTCRayHit rh;
    struct RTCIntersectContext ctx;
    int axis, k = patch_segment(t, o, d, &rh, &axis);
    if (k != 2) return k;
    rtcInitIntersectContext(&ctx);
    rtcIntersect1(t->scene, &ctx, &rh);
    return patch_after(t, o, d, axis, &rh, hit);
}

static void patch_coherent(const ms_tracer *t, size_t count, const double *o, const double d[3], ms_hit *hits,
                           int *result)
{
    enum { M = 64 };
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (size_t first = 0; first < count; first += M) {
        size_t m = count - first < M ? count - first : M, live = 0, idx[M];
        struct RTCRayHit rh[M];
        int axis[M];
        for (size_t i = 0; i < m; i++) {
            int k = patch_segment(t, o + 3 * (first + i), d, &rh[live], &axis[live]);
            if (k != 2) result[first + i] = k;
            else idx[live++] = first + i;
        }
        rtcIntersect1M(t->scene, &ctx, rh, (unsigned)live, sizeof rh[0]);
        for (size_t i = 0; i < live; i++)
            result[idx[i]] = patch_after(t, o + 3 * idx[i], d, axis[i], &rh[i], &hits[idx[i]]);
    }
}

int ms_trace(const ms_tracer *t, const double o[3], const double d[3], ms_hit *hit)
{
    if (t->patch) return patch_trace(t, o, d, hit);
    walk w;
    walk_begin(t, o, d, &w);
    return walk_on(t, d, &w, hit);
}

void ms_trace_coherent(const ms_tracer *t, size_t count, const double *o, const double d[3], ms_hit *hits, int *result)
{
    if (t->patch) {
        patch_coherent(t, count, o, d, hits, result);
        return;
    }
    enum { M = 64 };
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (size_t first = 0; first < count; first += M) {
        size_t m = count - first < M ? count - first : M, live = 0;
        walk w[M];
        struct RTCRayHit rh[M];
        size_t idx[M];
        /* the first segments of up to M rays in one stream; a ray that goes on into the next tile then walks alone */
        for (size_t i = 0; i < m; i++) {
            walk_begin(t, o + 3 * (first + i), d, &w[i]);
            int k = walk_segment(t, d, &w[i], &rh[live]);
            if (k != 2) result[first + i] = k;
            else w[live] = w[i], idx[live++] = first + i;
        }
        rtcIntersect1M(t->scene, &ctx, rh, (unsigned)live, sizeof rh[0]);
        for (size_t i = 0; i < live; i++) {
            int k = walk_after(t, d, &w[i], &rh[i], &hits[idx[i]]);
            result[idx[i]] = k == 2 ? walk_on(t, d, &w[i], &hits[idx[i]]) : k;
        }
    }
}
#else
struct ms_tracer {
    int unused;
};
ms_tracer *ms_tracer_new(const double *h, size_t n, const double tilt[2], char *err, size_t errn)
{
    (void)h, (void)n, (void)tilt;
    snprintf(err, errn, "the microsurface tracer is not built (Embree not found: apt-get install libembree-dev)");
    return NULL;
}
void ms_tracer_free(ms_tracer *t) { free(t); }
ms_tracer *ms_patch_new(const double *h, size_t nx, size_t ny, char *err, size_t errn)
{
    (void)h, (void)nx, (void)ny;
    snprintf(err, errn, "the microsurface tracer is not built (Embree not found: apt-get install libembree-dev)");
    return NULL;
}
int ms_tracer_patch(const ms_tracer *t, size_t *nx, size_t *ny, const double **h, size_t *missing, size_t *absent)
{
    (void)t, (void)nx, (void)ny, (void)h, (void)missing, (void)absent;
    return 0;
}
int ms_patch_present(const ms_tracer *t, size_t x, size_t y)
{
    (void)t, (void)x, (void)y;
    return 0;
}
double ms_patch_top(const ms_tracer *t)
{
    (void)t;
    return 0.0;
}
int ms_patch_window(const ms_tracer *t, const double v[3], int reflect, double w[4], char *err, size_t errn)
{
    (void)t, (void)v, (void)reflect, (void)w;
    snprintf(err, errn, "the microsurface tracer is not built");
    return -1;
}
void ms_tracer_bounds(const ms_tracer *t, double *zmin, double *zmax)
{
    (void)t;
    *zmin = *zmax = 0.0;
}
void ms_tracer_tilt(const ms_tracer *t, double tilt[2])
{
    (void)t;
    tilt[0] = tilt[1] = 0.0;
}
double ms_tracer_crossings(const ms_tracer *t, const double d[3])
{
    (void)t, (void)d;
    return 1.0;
}
int ms_trace(const ms_tracer *t, const double o[3], const double d[3], ms_hit *hit)
{
    (void)t, (void)o, (void)d, (void)hit;
    return 0;
}
void ms_trace_coherent(const ms_tracer *t, size_t count, const double *o, const double d[3], ms_hit *hits, int *result)
{
    (void)t, (void)o, (void)d, (void)hits;
    for (size_t i = 0; i < count; i++) result[i] = 0;
}
#endif
