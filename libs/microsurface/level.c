/* Levelling a measured height field (microsurface.h): the least-squares plane of its finite points removed, as surface
 * metrology removes a scan's mounting tilt. SPDX-License-Identifier: MIT */
#include <math.h>

#include "microsurface.h"

size_t ms_level(double *h, size_t nx, size_t ny, int keep_tilt, double plane_out[3])
{
    /* the normal equations of z = a (x - cx) + b (y - cy) + c over the finite points, coordinates about the centre */
    double m[3][4] = {{0}};
    size_t count = 0;
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            double z = h[y * nx + x];
            if (!isfinite(z)) continue;
            count++;
            double r[3] = {(double)x - 0.5 * (double)(nx - 1), (double)y - 0.5 * (double)(ny - 1), 1.0};
            for (int a = 0; a < 3; a++) {
                for (int b = 0; b < 3; b++) m[a][b] += r[a] * r[b];
                m[a][3] += r[a] * z;
            }
        }
    if (plane_out) plane_out[0] = plane_out[1] = plane_out[2] = 0.0;
    if (count == 0) return 0;
    double plane[3] = {0.0, 0.0, m[2][3] / m[2][2]};
    /* Gaussian elimination; a plane needs points off one line (else the mean alone) */
    if (!keep_tilt && m[0][0] * m[1][1] - m[0][1] * m[0][1] > 1e-12 * (m[0][0] * m[1][1] + 1.0)) {
        for (int c = 0; c < 3; c++)
            for (int r = c + 1; r < 3; r++) {
                double f = m[r][c] / m[c][c];
                for (int q = c; q < 4; q++) m[r][q] -= f * m[c][q];
            }
        for (int r = 2; r >= 0; r--) {
            double v = m[r][3];
            for (int q = r + 1; q < 3; q++) v -= m[r][q] * plane[q];
            plane[r] = v / m[r][r];
        }
    }
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            double *z = &h[y * nx + x];
            if (isfinite(*z))
                *z -= plane[0] * ((double)x - 0.5 * (double)(nx - 1)) +
                      plane[1] * ((double)y - 0.5 * (double)(ny - 1)) + plane[2];
        }
    if (plane_out) plane_out[0] = plane[0], plane_out[1] = plane[1], plane_out[2] = plane[2];
    return count;
}
