/* The public header compiles as strict C11 with every warning on, and links. SPDX-License-Identifier: MIT */
#include "ggx/ggx.h"

#include <string.h>

int main(void)
{
    ggx_shape s;
    ggx_vec3 n = {0.0, 0.0, 1.0};
    if (ggx_shape_iso(&s, 0.5) != GGX_OK) return 1;
    if (strcmp(ggx_status_str(GGX_OK), "ok") != 0) return 1;
    return ggx_ndf(&s, n) > 0.0 ? 0 : 1;
}
