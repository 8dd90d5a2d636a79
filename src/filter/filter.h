/* The filter's internals (src/filter/filter_lobes.c): its settings, each lobe's quadrature rule, the lobes in slope
 * space and EM over them, shared by ggx_filter_lobes and the mip levels (src/filter/filter_mip.c).
 * SPDX-License-Identifier: MIT */
#ifndef GGX_FILTER_INTERNAL_H
#define GGX_FILTER_INTERNAL_H

#include <stddef.h>

#include "fit/fit.h"
#include "ggx/ggx_filter.h"

enum { FILTER_MAX_RADIAL = 1024, FILTER_MAX_ANGULAR = 4096, FILTER_MAX_THREADS = 1024 };

typedef struct filter_settings {
    int max_iterations, radial, angular, threads;
    double tolerance;
} filter_settings;

/* opt (NULL: defaults) validated into f; GGX_ERR_RANGE for a bad option. */
ggx_status filter_settings_of(const ggx_filter_options *opt, filter_settings *f);

/* GGX_OK when ggx_shape_from_slopes accepts the lobe parameters c (t, Sigma), else its refusal; without building
 * the shape where c is clearly inside its domain (a fast path, the same verdict). */
ggx_status filter_params_check(const double c[GGX_LOBE_PARAMS]);

/* The standardised nodes z_k of a lobe's rule and their weights q_k (summing to 1): s_j Gauss-Legendre on (0, 1),
 * the radial probability u = 1 - (1 - s)^2 (du = 2 (1 - s) ds), the radius |z|^2 = u / (1 - u) (P22 of alpha = 1
 * puts probability u inside it), the angles 2 pi (k + 1/2) / M. */
typedef struct filter_rule {
    int n;
    double *zx, *zy, *q;
} filter_rule;
ggx_status filter_rule_make(const filter_settings *f, filter_rule *r); /* GGX_ERR_MEMORY or GGX_OK */
void filter_rule_free(filter_rule *r);

/* A lobe in slope space: its location, scale, the Cholesky factor L (Sigma = L L^T: l00, l10, l11), Sigma^-1,
 * log(pi sqrt(det Sigma)) and its weight share w (the shares of the lobes fitted together sum to 1). */
typedef struct filter_lobe {
    double t[2], sigma[3], l[3], p[3], log_norm, w;
} filter_lobe;
void filter_lobe_set(filter_lobe *b, const double t[2], const double sigma[3], double w);

/* EM over the n lobes (ggx_filter_lobes' start and stopping rule) into (t, s); returns the iterations, sets
 * *converged, and the log-likelihood into *ll when ll is not NULL. */
int filter_em(const filter_lobe *L, size_t n, const filter_rule *r, const filter_settings *f, double t[2], double s[3],
              int *converged, double *ll);

#endif
