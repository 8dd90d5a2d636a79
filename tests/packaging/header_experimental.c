/* ggx_experimental.h named beside ggx.h (its guard keeps one copy), its samplers link and keep their contract (a
 * sampler of visible normals gives a normal the view sees, and its inverse map gives back the numbers).
 * SPDX-License-Identifier: MIT */
#include "ggx/ggx.h"
#include "ggx/ggx_experimental.h"

int main(void)
{
    ggx_shape s;
    ggx_vec3 v = {0.6, 0.0, 0.8};
    if (ggx_shape_ellipsoid(&s, 0.2, 0.4, 0.1, -0.1, 0.3) != GGX_OK) return 1;
    ggx_vec3 m = ggx_sample_vndf_crescent(&s, v, 0.3, 0.7);
    ggx_vec2 u = ggx_sample_vndf_crescent_inv(&s, v, m);
    if (!(m.x * v.x + m.y * v.y + m.z * v.z > 0.0)) return 1;
    /* the inverse map gives back the numbers that made m */
    return u.x > 0.3 - 1e-9 && u.x < 0.3 + 1e-9 && u.y > 0.7 - 1e-9 && u.y < 0.7 + 1e-9 ? 0 : 1;
}
