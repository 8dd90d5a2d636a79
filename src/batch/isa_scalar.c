/* The batch loops compiled for the scalar path (flags in CMakeLists.txt). SPDX-License-Identifier: MIT */
#define KERNELS ggx_kernels_scalar
#include "loops.inc"
