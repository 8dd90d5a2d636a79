/* The public header compiles as strict C11 with every warning on, and links; it still declares the research entry
 * points of ggx_experimental.h (programs written against ggx.h alone keep compiling). SPDX-License-Identifier: MIT */
#include "ggx/ggx.h"

#include <string.h>

int main(void)
{
    ggx_shape s;
    ggx_vec3 n = {0.0, 0.0, 1.0};
    if (ggx_shape_iso(&s, 0.5) != GGX_OK) return 1;
    if (strcmp(ggx_status_str(GGX_OK), "ok") != 0) return 1;
    ggx_vec3 m = ggx_sample_vndf_heitz(&s, n, 0.25, 0.5);
    if (!(m.z > 0.0)) return 1;
    return ggx_ndf(&s, n) > 0.0 ? 0 : 1;
}
