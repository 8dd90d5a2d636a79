/* OpenEXR surfaces: not yet read (a later step adds the OpenEXR library's reader). SPDX-License-Identifier: MIT */
#include "surface.h"

int surface_parse_exr(const unsigned char *data, size_t n, const surface_read_options *o, surface *s, char *err,
                      size_t errn)
{
    (void)data, (void)n, (void)o, (void)s;
    return surface_fail(err, errn, "OpenEXR surfaces are not supported yet");
}

int surface_write_exr(const char *path, const surface *s, char *err, size_t errn)
{
    (void)path, (void)s;
    return surface_fail(err, errn, "OpenEXR surfaces are not supported yet");
}
