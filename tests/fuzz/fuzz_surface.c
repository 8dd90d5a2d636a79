/* libFuzzer target: the readers of measured surfaces (libs/surface) on arbitrary bytes. The first byte picks
 * the format, heights or normals and the y convention; the rest is the file. A reader must refuse (with a reason and
 * nothing allocated) or return a consistent surface; ASan, UBSan and LeakSanitizer catch the rest.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

#define REQUIRE(cond)                                                                                                  \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            fprintf(stderr, "contract violated: %s\n", #cond);                                                         \
            abort();                                                                                                   \
        }                                                                                                              \
    } while (0)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t n);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t n)
{
    if (n < 1) return 0;
    /* the formats parsed by this project's code: CSV to x3p, and PFM (Radiance .hdr is stb_image's own) */
    surface_format f = data[0] % 8 == 7 ? SURFACE_PFM : (surface_format)(data[0] % 8);
    surface_read_options o = {(data[0] >> 5) & 1   ? SURFACE_RADIANCE
                              : (data[0] >> 3) & 1 ? SURFACE_NORMALS
                                                   : SURFACE_HEIGHTS,
                              (data[0] >> 4) & 1};
    surface s;
    char err[256] = "";
    int rc = surface_parse(f, data + 1, n - 1, &o, &s, err, sizeof err);
    if (rc != 0) {
        REQUIRE(rc == -1 && err[0] != '\0');
        REQUIRE(s.h == NULL && s.m == NULL && s.w == NULL && s.rgb == NULL);
        return 0;
    }
    REQUIRE(s.kind == o.want && s.nx >= 1 && s.ny >= 1);
    size_t count = s.nx * s.ny;
    REQUIRE(count / s.nx == s.ny);
    if (s.kind == SURFACE_HEIGHTS) {
        REQUIRE(s.h != NULL && s.nx >= 2 && s.ny >= 2);
        double sum = 0.0;
        for (size_t i = 0; i < count; i++) sum += isfinite(s.h[i]) ? s.h[i] * 0.0 : 0.0; /* every element readable */
        REQUIRE(sum == 0.0);
    } else if (s.kind == SURFACE_RADIANCE) {
        REQUIRE(s.rgb != NULL);
        double sum = 0.0;
        for (size_t i = 0; i < 3 * count; i++) sum += isfinite(s.rgb[i]) ? s.rgb[i] * 0.0f : 0.0;
        REQUIRE(sum == 0.0);
    } else {
        REQUIRE(s.m != NULL);
        if (f != SURFACE_CSV)
            for (size_t i = 0; i < count; i++) { /* a map's texels are unit normals or the zero vector */
                double l = s.m[i].x * s.m[i].x + s.m[i].y * s.m[i].y + s.m[i].z * s.m[i].z;
                REQUIRE(l == 0.0 || fabs(l - 1.0) < 1e-9);
            }
    }
    REQUIRE(s.dx >= 0.0 && s.dy >= 0.0 && s.z_scale >= 0.0);
    surface_free(&s);
    return 0;
}
