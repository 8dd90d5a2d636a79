/* The batch loops compiled for the avx2 path (flags in CMakeLists.txt). SPDX-License-Identifier: MIT */
#define KERNELS ggx_kernels_avx2
#include "loops.inc"
