/* The batch kernels compiled for the scalar path (flags set in CMakeLists.txt). SPDX-License-Identifier: MIT */
#define KERNELS ggx_kernels_scalar
#include "batch_kernels.inc"
