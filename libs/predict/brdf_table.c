/* The tabulated BRDF of brdf_table.h. SPDX-License-Identifier: MIT */
#include "brdf_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The part of cell (i, j) inside the unit disk, in projected solid angle: the cell's area h^2 where its four corners
 * are inside, 0 where the disk misses it, else counted on 16 x 16 points. */
static double cell_area(int res, int i, int j)
{
    double h = 2.0 / res, x0 = -1 + i * h, y0 = -1 + j * h;
    int in = 0;
    for (int c = 0; c < 4; c++) {
        double x = x0 + (c & 1) * h, y = y0 + (c >> 1) * h;
        in += x * x + y * y <= 1;
    }
    double nx = fmax(fabs(x0), fabs(x0 + h)), ny = fmax(fabs(y0), fabs(y0 + h));
    double fx = fmin(fabs(x0), fabs(x0 + h)), fy = fmin(fabs(y0), fabs(y0 + h));
    if (x0 < 0 && x0 + h > 0) fx = 0;
    if (y0 < 0 && y0 + h > 0) fy = 0;
    if (in == 4 && nx * nx + ny * ny <= 1) return h * h;
    if (fx * fx + fy * fy >= 1) return 0;
    int k = 0;
    for (int a = 0; a < 16; a++)
        for (int b = 0; b < 16; b++) {
            double x = x0 + (a + 0.5) * h / 16, y = y0 + (b + 0.5) * h / 16;
            k += x * x + y * y < 1;
        }
    return k * h * h / 256.0;
}

int brdf_table_init(brdf_table *t, int n_theta, const double *theta, int n_phi, int res, int channels, char *err,
                    size_t errn)
{
    memset(t, 0, sizeof *t);
    if (n_theta < 1 || n_theta > BRDF_TABLE_MAX_THETA || n_phi < 1 || n_phi > 360 || res < 4 || res > 4096 ||
        (channels != 1 && channels != 3)) {
        snprintf(err, errn,
                 "BRDF table: 1 to %d polar angles, 1 to 360 azimuths, 4 to 4096 cells a side, 1 or 3 "
                 "channels",
                 BRDF_TABLE_MAX_THETA);
        return -1;
    }
    for (int i = 0; i < n_theta; i++)
        if (!(theta[i] >= 0 && theta[i] < GGX_PI / 2) || (i > 0 && !(theta[i] > theta[i - 1]))) {
            snprintf(err, errn, "BRDF table: polar angles increasing in [0, 90) degrees");
            return -1;
        }
    size_t cells = (size_t)res * (size_t)res;
    t->f = calloc((size_t)n_theta * (size_t)n_phi * (size_t)channels * cells, sizeof *t->f);
    t->area = malloc(cells * sizeof *t->area);
    t->known = malloc((size_t)n_theta * (size_t)n_phi);
    if (!t->f || !t->area || !t->known) {
        free(t->f), free(t->area), free(t->known);
        t->f = NULL, t->area = NULL, t->known = NULL;
        snprintf(err, errn, "BRDF table: out of memory for %d x %d incidences of %d^2 cells", n_theta, n_phi, res);
        return -1;
    }
    t->n_theta = n_theta, t->n_phi = n_phi, t->res = res, t->channels = channels;
    memcpy(t->theta, theta, (size_t)n_theta * sizeof *theta);
    memset(t->known, 1, (size_t)n_theta * (size_t)n_phi);
    for (int j = 0; j < res; j++)
        for (int i = 0; i < res; i++) t->area[(size_t)j * res + i] = cell_area(res, i, j);
    return 0;
}

void brdf_table_free(brdf_table *t)
{
    free(t->f), free(t->area), free(t->known);
    memset(t, 0, sizeof *t);
}

int brdf_table_count(const brdf_table *t) { return t->n_theta * t->n_phi; }

ggx_vec3 brdf_table_incidence(const brdf_table *t, int k)
{
    double th = t->theta[k / t->n_phi], ph = 2 * GGX_PI * (k % t->n_phi) / t->n_phi;
    ggx_vec3 w = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
    return w;
}

float *brdf_table_lobe(const brdf_table *t, int k, int ch)
{
    return t->f + ((size_t)k * (size_t)t->channels + (size_t)ch) * (size_t)t->res * (size_t)t->res;
}

int brdf_table_cell(const brdf_table *t, const double wo[3])
{
    if (!(wo[2] > 0)) return -1;
    double x = (wo[0] + 1) * 0.5 * t->res, y = (wo[1] + 1) * 0.5 * t->res;
    if (!(x >= 0 && y >= 0)) return -1;
    int i = x >= t->res ? t->res - 1 : (int)x, j = y >= t->res ? t->res - 1 : (int)y;
    return j * t->res + i;
}

ggx_vec3 brdf_table_cell_dir(const brdf_table *t, int cell)
{
    double h = 2.0 / t->res, x = -1 + (cell % t->res + 0.5) * h, y = -1 + (cell / t->res + 0.5) * h;
    double r2 = x * x + y * y, rmax = 1 - 1e-9;
    if (r2 > rmax * rmax) {
        double s = rmax / sqrt(r2);
        x *= s, y *= s, r2 = rmax * rmax;
    }
    ggx_vec3 w = {x, y, sqrt(1 - r2)};
    return w;
}

/* One lobe bilinearly between cell centres at the projected direction (x, y); 0 beyond the disk. */
static double lobe_at(const brdf_table *t, const float *lobe, double x, double y)
{
    if (!(x * x + y * y < 1)) return 0;
    double u = (x + 1) * 0.5 * t->res - 0.5, v = (y + 1) * 0.5 * t->res - 0.5;
    int i = (int)floor(u), j = (int)floor(v), n = t->res;
    double a = u - i, b = v - j, s = 0;
    for (int dj = 0; dj < 2; dj++)
        for (int di = 0; di < 2; di++) {
            int ii = i + di, jj = j + dj;
            if (ii < 0 || jj < 0 || ii >= n || jj >= n) continue;
            s += (di ? a : 1 - a) * (dj ? b : 1 - b) * lobe[(size_t)jj * n + ii];
        }
    return s;
}

void brdf_table_eval(const brdf_table *t, ggx_vec3 wi, ggx_vec3 wo, double f[3])
{
    f[0] = f[1] = f[2] = 0;
    if (!(wi.z > 0) || !(wo.z > 0)) return;
    double th = acos(fmin(wi.z, 1.0)), ph = atan2(wi.y, wi.x);
    /* the rows about theta_i, the columns about phi_i (periodic) */
    int r0 = 0, r1 = 0;
    double wr = 0;
    if (th >= t->theta[t->n_theta - 1]) r0 = r1 = t->n_theta - 1;
    else if (th > t->theta[0]) {
        while (t->theta[r0 + 1] <= th) r0++;
        r1 = r0 + 1, wr = (th - t->theta[r0]) / (t->theta[r1] - t->theta[r0]);
    }
    double p = ph / (2 * GGX_PI) * t->n_phi;
    p -= floor(p / t->n_phi) * t->n_phi;
    int c0 = (int)floor(p) % t->n_phi, c1 = (c0 + 1) % t->n_phi;
    double wc = p - floor(p);
    const int rows[2] = {r0, r1}, cols[2] = {c0, c1};
    const double wrow[2] = {1 - wr, wr}, wcol[2] = {1 - wc, wc};
    double wsum = 0;
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) wsum += t->known[rows[a] * t->n_phi + cols[b]] ? wrow[a] * wcol[b] : 0;
    int near = -1;
    if (!(wsum > 0)) { /* none of the four known: the nearest known incidence alone */
        double best = -2;
        for (int k = 0; k < brdf_table_count(t); k++) {
            ggx_vec3 wk = brdf_table_incidence(t, k);
            double c = wk.x * wi.x + wk.y * wi.y + wk.z * wi.z;
            if (t->known[k] && c > best) best = c, near = k;
        }
        if (near < 0) return;
    }
    for (int q = 0; q < 4; q++) {
        int k = near >= 0 ? near : rows[q / 2] * t->n_phi + cols[q % 2];
        double w = near >= 0 ? 1 : wrow[q / 2] * wcol[q % 2] / wsum;
        if (w == 0 || !t->known[k]) continue;
        ggx_vec3 wk = brdf_table_incidence(t, k);
        double x = wo.x + wi.x - wk.x, y = wo.y + wi.y - wk.y;
        for (int ch = 0; ch < t->channels; ch++) f[ch] += w * lobe_at(t, brdf_table_lobe(t, k, ch), x, y);
        if (near >= 0) break;
    }
    if (t->channels == 1) f[1] = f[2] = f[0];
}

void brdf_table_fill_incidence(brdf_table *t, int k, brdf_table_fn f, const void *ctx, int ss)
{
    double h = 2.0 / t->res;
    ggx_vec3 wi = brdf_table_incidence(t, k);
    for (int c = 0; c < t->res * t->res; c++) {
        double sum[3] = {0, 0, 0}, x0 = -1 + (c % t->res) * h, y0 = -1 + (c / t->res) * h;
        int n = 0;
        for (int a = 0; a < ss && t->area[c] > 0; a++)
            for (int b = 0; b < ss; b++) {
                double x = x0 + (a + 0.5) * h / ss, y = y0 + (b + 0.5) * h / ss, r2 = x * x + y * y, v[3] = {0, 0, 0};
                if (!(r2 < 1)) continue;
                ggx_vec3 wo = {x, y, sqrt(1 - r2)};
                f(ctx, wi, wo, v);
                for (int ch = 0; ch < t->channels; ch++) sum[ch] += v[ch];
                n++;
            }
        for (int ch = 0; ch < t->channels; ch++) brdf_table_lobe(t, k, ch)[c] = n ? (float)(sum[ch] / n) : 0.0f;
    }
}

void brdf_table_fill(brdf_table *t, brdf_table_fn f, const void *ctx, int ss)
{
    for (int k = 0; k < brdf_table_count(t); k++) brdf_table_fill_incidence(t, k, f, ctx, ss);
}

double brdf_table_albedo(const brdf_table *t, int k, int ch)
{
    if (!t->known[k]) return NAN;
    const float *f = brdf_table_lobe(t, k, ch);
    double s = 0;
    for (int c = 0; c < t->res * t->res; c++) s += f[c] * t->area[c];
    return s;
}

double brdf_table_l2(const brdf_table *a, int ca, const brdf_table *b, int cb, int k)
{
    if (a->res != b->res || brdf_table_count(a) != brdf_table_count(b) || !a->known[k] || !b->known[k]) return NAN;
    const float *fa = brdf_table_lobe(a, k, ca), *fb = brdf_table_lobe(b, k, cb);
    double d = 0, n = 0;
    for (int c = 0; c < a->res * a->res; c++) {
        double e = (double)fa[c] - fb[c];
        d += e * e * a->area[c], n += (double)fb[c] * fb[c] * a->area[c];
    }
    return n > 0 ? sqrt(d / n) : NAN;
}
