/* Shape setup: validation and the precomputed terms of Walter's ellipsoid NDF. SPDX-License-Identifier: MIT */
#include <string.h>

#include "internal.h"

static int all_finite(const double *x, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i])) return 0;
    return 1;
}

/* Validates alpha and applies the documented clamp to GGX_ALPHA_MIN. */
static ggx_status check_alpha(double *alpha)
{
    if (!isfinite(*alpha)) return GGX_ERR_NONFINITE;
    if (!(*alpha > 0.0) || *alpha > GGX_ALPHA_MAX) return GGX_ERR_ALPHA;
    if (*alpha < GGX_ALPHA_MIN) *alpha = GGX_ALPHA_MIN;
    return GGX_OK;
}

/* Fills s from a matrix already known to be finite. */
static ggx_status shape_from_matrix(ggx_shape *s, const double A[3][3])
{
    double a[3][3];
    memcpy(a, A, sizeof a);

    /* Cofactors: A^{-1} = C^T / det, hence A^{-T} = C / det. */
    double c[3][3];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            c[i][j] = a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1];
        }
    }
    double det = a[0][0] * c[0][0] + a[0][1] * c[0][1] + a[0][2] * c[0][2];
    double fro2 = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) fro2 += a[i][j] * a[i][j];
    double fro = sqrt(fro2);
    if (fro > 0.0 && (fro > GGX_MATRIX_SCALE_MAX || fro < 1.0 / GGX_MATRIX_SCALE_MAX)) return GGX_ERR_RANGE;
    if (!(fabs(det) > GGX_SINGULAR_TOL * fro2 * fro)) return GGX_ERR_SINGULAR;

    /* -A describes the same distributions (left-multiplication by the orthogonal -I); keeping det > 0 lets the
     * sampling code use A as an orientation-preserving map. */
    double sign = det < 0.0 ? -1.0 : 1.0;
    double b[3][3], bit[3][3]; /* sign * A and its inverse transpose */
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            b[i][j] = sign * a[i][j];
            bit[i][j] = sign * c[i][j] / det; /* cofactors of -A equal those of A; (-A)^{-T} = -A^{-T} */
        }
    }

    /* Canonical form A' = Q A with Q the rotation taking A n to +z: Q A describes the same distributions and areas
     * (Walter section 1), and with A' n = ||A n|| z the truncation m.n >= 0 is the hemisphere z >= 0 of sphere space
     * for every A, so samplers need no frame. Q = I exactly when A n is already along +z. */
    ggx_vec3 an = ggx_k_v3_d(b[0][2], b[1][2], b[2][2]);
    double an_len = ggx_k_len_d(an);
    double q[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (an.x != 0.0 || an.y != 0.0 || an.z < 0.0) {
        ggx_vec3 p = ggx_k_scale_d(an, 1.0 / an_len);
        double flip = 1.0;
        if (p.z < 0.0) { /* rotate by pi about x first (diag(1, -1, -1)), so that the rotation below is small */
            flip = -1.0;
            p = ggx_k_v3_d(p.x, -p.y, -p.z);
        }
        /* Rotation taking p to z about the axis p x z: I + [k]x + [k]x^2 / (1 + c), k = p x z, c = p.z > 0. */
        double kx = p.y, ky = -p.x, cz = p.z, f = 1.0 / (1.0 + cz);
        double r[3][3] = {{1.0 - f * ky * ky, f * kx * ky, ky}, {f * kx * ky, 1.0 - f * kx * kx, -kx}, {-ky, kx, cz}};
        for (int i = 0; i < 3; i++) {
            q[i][0] = r[i][0];
            q[i][1] = r[i][1] * flip;
            q[i][2] = r[i][2] * flip;
        }
    }
    ggx_shape t;
    memset(&t, 0, sizeof t);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            t.a[i][j] = q[i][0] * b[0][j] + q[i][1] * b[1][j] + q[i][2] * b[2][j];
            t.ainv_t[i][j] = q[i][0] * bit[0][j] + q[i][1] * bit[1][j] + q[i][2] * bit[2][j]; /* (QA)^{-T} = Q A^{-T} */
        }
    }
    t.a[0][2] = t.a[1][2] = 0.0; /* A' n is along z by construction; remove the rounding */
    t.a[2][2] = an_len;
    t.ainv_t[2][0] = t.ainv_t[2][1] = 0.0; /* so A'^{-T} has the third row (0, 0, 1 / ||A n||) */
    t.ainv_t[2][2] = 1.0 / an_len;
    t.det = fabs(det);
    t.an = ggx_k_v3_d(0.0, 0.0, an_len);
    t.an_len = an_len;
    t.ndf_scale = 1.0 / (GGX_PI * t.det * t.an_len);

    /* Classification, used by fast paths only: every evaluation uses Walter's general forms. A'^T A' n is along n
     * exactly when the third row of A' is (0, 0, a33): then A' = [B 0; 0 a33] and the distribution is anisotropic GGX
     * with B^T B / a33^2 = Rz^T diag(ax^2, ay^2) Rz. */
    double scale = fabs(t.a[0][0]) + fabs(t.a[0][1]) + fabs(t.a[1][0]) + fabs(t.a[1][1]) + an_len;
    if (hypot(t.a[2][0], t.a[2][1]) <= 1e-14 * scale) {
        double e = t.a[2][2];
        double m00 = (t.a[0][0] * t.a[0][0] + t.a[1][0] * t.a[1][0]) / (e * e);
        double m01 = (t.a[0][0] * t.a[0][1] + t.a[1][0] * t.a[1][1]) / (e * e);
        double m11 = (t.a[0][1] * t.a[0][1] + t.a[1][1] * t.a[1][1]) / (e * e);
        int diagonal = t.a[0][1] == 0.0 && t.a[1][0] == 0.0 && t.a[2][0] == 0.0 && t.a[2][1] == 0.0;
        if (diagonal || m01 == 0.0) {
            t.alpha_x = sqrt(m00);
            t.alpha_y = sqrt(m11);
            t.tangent_cos = 1.0;
            t.tangent_sin = 0.0;
        } else {
            /* Eigen-decomposition of the 2x2 symmetric M = B^T B / e^2. The major axis is at phi0 with
             * tan(2 phi0) = 2 m01 / (m00 - m11); its eigenvalue is computed without cancellation, and the minor one
             * from the determinant, det M = (det B / e^2)^2, which stays accurate when B is nearly singular. */
            double phi0 = 0.5 * atan2(2.0 * m01, m00 - m11);
            double half = 0.5 * (m00 - m11);
            double lmax = 0.5 * (m00 + m11) + sqrt(half * half + m01 * m01);
            double detb = fabs(t.a[0][0] * t.a[1][1] - t.a[0][1] * t.a[1][0]) / (e * e);
            t.alpha_x = sqrt(lmax);
            t.alpha_y = detb / t.alpha_x;
            t.tangent_cos = cos(phi0);
            t.tangent_sin = sin(phi0);
        }
        t.kind = diagonal ? GGX_SHAPE_DIAGONAL : GGX_SHAPE_UNSKEWED;
    } else {
        t.kind = GGX_SHAPE_SKEWED;
    }
    if (!all_finite(&t.ainv_t[0][0], 9) || !all_finite(&t.a[0][0], 9) || !isfinite(t.ndf_scale))
        return GGX_ERR_SINGULAR;
    *s = t;
    return GGX_OK;
}

GGX_API ggx_status ggx_shape_matrix(ggx_shape *s, const double A[3][3])
{
    if (!s || !A) return GGX_ERR_NULL;
    if (!all_finite(&A[0][0], 9)) return GGX_ERR_NONFINITE;
    return shape_from_matrix(s, A);
}

GGX_API ggx_status ggx_shape_aniso(ggx_shape *s, double alpha_x, double alpha_y)
{
    return ggx_shape_ellipsoid(s, alpha_x, alpha_y, 0.0, 0.0, 0.0);
}

GGX_API ggx_status ggx_shape_iso(ggx_shape *s, double alpha) { return ggx_shape_aniso(s, alpha, alpha); }

GGX_API ggx_status ggx_ellipsoid_matrix(double A[3][3], double alpha_x, double alpha_y, double theta_x, double theta_y,
                                        double theta_z)
{
    if (!A) return GGX_ERR_NULL;
    if (!isfinite(theta_x) || !isfinite(theta_y) || !isfinite(theta_z)) return GGX_ERR_NONFINITE;
    ggx_status st = check_alpha(&alpha_x);
    if (st == GGX_OK) st = check_alpha(&alpha_y);
    if (st != GGX_OK) return st;
    if (fabs(theta_x) > GGX_SKEW_MAX || fabs(theta_y) > GGX_SKEW_MAX) return GGX_ERR_ANGLE;

    /* R = Rx Ry Rz (Walter eq 3). Zero angles give exact zeros, so R = I yields a diagonal A. */
    double cx = cos(theta_x), sx = sin(theta_x), cy = cos(theta_y), sy = sin(theta_y);
    double cz = cos(theta_z), sz = sin(theta_z);
    if (theta_x == 0.0) cx = 1.0, sx = 0.0;
    if (theta_y == 0.0) cy = 1.0, sy = 0.0;
    if (theta_z == 0.0) cz = 1.0, sz = 0.0;
    double ry_rz[3][3] = {{cy * cz, -cy * sz, sy}, {sz, cz, 0.0}, {-sy * cz, sy * sz, cy}};
    double r[3][3];
    for (int j = 0; j < 3; j++) {
        r[0][j] = ry_rz[0][j];
        r[1][j] = cx * ry_rz[1][j] - sx * ry_rz[2][j];
        r[2][j] = sx * ry_rz[1][j] + cx * ry_rz[2][j];
    }
    double scale[3] = {alpha_x, alpha_y, 1.0};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) A[i][j] = scale[i] * r[i][j];
    return GGX_OK;
}

GGX_API ggx_status ggx_shape_ellipsoid(ggx_shape *s, double alpha_x, double alpha_y, double theta_x, double theta_y,
                                       double theta_z)
{
    if (!s) return GGX_ERR_NULL;
    double A[3][3];
    ggx_status st = ggx_ellipsoid_matrix(A, alpha_x, alpha_y, theta_x, theta_y, theta_z);
    if (st != GGX_OK) return st;
    return shape_from_matrix(s, (const double(*)[3])A);
}
