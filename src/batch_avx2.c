/* The batch kernels compiled for the avx2 path (flags set in CMakeLists.txt). SPDX-License-Identifier: MIT */
#define KERNELS ggx_kernels_avx2
#include "batch_kernels.inc"
