/* The engines' normal-map filters (normal_filters.h). SPDX-License-Identifier: MIT */
#include "normal_filters.h"

#include <math.h>

const char *const nf_name[NF_BASELINES] = {"no filtering", "Toksvig", "variance widening", "ours without skew"};

/* alpha'^2 of the isotropic baselines from the mean length len of the unit normals and the mean base alpha^2 */
static double widened(nf_kind k, double len, double a2)
{
    if (a2 >= 1.0) return a2; /* both assume alpha <= 1 (a Blinn-Phong exponent >= 0; a saturated alpha^2 <= 1) */
    if (k == NF_TOKSVIG) {
        double sp = 2.0 / a2 - 2.0, ft = len / (len + sp * (1.0 - len));
        return 2.0 / (ft * sp + 2.0);
    }
    if (k == NF_VARIANCE && len < 1.0) {
        double kappa = (3.0 * len - len * len * len) / (1.0 - len * len);
        return fmin(1.0, a2 + fmin(2.0 / kappa, 0.18));
    }
    return a2;
}

int nf_baseline(nf_kind k, ggx_vec3 m, double alpha2, const double sigma[3], nf_lobe *out)
{
    double len = sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
    if (!(len > 0.0) || !isfinite(len) || !(m.z > 0.0)) return -1;
    len = fmin(len, 1.0);
    double nx = m.x / len, ny = m.y / len, nz = fmin(m.z / len, 1.0), a = 1.0 / (1.0 + nz);
    /* the least rotation taking z to n: its images of x and y */
    const double F[3][3] = {
        {1.0 - a * nx * nx, -a * nx * ny, -nx}, {-a * nx * ny, 1.0 - a * ny * ny, -ny}, {nx, ny, nz}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) out->frame[i][j] = F[i][j];
    ggx_status st;
    if (k == NF_UNSKEWED) st = ggx_shape_from_slopes(&out->s, 0.0, 0.0, sigma[0], sigma[1], sigma[2]);
    else st = ggx_shape_iso(&out->s, sqrt(widened(k, len, alpha2)));
    return st == GGX_OK ? 0 : -1;
}

static ggx_vec3 to_frame(const double F[3][3], ggx_vec3 v)
{
    ggx_vec3 r = {F[0][0] * v.x + F[0][1] * v.y + F[0][2] * v.z, F[1][0] * v.x + F[1][1] * v.y + F[1][2] * v.z,
                  F[2][0] * v.x + F[2][1] * v.y + F[2][2] * v.z};
    return r;
}

double nf_radiance(const nf_lobe *b, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo)
{
    ggx_vec3 li = to_frame(b->frame, wi), lo = to_frame(b->frame, wo);
    if (!(li.z > 0.0) || !(lo.z > 0.0)) return 0.0;
    return ggx_brdf_eval(&b->s, f, li, lo) * li.z;
}

ggx_status nf_tangent_shape(const nf_lobe *b, ggx_shape *out)
{
    double A[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            A[i][j] = b->s.a[i][0] * b->frame[0][j] + b->s.a[i][1] * b->frame[1][j] + b->s.a[i][2] * b->frame[2][j];
    return ggx_shape_matrix(out, (const double(*)[3])A);
}
