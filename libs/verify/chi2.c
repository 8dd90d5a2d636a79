/* SPDX-License-Identifier: MIT */
#include "chi2.h"

#include "common/chi2_tail.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

double chi2_pvalue(double x, int dof) { return ggx_chi2_upper(x, dof); }

int normal_keys_key(void *ctx, ggx_vec3 m, int *region, ggx_vec3 *k)
{
    *region = 0;
    *k = key_of_normal(((const normal_keys *)ctx)->s, m);
    return 1;
}

double normal_keys_density(void *ctx, int region, ggx_vec3 k)
{
    (void)region;
    const normal_keys *c = ctx;
    double j;
    ggx_vec3 m = normal_of_key(c->s, k, &j);
    return c->pdf(c->s, c->v, m) * j;
}

double verify_pdf_ndf(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    (void)v;
    return ggx_pdf_ndf(s, m);
}

double chi2_sidak(int runs) { return 1.0 - pow(1.0 - 0.01, 1.0 / runs); }

static const double g4x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
static const double g4w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

static ggx_vec3 key_dir(double ct, double phi)
{
    double st = sqrt(fmax(0.0, 1.0 - ct * ct));
    return t_vec(st * cos(phi), st * sin(phi), ct);
}

/* Integral of the density over [c0, c1] x [p0, p1] in (cos theta, phi) with sub x sub panels of 4 x 4 nodes;
 * *mixed is set when some nodes are zero and others not, or when the nonzero nodes differ by more than a factor
 * GGX_CHI2_JUMP (a jump of the density inside the cell, as the bound per azimuth of bounded reflection sampling
 * makes, which a 4 x 4 rule integrates with an error of the order of the jump). */
#define GGX_CHI2_JUMP 1.5
static double cell_integral(const chi2_problem *p, int region, double c0, double c1, double p0, double p1, int sub,
                            int *mixed)
{
    double sum = 0.0;
    int zeros = 0, nonzeros = 0;
    double fmin = INFINITY, fmax = 0.0;
    double dc = (c1 - c0) / sub, dp = (p1 - p0) / sub;
    for (int i = 0; i < sub; i++) {
        for (int j = 0; j < sub; j++) {
            double cc = c0 + (i + 0.5) * dc, pc = p0 + (j + 0.5) * dp;
            for (int a = 0; a < 4; a++) {
                for (int b = 0; b < 4; b++) {
                    double f = p->density(p->ctx, region, key_dir(cc + 0.5 * dc * g4x[a], pc + 0.5 * dp * g4x[b]));
                    if (f > 0.0) {
                        nonzeros++;
                        fmin = f < fmin ? f : fmin;
                        fmax = f > fmax ? f : fmax;
                    } else {
                        zeros++;
                    }
                    sum += g4w[a] * g4w[b] * f;
                }
            }
        }
    }
    if (mixed) *mixed = (zeros > 0 && nonzeros > 0) || fmax > GGX_CHI2_JUMP * fmin;
    return sum * 0.25 * dc * dp;
}

/* The integral of a cell by adaptive subdivision: a panel is split 2 x 2 where its 4 x 4 nodes are mixed (zero
 * and nonzero, or a jump: cell_integral) or where the four 4 x 4 rules of its quarters differ from its own by more
 * than GGX_CHI2_REL of it (a feature smaller than the panel that no node of its own rule sees: the bound per azimuth
 * of bounded reflection sampling, whose kappa(phi) jumps along meridians of the cap that meet at the image of the
 * cap's pole, leaves a small region of 6 times the density between the nodes of the cells around it), to depth
 * levels. v is the panel's own rule (computed by the caller). *fine is the integral; *coarse the same to one level
 * less (its error estimate). */
#define GGX_CHI2_DEPTH 4
#define GGX_CHI2_REL 1e-3
static void cell_adaptive(const chi2_problem *p, int region, double c0, double c1, double p0, double p1, double v,
                          int mixed, int depth, double *fine, double *coarse)
{
    double cm = 0.5 * (c0 + c1), pm = 0.5 * (p0 + p1), q[4], sum = 0.0;
    int mq[4], any = mixed;
    const double cs[3] = {c0, cm, c1}, ps[3] = {p0, pm, p1};
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            q[2 * a + b] = cell_integral(p, region, cs[a], cs[a + 1], ps[b], ps[b + 1], 1, &mq[2 * a + b]);
            sum += q[2 * a + b];
            any |= mq[2 * a + b];
        }
    *coarse = v;
    *fine = sum;
    if (depth <= 1 || !(any || fabs(sum - v) > GGX_CHI2_REL * fabs(sum))) return;
    double f = 0.0, c = 0.0, fi, ci;
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            cell_adaptive(p, region, cs[a], cs[a + 1], ps[b], ps[b + 1], q[2 * a + b], mq[2 * a + b], depth - 1, &fi,
                          &ci);
            f += fi, c += ci;
        }
    *fine = f;
    *coarse = c;
}

/* The cells of the first and last rows are wedges that meet at a pole of the key (cos theta = +-1), where their
 * 4 x 4 nodes lie far from the pole in angle (cos theta is uniform in area: the innermost node of a row of 0.065
 * in cos theta is 5.4 degrees from the pole) and a small feature around it (the bound per azimuth's jumps meet at
 * the image of the cap's pole, which lies near the key's pole for views whose sphere-space view is near n) is not
 * seen by any of them: such a cell is split towards its pole GGX_CHI2_POLAR times, halving its extent in cos theta
 * each time, and each part is integrated by cell_adaptive. */
#define GGX_CHI2_POLAR 6
static void cell_polar(const chi2_problem *p, int region, double c0, double c1, double p0, double p1, double *fine,
                       double *coarse)
{
    double f = 0.0, c = 0.0, fi, ci;
    int top = c1 >= 1.0, mixed;
    for (int k = 0; k <= GGX_CHI2_POLAR; k++) {
        double cm = 0.5 * (c0 + c1);
        /* the half away from the pole, or at the end the rest */
        double a0 = k == GGX_CHI2_POLAR ? c0 : (top ? c0 : cm), a1 = k == GGX_CHI2_POLAR ? c1 : (top ? cm : c1);
        double v = cell_integral(p, region, a0, a1, p0, p1, 1, &mixed);
        cell_adaptive(p, region, a0, a1, p0, p1, v, mixed, GGX_CHI2_DEPTH, &fi, &ci);
        f += fi, c += ci;
        if (top) c0 = cm;
        else c1 = cm;
    }
    *fine = f;
    *coarse = c;
}

/* The histogram of observed and expected counts, for a failing run. */
static void write_failure(const chi2_problem *p, int ntheta, int nphi, const long *obs, const double *expd,
                          const chi2_result *res)
{
    char path[256];
    snprintf(path, sizeof path, "chi2_%s.csv", p->name);
    for (char *c = path; *c; c++)
        if (*c == ' ' || *c == '/' || *c == '(' || *c == ')' || *c == ',') *c = '_';
    FILE *f = fopen(path, "w");
    if (!f) return;
    fprintf(f, "region,itheta,iphi,observed,expected\n");
    for (int reg = 0; reg < p->nregions; reg++)
        for (int it = 0; it < ntheta; it++)
            for (int ip = 0; ip < nphi; ip++) {
                long idx = ((long)reg * ntheta + it) * nphi + ip;
                fprintf(f, "%d,%d,%d,%ld,%.6f\n", reg, it, ip, obs[idx], expd[idx]);
            }
    fprintf(f, "-1,-1,-1,%ld,%.6f\n", res->invalid, res->expected_invalid);
    fclose(f);
}

static chi2_result run(const chi2_problem *p, long n, int ntheta, int nphi, uint64_t seed, double alpha,
                       int write_failures)
{
    chi2_result res = {0};
    long ncells = (long)p->nregions * ntheta * nphi;
    long *obs = calloc((size_t)ncells, sizeof *obs);
    double *expd = calloc((size_t)ncells, sizeof *expd);
    rng r = {seed};
    for (long i = 0; i < n; i++) {
        ggx_vec3 w, k;
        int region = 0;
        if (!p->draw(p->ctx, &r, &w) || !p->key(p->ctx, w, &region, &k) || region < 0 || region >= p->nregions) {
            res.invalid++;
            continue;
        }
        int it = (int)floor((k.z + 1.0) * 0.5 * ntheta);
        double phi = atan2(k.y, k.x);
        if (phi < 0) phi += 2.0 * GGX_PI;
        int ip = (int)floor(phi / (2.0 * GGX_PI) * nphi);
        if (!(p->density(p->ctx, region, k) > 0.0)) res.zero_cell_hits++; /* a sample the pdf says is impossible */
        it = it < 0 ? 0 : (it >= ntheta ? ntheta - 1 : it);
        ip = ip < 0 ? 0 : (ip >= nphi ? nphi - 1 : ip);
        obs[((long)region * ntheta + it) * nphi + ip]++;
    }
    double mass = 0.0, quad_err = 0.0;
    for (int reg = 0; reg < p->nregions; reg++) {
        for (int it = 0; it < ntheta; it++) {
            double c0 = -1.0 + 2.0 * it / ntheta, c1 = -1.0 + 2.0 * (it + 1) / ntheta;
            for (int ip = 0; ip < nphi; ip++) {
                double p0 = 2.0 * GGX_PI * ip / nphi, p1 = 2.0 * GGX_PI * (ip + 1) / nphi;
                long idx = ((long)reg * ntheta + it) * nphi + ip;
                double v, vc;
                /* adaptive subdivision where the density jumps (a horizon, a bound) or has a feature its nodes
                 * miss, with the difference from one level less as the error estimate */
                if (it == 0 || it == ntheta - 1) {
                    cell_polar(p, reg, c0, c1, p0, p1, &v, &vc);
                } else {
                    int mixed;
                    double v1 = cell_integral(p, reg, c0, c1, p0, p1, 1, &mixed);
                    cell_adaptive(p, reg, c0, c1, p0, p1, v1, mixed, GGX_CHI2_DEPTH, &v, &vc);
                }
                quad_err += fabs(v - vc);
                if (v == 0.0 && obs[idx] > 0) v = cell_integral(p, reg, c0, c1, p0, p1, 8, NULL); /* a sliver */
                expd[idx] = v * (double)n;
                mass += v;
            }
        }
    }
    res.mass = mass;
    res.expected_invalid = (double)n * (1.0 - mass);
    if (res.expected_invalid < 0.0) res.expected_invalid = 0.0;
    /* The invalid category is known only as well as the total mass: where its expected count is below three times
     * the quadrature's error estimate (n quad_err) and the observed count is within that and its own noise of it,
     * it is left out of the test, whose cells still check the distribution (a sampler with few or no invalid
     * samples and a jump in its density, as bounded reflection sampling, would otherwise fail on quadrature error;
     * one with too many invalid samples still fails). */
    double unresolved = 3.0 * (double)n * quad_err;
    int drop_invalid = res.expected_invalid < unresolved &&
                       (double)res.invalid <= res.expected_invalid + unresolved + 5.0 * sqrt(unresolved + 1.0);
    /* Pool cells with expected count < 5 (the invalid category is one more cell). If the pool itself expects
     * fewer than 5, it is merged into the smallest regular bin so that every bin expects at least 5. */
    double *bo = malloc(sizeof(double) * (size_t)(ncells + 2)), *be = malloc(sizeof(double) * (size_t)(ncells + 2));
    double pool_o = 0.0, pool_e = 0.0;
    int bins = 0;
    for (long i = 0; i < ncells + !drop_invalid; i++) {
        double o = i < ncells ? (double)obs[i] : (double)res.invalid;
        double e = i < ncells ? expd[i] : res.expected_invalid;
        if (e < 5.0) {
            pool_o += o;
            pool_e += e;
        } else {
            bo[bins] = o;
            be[bins++] = e;
        }
    }
    if (pool_e == 0.0 && res.expected_invalid == 0.0 && res.invalid > 0 && !drop_invalid) {
        res.zero_cell_hits += res.invalid; /* invalid samples where the pdf integrates to 1 */
    } else if (pool_e >= 5.0 || bins == 0) {
        bo[bins] = pool_o;
        be[bins++] = pool_e;
    } else {
        int smallest = 0;
        for (int i = 1; i < bins; i++)
            if (be[i] < be[smallest]) smallest = i;
        bo[smallest] += pool_o;
        be[smallest] += pool_e;
    }
    double stat = 0.0;
    for (int i = 0; i < bins; i++) stat += (bo[i] - be[i]) * (bo[i] - be[i]) / be[i];
    free(bo);
    free(be);
    res.stat = stat;
    res.bins = bins;
    res.dof = bins - 1;
    res.pvalue = res.dof > 0 ? chi2_pvalue(stat, res.dof) : 1.0;
    if (write_failures && (res.pvalue < alpha || res.zero_cell_hits > 0))
        write_failure(p, ntheta, nphi, obs, expd, &res);
    free(obs);
    free(expd);
    return res;
}

static long runs_made; /* every run of the process, counted atomically */
long chi2_runs_made(void) { return __atomic_load_n(&runs_made, __ATOMIC_RELAXED); }

chi2_result chi2_run(const chi2_problem *p, long n, int ntheta, int nphi, uint64_t seed, double alpha)
{
    __atomic_add_fetch(&runs_made, 1, __ATOMIC_RELAXED);
    return run(p, n, ntheta, nphi, seed, alpha, 1);
}

chi2_result chi2_run_quiet(const chi2_problem *p, long n, int ntheta, int nphi, uint64_t seed, double alpha)
{
    __atomic_add_fetch(&runs_made, 1, __ATOMIC_RELAXED);
    return run(p, n, ntheta, nphi, seed, alpha, 0);
}
