/* Gauss-Legendre rules and global adaptive quadrature, written once for the library's albedo (src/api/albedo.c) and
 * the verification library (libs/verify/verify.c). Header-only, static functions; each includer keeps its own rule
 * tables (computed once, by pthread_once there). SPDX-License-Identifier: MIT */
#ifndef GGX_COMMON_GAUSS_H
#define GGX_COMMON_GAUSS_H

#include "ggx/ggx.h"

#include <math.h>

enum { GQ_N = 12, GQ_M = 6 };

/* The order-12 rule and the order-6 rule whose difference estimates its error. */
typedef struct gq_rule {
    double x[GQ_N], w[GQ_N], xm[GQ_M], wm[GQ_M];
} gq_rule;

/* Gauss-Legendre nodes and weights of order n on [-1, 1] by Newton's method on P_n (no tabulated constants). */
static inline void gq_nodes(int n, double *xs, double *ws)
{
    for (int i = 0; i < n; i++) {
        double x = cos(GGX_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; it++) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; k++) {
                double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            double dx = p1 / dp;
            x -= dx;
            if (fabs(dx) < 1e-16) break;
        }
        xs[i] = x;
        ws[i] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
}

static inline void gq_rule_init(gq_rule *r)
{
    gq_nodes(GQ_N, r->x, r->w);
    gq_nodes(GQ_M, r->xm, r->wm);
}

typedef double (*gq_fn)(double x, void *ctx);

typedef struct gq_panel {
    double a, b, value, err;
} gq_panel;

/* The order-12 rule on [a, b], with |order 12 - order 6| as its (pessimistic) error estimate. */
static inline gq_panel gq_make_panel(const gq_rule *r, gq_fn f, void *ctx, double a, double b)
{
    double c = 0.5 * (a + b), h = 0.5 * (b - a), hi = 0.0, lo = 0.0;
    for (int i = 0; i < GQ_N; i++) hi += r->w[i] * f(c + h * r->x[i], ctx);
    for (int i = 0; i < GQ_M; i++) lo += r->wm[i] * f(c + h * r->xm[i], ctx);
    gq_panel p = {a, b, hi * h, fabs(hi - lo) * fabs(h)};
    return p;
}

/* Global adaptive quadrature over the break points br[0] < ... < br[nb - 1]: bisect the panel with the largest
 * error estimate until the estimates sum to abs_tol or max_panels (the size of ps) are in use. Unlike a recursion
 * with a per-panel tolerance, this converges at jumps and kinks (each bisection halves the error of the panel that
 * holds one). Reentrant: ps is the caller's (nested integrals keep theirs on the stack). */
static inline double gq_adapt(const gq_rule *r, gq_fn f, void *ctx, const double *br, int nb, double abs_tol,
                              gq_panel *ps, int max_panels)
{
    int n = 0;
    for (int i = 0; i + 1 < nb && n < max_panels; i++)
        if (br[i + 1] > br[i]) ps[n++] = gq_make_panel(r, f, ctx, br[i], br[i + 1]);
    for (;;) {
        double total = 0.0;
        int worst = 0;
        for (int i = 0; i < n; i++) {
            total += ps[i].err;
            if (ps[i].err > ps[worst].err) worst = i;
        }
        if (n == 0 || total <= abs_tol || n + 1 >= max_panels) break;
        gq_panel w = ps[worst];
        double m = 0.5 * (w.a + w.b);
        if (!(m > w.a && m < w.b)) break; /* no more resolution */
        ps[worst] = gq_make_panel(r, f, ctx, w.a, m);
        ps[n++] = gq_make_panel(r, f, ctx, m, w.b);
    }
    double sum = 0.0;
    for (int i = 0; i < n; i++) sum += ps[i].value;
    return sum;
}

#endif
