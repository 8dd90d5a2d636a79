/* The seed audit's shared parts (libs/verify/audit_internal.h). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "audit_internal.h"

static int au_a_draw(void *vc, rng *r, ggx_vec3 *m)
{
    au_actx *c = vc;
    double u1 = rng_uniform(r), u2 = rng_uniform(r);
    *m = c->literal ? c->literal(c->A, c->keys.v, u1, u2) : c->f(c->keys.s, c->keys.v, u1, u2);
    return t_dot(*m, *m) > 0.5;
}

typedef struct draw_ctx {
    normal_keys keys; /* first, as in au_actx */
    int (*draw)(void *ctx, rng *r, ggx_vec3 *m);
    void *ctx;
} draw_ctx;
static int draw_fwd(void *vc, rng *r, ggx_vec3 *m)
{
    draw_ctx *c = vc;
    return c->draw(c->ctx, r, m);
}
double au_chi2_draw(const ggx_shape *s, ggx_vec3 v, int (*draw)(void *ctx, rng *r, ggx_vec3 *m), void *ctx,
                    verify_pdf_fn pdf, uint64_t seed, int progress)
{
    draw_ctx c = {{s, v, pdf}, draw, ctx};
    chi2_problem p = {"audit", 1, draw_fwd, normal_keys_key, normal_keys_density, &c};
    chi2_result r = chi2_run_quiet(&p, 1000000, 100, 200, seed, 0.0);
    if (progress) fputc('.', stderr);
    return r.zero_cell_hits ? 0.0 : r.pvalue;
}

double au_chi2_p(au_actx *c, uint64_t seed, int progress)
{
    return au_chi2_draw(c->keys.s, c->keys.v, au_a_draw, c, c->keys.pdf, seed, progress);
}

double au_chi2_sampler(const ggx_shape *s, ggx_vec3 v, au_vndf_fn f, verify_pdf_fn pdf, uint64_t seed, int progress)
{
    au_actx c = {{s, v, pdf}, f, NULL, NULL};
    return au_chi2_p(&c, seed, progress);
}

/* the level of the audit running on this thread (audit_run_at); each thread's audit has its own */
static _Thread_local double level_of_thread = -1;
void au_set_alpha_level(double alpha) { level_of_thread = alpha; }
double au_alpha_level(void) { return level_of_thread >= 0 ? level_of_thread : chi2_sidak(CHI2_SUITE_RUNS); }

void au_set(audit_row *r, int k, audit_verdict v, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    r->verdict[k] = v;
    vsnprintf(r->text[k], AUDIT_TEXT, fmt, ap);
    va_end(ap);
}

void au_append(audit_row *r, int k, const char *fmt, ...)
{
    size_t l = strlen(r->text[k]);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->text[k] + l, AUDIT_TEXT - l, fmt, ap);
    va_end(ap);
}

void au_verdict_p(audit_row *r, int k, double p)
{
    au_set(r, k, p >= au_alpha_level() ? AUDIT_HOLDS : AUDIT_FAILS, "chi-square p = %.2g", p);
}

audit_row *au_add(audit_row *rows, int *n, const char *id, const char *claim, const char *seed, const char *where,
                  audit_scope scope)
{
    if (*n >= AUDIT_MAX_ROWS) abort(); /* a claim added beyond the table's size: raise AUDIT_MAX_ROWS */
    audit_row *r = &rows[(*n)++];
    memset(r, 0, sizeof *r);
    r->id = id, r->claim = claim, r->seed = seed, r->where = where, r->scope = scope;
    for (int k = 0; k < AUDIT_SHAPES; k++) au_set(r, k, AUDIT_NOT_CLAIMED, "not checked");
    return r;
}

int au_in_scope(audit_scope scope, const ggx_shape *s)
{
    return scope == AUDIT_SCOPE_ANY || s->kind == GGX_SHAPE_DIAGONAL ||
           (scope == AUDIT_SCOPE_ROTATED && s->kind == GGX_SHAPE_UNSKEWED);
}

double au_uniform_cb(void *st) { return rng_uniform((rng *)st); }

void au_inv_t(const double A[3][3], double Ait[3][3])
{
    double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                 A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            Ait[i][j] = (A[i1][j1] * A[i2][j2] - A[i1][j2] * A[i2][j1]) / det;
        }
}

double au_ray_area(const double A[3][3], ggx_vec3 u, ggx_vec3 v, int lune, long N, uint64_t seed, double *sigma)
{
    double M[3][3], Ait[3][3]; /* A^T A and A^-T */
    au_inv_t(A, Ait);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            M[i][j] = 0;
            for (int k = 0; k < 3; k++) M[i][j] += A[k][i] * A[k][j];
        }
    ggx_vec3 e1, e2;
    t_frame(u, &e1, &e2);
    ggx_vec3 h1v = t_matvec((const double(*)[3])Ait, e1), h2v = t_matvec((const double(*)[3])Ait, e2);
    double h1 = sqrt(t_dot(h1v, h1v)), h2 = sqrt(t_dot(h2v, h2v));
    ggx_vec3 Mu = t_matvec((const double(*)[3])M, u);
    double a = t_dot(u, Mu);
    rng g = {seed};
    long hits = 0;
    for (long i = 0; i < N; i++) {
        ggx_vec3 p = t_add(t_scale(e1, h1 * (2 * rng_uniform(&g) - 1)), t_scale(e2, h2 * (2 * rng_uniform(&g) - 1)));
        ggx_vec3 Mp = t_matvec((const double(*)[3])M, p);
        double b = t_dot(u, Mp), c = t_dot(p, Mp) - 1, disc = b * b - a * c;
        if (disc < 0) continue;
        if (lune) {
            ggx_vec3 x = t_add(p, t_scale(u, (-b + sqrt(disc)) / a)), nrm = t_matvec((const double(*)[3])M, x);
            if (t_dot(nrm, v) < 0) continue;
        }
        hits++;
    }
    double f = (double)hits / (double)N, box = 4 * h1 * h2;
    *sigma = box * sqrt(f * (1 - f) / (double)N);
    return box * f;
}

double au_norm_of(const double M[3][3], ggx_vec3 v)
{
    ggx_vec3 r = t_matvec(M, v);
    return sqrt(t_dot(r, r));
}

int au_diag_alphas(const ggx_shape *s, double *ax, double *ay)
{
    *ax = s->alpha_x, *ay = s->alpha_y;
    return s->kind != GGX_SHAPE_SKEWED;
}

int au_alphas_or_skip(audit_row *r, int k, const ggx_shape *s, double *ax, double *ay)
{
    if (au_diag_alphas(s, ax, ay)) return 1;
    au_set(r, k, AUDIT_NOT_CLAIMED, "cannot be applied (a skewed A has no ax, ay)");
    return 0;
}

ggx_vec3 au_view_near_n(rng *g)
{
    if (rng_uniform(g) < 0.5) return au_random_upper(g);
    double r = rng_uniform(g);
    return t_dir(0.5 * r * r * r * r, 2 * GGX_PI * rng_uniform(g));
}
ggx_vec3 au_random_upper(rng *g) { return t_dir(acos(0.02 + 0.98 * rng_uniform(g)), 2 * GGX_PI * rng_uniform(g)); }

double au_ggx_formula(double ax, double ay, ggx_vec3 m)
{
    double q = m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay) + m.z * m.z;
    return 1.0 / (GGX_PI * ax * ay * q * q);
}

ggx_vec3 au_point_of_normal(const double Ait[3][3], ggx_vec3 m)
{
    ggx_vec3 q = t_matvec(Ait, m);
    return t_scale(t_mattvec(Ait, q), 1 / sqrt(t_dot(q, q)));
}

void au_sym_eigenvalues(int nn, double M[9][9], double *ev)
{
    for (int sweep = 0; sweep < 100; sweep++) {
        double off = 0;
        for (int p = 0; p < nn; p++)
            for (int q = p + 1; q < nn; q++) off += M[p][q] * M[p][q];
        if (off < 1e-300) break;
        for (int p = 0; p < nn; p++)
            for (int q = p + 1; q < nn; q++) {
                if (M[p][q] == 0) continue;
                double th = 0.5 * atan2(2 * M[p][q], M[q][q] - M[p][p]), c = cos(th), sn = sin(th);
                for (int k = 0; k < nn; k++) {
                    double a = M[k][p], b = M[k][q];
                    M[k][p] = c * a - sn * b, M[k][q] = sn * a + c * b;
                }
                for (int k = 0; k < nn; k++) {
                    double a = M[p][k], b = M[q][k];
                    M[p][k] = c * a - sn * b, M[q][k] = sn * a + c * b;
                }
            }
    }
    for (int i = 0; i < nn; i++) ev[i] = M[i][i];
}

double au_fd_jacobian(au_map2_fn f, const void *ctx, double a, double b, double h)
{
    ggx_vec3 da = t_scale(t_add(f(ctx, a + h, b), t_scale(f(ctx, a - h, b), -1)), 0.5 / h);
    ggx_vec3 db = t_scale(t_add(f(ctx, a, b + h), t_scale(f(ctx, a, b - h), -1)), 0.5 / h);
    ggx_vec3 c = t_cross(da, db);
    return sqrt(t_dot(c, c));
}

/* Shape (ax, ay, tx, ty, tz) into out; 0 if the library refuses it. */
static int kin_make(double ax, double ay, double tx, double ty, double tz, au_kin *out)
{
    out->params[0] = ax, out->params[1] = ay, out->params[2] = tx, out->params[3] = ty, out->params[4] = tz;
    out->has_params = 1, out->searching = 0;
    if (ggx_ellipsoid_matrix(out->A, ax, ay, tx, ty, tz) != GGX_OK ||
        ggx_shape_matrix(&out->s, (const double(*)[3])out->A) != GGX_OK)
        return 0;
    snprintf(out->label, sizeof out->label, "alphas (%.3g, %.3g), angles (%.3g, %.3g, %.3g) rad", ax, ay, tx, ty, tz);
    return 1;
}
static void kin_offdiag(au_kin *out)
{
    double M[3][3];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            M[a][b] = out->A[0][a] * out->A[0][b] + out->A[1][a] * out->A[1][b] + out->A[2][a] * out->A[2][b];
    out->offdiag = sqrt(M[0][1] * M[0][1] + M[0][2] * M[0][2] + M[1][2] * M[1][2]) / (M[0][0] + M[1][1] + M[2][2]);
}

void au_kin_shape(const ggx_shape *s0, const double A0[3][3], int i, uint64_t seed, au_kin *out)
{
    if (i == 0) {
        memcpy(out->A, A0, sizeof out->A);
        out->s = *s0;
        out->has_params = 0, out->searching = 0;
        snprintf(out->label, sizeof out->label, "the audit's shape");
    } else {
        rng g = {seed * 1000003u + (uint64_t)i};
        double ax = 0.05 * pow(40.0, rng_uniform(&g)), ay = 0.05 * pow(40.0, rng_uniform(&g)), tx = 0, ty = 0, tz = 0;
        if (s0->kind != GGX_SHAPE_DIAGONAL) tz = GGX_PI * (2 * rng_uniform(&g) - 1);
        if (s0->kind == GGX_SHAPE_SKEWED) {
            tx = (0.02 + 0.58 * rng_uniform(&g)) * (rng_uniform(&g) < 0.5 ? -1 : 1);
            ty = (0.02 + 0.58 * rng_uniform(&g)) * (rng_uniform(&g) < 0.5 ? -1 : 1);
        }
        if (!kin_make(ax, ay, tx, ty, tz, out)) abort(); /* every shape drawn is valid */
    }
    kin_offdiag(out);
}

void au_kin_alphas(const au_kin *K, double *ax, double *ay)
{
    *ax = sqrt(K->A[0][0] * K->A[0][0] + K->A[0][1] * K->A[0][1] + K->A[0][2] * K->A[0][2]);
    *ay = sqrt(K->A[1][0] * K->A[1][0] + K->A[1][1] * K->A[1][1] + K->A[1][2] * K->A[1][2]);
}

typedef struct kin_result {
    double worst;                   /* the largest error (infinite for NaN) */
    int failed;                     /* points with error > tol */
    int ex_index;                   /* the smallest failing shape (-1: none) */
    double ex_key, ex_err;          /* its size (kin_size) and worst error */
    char ex_shape[120], ex_at[160]; /* and where */
    char shrunk[480];               /* what the shrinking search found, or "" */
} kin_result;

/* theta_z reduced to (-pi/2, pi/2]: a rotation by pi is the same shape. */
static double reduce_tz(double tz)
{
    double r = tz - GGX_PI * floor(tz / GGX_PI + 0.5);
    return r <= -0.5 * GGX_PI ? r + GGX_PI : r;
}
/* How far a shape of the family is from the claim's simplest case, by which counterexamples are ordered: for a
 * rotated family the rotation |theta_z| (reduced), for a skewed one the off-diagonal share of A^T A (the tilt). */
static double kin_size(const ggx_shape *s0, const au_kin *K)
{
    if (s0->kind != GGX_SHAPE_UNSKEWED) return K->offdiag;
    double tz = K->has_params ? K->params[4] : atan2(-K->A[0][1], K->A[0][0]);
    return fabs(reduce_tz(tz));
}

/* The worst error of err on shape K at `points` points (seeded as shape index i), the point into at. Several
 * passes (more points) than the family's first one, so that failures confined to small regions are found. */
static double kin_points(au_kin *K, int i, au_err_fn err, void *ctx, int points, double tol, char *at, size_t nat)
{
    double worst = 0;
    K->searching = 1; /* err functions keep their tallies out of the search */
    for (int pass = 0; pass < 4; pass++) {
        rng g = {977 + (uint64_t)i + 7919 * (uint64_t)pass};
        for (int j = 0; j < points; j++) {
            char here[160] = "";
            double e = err(K, &g, ctx, here, sizeof here);
            if (!(e <= tol) && !(e <= worst)) worst = isnan(e) ? INFINITY : e, snprintf(at, nat, "%s", here);
        }
    }
    return worst;
}

static kin_result kin_run(const ggx_shape *s0, const double A0[3][3], au_err_fn err, void *ctx, int points, double tol)
{
    kin_result res = {0, 0, -1, INFINITY, 0, "", "", ""};
    au_kin ex;
    memset(&ex, 0, sizeof ex);
    for (int i = 0; i < AU_KIN; i++) {
        au_kin K;
        au_kin_shape(s0, A0, i, 0x5eed, &K);
        K.searching = 0;
        double key = kin_size(s0, &K);
        rng g = {977 + (uint64_t)i};
        for (int j = 0; j < points; j++) {
            char at[160] = "";
            double e = err(&K, &g, ctx, at, sizeof at);
            if (!(e <= tol)) {
                if (isnan(e)) e = INFINITY;
                res.failed++;
                /* the smallest shape (ties: the first found, the audit's own first), at its worst point */
                if (key < res.ex_key || (i == res.ex_index && e > res.ex_err)) {
                    res.ex_index = i, res.ex_key = key, res.ex_err = e, ex = K;
                    snprintf(res.ex_shape, sizeof res.ex_shape, "%s", K.label);
                    snprintf(res.ex_at, sizeof res.ex_at, "%s", at);
                }
            }
            if (e > res.worst) res.worst = e;
        }
    }
    /* The smallest counterexample: the smallest failing shape (a random one, whose angles are known) shrunk toward
     * the claim's simplest case, each step checked at four times the points. A skewed shape is first tried without
     * its skew: a claim that still fails there fails from the rotation alone, which is then halved instead. Every
     * one of 30 halvings is tried (a step whose points miss the failure does not end the search); the smallest
     * that still fails is reported. */
    if (res.ex_index >= 0 && ex.has_params && s0->kind != GGX_SHAPE_DIAGONAL) {
        const double *q = ex.params;
        int skew = s0->kind == GGX_SHAPE_SKEWED, from_rotation = 0, halvings = 0;
        double tz = reduce_tz(q[4]), f = 1, last_err = 0;
        char at[160] = "", last_at[160] = "";
        au_kin K;
        if (skew && kin_make(q[0], q[1], 0, 0, tz, &K) &&
            kin_points(&K, res.ex_index, err, ctx, points, tol, at, sizeof at) > tol)
            from_rotation = 1, skew = 0;
        for (int h = 1; h <= 30; h++) {
            double g2 = (double)1 / (double)(1u << h);
            if (!kin_make(q[0], q[1], skew ? q[2] * g2 : 0, skew ? q[3] * g2 : 0, skew ? q[4] : tz * g2, &K)) break;
            double e = kin_points(&K, res.ex_index, err, ctx, points, tol, at, sizeof at);
            if (e > tol) f = g2, halvings = h, last_err = e, snprintf(last_at, sizeof last_at, "%s", at);
        }
        size_t l = 0;
        if (from_rotation)
            l = (size_t)snprintf(res.shrunk, sizeof res.shrunk, "; it fails without skew, from the rotation alone");
        if (halvings > 0 && skew)
            snprintf(res.shrunk + l, sizeof res.shrunk - l,
                     "; with its skew scaled by 2^-%d, (theta_x, theta_y) = (%.3g, "
                     "%.3g) rad, it still fails: %s, error %.3g",
                     halvings, q[2] * f, q[3] * f, last_at, last_err);
        else if (halvings > 0)
            snprintf(res.shrunk + l, sizeof res.shrunk - l,
                     "; with its rotation scaled by 2^-%d, theta_z = %.3g rad, it "
                     "still fails: %s, error %.3g",
                     halvings, tz * f, last_at, last_err);
        else if (!from_rotation)
            snprintf(res.shrunk + l, sizeof res.shrunk - l,
                     "; halved, the failure was not found again at the points tried");
    }
    return res;
}

double au_kin_worst(const ggx_shape *s0, const double A0[3][3], au_err_fn err, void *ctx, int points, double tol,
                    char *example, size_t nexample)
{
    kin_result res = kin_run(s0, A0, err, ctx, points, tol);
    if (example) {
        if (res.failed) snprintf(example, nexample, "%s, %s, error %.3g", res.ex_shape, res.ex_at, res.ex_err);
        else example[0] = 0;
    }
    return res.worst;
}

void au_verdict_kin(audit_row *r, int k, const ggx_shape *s0, const double A0[3][3], au_err_fn err, void *ctx,
                    int points, double tol, const char *what)
{
    kin_result res = kin_run(s0, A0, err, ctx, points, tol);
    if (!res.failed)
        au_set(r, k, AUDIT_HOLDS, "%s within %.1e at %d points on %d shapes of this kind", what, res.worst,
               points * AU_KIN, AU_KIN);
    else
        au_set(r, k, AUDIT_FAILS,
               "%s off by up to %.3g (%d of %d points); smallest counterexample (%s %.2g): %s, %s, "
               "error %.3g%s",
               what, res.worst, res.failed, points * AU_KIN,
               s0->kind == GGX_SHAPE_UNSKEWED ? "|theta_z|" : "off-diagonal share of A^T A", res.ex_key, res.ex_shape,
               res.ex_at, res.ex_err, res.shrunk);
}

ggx_vec3 au_map_cosine(const void *ctx, double u, double v)
{
    (void)ctx;
    return t_vec(sqrt(u) * cos(2 * GGX_PI * v), sqrt(u) * sin(2 * GGX_PI * v), sqrt(1 - u));
}

double au_det3(ggx_vec3 a, ggx_vec3 b, ggx_vec3 c) { return t_dot(a, t_cross(b, c)); }

ggx_vec3 au_literal_heitz(const double A[3][3], ggx_vec3 v, double u1, double u2)
{
    ggx_vec3 vh = t_normalize(t_matvec(A, v));
    double l = hypot(vh.x, vh.y);
    ggx_vec3 t1v = l > 0 ? t_vec(-vh.y / l, vh.x / l, 0) : t_vec(1, 0, 0), t2v = t_cross(vh, t1v);
    double r = sqrt(u1), ph = 2 * GGX_PI * u2, t1 = r * cos(ph), t2 = r * sin(ph), sq = 0.5 * (1 + vh.z);
    t2 = (1 - sq) * sqrt(1 - t1 * t1) + sq * t2;
    ggx_vec3 nh = t_add(t_add(t_scale(t1v, t1), t_scale(t2v, t2)), t_scale(vh, sqrt(fmax(0, 1 - t1 * t1 - t2 * t2))));
    return t_normalize(t_matvec(A, nh));
}

void au_verdict_views(audit_row *r, int k, double (*f)(const ggx_shape *, ggx_vec3), const ggx_shape *s, double tol,
                      const char *what)
{
    static const double thetas[AU_VIEW_THETAS] = {0.3, 0.7, 1.0, 1.2, 1.4, 1.5};
    double worst = -1, th = 0, ph = 0, x = 1, first_th = INFINITY, first_ph = 0, first_x = 1;
    for (int i = 0; i < AU_VIEW_THETAS; i++)
        for (int j = 0; j < AU_VIEW_PHIS; j++) {
            double phi = -GGX_PI + 2 * GGX_PI * (j + 0.5) / AU_VIEW_PHIS, y = f(s, t_dir(thetas[i], phi));
            if (fabs(y - 1) > worst) worst = fabs(y - 1), th = thetas[i], ph = phi, x = y;
            if (!(fabs(y - 1) < tol) && thetas[i] < first_th) first_th = thetas[i], first_ph = phi, first_x = y;
        }
    if (worst < tol)
        au_set(r, k, AUDIT_HOLDS, "%s integrates to 1 within %.0e at all %d views of the grid", what,
               fmax(worst, 1e-16), AU_VIEWS);
    else
        au_set(r, k, AUDIT_FAILS,
               "%s integrates to %.4f at theta %.1f, phi %.2f rad (worst of %d views); the view nearest "
               "n where it fails: %.4f at theta %.1f, phi %.2f",
               what, x, th, ph, AU_VIEWS, first_x, first_th, first_ph);
}

void au_kin_row(const au_ctx *c, audit_row *r, int unskewed_only, au_err_fn err, void *ctx, int points, double tol,
                const char *what)
{
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double ax, ay;
        if (unskewed_only && !au_alphas_or_skip(r, k, &c->sh[k], &ax, &ay)) continue;
        au_verdict_kin(r, k, &c->sh[k], c->A[k], err, ctx, points, tol, what);
    }
}
