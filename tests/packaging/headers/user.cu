/* A user's CUDA translation unit: the header and two kernels, compiled by tests/packaging/header_matrix.sh under nvcc with the
 * host compilers it finds, every host warning an error. SPDX-License-Identifier: MIT */
#include "ggx/ggx_inline.h"

__global__ void user_pdf(const ggx_shapef *s, ggx_vec3f v, const float *u, float *out, int n)
{
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    ggx_vec3f m = ggx_sample_vndf_f(s, v, u[2 * i], u[2 * i + 1]);
    out[i] = ggx_pdf_vndf_f(s, v, m);
}
