/* Status messages. SPDX-License-Identifier: MIT */
#include "internal.h"

GGX_API const char *ggx_status_str(ggx_status status)
{
    switch (status) {
    case GGX_OK: return "ok";
    case GGX_ERR_NULL: return "a required pointer argument is NULL";
    case GGX_ERR_NONFINITE: return "a parameter is NaN or infinite";
    case GGX_ERR_ALPHA: return "roughness alpha must be in (0, 1e4]";
    case GGX_ERR_ANGLE: return "skew angles theta_x, theta_y must be within [-pi/2, pi/2]";
    case GGX_ERR_SINGULAR:
        return "the shape matrix is singular or too ill-conditioned (|det A| <= 1e-12 ||A||_F^3, e.g. roughnesses "
               "1e-4 and 1e4 together)";
    case GGX_ERR_ETA:
        return "an index of refraction must be in (0, 1e300] (and k >= 0), and not exactly 1 for a rough "
               "dielectric's energy tables";
    case GGX_ERR_RANGE: return "a parameter is outside its documented range";
    case GGX_ERR_MEMORY: return "memory could not be allocated";
    case GGX_ERR_DATA:
        return "too few usable samples to fit: fewer than 5 normals above the horizon with finite components and a "
               "positive weight";
    }
    return "unknown status";
}
