/* Decodes a PNG completely with cairo (libpng inside) and prints "WIDTH HEIGHT"; exit 1 if it is not a valid PNG.
 * Used by the CLI tests. SPDX-License-Identifier: MIT */
#include <cairo.h>
#include <stdio.h>

int main(int argc, char **argv)
{
    if (argc != 2) return 2;
    cairo_surface_t *s = cairo_image_surface_create_from_png(argv[1]);
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        fprintf(stderr, "png_info: %s is not a valid PNG (%s)\n", argv[1],
                cairo_status_to_string(cairo_surface_status(s)));
        return 1;
    }
    printf("%d %d\n", cairo_image_surface_get_width(s), cairo_image_surface_get_height(s));
    cairo_surface_destroy(s);
    return 0;
}
