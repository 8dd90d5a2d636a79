/* Decodes a PNG completely with libpng and prints "WIDTH HEIGHT"; exit 1 if it is not a valid PNG.
 * Used by the CLI tests. SPDX-License-Identifier: MIT */
#include <png.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc != 2) return 2;
    FILE *f = fopen(argv[1], "rb");
    if (!f) return 1;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    unsigned char *row = NULL;
    if (setjmp(png_jmpbuf(png))) {
        fprintf(stderr, "png_info: %s is not a valid PNG\n", argv[1]);
        return 1;
    }
    png_init_io(png, f);
    png_read_info(png, info);
    png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    row = malloc(png_get_rowbytes(png, info));
    for (png_uint_32 y = 0; y < h; y++) png_read_row(png, row, NULL);
    png_read_end(png, NULL);
    printf("%u %u\n", (unsigned)w, (unsigned)h);
    free(row);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    return 0;
}
