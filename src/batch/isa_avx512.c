/* The batch loops compiled for the avx512 path (flags in CMakeLists.txt). SPDX-License-Identifier: MIT */
#define KERNELS ggx_kernels_avx512
#include "loops.inc"
