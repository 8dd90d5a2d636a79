/* Masking measured on a microsurface: G1(v) of its facets and the visible share of each normal bin by the tracer
 * (microsurface.h; docs/design/microsurface.md). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/parallel.h"
#include "microsurface.h"

static const double PI = 3.14159265358979323846;

double ms_beckmann_g1(const double cov[3], const double v[3])
{
    double r = hypot(v[0], v[1]);
    if (!(r > 0.0)) return 1.0;
    double c = v[0] / r, s = v[1] / r, a2 = 2.0 * (c * c * cov[0] + 2.0 * c * s * cov[1] + s * s * cov[2]);
    double a = v[2] / (r * sqrt(a2));
    return 1.0 / (1.0 + 0.5 * (erf(a) - 1.0) + exp(-a * a) / (2.0 * a * sqrt(PI)));
}

int ms_bin(const double m[3], int rings, int sectors)
{
    double s2 = m[0] * m[0] + m[1] * m[1], l2 = s2 + m[2] * m[2];
    int ring = (int)(s2 / l2 * rings);
    if (ring >= rings) ring = rings - 1;
    double phi = atan2(m[1], m[0]);
    if (phi < 0.0) phi += 2.0 * PI;
    int sector = (int)(phi / (2.0 * PI) * sectors);
    if (sector >= sectors) sector = sectors - 1;
    return ring * sectors + sector;
}

/* the next uniform in [0, 1) of a ray loop's xorshift stream */
int ms_ring_bin(const void *ctx, const double wo[3])
{
    const ms_ring_bins *r = ctx;
    return ms_bin(wo, r->rings, r->sectors);
}

ms_binning ms_ring_binning(ms_ring_bins *rb, int rings, int sectors)
{
    rb->rings = rings, rb->sectors = sectors;
    return (ms_binning){rings * sectors, ms_ring_bin, rb};
}

static double next_uniform(uint64_t *s)
{
    *s ^= *s << 13, *s ^= *s >> 7, *s ^= *s << 17;
    return (double)(*s >> 11) * 0x1p-53;
}

/* the seed of row r's stream of a ray loop (salt: the loop's own), nonzero: each row draws the same numbers
 * whichever thread traces it, so the result does not depend on the threads */
static uint64_t row_seed(uint64_t salt, long r)
{
    uint64_t z = salt + 0x9E3779B97F4A7C15ull * ((uint64_t)r + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return z ? z : 1;
}

/* the jobs of a ray loop: job k is jobs + k size bytes */
typedef struct job_array {
    void (*fn)(void *job);
    char *jobs;
    size_t size;
} job_array;

static void run_job(void *ctx, int k)
{
    const job_array *a = ctx;
    a->fn(a->jobs + a->size * (size_t)k);
}

/* runs fn over jobs[0 .. count) (each size bytes), one a thread, and waits for all */
static void run_jobs(void (*fn)(void *), void *jobs, size_t size, int count)
{
    job_array a = {fn, jobs, size};
    ggx_internal_parallel_for(count, run_job, &a);
}

/* the slopes of the two triangles of a cell of corners h00, h10, h01, h11: the lower-left (h10 - h00, h01 - h00),
 * the upper-right (h11 - h01, h11 - h10) */
static void corner_slopes(double h00, double h10, double h01, double h11, double s[2][2])
{
    s[0][0] = h10 - h00, s[0][1] = h01 - h00;
    s[1][0] = h11 - h01, s[1][1] = h11 - h10;
}

/* the slopes of the two triangles of cell (x, y), the heights across the tile's sides raised by the tilt times n
 * (tilt may be NULL: none) */
static void cell_slopes(const double *h, size_t n, const double *tilt, size_t x, size_t y, double s[2][2])
{
    size_t x1 = (x + 1) % n, y1 = (y + 1) % n;
    double ex = tilt && x1 == 0 ? tilt[0] * (double)n : 0.0, ey = tilt && y1 == 0 ? tilt[1] * (double)n : 0.0;
    corner_slopes(h[y * n + x], h[y * n + x1] + ex, h[y1 * n + x] + ey, h[y1 * n + x1] + ex + ey, s);
}

/* the slopes of the two triangles of cell (x, y) of a patch of nx heights a row (no wrap: x + 1 < nx, and the row
 * above exists) */
static void patch_slopes(const double *h, size_t nx, size_t x, size_t y, double s[2][2])
{
    const double *p = h + y * nx + x;
    corner_slopes(p[0], p[1], p[nx], p[nx + 1], s);
}

static void normal_of(const double s[2], double m[3])
{
    double l = sqrt(1.0 + s[0] * s[0] + s[1] * s[1]);
    m[0] = -s[0] / l, m[1] = -s[1] / l, m[2] = 1.0 / l;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int ms_find_risers(const double *h, size_t n, size_t P, size_t risers[2], char *err, size_t errn)
{
    risers[0] = risers[1] = 0;
    if (P == 0) return 0;
    if (P < 2 || n % P != 0 || P > n / 2) {
        snprintf(err, errn, "masking: a sawtooth's period must divide the size and be from 2 to half of it");
        return -1;
    }
    double *col = malloc(n * sizeof *col), *med = malloc(n * sizeof *med), *off = malloc(n * sizeof *off);
    if (!col || !med || !off) {
        free(col), free(med), free(off);
        snprintf(err, errn, "masking: out of memory");
        return -1;
    }
    int ok = 1;
    for (int ax = 0; ax < 2 && ok; ax++) {
        size_t k = 0, steps_on = 0, steps_off = 0;
        for (size_t i = 0; i < n; i++) {
            for (size_t j = 0; j < n; j++)
                col[j] = ax == 0 ? h[j * n + (i + 1) % n] - h[j * n + i] : h[((i + 1) % n) * n + j] - h[i * n + j];
            qsort(col, n, sizeof *col, cmp_double);
            med[i] = 0.5 * (col[(n - 1) / 2] + col[n / 2]);
            if (i % P != P - 1) off[k++] = med[i];
        }
        qsort(off, k, sizeof *off, cmp_double);
        double base = 0.5 * (off[(k - 1) / 2] + off[k / 2]);
        for (size_t i = 0; i < n; i++) {
            int step = fabs(med[i] - base) > 1.0;
            if (i % P == P - 1) steps_on += (size_t)step;
            else steps_off += (size_t)step;
        }
        risers[ax] = steps_on == n / P ? P : 0;
        ok = steps_off == 0 && (steps_on == 0 || steps_on == n / P);
    }
    free(col), free(med), free(off);
    if (!ok) {
        risers[0] = risers[1] = 0;
        snprintf(err, errn,
                 "masking: not a sawtooth of period %zu: steps steeper than 45 degrees in other columns or "
                 "rows than %zu mod %zu, or in only some of those",
                 P, P - 1, P);
        return -1;
    }
    if (!risers[0] && !risers[1]) {
        snprintf(err, errn, "masking: no risers of period %zu: the columns and rows %zu mod %zu step like the others",
                 P, P - 1, P);
        return -1;
    }
    return 0;
}


/* the footprint's projected area towards v per unit tile area: v.z, less the tilt's share */
static double footprint(const double *tilt, const double v[3])
{
    return tilt ? v[2] - tilt[0] * v[0] - tilt[1] * v[1] : v[2];
}

int ms_view_clear(const double tilt[2], const double v[3])
{
    double z = footprint(tilt, v);
    return z > 1e-3 * sqrt(v[0] * v[0] + v[1] * v[1] + z * z);
}

int ms_riser_cell(const size_t risers[2], size_t n, size_t cell)
{
    size_t x = cell % n, y = cell / n, px = risers[0], py = risers[1];
    return (px >= 2 && x % px == px - 1) || (py >= 2 && y % py == py - 1);
}

size_t ms_facet_normals(const double *h, size_t n, const size_t risers[2], ggx_vec3 *m)
{
    size_t k = 0;
    for (size_t y = 0; y + 1 < n; y++)
        for (size_t x = 0; x + 1 < n; x++) {
            if (ms_riser_cell(risers, n, y * n + x)) continue;
            double h00 = h[y * n + x], h10 = h[y * n + x + 1], h01 = h[(y + 1) * n + x], h11 = h[(y + 1) * n + x + 1];
            double sx[2] = {h10 - h00, h11 - h01}, sy[2] = {h01 - h00, h11 - h10};
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++) {
                    double l = sqrt(1.0 + sx[a] * sx[a] + sy[b] * sy[b]);
                    m[k++] = (ggx_vec3){-sx[a] / l, -sy[b] / l, 1.0 / l};
                }
        }
    return k;
}

/* the running sums of facets' projected areas towards v and slope moments */
typedef struct facet_sums {
    double total, cnt, mx, my, sxx, sxy, syy;
} facet_sums;

/* one facet of slope s (projected area 1/2) into the sums, its front-facing projected area towards v into
 * area[bin] times scale (area may be NULL); returns that area (0 where it faces away) */
static double facet_add(facet_sums *f, const double s[2], const double v[3], int rings, int sectors, double *area,
                        double scale)
{
    double a = fmax(0.5 * (v[2] - s[0] * v[0] - s[1] * v[1]), 0.0), m[3];
    f->total += a, f->cnt += 1.0, f->mx += s[0], f->my += s[1];
    f->sxx += s[0] * s[0], f->sxy += s[0] * s[1], f->syy += s[1] * s[1];
    if (a > 0.0 && area) {
        normal_of(s, m);
        area[ms_bin(m, rings, sectors)] += a * scale;
    }
    return a;
}

/* the slopes' mean and covariance of the sums (either may be NULL) */
static void facet_moments(const facet_sums *f, double mean[2], double cov[3])
{
    double mx = f->mx / f->cnt, my = f->my / f->cnt;
    if (mean) mean[0] = mx, mean[1] = my;
    if (cov) cov[0] = f->sxx / f->cnt - mx * mx, cov[1] = f->sxy / f->cnt - mx * my, cov[2] = f->syy / f->cnt - my * my;
}

/* the facets off the risers: their projected area towards v per bin (area may be NULL) and their slopes' mean and
 * covariance (mean, cov may be NULL); the risers' projected area towards v (riser may be NULL); G1 of all facets */
static void facets_towards(const double *h, size_t n, const double *tilt, const size_t risers[2], const double v[3],
                           int rings, int sectors, double *area, double mean[2], double cov[3], double *riser,
                           double *g1)
{
    facet_sums off = {0}, on = {0};
    double tile = (double)n * (double)n;
    for (size_t y = 0; y < n; y++)
        for (size_t x = 0; x < n; x++) {
            double sl[2][2];
            int vertical = ms_riser_cell(risers, n, y * n + x);
            cell_slopes(h, n, tilt, x, y, sl);
            for (int k = 0; k < 2; k++)
                facet_add(vertical ? &on : &off, sl[k], v, rings, sectors, vertical ? NULL : area, 1.0 / tile);
        }
    facet_moments(&off, mean, cov);
    if (riser) *riser = on.total / tile;
    *g1 = tile * footprint(tilt, v) / (off.total + on.total);
}

double ms_facets_g1(const double *h, size_t n, const double tilt[2], const double v[3])
{
    double g1;
    const size_t none[2] = {0, 0};
    facets_towards(h, n, tilt, none, v, 1, 1, NULL, NULL, NULL, NULL, &g1);
    return g1;
}

/* 1 with err where rays along v (times passes) would cross more tiles than MS_MAX_CROSSINGS: the tracer's work */
static int work_refused(const ms_tracer *t, size_t n, const double v[3], long rays, double passes, const char *what,
                        char *err, size_t errn)
{
    double per = ms_tracer_crossings(t, v), g = ceil(sqrt((double)rays)), work = g * g * per * passes;
    if (work <= MS_MAX_CROSSINGS) return 0;
    double zmin, zmax, side = floor(sqrt(MS_MAX_CROSSINGS / (per * passes))); /* the grid of rays that fits */
    ms_tracer_bounds(t, &zmin, &zmax);
    char fewer[64] = "";
    if (side >= 1.0) snprintf(fewer, sizeof fewer, "at most %.0f rays, ", side * side);
    snprintf(err, errn,
             "%s: the heights span %.3g spacings over a tile of %zu, so each ray at this view crosses about %.3g "
             "tiles: %.3g crossings for %.0f rays, more than the %.3g the tracer takes on (give %sa steeper view, "
             "or a tile without its outliers)",
             what, zmax - zmin, n, per, work, g * g, MS_MAX_CROSSINGS, fewer);
    return 1;
}

/* where a ray loop's rays start: a tile's jittered grid over [0, n)^2 at zmax + 1, or a patch's over its window at
 * ms_patch_top (its own streams: a patch's rays are independent of a tile's) */
typedef struct ray_grid {
    double x0, y0, sx, sy, z;
    uint64_t salt;
    int patch;
} ray_grid;

static ray_grid grid_of(const ms_tracer *t, size_t n, const double *win, long g, uint64_t salt)
{
    double zmin, zmax;
    ms_tracer_bounds(t, &zmin, &zmax);
    ray_grid rg = {0.0, 0.0, (double)n / (double)g, (double)n / (double)g, zmax + 1.0, salt, 0};
    if (win)
        rg = (ray_grid){win[0], win[1], (win[2] - win[0]) / (double)g, (win[3] - win[1]) / (double)g, ms_patch_top(t),
                        ~salt,  1};
    return rg;
}

typedef struct g1_job {
    const ms_tracer *t;
    const double *h;
    size_t n; /* the tile's size, or a patch's nx (its cells' stride) */
    const double *v, *tilt;
    const size_t *risers;
    ray_grid rg;
    long g, row0, row1;
    int bins, rings, sectors;
    long *hits, missed, riser_hits, left, holes;
    int failed; /* no memory for a row */
} g1_job;

static void g1_rows(void *p)
{
    g1_job *j = p;
    double d[3] = {-j->v[0], -j->v[1], -j->v[2]};
    uint64_t s;
    size_t g = (size_t)j->g;
    double *o = malloc(3 * g * sizeof *o);
    ms_hit *hits = malloc(g * sizeof *hits);
    int *res = malloc(g * sizeof *res);
    if (!o || !hits || !res) {
        free(o), free(hits), free(res);
        j->failed = 1;
        return;
    }
    for (long r = j->row0; r < j->row1; r++) {
        /* a row of the jittered grid, traced as one stream of coherent rays */
        s = row_seed(j->rg.salt, r);
        for (size_t c = 0; c < g; c++) {
            double u = next_uniform(&s), w = next_uniform(&s);
            o[3 * c] = j->rg.x0 + ((double)c + u) * j->rg.sx, o[3 * c + 1] = j->rg.y0 + ((double)r + w) * j->rg.sy;
            o[3 * c + 2] = j->rg.z;
        }
        ms_trace_coherent(j->t, g, o, d, hits, res);
        for (size_t c = 0; c < g; c++) {
            if (res[c] != 1) {
                j->missed++;
                if (res[c] == MS_LEFT) j->left++;
                else if (j->rg.patch) j->holes++;
                continue;
            }
            ms_hit *hit = &hits[c];
            size_t cx = hit->cell % j->n, cy = hit->cell / j->n;
            if (ms_riser_cell(j->risers, j->n, hit->cell)) {
                j->riser_hits++;
                continue;
            }
            double fx = hit->p[0] - (double)cx, fy = hit->p[1] - (double)cy, sl[2][2], m[3];
            if (j->rg.patch) patch_slopes(j->h, j->n, cx, cy, sl);
            else cell_slopes(j->h, j->n, j->tilt, cx, cy, sl);
            normal_of(sl[fx + fy < 1.0 ? 0 : 1], m);
            j->hits[ms_bin(m, j->rings, j->sectors)]++;
        }
    }
    free(o), free(hits), free(res);
}

void ms_g1_free(ms_g1 *r)
{
    free(r->area);
    r->area = r->visible = NULL;
}

/* the checks both kinds of G1 share; 0 or -1 with err */
static int g1_args(const double v[3], long rays, int rings, int sectors, int threads, char *err, size_t errn)
{
    if (!(v[2] > 0.0) || rays < 1 || rings < 1 || sectors < 1 || rings * sectors > 1 << 16 || threads < 1 ||
        threads > 256) {
        snprintf(err, errn, "masking: a view above the plane, rays, bins and threads are required");
        return -1;
    }
    return 0;
}

/* traces proto's rays (g x g, rows split among threads) into r: visible (foot, the footprint's projected area per unit
 * area, times each bin's share of the rays), rays, missed, left, holes, g1_off_risers (against r->area), riser_visible;
 * 0, or -1 with err (no memory: r freed) */
static int g1_trace(const g1_job *proto, int threads, double foot, ms_g1 *r, char *err, size_t errn)
{
    int bins = proto->bins;
    long g = proto->g;
    if (threads > g) threads = (int)g;
    long *hits = calloc((size_t)bins * (size_t)threads, sizeof *hits);
    g1_job *jobs = calloc((size_t)threads, sizeof *jobs);
    int failed = !hits || !jobs;
    for (int k = 0; !failed && k < threads; k++) {
        jobs[k] = *proto;
        jobs[k].row0 = g * k / threads, jobs[k].row1 = g * (k + 1) / threads;
        jobs[k].hits = hits + (size_t)k * (size_t)bins;
    }
    if (!failed) run_jobs(g1_rows, jobs, sizeof *jobs, threads);
    for (int k = 0; !failed && k < threads; k++) failed |= jobs[k].failed;
    if (failed) {
        free(hits), free(jobs), ms_g1_free(r);
        snprintf(err, errn, "masking: out of memory");
        return -1;
    }
    r->rays = g * g;
    /* each ray's projected area, per unit area of the tile (or window) it starts over */
    double per = foot / (double)r->rays, seen = 0.0, front = 0.0;
    long riser_hits = 0;
    /* the threads' counts summed as integers first: the same sums in any order */
    for (int k = 0; k < threads; k++) {
        r->missed += jobs[k].missed, riser_hits += jobs[k].riser_hits;
        r->left += jobs[k].left, r->holes += jobs[k].holes;
        if (k > 0)
            for (int b = 0; b < bins; b++) hits[b] += hits[(size_t)k * (size_t)bins + (size_t)b];
    }
    for (int b = 0; b < bins; b++) r->visible[b] = per * (double)hits[b];
    for (int b = 0; b < bins; b++) seen += r->visible[b], front += r->area[b];
    r->riser_visible = per * (double)riser_hits;
    r->g1_off_risers = seen / front;
    free(hits), free(jobs);
    return 0;
}

/* r's bins (area, visible), zeroed; 0 or -1 with err */
static int g1_alloc(ms_g1 *r, int rings, int sectors, char *err, size_t errn)
{
    int bins = rings * sectors;
    r->rings = rings, r->sectors = sectors;
    r->area = calloc(2 * (size_t)bins, sizeof *r->area);
    if (!r->area) {
        snprintf(err, errn, "masking: out of memory");
        return -1;
    }
    r->visible = r->area + bins;
    return 0;
}

int ms_measure_g1(const ms_tracer *t, const double *h, size_t n, const double v[3], long rays, int rings, int sectors,
                  const size_t risers[2], int threads, ms_g1 *r, char *err, size_t errn)
{
    if (ms_tracer_patch(t, NULL, NULL, NULL, NULL, NULL)) {
        memset(r, 0, sizeof *r);
        if (risers && (risers[0] || risers[1])) {
            snprintf(err, errn, "masking: a patch has no risers");
            return -1;
        }
        return ms_patch_g1(t, v, NULL, rays, rings, sectors, threads, r, err, errn);
    }
    memset(r, 0, sizeof *r);
    double tilt[2];
    ms_tracer_tilt(t, tilt);
    if (risers) r->risers[0] = risers[0], r->risers[1] = risers[1];
    if (!ms_view_clear(tilt, v)) {
        snprintf(err, errn,
                 "masking: the view must be at least 0.06 degrees above the %splane (rays that graze it "
                 "cross tiles without end)",
                 tilt[0] != 0.0 || tilt[1] != 0.0 ? "tilted " : "");
        return -1;
    }
    if (g1_args(v, rays, rings, sectors, threads, err, errn) != 0) return -1;
    if (work_refused(t, n, v, rays, 1.0, "masking", err, errn)) return -1;
    if (g1_alloc(r, rings, sectors, err, errn) != 0) return -1;
    r->window[2] = r->window[3] = (double)n;
    facets_towards(h, n, tilt, r->risers, v, rings, sectors, r->area, r->slope_mean, r->slope_cov, &r->riser_area,
                   &r->g1);
    long g = (long)ceil(sqrt((double)rays));
    /* the rays from above the tile see the footprint of one tile (of a tilted patch too: its surface repeats, tile
     * after tile, under parallel rays) */
    g1_job proto = {.t = t,
                    .h = h,
                    .n = n,
                    .v = v,
                    .tilt = tilt,
                    .risers = r->risers,
                    .g = g,
                    .rg = grid_of(t, n, NULL, g, 0x9E3779B97F4A7C15ull),
                    .bins = rings * sectors,
                    .rings = rings,
                    .sectors = sectors};
    return g1_trace(&proto, threads, footprint(tilt, v), r, err, errn);
}

/* a band of a patch's rows for patch_facets: its sums, cells and bins */
typedef struct facet_band {
    const ms_tracer *t;
    const double *h, *v;
    size_t nx, x0, x1, y0, y1, cells, present;
    int rings, sectors;
    facet_sums f;
    double *area;
} facet_band;

/* the bands k, k + stride, ... of a band array (one thread's share) */
typedef struct band_share {
    facet_band *bands;
    int count, stride;
} band_share;

static void band_rows(void *p, int k)
{
    const band_share *sh = p;
    for (int i = k; i < sh->count; i += sh->stride) {
        facet_band *b = &sh->bands[i];
        for (size_t y = b->y0; y < b->y1; y++)
            for (size_t x = b->x0; x < b->x1; x++) {
                b->cells++;
                if (!ms_patch_present(b->t, x, y)) continue;
                b->present++;
                double sl[2][2];
                patch_slopes(b->h, b->nx, x, y, sl);
                for (int q = 0; q < 2; q++) facet_add(&b->f, sl[q], b->v, b->rings, b->sectors, b->area, 1.0);
            }
    }
}

/* the facets of the present cells of a patch whose centres lie in w, as facets_towards: area per bin and g1 over
 * the count of all the cells there, the footprint that of their mean slope; in at most 64 bands of rows on threads
 * threads, summed in the bands' order (the same for any threads); 0, or -1 with err where no present cell lies in w
 * or there is no memory */
static int patch_facets(const ms_tracer *t, const double w[4], const double v[3], int threads, ms_g1 *r, char *err,
                        size_t errn)
{
    size_t nx, ny, cells = 0, present = 0, bins = (size_t)r->rings * (size_t)r->sectors;
    const double *h;
    ms_tracer_patch(t, &nx, &ny, &h, NULL, NULL);
    size_t x0 = (size_t)fmax(ceil(w[0] - 0.5), 0.0), y0 = (size_t)fmax(ceil(w[1] - 0.5), 0.0);
    size_t x1 = (size_t)fmin(floor(w[2] - 0.5) + 1.0, (double)(nx - 1));
    size_t y1 = (size_t)fmin(floor(w[3] - 0.5) + 1.0, (double)(ny - 1)), rows = y1 > y0 ? y1 - y0 : 0;
    size_t per = rows / 64 + 1, count = (rows + per - 1) / per;
    facet_band *bands = calloc(count ? count : 1, sizeof *bands);
    double *area = calloc((count ? count : 1) * bins, sizeof *area);
    if (!bands || !area) {
        free(bands), free(area);
        snprintf(err, errn, "masking: out of memory");
        return -1;
    }
    for (size_t i = 0; i < count; i++)
        bands[i] = (facet_band){.t = t,
                                .h = h,
                                .v = v,
                                .nx = nx,
                                .x0 = x0,
                                .x1 = x1,
                                .y0 = y0 + i * per,
                                .y1 = y0 + (i + 1) * per < y1 ? y0 + (i + 1) * per : y1,
                                .rings = r->rings,
                                .sectors = r->sectors,
                                .area = area + i * bins};
    band_share sh = {bands, (int)count, threads < (int)count ? threads : (int)count};
    ggx_internal_parallel_for(sh.stride, band_rows, &sh);
    facet_sums f = {0};
    for (size_t i = 0; i < count; i++) {
        const facet_sums *g = &bands[i].f;
        cells += bands[i].cells, present += bands[i].present;
        f.total += g->total, f.cnt += g->cnt, f.mx += g->mx, f.my += g->my;
        f.sxx += g->sxx, f.sxy += g->sxy, f.syy += g->syy;
        for (size_t b = 0; b < bins; b++) r->area[b] += bands[i].area[b];
    }
    free(bands), free(area);
    if (!present) {
        snprintf(err, errn, "masking: no present cell of the patch has its centre in the window");
        return -1;
    }
    for (size_t b = 0; b < bins; b++) r->area[b] /= (double)cells;
    facet_moments(&f, r->slope_mean, r->slope_cov);
    /* a patch keeps the tilt it was measured with: its mean slope's footprint, as a tilted tile's */
    r->g1 = (double)present * footprint(r->slope_mean, v) / f.total;
    return 0;
}

/* 0 where w is a rectangle of at least one cell inside the patch, else -1 with err */
static int window_ok(const ms_tracer *t, const double w[4], const char *what, char *err, size_t errn)
{
    size_t nx, ny;
    ms_tracer_patch(t, &nx, &ny, NULL, NULL, NULL);
    if (w[0] >= 0.0 && w[1] >= 0.0 && w[2] <= (double)(nx - 1) && w[3] <= (double)(ny - 1) && w[2] - w[0] >= 1.0 &&
        w[3] - w[1] >= 1.0)
        return 0;
    snprintf(err, errn,
             "%s: the window [%g, %g] x [%g, %g] is not a rectangle of a cell or more inside the %zu x %zu "
             "patch",
             what, w[0], w[2], w[1], w[3], nx, ny);
    return -1;
}

int ms_patch_g1(const ms_tracer *t, const double v[3], const double w[4], long rays, int rings, int sectors,
                int threads, ms_g1 *r, char *err, size_t errn)
{
    memset(r, 0, sizeof *r);
    size_t nx;
    const double *h;
    if (!ms_tracer_patch(t, &nx, NULL, &h, NULL, NULL)) {
        snprintf(err, errn, "masking: ms_patch_g1 takes a patch (ms_patch_new)");
        return -1;
    }
    if (g1_args(v, rays, rings, sectors, threads, err, errn) != 0) return -1;
    if (!ms_view_clear(NULL, v)) {
        snprintf(err, errn, "masking: the view must be at least 0.06 degrees above the plane");
        return -1;
    }
    if (w) memcpy(r->window, w, sizeof r->window);
    else if (ms_patch_window(t, v, 0, r->window, err, errn) != 0) return -1;
    if (window_ok(t, r->window, "masking", err, errn) != 0) return -1;
    if (g1_alloc(r, rings, sectors, err, errn) != 0) return -1;
    if (patch_facets(t, r->window, v, threads, r, err, errn) != 0) {
        ms_g1_free(r);
        return -1;
    }
    long g = (long)ceil(sqrt((double)rays));
    g1_job proto = {.t = t,
                    .h = h,
                    .n = nx,
                    .v = v,
                    .risers = r->risers,
                    .g = g,
                    .rg = grid_of(t, nx, r->window, g, 0x9E3779B97F4A7C15ull),
                    .bins = rings * sectors,
                    .rings = rings,
                    .sectors = sectors};
    return g1_trace(&proto, threads, footprint(r->slope_mean, v), r, err, errn);
}

typedef struct brdf_job {
    const ms_tracer *t;
    size_t n;
    const double *wi; /* NULL: each ray's wi uniform in projected solid angle over the bin in_bin */
    int in_bin;
    ray_grid rg;
    long g, row0, row1;
    int rings, sectors, max_bounces; /* rings, sectors: in_bin's binning */
    const ms_binning *out;           /* the outgoing directions' */
    long *single, *all, lost, capped, left;
    int failed; /* no memory for a row */
} brdf_job;

/* one ray from o along d, whose first trace gave k and *hit: reflected until it escapes (at most max_bounces times),
 * then tallied */
static void brdf_follow(brdf_job *j, double o[3], double d[3], int k, ms_hit *hit)
{
    int bounces = 0;
    while (k == 1 && bounces < j->max_bounces) {
        double dm = d[0] * hit->m[0] + d[1] * hit->m[1] + d[2] * hit->m[2];
        /* reflect; the next ray from just above the facet (the hit carries single precision) */
        for (int q = 0; q < 3; q++) d[q] -= 2.0 * dm * hit->m[q], o[q] = hit->p[q] + 1e-3 * hit->m[q];
        bounces++;
        k = ms_trace(j->t, o, d, hit);
    }
    if (k == MS_LEFT) j->left++;
    else if (k < 0) j->lost++;
    else if (k == 1) j->capped++;
    else if (bounces > 0) { /* (none is 0: every ray from above hits) */ int b = j->out->bin(j->out->ctx, d);
        if (b >= 0 && b < j->out->bins) {
            j->all[b]++;
            if (bounces == 1) j->single[b]++;
        }
    }
}

static void brdf_rows(void *p)
{
    brdf_job *j = p;
    size_t g = (size_t)j->g;
    double *o = malloc(6 * g * sizeof *o), *d = o ? o + 3 * g : NULL;
    ms_hit *hits = malloc(g * sizeof *hits);
    int *res = malloc(g * sizeof *res);
    if (!o || !hits || !res) {
        free(o), free(hits), free(res);
        j->failed = 1;
        return;
    }
    for (long r = j->row0; r < j->row1; r++) {
        uint64_t s = row_seed(j->rg.salt, r);
        for (size_t c = 0; c < g; c++) {
            double u = next_uniform(&s), w = next_uniform(&s), *oc = o + 3 * c, *dc = d + 3 * c;
            oc[0] = j->rg.x0 + ((double)c + u) * j->rg.sx, oc[1] = j->rg.y0 + ((double)r + w) * j->rg.sy;
            oc[2] = j->rg.z;
            if (j->wi) {
                dc[0] = -j->wi[0], dc[1] = -j->wi[1], dc[2] = -j->wi[2];
            } else {
                double a = next_uniform(&s), b = next_uniform(&s);
                double q = ((double)(j->in_bin / j->sectors) + a) / j->rings;
                double ph = 2.0 * PI * ((double)(j->in_bin % j->sectors) + b) / j->sectors;
                dc[0] = -sqrt(q) * cos(ph), dc[1] = -sqrt(q) * sin(ph), dc[2] = -sqrt(1.0 - q);
            }
        }
        /* one light: the row's first segments as one stream of coherent rays (the same hits as one at a time) */
        if (j->wi) ms_trace_coherent(j->t, g, o, d, hits, res);
        for (size_t c = 0; c < g; c++) {
            int k = j->wi ? res[c] : ms_trace(j->t, o + 3 * c, d + 3 * c, &hits[c]);
            brdf_follow(j, o + 3 * c, d + 3 * c, k, &hits[c]);
        }
    }
    free(o), free(hits), free(res);
}

void ms_brdf_free(ms_brdf *r)
{
    free(r->single);
    r->single = r->all = NULL;
}

/* the BRDF of rays from wi (NULL: from bin in_bin) over the tile, or over a patch's window win */
static int brdf_run(const ms_tracer *t, size_t n, const double *wi, int in_bin, const double *win, long rays,
                    const ms_binning *out, int rings, int sectors, int max_bounces, int threads, ms_brdf *r, char *err,
                    size_t errn)
{
    int bad_wi = wi ? !(wi[2] > 0.0) : in_bin < 0 || in_bin >= rings * sectors;
    if (bad_wi || rays < 1 || out->bins < 1 || out->bins > 1 << 24 || threads < 1 || threads > 256 || max_bounces < 1) {
        snprintf(err, errn, "BRDF: a light above the plane, rays, bins, bounces and threads are required");
        return -1;
    }
    if (!win && wi && work_refused(t, n, wi, rays, 2.0, "BRDF", err, errn)) return -1;
    int bins = out->bins;
    long g = (long)ceil(sqrt((double)rays));
    if (threads > g) threads = (int)g;
    r->rings = rings, r->sectors = sectors, r->rays = g * g;
    r->single = calloc(2 * (size_t)bins, sizeof *r->single);
    long *counts = calloc(2 * (size_t)bins * (size_t)threads, sizeof *counts);
    brdf_job *jobs = calloc((size_t)threads, sizeof *jobs);
    if (!r->single || !counts || !jobs) {
        free(counts), free(jobs), ms_brdf_free(r);
        snprintf(err, errn, "BRDF: out of memory");
        return -1;
    }
    r->all = r->single + bins;
    for (int k = 0; k < threads; k++) {
        long *c = counts + 2 * (size_t)bins * (size_t)k;
        jobs[k] = (brdf_job){.t = t,
                             .n = n,
                             .wi = wi,
                             .in_bin = in_bin,
                             .rg = grid_of(t, n, win, g, 0xD1B54A32D192ED03ull),
                             .g = g,
                             .row0 = g * k / threads,
                             .row1 = g * (k + 1) / threads,
                             .rings = rings,
                             .sectors = sectors,
                             .max_bounces = max_bounces,
                             .out = out,
                             .single = c,
                             .all = c + bins};
    }
    run_jobs(brdf_rows, jobs, sizeof *jobs, threads);
    int failed = 0;
    for (int k = 0; k < threads; k++) failed |= jobs[k].failed;
    if (failed) {
        free(counts), free(jobs), ms_brdf_free(r);
        snprintf(err, errn, "BRDF: out of memory");
        return -1;
    }
    /* the threads' counts summed as integers first: the same sums in any order */
    for (int k = 0; k < threads; k++) {
        r->lost += jobs[k].lost, r->capped += jobs[k].capped, r->left += jobs[k].left;
        if (k > 0)
            for (int b = 0; b < bins; b++) jobs[0].single[b] += jobs[k].single[b], jobs[0].all[b] += jobs[k].all[b];
    }
    for (int b = 0; b < bins; b++) {
        r->single[b] = (double)jobs[0].single[b] / (double)r->rays;
        r->all[b] = (double)jobs[0].all[b] / (double)r->rays;
    }
    free(counts), free(jobs);
    return 0;
}

int ms_measure_brdf(const ms_tracer *t, size_t n, const double wi[3], long rays, int rings, int sectors,
                    int max_bounces, int threads, ms_brdf *r, char *err, size_t errn)
{
    if (ms_tracer_patch(t, NULL, NULL, NULL, NULL, NULL))
        return ms_patch_brdf(t, wi, NULL, rays, rings, sectors, max_bounces, threads, r, err, errn);
    memset(r, 0, sizeof *r);
    r->window[2] = r->window[3] = (double)n;
    ms_ring_bins rb;
    ms_binning out = ms_ring_binning(&rb, rings, sectors);
    return brdf_run(t, n, wi, -1, NULL, rays, &out, rings, sectors, max_bounces, threads, r, err, errn);
}

int ms_patch_brdf_binned(const ms_tracer *t, const double wi[3], const double w[4], long rays, const ms_binning *out,
                         int max_bounces, int threads, ms_brdf *r, char *err, size_t errn)
{
    memset(r, 0, sizeof *r);
    size_t nx;
    if (!ms_tracer_patch(t, &nx, NULL, NULL, NULL, NULL)) {
        snprintf(err, errn, "BRDF: ms_patch_brdf takes a patch (ms_patch_new)");
        return -1;
    }
    if (!(wi[2] > 0.0) || !ms_view_clear(NULL, wi)) {
        snprintf(err, errn, "BRDF: the light must be at least 0.06 degrees above the plane");
        return -1;
    }
    if (w) memcpy(r->window, w, sizeof r->window);
    else if (ms_patch_window(t, wi, 1, r->window, err, errn) != 0) return -1;
    if (window_ok(t, r->window, "BRDF", err, errn) != 0) return -1;
    double win[4];
    memcpy(win, r->window, sizeof win);
    int st = brdf_run(t, nx, wi, -1, win, rays, out, 1, 1, max_bounces, threads, r, err, errn);
    r->rings = out->bins, r->sectors = 1;
    return st;
}

int ms_patch_brdf(const ms_tracer *t, const double wi[3], const double w[4], long rays, int rings, int sectors,
                  int max_bounces, int threads, ms_brdf *r, char *err, size_t errn)
{
    if (rings < 1 || sectors < 1) {
        memset(r, 0, sizeof *r);
        snprintf(err, errn, "BRDF: a light above the plane, rays, bins, bounces and threads are required");
        return -1;
    }
    ms_ring_bins rb;
    ms_binning out = ms_ring_binning(&rb, rings, sectors);
    int st = ms_patch_brdf_binned(t, wi, w, rays, &out, max_bounces, threads, r, err, errn);
    r->rings = rings, r->sectors = sectors;
    return st;
}

int ms_measure_brdf_from_bin(const ms_tracer *t, size_t n, int bin, long rays, int rings, int sectors, int max_bounces,
                             int threads, ms_brdf *r, char *err, size_t errn)
{
    memset(r, 0, sizeof *r);
    if (ms_tracer_patch(t, NULL, NULL, NULL, NULL, NULL)) {
        snprintf(err, errn, "BRDF: the light from a bin takes a tile (a patch's window depends on each ray's light)");
        return -1;
    }
    r->window[2] = r->window[3] = (double)n;
    if (rings < 1 || sectors < 1) {
        snprintf(err, errn, "BRDF: a light above the plane, rays, bins, bounces and threads are required");
        return -1;
    }
    ms_ring_bins rb;
    ms_binning out = ms_ring_binning(&rb, rings, sectors);
    return brdf_run(t, n, NULL, bin, NULL, rays, &out, rings, sectors, max_bounces, threads, r, err, errn);
}
