/* V-grooves (microsurface.h). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "microsurface.h"

int ms_vgroove(size_t n, size_t p, double s, double *h, char *err, size_t errn)
{
    if (n < 2 || n > 16384 || p < 2 || p % 2 != 0 || n % p != 0 || !(s > 0.0 && s <= 100.0)) {
        snprintf(err, errn,
                 "V-grooves: size %zu, period %zu, slope %g: give an even period dividing the size and a "
                 "slope in (0, 100]",
                 n, p, s);
        return -1;
    }
    for (size_t y = 0; y < n; y++)
        for (size_t x = 0; x < n; x++) {
            size_t r = x % p;
            h[y * n + x] = s * (double)(r <= p / 2 ? r : p - r);
        }
    return 0;
}
