/* The SGGX flake distribution (ggx_sggx.h): setup from S or from a shape, D, the projected area sigma and the
 * specular phase function. Derivations: docs/design/sggx.md. SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "common/eig3.h"
#include "internal.h"
#include "sggx_internal.h"

/* Validates S and fills f; f is written only on success. */
static ggx_status sggx_init(ggx_sggx *f, const double S[3][3])
{
    double big = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            if (!isfinite(S[i][j])) return GGX_ERR_NONFINITE;
            big = fmax(big, fabs(S[i][j]));
        }
    ggx_sggx g;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            if (fabs(S[i][j] - S[j][i]) > 1e-12 * big) return GGX_ERR_RANGE;
            g.s[i][j] = 0.5 * (S[i][j] + S[j][i]);
        }
    double trace = g.s[0][0] + g.s[1][1] + g.s[2][2];
    const double scale_max = GGX_MATRIX_SCALE_MAX * GGX_MATRIX_SCALE_MAX;
    /* a positive definite S has a positive trace; a trace <= 0 is indefinite or zero */
    if (trace > scale_max) return GGX_ERR_RANGE;
    if (!(trace >= 1.0 / scale_max)) return trace > 0.0 ? GGX_ERR_RANGE : GGX_ERR_SINGULAR;
    double a[3][3], vec[3][3];
    memcpy(a, g.s, sizeof a);
    ggx_eig3(a, vec);
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (a[order[j]][order[j]] < a[order[i]][order[i]]) {
                int t = order[i];
                order[i] = order[j];
                order[j] = t;
            }
    for (int i = 0; i < 3; i++) {
        g.eig[i] = a[order[i]][order[i]];
        for (int k = 0; k < 3; k++) g.axes[i][k] = vec[order[i]][k];
    }
    if (!(g.eig[0] > GGX_SINGULAR_TOL * g.eig[2])) return GGX_ERR_SINGULAR;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double h = 0.0, hi = 0.0;
            for (int k = 0; k < 3; k++) {
                double p = g.axes[k][i] * g.axes[k][j], r = sqrt(g.eig[k]);
                h += r * p;
                hi += p / r;
            }
            g.half[i][j] = h;
            g.half_inv[i][j] = hi;
        }
    g.ndf_scale = 1.0 / (GGX_PI * sqrt(g.eig[0]) * sqrt(g.eig[1]) * sqrt(g.eig[2]));
    *f = g;
    return GGX_OK;
}

GGX_API ggx_status ggx_sggx_from_matrix(ggx_sggx *f, const double S[3][3])
{
    if (!f || !S) return GGX_ERR_NULL;
    return sggx_init(f, S);
}

GGX_API ggx_status ggx_sggx_from_shape(ggx_sggx *f, const ggx_shape *s)
{
    if (!f || !s) return GGX_ERR_NULL;
    double S[3][3]; /* A^T A of the stored A' = Q A, which is A^T A itself */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            S[i][j] = s->a[0][i] * s->a[0][j] + s->a[1][i] * s->a[1][j] + s->a[2][i] * s->a[2][j];
    return sggx_init(f, (const double(*)[3])S);
}

GGX_API double ggx_sggx_ndf(const ggx_sggx *f, ggx_vec3 m)
{
    ggx_vec3 p = ggx_k_mul_d(f->half_inv, m);
    double q = ggx_k_dot_d(p, p);
    return ggx_k_finite0_d(f->ndf_scale / (q * q));
}

GGX_API double ggx_sggx_sigma(const ggx_sggx *f, ggx_vec3 w) { return ggx_internal_sggx_sigma(f, w); }

GGX_API double ggx_sggx_phase_specular(const ggx_sggx *f, ggx_vec3 wi, ggx_vec3 wo)
{
    ggx_vec3 i = ggx_k_unit_d(wi), o = ggx_k_unit_d(wo), h = ggx_k_normalize_d(ggx_k_add_d(i, o));
    if (ggx_k_is_zero_d(i) || ggx_k_is_zero_d(o) || ggx_k_is_zero_d(h)) return 0.0;
    return ggx_k_finite0_d(ggx_sggx_ndf(f, h) / (4.0 * ggx_internal_sggx_sigma(f, i)));
}
