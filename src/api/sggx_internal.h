/* What the SGGX sources share (src/api/sggx*.c): sigma, written once. SPDX-License-Identifier: MIT */
#ifndef GGX_API_SGGX_INTERNAL_H
#define GGX_API_SGGX_INTERNAL_H

#include "internal.h"

/* sigma(w) = ||S^(1/2) w||: 0 for a zero or NaN w. */
static inline double ggx_internal_sggx_sigma(const ggx_sggx *f, ggx_vec3 w)
{
    return ggx_k_finite0_d(ggx_k_len_d(ggx_k_mul_d(f->half, w)));
}

#endif
