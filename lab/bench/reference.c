/* Plain transcriptions of the formulas libggx implements, written the way a renderer would: straight from the
 * equations, with no guards, clamps or special cases beyond those the formulas themselves contain. The benchmark
 * times them beside the library on the same inputs, so the ratio printed is what the library's domain checks,
 * rim handling and generality cost, and it checks that both compute the same values. Valid only for the inputs
 * the benchmark gives them (unit directions above the horizon, u in [0, 1)). Not part of the library.
 * SPDX-License-Identifier: MIT */
#include "reference.h"

#include <math.h>


/* Spherical caps (Dupuy & Benyoub 2023) for any A: in sphere space the visible normals of the unit sphere seen from
 * v' = normalize(A v) are v' + c with c uniform on the cap c.z >= -v'.z; A^T maps a sphere normal back to the
 * ellipsoid's (Walter section 1). A is canonical, so the truncation m.n >= 0 is c.z >= -v'.z. */
ggx_vec3 REF_FN(ref_caps_vndf_d)(const double A[3][3], ggx_vec3 v, double u1, double u2)
{
    double sx = A[0][0] * v.x + A[0][1] * v.y + A[0][2] * v.z;
    double sy = A[1][0] * v.x + A[1][1] * v.y + A[1][2] * v.z;
    double sz = A[2][0] * v.x + A[2][1] * v.y + A[2][2] * v.z;
    double il = 1.0 / sqrt(sx * sx + sy * sy + sz * sz);
    sx *= il, sy *= il, sz *= il;
    double phi = 2.0 * GGX_PI * u1;
    double z = (1.0 - u2) * (1.0 + sz) - sz;
    double r = sqrt(1.0 - z * z);
    double hx = sx + r * cos(phi), hy = sy + r * sin(phi), hz = sz + z;
    ggx_vec3 m = {A[0][0] * hx + A[1][0] * hy + A[2][0] * hz, A[0][1] * hx + A[1][1] * hy + A[2][1] * hz,
                  A[0][2] * hx + A[1][2] * hy + A[2][2] * hz};
    double im = 1.0 / sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
    m.x *= im, m.y *= im, m.z *= im;
    return m;
}

/* The published listing (float, diagonal A: the stretch is a per-axis scale and A^T = A), with phi = 2 pi u1 as the
 * library maps u1, so that both map the same u to the same normal. The clamp is the listing's own, written with
 * comparisons: a shader's clamp is one min and one max, where fminf/fmaxf would be libm calls (ISO C NaN rules).
 * fmaf is the listing's fma; at the baseline x86-64 ISA it is a libm call. */
typedef struct rvec3f {
    float x, y, z;
} rvec3f;

static rvec3f normalize_f(rvec3f a)
{
    float il = 1.0f / sqrtf(a.x * a.x + a.y * a.y + a.z * a.z);
    rvec3f r = {a.x * il, a.y * il, a.z * il};
    return r;
}

void REF_FN(ref_caps_vndf_f_diag)(float ax, float ay, float vx, float vy, float vz, float u1, float u2, float out[3])
{
    rvec3f wi = normalize_f((rvec3f){ax * vx, ay * vy, vz});
    float phi = 2.0f * (float)GGX_PI * u1;
    float z = fmaf(1.0f - u2, 1.0f + wi.z, -wi.z);
    float s2 = 1.0f - z * z;
    float sin_theta = sqrtf(s2 < 0.0f ? 0.0f : (s2 > 1.0f ? 1.0f : s2));
    rvec3f h = {sin_theta * cosf(phi) + wi.x, sin_theta * sinf(phi) + wi.y, z + wi.z};
    rvec3f m = normalize_f((rvec3f){ax * h.x, ay * h.y, h.z});
    out[0] = m.x, out[1] = m.y, out[2] = m.z;
}

/* Walter eq 6 with eq 26 and 28: G1 = min(1, A_e(n) |u.n| / A_l(u, n))
 * = min(1, 2 ||A n||^2 |u.n| / (||A u|| ||A n|| + (A u).(A n))) X+(u.m); n = +z, so A n is A's third column. */
double REF_FN(ref_g1_eq6)(const double A[3][3], ggx_vec3 u, ggx_vec3 m)
{
    if (!(u.x * m.x + u.y * m.y + u.z * m.z > 0.0)) return 0.0;
    double nx = A[0][2], ny = A[1][2], nz = A[2][2];
    double ux = A[0][0] * u.x + A[0][1] * u.y + A[0][2] * u.z;
    double uy = A[1][0] * u.x + A[1][1] * u.y + A[1][2] * u.z;
    double uz = A[2][0] * u.x + A[2][1] * u.y + A[2][2] * u.z;
    double n2 = nx * nx + ny * ny + nz * nz;
    double g = 2.0 * n2 * fabs(u.z) / (sqrt(ux * ux + uy * uy + uz * uz) * sqrt(n2) + ux * nx + uy * ny + uz * nz);
    return g < 1.0 ? g : 1.0;
}

/* Walter eq 33: D_v(m) = A_e(n) / A_l(v, n) X+(m.v) D(m) (m.v), with D(m) = X+(m.n) / (pi |A| ||A n||
 * ||A^{-T} m||^4) (eq 1) and the area ratio from eq 26 and 28 as in ref_g1_eq6. */
double REF_FN(ref_pdf_vndf_eq33)(const double A[3][3], const double AinvT[3][3], double det, ggx_vec3 v, ggx_vec3 m)
{
    double nx = A[0][2], ny = A[1][2], nz = A[2][2];
    double vx = A[0][0] * v.x + A[0][1] * v.y + A[0][2] * v.z;
    double vy = A[1][0] * v.x + A[1][1] * v.y + A[1][2] * v.z;
    double vz = A[2][0] * v.x + A[2][1] * v.y + A[2][2] * v.z;
    double qx = AinvT[0][0] * m.x + AinvT[0][1] * m.y + AinvT[0][2] * m.z;
    double qy = AinvT[1][0] * m.x + AinvT[1][1] * m.y + AinvT[1][2] * m.z;
    double qz = AinvT[2][0] * m.x + AinvT[2][1] * m.y + AinvT[2][2] * m.z;
    double n2 = nx * nx + ny * ny + nz * nz, nl = sqrt(n2), q2 = qx * qx + qy * qy + qz * qz;
    double d = m.z >= 0.0 ? 1.0 / (GGX_PI * det * nl * q2 * q2) : 0.0;
    double ratio = 2.0 * n2 / (sqrt(vx * vx + vy * vy + vz * vz) * nl + vx * nx + vy * ny + vz * nz);
    double mv = m.x * v.x + m.y * v.y + m.z * v.z;
    return ratio * (mv > 0.0 ? mv : 0.0) * d;
}

float REF_FN(ref_sqrt_sincos_f)(float u1, float x)
{
    float phi = 2.0f * (float)GGX_PI * u1;
    return sqrtf(x) + sinf(phi) + cosf(phi);
}
