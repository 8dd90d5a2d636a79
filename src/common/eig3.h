/* Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations, written once for the albedo's horizon
 * cone (src/api/albedo.c) and the ellipsoid's principal axes (src/api/slopes.c). Header-only, static.
 * SPDX-License-Identifier: MIT */
#ifndef GGX_COMMON_EIG3_H
#define GGX_COMMON_EIG3_H

#include <math.h>

/* a[i][i] become the eigenvalues (in no particular order) and row i of vec the unit eigenvector of eigenvalue i;
 * the off-diagonal entries of a end below 2^-60 times its diagonal's magnitude. Each rotation is orthogonal to
 * rounding, so the rows of vec are orthonormal to a few ulp. */
static inline void ggx_eig3(double a[3][3], double vec[3][3])
{
    double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int sweep = 0; sweep < 64; sweep++) {
        double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
        double diag = fabs(a[0][0]) + fabs(a[1][1]) + fabs(a[2][2]);
        if (!(off > 1e-300 * diag) || off <= 0x1p-60 * diag) break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                if (a[p][q] == 0) continue;
                double th = 0.5 * atan2(2 * a[p][q], a[q][q] - a[p][p]), c = cos(th), s = sin(th);
                for (int k = 0; k < 3; k++) {
                    double kp = a[k][p], kq = a[k][q];
                    a[k][p] = c * kp - s * kq;
                    a[k][q] = s * kp + c * kq;
                }
                for (int k = 0; k < 3; k++) {
                    double pk = a[p][k], qk = a[q][k];
                    a[p][k] = c * pk - s * qk;
                    a[q][k] = s * pk + c * qk;
                }
                for (int k = 0; k < 3; k++) {
                    double kp = v[k][p], kq = v[k][q];
                    v[k][p] = c * kp - s * kq;
                    v[k][q] = s * kp + c * kq;
                }
            }
    }
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) vec[i][k] = v[k][i];
}

#endif
