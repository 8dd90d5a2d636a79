/* The library's version. SPDX-License-Identifier: MIT */
#include "internal.h"

GGX_API const char *ggx_version(void) { return GGX_VERSION_STRING; }
