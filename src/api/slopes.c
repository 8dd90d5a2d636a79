/* The ellipsoid in slope space: (t, Sigma) of a shape and back, and the parameters of ggx_shape_ellipsoid that give
 * a shape (docs/design/slopes.md). SPDX-License-Identifier: MIT */
#include "internal.h"

GGX_API ggx_status ggx_shape_slopes(const ggx_shape *s, double t[2], double sigma[3])
{
    if (!s || !t || !sigma) return GGX_ERR_NULL;
    /* A' = [B 0; b^T a33]: A'^T A' = [B^T B + b b^T, a33 b; a33 b^T, a33^2], whose Schur complement is B^T B. */
    const double(*a)[3] = s->a;
    double e = 1.0 / a[2][2];
    double b00 = a[0][0] * e, b01 = a[0][1] * e, b10 = a[1][0] * e, b11 = a[1][1] * e;
    t[0] = -a[2][0] * e;
    t[1] = -a[2][1] * e;
    sigma[0] = b00 * b00 + b10 * b10;
    sigma[1] = b00 * b01 + b10 * b11;
    sigma[2] = b01 * b01 + b11 * b11;
    return GGX_OK;
}

GGX_API ggx_status ggx_shape_from_slopes(ggx_shape *s, double tx, double ty, double sxx, double sxy, double syy)
{
    if (!s) return GGX_ERR_NULL;
    if (!isfinite(tx) || !isfinite(ty) || !isfinite(sxx) || !isfinite(sxy) || !isfinite(syy)) return GGX_ERR_NONFINITE;
    /* Eigen-decomposition of Sigma: the major axis at phi with tan(2 phi) = 2 sxy / (sxx - syy). */
    double half = 0.5 * (sxx - syy), rad = hypot(half, sxy), mean = 0.5 * (sxx + syy);
    double l1 = mean + rad, l2 = mean - rad;
    /* The smaller eigenvalue from det Sigma, computed exactly for the given entries (Kahan's fma form), rather than
     * by the difference, which loses it when Sigma is ill-conditioned. */
    double w = sxy * sxy, det = fma(sxx, syy, -w) - fma(sxy, sxy, -w);
    if (l1 > 0.0) l2 = det / l1;
    if (sxx < 0.0 || syy < 0.0 || l2 < -1e-12 * l1) return GGX_ERR_ALPHA;
    const double lo = GGX_ALPHA_MIN * GGX_ALPHA_MIN, hi = GGX_ALPHA_MAX * GGX_ALPHA_MAX;
    if (l1 > hi) return GGX_ERR_ALPHA;
    if (l1 < lo) l1 = lo;
    if (l2 < lo) l2 = lo;
    double phi = 0.5 * atan2(2.0 * sxy, sxx - syy), c = cos(phi), sn = sin(phi);
    if (sxy == 0.0) c = sxx >= syy ? 1.0 : 0.0, sn = sxx >= syy ? 0.0 : 1.0;
    double r1 = sqrt(l1), r2 = sqrt(l2);
    /* B = r1 u u^T + r2 w w^T with u = (c, s), w = (-s, c). */
    double A[3][3] = {{r1 * c * c + r2 * sn * sn, (r1 - r2) * c * sn, 0.0},
                      {(r1 - r2) * c * sn, r1 * sn * sn + r2 * c * c, 0.0},
                      {-tx, -ty, 1.0}};
    return ggx_shape_matrix(s, (const double(*)[3])A);
}

/* One-sided Jacobi (Hestenes): rotations on the right orthogonalise the columns of w = A V, so that the column norms
 * are the singular values of A to high relative accuracy and the columns of V the eigenvectors of A^T A (computing
 * A^T A first would lose the small eigenvalues: alpha 1e-4 beside 1 leaves 1e-8 of the scale). */
static void right_singular(const double A[3][3], double sv[3], double V[3][3])
{
    double w[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) w[i][j] = A[i][j], V[i][j] = i == j;
    for (int sweep = 0; sweep < 60; sweep++) {
        int rotated = 0;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                double al = 0, be = 0, ga = 0;
                for (int k = 0; k < 3; k++) al += w[k][p] * w[k][p], be += w[k][q] * w[k][q], ga += w[k][p] * w[k][q];
                if (!(fabs(ga) > 0x1p-54 * sqrt(al * be))) continue;
                rotated = 1;
                double zeta = (be - al) / (2.0 * ga);
                double tn = (zeta >= 0 ? 1.0 : -1.0) / (fabs(zeta) + sqrt(1.0 + zeta * zeta));
                double c = 1.0 / sqrt(1.0 + tn * tn), s = c * tn;
                for (int k = 0; k < 3; k++) {
                    double wp = w[k][p], wq = w[k][q], vp = V[k][p], vq = V[k][q];
                    w[k][p] = c * wp - s * wq, w[k][q] = s * wp + c * wq;
                    V[k][p] = c * vp - s * vq, V[k][q] = s * vp + c * vq;
                }
            }
        if (!rotated) break;
    }
    for (int j = 0; j < 3; j++) sv[j] = sqrt(w[0][j] * w[0][j] + w[1][j] * w[1][j] + w[2][j] * w[2][j]);
}

GGX_API ggx_status ggx_shape_ellipsoid_params(const ggx_shape *s, double *alpha_x, double *alpha_y, double *theta_x,
                                              double *theta_y, double *theta_z)
{
    if (!s) return GGX_ERR_NULL;
    /* A^T A = R^T diag(ax^2, ay^2, 1) R (up to scale) with R = Rx Ry Rz: the rows of R are unit eigenvectors of A^T A,
     * the third the one of eigenvalue 1. R n = (sin ty, -sin tx cos ty, cos tx cos ty) and the first row of R is
     * (cos ty cos tz, -cos ty sin tz, sin ty), which give the angles. */
    double sv[3], V[3][3];
    right_singular((const double(*)[3])s->a, sv, V);
    ggx_vec3 ev[3];
    int k3 = 0;
    for (int j = 0; j < 3; j++) {
        ev[j] = ggx_k_v3_d(V[0][j], V[1][j], V[2][j]);
        if (fabs(ev[j].z) > fabs(ev[k3].z)) k3 = j;
    }
    int i = (k3 + 1) % 3, j = (k3 + 2) % 3;
    ggx_vec3 r2 = ev[k3].z < 0 ? ggx_k_scale_d(ev[k3], -1.0) : ev[k3];
    double li = sv[i] / sv[k3], lj = sv[j] / sv[k3];
    ggx_vec3 r0, r1;
    double ax, ay;
    if (fabs(li - lj) <= 1e-12 * fmax(li, lj)) {
        /* A circular cross-section: any orthonormal pair spans it; the one with theta_z = 0 has r0 orthogonal to y. */
        ggx_vec3 y = ggx_k_v3_d(0.0, 1.0, 0.0);
        r0 = ggx_k_cross_d(y, r2);
        r0 = ggx_k_scale_d(r0, 1.0 / ggx_k_len_d(r0));
        r1 = ggx_k_cross_d(r2, r0);
        ax = ay = 0.5 * (li + lj);
    } else {
        r0 = ev[i], r1 = ev[j], ax = li, ay = lj;
        if (ggx_k_dot_d(ggx_k_cross_d(r0, r1), r2) < 0.0) r1 = ggx_k_scale_d(r1, -1.0);
        /* The four quarter turns of (r0, r1) about r2 are the same distribution (the alphas swapped for odd turns):
         * keep the one with the smallest |theta_z|. */
        ggx_vec3 b0 = r0, b1 = r1;
        double bx = ax, by = ay, best = fabs(atan2(-r0.y, r0.x));
        for (int turn = 1; turn < 4; turn++) {
            ggx_vec3 n0 = r1, n1 = ggx_k_scale_d(r0, -1.0);
            double t = ax;
            r0 = n0, r1 = n1, ax = ay, ay = t;
            double tz = fabs(atan2(-r0.y, r0.x));
            if (tz < best) b0 = r0, b1 = r1, bx = ax, by = ay, best = tz;
        }
        r0 = b0, r1 = b1, ax = bx, ay = by;
    }
    if (alpha_x) *alpha_x = ax;
    if (alpha_y) *alpha_y = ay;
    if (theta_x) *theta_x = atan2(-r1.z, r2.z);
    if (theta_y) *theta_y = atan2(r0.z, hypot(r1.z, r2.z));
    if (theta_z) *theta_z = atan2(-r0.y, r0.x);
    return GGX_OK;
}
