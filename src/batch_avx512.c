/* The batch kernels compiled for the avx512 path (flags set in CMakeLists.txt). SPDX-License-Identifier: MIT */
#define KERNELS ggx_kernels_avx512
#include "batch_kernels.inc"
