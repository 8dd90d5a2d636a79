// The public header compiles as C++11 (extern "C", no C-only constructs) and links. SPDX-License-Identifier: MIT
#include "ggx/ggx.h"

#include <cstring>

int main()
{
    ggx_shape s;
    ggx_vec3 n = {0.0, 0.0, 1.0};
    const double A[3][3] = {{0.5, 0.0, 0.0}, {0.0, 0.5, 0.0}, {0.0, 0.0, 1.0}};
    if (ggx_shape_matrix(&s, A) != GGX_OK) return 1;
    if (std::strcmp(ggx_status_str(GGX_ERR_SINGULAR), "ok") == 0) return 1;
    return ggx_ndf(&s, n) > 0.0 ? 0 : 1;
}
