/* Small vector helpers shared by the library sources. SPDX-License-Identifier: MIT */
#ifndef GGX_INTERNAL_H
#define GGX_INTERNAL_H

#include <math.h>

#include "ggx/ggx.h"

#define GGX_PI 3.14159265358979323846

static inline ggx_vec3 v3(double x, double y, double z)
{
    ggx_vec3 r = {x, y, z};
    return r;
}
static inline double v3_dot(ggx_vec3 a, ggx_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline double v3_len(ggx_vec3 a) { return sqrt(v3_dot(a, a)); }
static inline ggx_vec3 v3_add(ggx_vec3 a, ggx_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline ggx_vec3 v3_sub(ggx_vec3 a, ggx_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline ggx_vec3 v3_scale(ggx_vec3 a, double k) { return v3(a.x * k, a.y * k, a.z * k); }
static inline ggx_vec3 v3_neg(ggx_vec3 a) { return v3(-a.x, -a.y, -a.z); }

/* M v for a row-major 3x3 matrix. */
static inline ggx_vec3 mat_mul(const double M[3][3], ggx_vec3 v)
{
    return v3(M[0][0] * v.x + M[0][1] * v.y + M[0][2] * v.z, M[1][0] * v.x + M[1][1] * v.y + M[1][2] * v.z,
              M[2][0] * v.x + M[2][1] * v.y + M[2][2] * v.z);
}

/* Hot functions promise a finite value >= 0: NaN (from NaN input) and Inf (from a zero vector where the formula
 * divides by its length) both become 0. Written so that a NaN fails the comparison. */
static inline double finite_or_zero(double r) { return (r >= 0.0 && r < HUGE_VAL) ? r : 0.0; }

#endif
