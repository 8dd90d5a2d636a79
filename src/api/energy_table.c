/* The albedo table of the energy compensation: E(v) over the upper hemisphere, its interpolation, and the sampling
 * distribution of the multiple-scattering lobe built on its cells (docs/design/energy.md). SPDX-License-Identifier: MIT
 *
 * E = P(v) I(v) (internal.h): P is closed-form and carries E's steep dependence on the view at grazing and the kink
 * of Walter's min through n for skewed shapes; the table holds I at nodes
 *   mu = sin(pi y^2 / 2), y = i / (t->nm - 1)        (theta = (pi / 2)(1 - y^2): dense towards grazing, and linear in
 *                                                  theta at the pole, where I is smooth in the view's components)
 *   phi = phi0 + W(2 pi j / np)                   (phi0: the axis of alpha_x for unskewed shapes; W the columns'
 *                                                  warp of common/albedo_rows.h, denser at the tangent axes, for
 *                                                  the conductor's unskewed shapes, else the identity)
 * and is read by Catmull-Rom interpolation in (y, phi). Across the pole a column continues as the opposite column
 * (the view at (y, phi) beyond y = 1 is the view at (2 - y, phi + pi)), so the pole needs no special case; below
 * y = 0 the rows are extrapolated. Isotropic shapes need one column, unskewed ones a quarter turn (E is even about
 * both tangent axes), skewed ones a full turn.
 *
 * Sampling: the cosine-weighted measure is uniform in (t, phi) with t = mu^2 (w.z dw = dt dphi / 2); each table cell
 * [y_i, y_i+1] x [phi_j, phi_j+1] is a sampling cell with weight int (1 - E) dt dphi (4 x 4 Gauss-Legendre in
 * (y, phi)), drawn from their cumulative sum, and uniform in (t, phi) inside: a piecewise-constant pdf, exact for
 * what it draws, close to the lobe's shape. The sum of the weights also gives E_avg of the interpolant, so that the
 * lobe (1 - E(wi)) (1 - E(wo)) / (pi (1 - E_avg)) integrates to 1 - E(wi) up to the cells' quadrature. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

#include "common/albedo_rows.h"
#include "common/gauss.h"
#include "common/interp.h"
#include "energy_table.h"

enum { CELL_GL = 4 };

static double cell_x[CELL_GL], cell_w[CELL_GL];
static pthread_once_t once = PTHREAD_ONCE_INIT;
static void init_rule(void) { gq_nodes(CELL_GL, cell_x, cell_w); }

static double mu_of_y(double y) { return sin(0.5 * GGX_PI * y * y); }

/* The azimuth of column coordinate q (in columns, any real): phi0 + W(2 pi q / np). */
static double phi_of_col(const energy_table *t, double q)
{
    double psi = 2.0 * GGX_PI * q / t->np;
    return t->phi0 + (t->warp == 1.0 ? psi : cols_phi_of_psi(psi, t->warp));
}

static ggx_vec3 view_at(double y, double phi)
{
    double th = rows_theta_of_y(y), st = sin(th);
    ggx_vec3 v = {st * cos(phi), st * sin(phi), cos(th)};
    return v;
}

static double node(const energy_table *t, int i, int j)
{
    int np = t->np;
    if (i >= t->nm) { /* across the pole */
        i = 2 * (t->nm - 1) - i;
        j += np / 2;
    }
    j %= np;
    if (j < 0) j += np;
    if (i < 0) return 2.0 * t->tab[j] - t->tab[(size_t)np + j]; /* linear extrapolation below grazing */
    return t->tab[(size_t)i * np + j];
}

/* The table cell of a unit w with w.z > 0: row i (y in [i, i + 1] / (t->nm - 1)) and column j, and the fractions
 * fy, fp inside it. Used by the lookup and by the lobe's pdf, whose cells are the table's. */
static void table_cell(const energy_table *t, ggx_vec3 w, int *i, double *fy, int *j, double *fp)
{
    double st = sqrt(w.x * w.x + w.y * w.y), th = atan2(st, w.z);
    double y = rows_y_of_theta(th) * (t->nm - 1);
    *i = (int)y;
    if (*i > t->nm - 2) *i = t->nm - 2;
    if (*i < 0) *i = 0;
    *fy = y - *i;
    *j = 0;
    *fp = 0.0;
    if (t->np == 1) return;
    double x = t->cos0 * w.x + t->sin0 * w.y, yy = t->cos0 * w.y - t->sin0 * w.x; /* in the frame of phi0 */
    double psi = t->warp == 1.0 ? atan2(yy, x) : cols_psi_of_xy(x, yy, t->warp);
    double p = psi * (t->np / (2.0 * GGX_PI));
    p -= t->np * floor(p / t->np);
    *j = (int)p;
    if (*j > t->np - 1) *j = t->np - 1;
    if (*j < 0) *j = 0;
    *fp = p - *j;
}

/* I in cell (i, j) at fractions (fy, fp): Catmull-Rom over the padded nodes around the cell. */
static double interp_i(const energy_table *t, int i, double fy, int j, double fp)
{
    const double *r0 = t->pad + (size_t)i * t->pw; /* row i - 1 */
    if (t->np == 1) {
        double p[4] = {r0[0], r0[1], r0[2], r0[3]};
        return catmull_rom(p, fy);
    }
    double col[4];
    for (int dj = 0; dj < 4; dj++) {
        const double *c = r0 + j + dj; /* column j - 1 + dj */
        double p[4] = {c[0], c[t->pw], c[2 * t->pw], c[3 * t->pw]};
        col[dj] = catmull_rom(p, fy);
    }
    return catmull_rom(col, fp);
}

static double clamp01(double r) { return r > 0 ? (r < 1 ? r : 1) : 0; }

double ggx_internal_etab_albedo(const energy_table *t, ggx_vec3 v)
{
    int i, j;
    double fy, fp;
    table_cell(t, v, &i, &fy, &j, &fp);
    size_t c = (size_t)i * t->np + j;
    double g = interp_i(t, i, fy, j, fp), lift = t->guard[c];
    if (!isnan(lift)) g = fmin(t->guard[(size_t)(t->nm - 1) * t->np + c], g + lift);
    return clamp01(g * ggx_internal_albedo_scale(t->s, v));
}

int ggx_internal_unit_up(ggx_vec3 w, ggx_vec3 *out)
{
    double l = sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
    if (!(l > 0 && l <= 1e300)) return 0;
    out->x = w.x / l;
    out->y = w.y / l;
    out->z = w.z / l;
    return out->z > 0;
}

static int columns(const ggx_shape *s, int np_full) { return ggx_internal_is_isotropic(s) ? 1 : np_full; }

size_t ggx_internal_etab_size(const ggx_shape *s, int nm, int np_full)
{
    int np = columns(s, np_full), pw = np == 1 ? 1 : np + 3;
    return (size_t)nm * np + (size_t)(nm + 2) * pw + (size_t)(nm - 1) * np + 1 + 2 * (size_t)(nm - 1) * np;
}

/* The guard of the interpolation (docs/design/energy.md, "Where the table cannot follow E"). Every cell whose 4 x 4
 * stencil has a third difference of I above CHECK_D3 (a kink or a step near it: Catmull-Rom is exact for quadratics,
 * and a smooth I gives third differences far below it at the tables' spacing) is compared with the node function at
 * GUARD_SAMPLES points inside it. Where the interpolant falls below E by more than GUARD_TOL at one of them, E holds
 * a feature narrower than the nodes (the mirror horizon of a sharp skewed lobe: the views whose mirror direction
 * about the lobe's peak is horizontal; anisotropy beyond the columns' resolution at grazing) and the interpolant,
 * which rings there by up to a sixth of the feature's height, would add energy. The cell is then guarded: the
 * interpolant there is lifted by GUARD_LIFT times the largest shortfall of I found at the samples, up to a cap, the
 * largest of the cell's corner nodes and samples (a step of E lies between its high and its low side, and I on the
 * high side varies slowly, so the cap bounds E in the cell). The compensation there loses a little of the multiple
 * scattering instead of adding energy: about the lift where the interpolant nearly follows E, up to the feature's
 * height where it does not. Unskewed shapes check a quarter turn and guard the mirror images of its cells too. */
#define CHECK_D3 1e-3
#define GUARD_TOL 3e-4
#define GUARD_LIFT 2.0
/* The grazing band: the cells wholly beyond GRAZING_DEG, where E of sharp lobes changes fastest, hold the largest of
 * their corner nodes (or the guard's cap, where that is larger). The shipped anisotropic table's
 * 33 rows, which are not guarded, left the interpolant 2.9e-3 below E at 89.5 degrees for (0.012, 0.18); a guarded
 * table of (0.03, 0.03) skewed by theta_x 1 was 2.3e-3 below E at 89.9 degrees, between the guard's samples. A bound
 * that costs no quadrature, on views that weigh 3e-4 of the cosine-weighted hemisphere. */
#define GRAZING_DEG 89.0
enum { GUARD_SAMPLES = 5 };

static void guard_one(energy_table *t, size_t c, double lift, double cap)
{
    t->guard[c] = lift;
    t->guard[(size_t)(t->nm - 1) * t->np + c] = cap;
}

static void guard_cell(energy_table *t, int i, int j, double lift, double cap)
{
    int np = t->np;
    guard_one(t, (size_t)i * np + j, lift, cap);
    if (t->s->kind == GGX_SHAPE_SKEWED || np == 1) return;
    const int mirror[3] = {np - 1 - j, np / 2 - 1 - j, np / 2 + j}; /* about phi0, phi0 + pi / 2, and the turn by pi */
    for (int m = 0; m < 3; m++) guard_one(t, (size_t)i * np + mirror[m], lift, cap);
}

static void guard_cells(energy_table *t, energy_node_fn fn, void *ctx)
{
    static const double at[GUARD_SAMPLES][2] = {{0.5, 0.5}, {0.25, 0.25}, {0.25, 0.75}, {0.75, 0.25}, {0.75, 0.75}};
    /* unskewed shapes: the first quarter turn from phi0 (the others are its mirror images) */
    int np = t->np, pw = t->pw, jn = t->s->kind == GGX_SHAPE_SKEWED || np == 1 ? np : np / 4;
    for (int i = 0; i < t->nm - 1; i++)
        for (int j = 0; j < jn; j++) {
            const double *r0 = t->pad + (size_t)i * pw; /* node row i - 1 */
            double d3 = 0;
            if (np == 1) {
                d3 = fabs(r0[3] - 3 * r0[2] + 3 * r0[1] - r0[0]);
            } else {
                for (int k = 0; k < 4; k++) {
                    const double *row = r0 + (size_t)k * pw + j, *col = r0 + j + k;
                    d3 = fmax(d3, fabs(row[3] - 3 * row[2] + 3 * row[1] - row[0]));
                    d3 = fmax(d3, fabs(col[3 * pw] - 3 * col[2 * pw] + 3 * col[pw] - col[0]));
                }
            }
            if (!(d3 > CHECK_D3)) continue;
            double under = 0.0, under_i = 0.0,
                   top = fmax(fmax(node(t, i, j), node(t, i, j + 1)), fmax(node(t, i + 1, j), node(t, i + 1, j + 1)));
            for (int q = 0; q < GUARD_SAMPLES; q++) {
                double fy = at[q][0], fp = np == 1 ? 0.0 : at[q][1];
                if (np == 1 && q > 2) break; /* one column: the samples along y */
                if (np == 1) fy = 0.25 * (q + 1);
                double y = (i + fy) / (t->nm - 1), phi = np == 1 ? 0.0 : phi_of_col(t, j + fp);
                ggx_vec3 v = view_at(y, phi);
                double p = ggx_internal_albedo_scale(t->s, v), iv = fn(ctx, v, y);
                if (!(iv >= 0 && iv <= 1e300 && p > 0)) continue;
                double ii = interp_i(t, i, fy, j, fp);
                under = fmax(under, clamp01(iv * p) - clamp01(ii * p));
                under_i = fmax(under_i, iv - ii);
                top = fmax(top, iv);
            }
            if (under > GUARD_TOL) guard_cell(t, i, j, GUARD_LIFT * under_i, top);
        }
}

void ggx_internal_etab_build(energy_table *t, const ggx_shape *s, int nm, int np_full, double warp, int check,
                             double *storage, energy_node_fn fn, void *ctx)
{
    pthread_once(&once, init_rule);
    int np = columns(s, np_full), pw = np == 1 ? 1 : np + 3;
    t->s = s;
    t->nm = nm;
    t->np = np;
    t->phi0 = s->kind == GGX_SHAPE_SKEWED ? 0.0 : atan2(s->tangent_sin, s->tangent_cos);
    t->cos0 = cos(t->phi0);
    t->sin0 = sin(t->phi0);
    t->warp = s->kind == GGX_SHAPE_SKEWED ? 1.0 : warp;
    t->tab = storage;
    t->pad = t->tab + (size_t)t->nm * np;
    t->pw = pw;
    t->cdf = t->pad + (size_t)(t->nm + 2) * pw;
    t->guard = t->cdf + (size_t)(t->nm - 1) * np + 1;
    for (size_t c = 0; c < 2 * (size_t)(t->nm - 1) * np; c++) t->guard[c] = NAN;

    /* Nodes. Unskewed: E(phi0 + d) = E(phi0 - d) = E(phi0 + pi - d), so columns 0..np/4 determine the rest. */
    int jmax = s->kind == GGX_SHAPE_SKEWED ? np - 1 : np / 4;
    for (int i = 1; i < t->nm; i++) {
        double y = (double)i / (t->nm - 1);
        for (int j = 0; j <= jmax; j++) {
            ggx_vec3 v = view_at(y, phi_of_col(t, j));
            if (i == t->nm - 1) v.x = v.y = 0.0, v.z = 1.0; /* the pole, every column the same */
            t->tab[(size_t)i * np + j] = (i == t->nm - 1 && j > 0) ? t->tab[(size_t)i * np] : fn(ctx, v, y);
        }
        if (s->kind != GGX_SHAPE_SKEWED && np > 1)
            for (int j = 0; j <= jmax; j++) {
                double val = t->tab[(size_t)i * np + j];
                t->tab[(size_t)i * np + (np - j) % np] = val;
                t->tab[(size_t)i * np + np / 2 - j] = val;
                t->tab[(size_t)i * np + (np / 2 + j) % np] = val;
            }
    }
    for (int j = 0; j < np; j++) /* grazing row: quadratic extrapolation (E needs v.z > 0) */
        t->tab[j] = 3.0 * t->tab[np + j] - 3.0 * t->tab[2 * np + j] + t->tab[3 * np + j];

    /* The padded copy that the lookup reads: row r is node row r - 1 (the columns of the isotropic table are rows). */
    for (int r = 0; r < t->nm + 2; r++) {
        if (np == 1) {
            t->pad[r] = node(t, r - 1, 0);
            continue;
        }
        for (int c = 0; c < pw; c++) t->pad[(size_t)r * pw + c] = node(t, r - 1, c - 1);
    }

    if (check) guard_cells(t, fn, ctx);
    double y_band = rows_y_of_theta(GRAZING_DEG * GGX_PI / 180);
    for (int i = 0; (double)(i + 1) / (t->nm - 1) <= y_band; i++)
        for (int j = 0; j < np; j++) {
            size_t c = (size_t)i * np + j;
            double top = fmax(fmax(node(t, i, j), node(t, i, j + 1)), fmax(node(t, i + 1, j), node(t, i + 1, j + 1)));
            if (!isnan(t->guard[c])) top = fmax(top, t->guard[(size_t)(t->nm - 1) * np + c]);
            guard_one(t, c, INFINITY, top);
        }

    /* Cell weights int (1 - E) dt dphi, t = mu^2: dt = 2 mu mu'(y) dy; the cell spans [phi_j, phi_j+1]. */
    double sum = 0.0;
    t->cdf[0] = 0.0;
    for (int i = 0; i < t->nm - 1; i++)
        for (int j = 0; j < np; j++) {
            double w = 0.0, pa = phi_of_col(t, j), dphi = np == 1 ? 2.0 * GGX_PI : phi_of_col(t, j + 1) - pa;
            for (int a = 0; a < CELL_GL; a++) {
                double y = (i + 0.5 + 0.5 * cell_x[a]) / (t->nm - 1);
                double mu = mu_of_y(y), dmu = cos(0.5 * GGX_PI * y * y) * GGX_PI * y;
                for (int b = 0; b < CELL_GL; b++) {
                    double phi = pa + dphi * (0.5 + 0.5 * cell_x[b]);
                    double ev = mu > 0 ? ggx_internal_etab_albedo(t, view_at(y, phi)) : 0.0;
                    w += cell_w[a] * cell_w[b] * (1.0 - ev) * 2.0 * mu * dmu;
                }
            }
            w *= 0.25 * dphi / (t->nm - 1); /* the two half-widths of the Gauss-Legendre rule */
            if (!(w > 0)) w = 0.0;
            sum += w;
            t->cdf[i * np + j + 1] = sum;
        }
    t->total = sum;
    t->e_avg = 1.0 - sum / (2.0 * GGX_PI);
    if (t->e_avg < 0) t->e_avg = 0;
    if (t->e_avg > 1) t->e_avg = 1;
}

/* The cell of a unit w with w.z > 0: its index and its (t, phi) area. */
static int cell_of(const energy_table *t, ggx_vec3 w, double *area)
{
    int i, j;
    double fy, fp;
    table_cell(t, w, &i, &fy, &j, &fp);
    double m0 = mu_of_y((double)i / (t->nm - 1)), m1 = mu_of_y((double)(i + 1) / (t->nm - 1));
    *area = (m1 * m1 - m0 * m0) * (t->np == 1 ? 2.0 * GGX_PI : phi_of_col(t, j + 1) - phi_of_col(t, j));
    return i * t->np + j;
}

double ggx_internal_etab_pdf(const energy_table *t, ggx_vec3 w)
{
    if (!(t->total > 0)) return 0.0;
    double area;
    int c = cell_of(t, w, &area);
    double wc = t->cdf[c + 1] - t->cdf[c];
    return area > 0 ? wc / (t->total * area) * 2.0 * w.z : 0.0;
}

double ggx_internal_clamp01(double u) { return u >= 0 ? (u < 1 ? u : 0x1.fffffffffffffp-1) : 0.0; }

ggx_vec3 ggx_internal_etab_sample(const energy_table *t, double u1, double u2)
{
    ggx_vec3 zero = {0, 0, 0};
    if (!(t->total > 0)) return zero;
    int ncell = (t->nm - 1) * t->np;
    double x = ggx_internal_clamp01(u1) * t->total;
    int lo = 0, hi = ncell; /* the cell c with cdf[c] <= x < cdf[c + 1], skipping empty cells */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (t->cdf[mid] <= x) lo = mid;
        else hi = mid;
    }
    double wc = t->cdf[lo + 1] - t->cdf[lo];
    double f = wc > 0 ? (x - t->cdf[lo]) / wc : 0.5;
    f = f >= 0 ? (f <= 1 ? f : 1) : 0;
    int i = lo / t->np, j = lo % t->np;
    double m0 = mu_of_y((double)i / (t->nm - 1)), m1 = mu_of_y((double)(i + 1) / (t->nm - 1));
    double tt = m0 * m0 + f * (m1 * m1 - m0 * m0);
    double pa = phi_of_col(t, j), pb = t->np == 1 ? pa + 2.0 * GGX_PI : phi_of_col(t, j + 1);
    double phi = pa + ggx_internal_clamp01(u2) * (pb - pa);
    double st = sqrt(fmax(0.0, 1.0 - tt));
    ggx_vec3 w = {st * cos(phi), st * sin(phi), sqrt(tt)};
    return w;
}

ggx_sample ggx_internal_invalid_sample(void)
{
    ggx_sample r = {{0, 0, 0}, 0.0, 0.0, GGX_EVENT_INVALID};
    return r;
}
