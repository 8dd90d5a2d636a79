/* The exported double API: the kernels of ggx_inline.h and the export macro. SPDX-License-Identifier: MIT */
#ifndef GGX_API_INTERNAL_H
#define GGX_API_INTERNAL_H

/* The library inlines every kernel into its exported functions and batch loops (no call overhead, and loops the
 * compiler can vectorise). */
#if defined(__GNUC__)
#define GGX_HD static inline __attribute__((always_inline, unused))
#endif
#include "ggx/ggx_inline.h"

#define GGX_PI 3.14159265358979323846

/* Every public function is defined with GGX_API; the library is built with hidden visibility, so libggx.so exports
 * exactly the public ggx_* API (tests/exports.sh checks it). */
#if defined(__GNUC__)
#define GGX_API __attribute__((visibility("default")))
#else
#define GGX_API
#endif

#endif
