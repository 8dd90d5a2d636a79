/* Sampling of normals and directions, with inverse maps. All samplers work in the sphere space of the canonical
 * A (shape.c), where the ellipsoid is the unit sphere and the truncation m.n >= 0 is the hemisphere z >= 0.
 * SPDX-License-Identifier: MIT */
#include "internal.h"

static const ggx_vec3 zero3 = {0.0, 0.0, 0.0};

static int is_zero(ggx_vec3 v) { return v.x == 0.0 && v.y == 0.0 && v.z == 0.0; }

/* x if x > 0, else 0 (also for NaN): a compare-and-select, where fmax is a library call. */
static double max0(double x) { return x > 0.0 ? x : 0.0; }

/* cos and sin of 2 pi t, our own: t is reduced by the nearest quarter turn q to x in [-pi/4, pi/4], where the Taylor
 * series to x^17 (sin) and x^18 (cos) leave remainders below 1e-19, then the quarter turn is applied exactly. Faster
 * than sincos (no general range reduction) and within 2 ulp of it (tested). */
static void sincos_2pi(double t, double *c, double *s)
{
    double q = floor(4.0 * t + 0.5);
    double x = (t - 0.25 * q) * (2.0 * GGX_PI), x2 = x * x;
    double sn = x * (1.0 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880 +
                x2 * (-1.0 / 39916800 + x2 * (1.0 / 6227020800.0 + x2 * (-1.0 / 1307674368000.0 +
                x2 * (1.0 / 355687428096000.0)))))))));
    double cs = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 + x2 * (-1.0 / 3628800 +
                x2 * (1.0 / 479001600.0 + x2 * (-1.0 / 87178291200.0 + x2 * (1.0 / 20922789888000.0 +
                x2 * (-1.0 / 6402373705728000.0)))))))));
    switch ((int)fmod(q, 4.0) & 3) {
    case 0: *c = cs, *s = sn; break;
    case 1: *c = -sn, *s = cs; break;
    case 2: *c = -cs, *s = -sn; break;
    default: *c = sn, *s = -cs; break;
    }
}

static double clamp01(double u) { return u > 0.0 ? (u < 1.0 ? u : 1.0) : 0.0; } /* NaN -> 0 */

static ggx_vec3 normalize(ggx_vec3 v)
{
    double l = v3_len(v);
    return (l > 0.0 && l < HUGE_VAL) ? v3_scale(v, 1.0 / l) : zero3;
}

/* The direction of a caller's vector, robust to huge and denormal components (scaled by the largest one first);
 * the zero vector for a zero, infinite or NaN input. */
static ggx_vec3 safe_unit(ggx_vec3 v)
{
    double l2 = v3_dot(v, v);
    if (l2 > 1e-200 && l2 < 1e200) return v3_scale(v, 1.0 / sqrt(l2)); /* the usual case: no scaling needed */
    double m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
    if (!(m > 0.0 && m < HUGE_VAL)) return zero3;
    v = v3(v.x / m, v.y / m, v.z / m);
    return v3_scale(v, 1.0 / v3_len(v));
}

static ggx_vec3 cross(ggx_vec3 a, ggx_vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

/* A^T p, the map from a sphere-space point (or normal) to an ellipsoid normal direction. */
static ggx_vec3 mat_tmul(const double M[3][3], ggx_vec3 p)
{
    return v3(M[0][0] * p.x + M[1][0] * p.y + M[2][0] * p.z, M[0][1] * p.x + M[1][1] * p.y + M[2][1] * p.z,
              M[0][2] * p.x + M[1][2] * p.y + M[2][2] * p.z);
}

/* The ellipsoid normal of a sphere-space point p of the lune {p.z >= 0, p.vs >= 0}, kept strictly inside so that
 * its pdf is > 0: a point on the rim (u at the edge of the square, the rim of the disk) would give a normal on the
 * horizon or edge-on to the view. p is moved by 2^-30 along vs + z (raising both dot products by >= 2^-30, a set of
 * probability ~1e-9); then m.z >= 0 and m.v >= 2^-48 are verified in ellipsoid space, where rounding in A^T p can
 * still flip a sign for ill-conditioned A (alpha 1e-4 with a skew), doubling the step until they hold. v is the
 * unit view (z for NDF sampling). */
static ggx_vec3 finish_normal(const ggx_shape *s, ggx_vec3 p, ggx_vec3 vs, ggx_vec3 v)
{
    const double margin = 0x1p-48; /* far above the rounding of a dot product of unit vectors (~1e-16) */
    ggx_vec3 d = v3(vs.x, vs.y, vs.z + 1.0);
    double step = 0x1p-30;
    if (!(p.z >= step && v3_dot(p, vs) >= step)) p = v3_add(p, v3_scale(d, step));
    for (int k = 0; k < 64; k++, step *= 2.0) {
        ggx_vec3 m = normalize(mat_tmul(s->a, p));
        if (m.z >= 0.0 && v3_dot(m, v) >= margin) return m;
        p = v3_add(p, v3_scale(d, step));
    }
    /* The lune is too thin for any normal to clear the margin: a view within ~1e-9 of grazing the truncated
     * ellipsoid, which takes an ill-conditioned A. The documented invalid sample. */
    return zero3;
}

/* The same for a normal m in ellipsoid space (samplers that do not pass through sphere space). */
static ggx_vec3 above_horizon(ggx_vec3 m)
{
    const double d = 0x1p-30;
    if (!(m.z >= d)) m = normalize(v3(m.x, m.y, d));
    return m;
}

/* The sphere-space normal of an ellipsoid normal m: normalize(A^{-T} m). */
static ggx_vec3 stretch_normal(const ggx_shape *s, ggx_vec3 m) { return normalize(mat_mul(s->ainv_t, m)); }

/* The sphere-space view normalize(A v) and the unit view *vn; zero vector when v.z <= 0 or v is not finite. */
static ggx_vec3 stretch_view(const ggx_shape *s, ggx_vec3 v, ggx_vec3 *vn)
{
    *vn = safe_unit(v);
    if (!(vn->z > 0.0)) return zero3;
    return normalize(mat_mul(s->a, *vn));
}

static double angle01(double y, double x) /* atan2 mapped to [0, 1) */
{
    double t = atan2(y, x) / (2.0 * GGX_PI);
    return t < 0.0 ? t + 1.0 : (t < 1.0 ? t : 0.0);
}

/* ---- disk maps ---- */

ggx_vec2 ggx_disk_polar(double u1, double u2)
{
    double r = sqrt(clamp01(u1)), c, sn;
    sincos_2pi(clamp01(u2), &c, &sn);
    ggx_vec2 d = {r * c, r * sn};
    return d;
}

ggx_vec2 ggx_disk_polar_inv(ggx_vec2 d)
{
    ggx_vec2 u = {clamp01(d.x * d.x + d.y * d.y), angle01(d.y, d.x)};
    return u;
}

ggx_vec2 ggx_disk_concentric(double u1, double u2)
{
    double a = 2.0 * clamp01(u1) - 1.0, b = 2.0 * clamp01(u2) - 1.0;
    ggx_vec2 d = {0.0, 0.0};
    if (a == 0.0 && b == 0.0) return d; /* the centre: the angle below would divide 0 by 0 */
    if (fabs(a) > fabs(b)) {             /* Walter eq 36-37 */
        double phi = 0.25 * GGX_PI * b / a;
        d.x = a * cos(phi);
        d.y = a * sin(phi);
    } else {
        double phi = 0.25 * GGX_PI * a / b;
        d.x = b * sin(phi);
        d.y = b * cos(phi);
    }
    return d;
}

ggx_vec2 ggx_disk_concentric_inv(ggx_vec2 d)
{
    double r = hypot(d.x, d.y), a, b;
    if (!(r > 0.0)) {
        a = b = 0.0;
    } else if (fabs(d.x) >= fabs(d.y)) { /* left and right wedges: r = |a|, angle pi b / (4 a) */
        a = d.x >= 0.0 ? r : -r;
        b = a * atan(d.y / d.x) / (0.25 * GGX_PI);
    } else { /* top and bottom wedges: r = |b|, angle pi a / (4 b) measured from the y axis */
        b = d.y >= 0.0 ? r : -r;
        a = b * atan(d.x / d.y) / (0.25 * GGX_PI);
    }
    ggx_vec2 u = {clamp01(0.5 * (a + 1.0)), clamp01(0.5 * (b + 1.0))};
    return u;
}

/* ---- NDF sampling ---- */

double ggx_pdf_ndf(const ggx_shape *s, ggx_vec3 m) { return finite_or_zero(ggx_ndf(s, m) * m.z); }

ggx_vec3 ggx_sample_ndf(const ggx_shape *s, double u1, double u2) { return ggx_sample_ndf_stretch(s, u1, u2); }

/* Engstad: the cosine-weighted hemisphere about the sphere-space pole z, then the stretch. In sphere space the pdf
 * D(m) m.n is the cosine lobe (m'.z) / pi (the change of variables d omega_m = |A| / ||A^T m'||^3 d omega_m'). */
ggx_vec3 ggx_sample_ndf_stretch(const ggx_shape *s, double u1, double u2)
{
    u1 = clamp01(u1);
    double r = sqrt(u1), c, sn;
    sincos_2pi(clamp01(u2), &c, &sn);
    ggx_vec3 z = v3(0.0, 0.0, 1.0);
    return finish_normal(s, v3(r * c, r * sn, sqrt(1.0 - u1)), z, z);
}

ggx_vec2 ggx_sample_ndf_stretch_inv(const ggx_shape *s, ggx_vec3 m)
{
    ggx_vec3 c = stretch_normal(s, m);
    ggx_vec2 u = {clamp01(c.x * c.x + c.y * c.y), angle01(c.y, c.x)};
    return u;
}

/* Blog Part 2 for any A. With M = A^T A the ellipsoid is x^T M x = 1; its shadow on the tangent plane is the
 * ellipse q^T S q <= 1 with S the Schur complement M_xy - M_xz M_zx / M_zz. A uniform point q = L^{-T} d (S = L L^T,
 * d uniform in the unit disk) is lifted to the upper surface (the larger root z) and m = M x / ||M x||. */
ggx_vec3 ggx_sample_ndf_ellipse(const ggx_shape *s, double u1, double u2)
{
    const double(*A)[3] = s->a;
    double M[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) M[i][j] = A[0][i] * A[0][j] + A[1][i] * A[1][j] + A[2][i] * A[2][j];
    double s00 = M[0][0] - M[0][2] * M[0][2] / M[2][2];
    double s01 = M[0][1] - M[0][2] * M[1][2] / M[2][2];
    double s11 = M[1][1] - M[1][2] * M[1][2] / M[2][2];
    /* S = L L^T with L = [l00 0; l10 l11]; q = L^{-T} d solves l00 q0 + l10 q1 = d0, l11 q1 = d1. */
    double l00 = sqrt(s00), l10 = s01 / l00, l11 = sqrt(s11 - l10 * l10);
    ggx_vec2 d = ggx_disk_polar(u1, u2);
    double q1 = d.y / l11, q0 = (d.x - l10 * q1) / l00;
    /* M_zz z^2 + 2 b z + (q^T M_xy q - 1) = 0 with b = M_xz q0 + M_yz q1; since q^T S q = |d|^2 <= 1 the
     * discriminant is M_zz (1 - |d|^2) >= 0. */
    double b = M[0][2] * q0 + M[1][2] * q1;
    double disc = M[2][2] * (1.0 - (d.x * d.x + d.y * d.y));
    double z = (-b + sqrt(disc > 0.0 ? disc : 0.0)) / M[2][2];
    ggx_vec3 x = v3(q0, q1, z);
    return above_horizon(normalize(mat_mul((const double(*)[3])M, x))); /* the rim of the silhouette */
}

ggx_vec3 ggx_sample_ndf_inversion(const ggx_shape *s, double u1, double u2)
{
    if (s->kind == GGX_SHAPE_SKEWED) return zero3;
    u1 = clamp01(u1);
    double phi = 2.0 * GGX_PI * clamp01(u2), c = cos(phi), sn = sin(phi);
    double ax = s->alpha_x, ay = s->alpha_y;
    double tan_t = sqrt(u1 / (1.0 - u1)) * sqrt(ax * ax * c * c + ay * ay * sn * sn);
    double cos_t = 1.0 / sqrt(1.0 + tan_t * tan_t), sin_t = tan_t * cos_t;
    if (!(tan_t < HUGE_VAL)) cos_t = 0.0, sin_t = 1.0; /* u1 = 1: the horizon */
    double phi_m = atan2(ay * sn, ax * c);
    double xt = sin_t * cos(phi_m), yt = sin_t * sin(phi_m); /* tangent frame of the shape */
    double tc = s->tangent_cos, ts = s->tangent_sin;
    return above_horizon(v3(tc * xt - ts * yt, ts * xt + tc * yt, cos_t));
}

ggx_vec3 ggx_sample_ndf_visible(const ggx_shape *s, double u1, double u2)
{
    return ggx_sample_vndf_caps(s, v3(0.0, 0.0, 1.0), u1, u2);
}

/* ---- VNDF sampling ---- */

ggx_vec3 ggx_sample_vndf(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    return ggx_sample_vndf_caps(s, v, u1, u2);
}

ggx_vec3 ggx_sample_vndf_caps(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    ggx_vec3 vn, vs = stretch_view(s, v, &vn);
    if (is_zero(vs)) return zero3; /* no view; note vs.z = 0 is a valid view (skewed A, grazing v) */
    double c, sn;
    sincos_2pi(clamp01(u1), &c, &sn);
    double z = (1.0 - clamp01(u2)) * (1.0 + vs.z) - vs.z;
    double r = sqrt(max0(1.0 - z * z));
    ggx_vec3 h = v3(vs.x + r * c, vs.y + r * sn, vs.z + z); /* unnormalised sphere-space normal */
    return finish_normal(s, h, vs, vn); /* also covers c = -v', where h vanishes */
}

ggx_vec2 ggx_sample_vndf_caps_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    ggx_vec3 vn, vs = stretch_view(s, v, &vn), ms = stretch_normal(s, m);
    ggx_vec3 c = v3_sub(v3_scale(ms, 2.0 * v3_dot(vs, ms)), vs); /* reflect v' about m' */
    ggx_vec2 u = {angle01(c.y, c.x), clamp01(1.0 - (c.z + vs.z) / (1.0 + vs.z))};
    return u;
}

/* Walter's frame (eq 42-44) in canonical sphere space, where A n is along z: e3 = v', e2 = v' x z normalised, e1 =
 * e2 x e3, the direction perpendicular to v' closest to A n. For v' along z any e2 will do. */
static void crescent_frame(ggx_vec3 vs, ggx_vec3 *e1, ggx_vec3 *e2)
{
    double l = hypot(vs.x, vs.y);
    *e2 = l > 0.0 ? v3(vs.y / l, -vs.x / l, 0.0) : v3(0.0, 1.0, 0.0);
    *e1 = cross(*e2, vs);
}

static ggx_vec3 crescent(const ggx_shape *s, ggx_vec3 v, ggx_vec2 d)
{
    ggx_vec3 vn, vs = stretch_view(s, v, &vn);
    if (is_zero(vs)) return zero3; /* no view; note vs.z = 0 is a valid view (skewed A, grazing v) */
    ggx_vec3 e1, e2;
    crescent_frame(vs, &e1, &e2);
    double sc = 0.5 * (1.0 + vs.z); /* eq 38 with A n / ||A n|| = z */
    double xb = sc * d.x + (1.0 - sc) * sqrt(max0(1.0 - d.y * d.y)); /* eq 39 */
    double zb = sqrt(max0(1.0 - xb * xb - d.y * d.y));             /* eq 41 */
    ggx_vec3 p = v3_add(v3_add(v3_scale(e1, xb), v3_scale(e2, d.y)), v3_scale(vs, zb)); /* eq 45 */
    return finish_normal(s, p, vs, vn);
}

/* Disk coordinates of m under the crescent map: the inverse of eq 39-45. */
static ggx_vec2 crescent_disk(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    ggx_vec3 vn, vs = stretch_view(s, v, &vn), p = stretch_normal(s, m), e1, e2;
    crescent_frame(vs, &e1, &e2);
    double sc = 0.5 * (1.0 + vs.z);
    double xb = v3_dot(p, e1), yb = v3_dot(p, e2);
    ggx_vec2 d = {(xb - (1.0 - sc) * sqrt(max0(1.0 - yb * yb))) / sc, yb};
    return d;
}

ggx_vec3 ggx_sample_vndf_crescent(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    return crescent(s, v, ggx_disk_concentric(u1, u2));
}

ggx_vec3 ggx_sample_vndf_crescent_polar(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    return crescent(s, v, ggx_disk_polar(u1, u2));
}

ggx_vec2 ggx_sample_vndf_crescent_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    return ggx_disk_concentric_inv(crescent_disk(s, v, m));
}

ggx_vec2 ggx_sample_vndf_crescent_polar_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    return ggx_disk_polar_inv(crescent_disk(s, v, m));
}

/* Heitz's frame: T1 = z x v' normalised (x axis when v' is along z), T2 = v' x T1. */
static void heitz_frame(ggx_vec3 vs, ggx_vec3 *t1, ggx_vec3 *t2)
{
    double l = hypot(vs.x, vs.y);
    *t1 = l > 0.0 ? v3(-vs.y / l, vs.x / l, 0.0) : v3(1.0, 0.0, 0.0);
    *t2 = cross(vs, *t1);
}

ggx_vec3 ggx_sample_vndf_heitz(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    ggx_vec3 vn, vs = stretch_view(s, v, &vn);
    if (is_zero(vs)) return zero3; /* no view; note vs.z = 0 is a valid view (skewed A, grazing v) */
    ggx_vec3 t1, t2;
    heitz_frame(vs, &t1, &t2);
    ggx_vec2 d = ggx_disk_polar(u1, u2);
    double sq = 0.5 * (1.0 + vs.z);
    double y = (1.0 - sq) * sqrt(max0(1.0 - d.x * d.x)) + sq * d.y; /* the squish (Engstad's zeta) */
    double z = sqrt(max0(1.0 - d.x * d.x - y * y));
    return finish_normal(s, v3_add(v3_add(v3_scale(t1, d.x), v3_scale(t2, y)), v3_scale(vs, z)), vs, vn);
}

ggx_vec2 ggx_sample_vndf_heitz_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    ggx_vec3 vn, vs = stretch_view(s, v, &vn), p = stretch_normal(s, m), t1, t2;
    heitz_frame(vs, &t1, &t2);
    double sq = 0.5 * (1.0 + vs.z);
    double x = v3_dot(p, t1), y = v3_dot(p, t2);
    ggx_vec2 d = {x, (y - (1.0 - sq) * sqrt(max0(1.0 - x * x))) / sq};
    return ggx_disk_polar_inv(d);
}

enum { MAX_TRIALS = 100000 };

/* Smallest singular value of A: the square root of the smallest eigenvalue of the symmetric M = A^T A, by the
 * trigonometric solution of its characteristic cubic. */
static double sigma_min(const ggx_shape *s)
{
    const double(*A)[3] = s->a;
    double M[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) M[i][j] = A[0][i] * A[0][j] + A[1][i] * A[1][j] + A[2][i] * A[2][j];
    double q = (M[0][0] + M[1][1] + M[2][2]) / 3.0;
    double p1 = M[0][1] * M[0][1] + M[0][2] * M[0][2] + M[1][2] * M[1][2];
    double p2 = (M[0][0] - q) * (M[0][0] - q) + (M[1][1] - q) * (M[1][1] - q) + (M[2][2] - q) * (M[2][2] - q) + 2 * p1;
    double p = sqrt(p2 / 6.0);
    if (!(p > 0.0)) return sqrt(q);
    double B[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) B[i][j] = (M[i][j] - (i == j ? q : 0.0)) / p;
    double detb = B[0][0] * (B[1][1] * B[2][2] - B[1][2] * B[2][1]) - B[0][1] * (B[1][0] * B[2][2] - B[1][2] * B[2][0]) +
                  B[0][2] * (B[1][0] * B[2][1] - B[1][1] * B[2][0]);
    double r = fmax(-1.0, fmin(1.0, 0.5 * detb));
    /* The two largest roots are accurate; the smallest, where the spread is large, is taken from the determinant:
     * lambda_min = det(M) / (lambda_max lambda_mid) = |A|^2 / (lambda_max lambda_mid). */
    double lmax = q + 2.0 * p * cos(acos(r) / 3.0);
    double lmin_trig = q + 2.0 * p * cos(acos(r) / 3.0 + 2.0 * GGX_PI / 3.0);
    double lmid = 3.0 * q - lmax - lmin_trig;
    return sqrt(s->det * s->det / (lmax * lmid));
}

/* An orthonormal pair perpendicular to the unit vector w. */
static void perp_frame(ggx_vec3 w, ggx_vec3 *f1, ggx_vec3 *f2)
{
    ggx_vec3 a = fabs(w.x) < 0.6 ? v3(1.0, 0.0, 0.0) : v3(0.0, 1.0, 0.0);
    *f1 = normalize(cross(a, w));
    *f2 = cross(w, *f1);
}

ggx_vec3 ggx_sample_vndf_walter_v1(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state,
                                   unsigned *trials)
{
    if (trials) *trials = 0;
    v = safe_unit(v);
    if (!(v.z > 0.0) || !next) return zero3;
    double R = (1.0 + 1e-9) / sigma_min(s); /* bounding sphere of {x : ||A x|| = 1}, with a rounding margin */
    ggx_vec3 f1, f2;
    perp_frame(v, &f1, &f2);
    ggx_vec3 av = mat_mul(s->a, v);
    double aa = v3_dot(av, av);
    for (unsigned t = 1; t <= MAX_TRIALS; t++) {
        if (trials) *trials = t;
        double u1 = next(state);
        ggx_vec2 d = ggx_disk_polar(u1, next(state));
        ggx_vec3 o = v3_add(v3_scale(f1, R * d.x), v3_scale(f2, R * d.y));
        /* ||A (o + t v)||^2 = 1; the first hit seen from v is the larger root. */
        ggx_vec3 ao = mat_mul(s->a, o);
        double b = v3_dot(ao, av), c = v3_dot(ao, ao) - 1.0, disc = b * b - aa * c;
        if (disc < 0.0) continue; /* the ray misses the ellipsoid */
        double tt = (-b + sqrt(disc)) / aa;
        ggx_vec3 ax = v3_add(ao, v3_scale(av, tt)); /* A x, a point of the unit sphere */
        if (ax.z < 0.0) continue;                   /* m.n < 0: outside the truncated ellipsoid */
        return finish_normal(s, ax, normalize(av), v);
    }
    return zero3;
}

ggx_vec3 ggx_sample_vndf_walter_v2(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state,
                                   unsigned *trials)
{
    if (trials) *trials = 0;
    ggx_vec3 vn, vs = stretch_view(s, v, &vn);
    if (is_zero(vs) || !next) return zero3;
    ggx_vec3 f1, f2;
    perp_frame(vs, &f1, &f2);
    for (unsigned t = 1; t <= MAX_TRIALS; t++) {
        if (trials) *trials = t;
        double u1 = next(state);
        ggx_vec2 d = ggx_disk_polar(u1, next(state));
        /* Project the silhouette point onto the sphere along A v, the side facing the viewer. */
        double h = sqrt(max0(1.0 - d.x * d.x - d.y * d.y));
        ggx_vec3 p = v3_add(v3_add(v3_scale(f1, d.x), v3_scale(f2, d.y)), v3_scale(vs, h));
        if (p.z < 0.0) continue; /* outside the lune */
        return finish_normal(s, p, vs, vn);
    }
    return zero3;
}

/* ---- directions ---- */

static ggx_sample invalid_sample(void)
{
    ggx_sample r = {{0.0, 0.0, 0.0}, 0.0, 0.0, GGX_EVENT_INVALID};
    return r;
}

double ggx_pdf_brdf(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo)
{
    if (!(wi.z > 0.0 && wo.z > 0.0)) return 0.0;
    ggx_vec3 h = ggx_half_reflect(wi, wo);
    return finite_or_zero(ggx_pdf_vndf(s, wi, h) / (4.0 * v3_dot(wi, h))); /* eq 48 */
}

ggx_sample ggx_sample_brdf(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2)
{
    wi = safe_unit(wi); /* the samplers depend on the direction of the view only */
    if (!(wi.z > 0.0)) return invalid_sample();
    ggx_vec3 m = ggx_sample_vndf(s, wi, u1, u2);
    double wm = v3_dot(wi, m);
    if (!(wm > 0.0)) return invalid_sample();
    ggx_vec3 wo = ggx_reflect(wi, m); /* eq 47 */
    if (!(wo.z > 0.0)) return invalid_sample();
    double pdf = ggx_pdf_vndf(s, wi, m) / (4.0 * wm);
    if (!(pdf > 0.0 && pdf < HUGE_VAL)) return invalid_sample();
    /* eq 50-51 in closed form: with r = A_l(wi, n) / (A_e(n) wi.n) = 1 / G1_smith(wi), the weight is
     * G1(wi) r G1(wo) F = min(1, r) G1(wo, m) F, a product of factors <= 1, so eq 52 holds in floating point too. */
    double g1s = ggx_g1_smith(s, wi);
    double weight = (g1s > 1.0 ? 1.0 / g1s : 1.0) * ggx_g1(s, wo, m) * ggx_fresnel_eval(f, wm);
    ggx_sample r = {wo, pdf, finite_or_zero(weight), GGX_EVENT_REFLECT};
    return r;
}

/* Indices on the two sides: the known direction v's side and the other. */
static void sides(double eta, ggx_vec3 v, double *eta_v, double *eta_t)
{
    *eta_v = v.z > 0.0 ? 1.0 : eta;
    *eta_t = v.z > 0.0 ? eta : 1.0;
}

ggx_sample ggx_sample_bsdf(const ggx_shape *s, double eta, ggx_vec3 v, double u1, double u2, double u3,
                           ggx_transport mode)
{
    v = safe_unit(v); /* the samplers depend on the direction of the view only */
    if (!(eta > 0.0 && eta < HUGE_VAL) || !(v.z != 0.0)) return invalid_sample();
    ggx_vec3 vu = v.z > 0.0 ? v : v3_neg(v);
    ggx_vec3 m = ggx_sample_vndf(s, vu, u1, u2);
    double vm = v3_dot(vu, m);
    if (!(vm > 0.0)) return invalid_sample();
    double eta_v, eta_t;
    sides(eta, v, &eta_v, &eta_t);
    double F = ggx_fresnel_dielectric_eval(vm, eta_t / eta_v);
    double dv = ggx_pdf_vndf(s, vu, m);
    ggx_sample r;
    if (clamp01(u3) < F) {
        r.w = ggx_reflect(v, m);
        if (!((r.w.z > 0.0) == (v.z > 0.0)) || r.w.z == 0.0) return invalid_sample();
        r.pdf = dv * F / (4.0 * vm);
        r.event = GGX_EVENT_REFLECT;
    } else {
        if (!ggx_refract(v, m, eta_t / eta_v, &r.w)) return invalid_sample();
        if (!((r.w.z > 0.0) != (v.z > 0.0)) || r.w.z == 0.0) return invalid_sample();
        r.pdf = dv * (1.0 - F) * ggx_jacobian_refract(v, r.w, m, eta_v, eta_t);
        r.event = GGX_EVENT_TRANSMIT;
    }
    if (!(r.pdf > 0.0 && r.pdf < HUGE_VAL)) return invalid_sample();
    r.weight = finite_or_zero(ggx_bsdf_eval(s, eta, r.w, v, mode) * fabs(r.w.z) / r.pdf);
    return r;
}

double ggx_pdf_bsdf(const ggx_shape *s, double eta, ggx_vec3 v, ggx_vec3 w)
{
    if (!(eta > 0.0 && eta < HUGE_VAL) || !(v.z != 0.0 && w.z != 0.0)) return 0.0;
    ggx_vec3 vu = v.z > 0.0 ? v : v3_neg(v);
    double eta_v, eta_t;
    sides(eta, v, &eta_v, &eta_t);
    if ((v.z > 0.0) == (w.z > 0.0)) {
        ggx_vec3 h = ggx_half_reflect(v, w);
        double vm = v3_dot(vu, h);
        if (!(vm > 0.0) || !(v3_dot(w, h) * (w.z > 0.0 ? 1.0 : -1.0) > 0.0)) return 0.0;
        double F = ggx_fresnel_dielectric_eval(vm, eta_t / eta_v);
        return finite_or_zero(ggx_pdf_vndf(s, vu, h) * F / (4.0 * vm));
    }
    ggx_vec3 h = ggx_half_refract(v, w, eta_v, eta_t);
    double vm = v3_dot(vu, h);
    /* m must face v's side and w must leave through the other side of the facet */
    if (!(vm > 0.0) || !(v3_dot(w, h) * (v.z > 0.0 ? 1.0 : -1.0) < 0.0)) return 0.0;
    double F = ggx_fresnel_dielectric_eval(vm, eta_t / eta_v);
    return finite_or_zero(ggx_pdf_vndf(s, vu, h) * (1.0 - F) * ggx_jacobian_refract(v, w, h, eta_v, eta_t));
}
