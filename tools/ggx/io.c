/* Output files written atomically, and PNG images with a small bitmap font. SPDX-License-Identifier: MIT */
#include <errno.h>
#include <png.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

void ensure_dir(const char *dir)
{
    struct stat st;
    if (stat(dir, &st) == 0) {
        if (!S_ISDIR(st.st_mode)) die("output folder '%s' is not a folder", dir);
    } else if (mkdir(dir, 0777) != 0) {
        die("cannot create output folder '%s': %s", dir, strerror(errno));
    }
    if (access(dir, W_OK) != 0) die("output folder '%s' is not writable", dir);
}

void out_open(out_file *o, const char *path)
{
    memset(o, 0, sizeof *o);
    if (!path || strcmp(path, "-") == 0) {
        o->f = stdout;
        return;
    }
    size_t n = strlen(path) + 16;
    o->path = malloc(n);
    o->tmp = malloc(n);
    if (!o->path || !o->tmp) die("out of memory");
    snprintf(o->path, n, "%s", path);
    snprintf(o->tmp, n, "%s.tmpXXXXXX", path);
    int fd = mkstemp(o->tmp);
    if (fd < 0) die("cannot write '%s': %s", path, strerror(errno));
    o->f = fdopen(fd, "wb");
    if (!o->f) die("cannot write '%s': %s", path, strerror(errno));
}

void out_close(out_file *o)
{
    if (!o->path) {
        if (fflush(o->f) != 0) die("cannot write to standard output: %s", strerror(errno));
        return;
    }
    int bad = ferror(o->f) || fflush(o->f) != 0;
    if (fclose(o->f) != 0) bad = 1;
    if (bad || rename(o->tmp, o->path) != 0) {
        int e = errno;
        unlink(o->tmp);
        die("cannot write '%s': %s", o->path, strerror(e));
    }
    chmod(o->path, 0644);
    free(o->path);
    free(o->tmp);
    memset(o, 0, sizeof *o);
}

image image_new(int w, int h, unsigned char r, unsigned char g, unsigned char b)
{
    image im = {w, h, malloc((size_t)w * (size_t)h * 3)};
    if (!im.rgb) die("out of memory");
    for (long i = 0; i < (long)w * h; i++) im.rgb[3 * i] = r, im.rgb[3 * i + 1] = g, im.rgb[3 * i + 2] = b;
    return im;
}

void image_free(image *im)
{
    free(im->rgb);
    im->rgb = NULL;
}

void image_set(image *im, int x, int y, const unsigned char c[3])
{
    if (x < 0 || y < 0 || x >= im->w || y >= im->h) return;
    memcpy(im->rgb + 3 * ((long)y * im->w + x), c, 3);
}

/* A 5 x 7 font of our own: each glyph is 7 rows, the low 5 bits of each row from left (bit 4) to right (bit 0). */
typedef struct glyph {
    char c;
    unsigned char rows[7];
} glyph;
static const glyph FONT[] = {
    {'0', {14, 17, 19, 21, 25, 17, 14}}, {'1', {4, 12, 4, 4, 4, 4, 14}},      {'2', {14, 17, 1, 2, 4, 8, 31}},
    {'3', {31, 2, 4, 2, 1, 17, 14}},     {'4', {2, 6, 10, 18, 31, 2, 2}},     {'5', {31, 16, 30, 1, 1, 17, 14}},
    {'6', {6, 8, 16, 30, 17, 17, 14}},   {'7', {31, 1, 2, 4, 8, 8, 8}},       {'8', {14, 17, 17, 14, 17, 17, 14}},
    {'9', {14, 17, 17, 15, 1, 2, 12}},   {'.', {0, 0, 0, 0, 0, 12, 12}},      {'-', {0, 0, 0, 31, 0, 0, 0}},
    {'+', {0, 4, 4, 31, 4, 4, 0}},       {',', {0, 0, 0, 0, 12, 4, 8}},       {'(', {2, 4, 8, 8, 8, 4, 2}},
    {')', {8, 4, 2, 2, 2, 4, 8}},        {'=', {0, 0, 31, 0, 31, 0, 0}},      {':', {0, 12, 12, 0, 12, 12, 0}},
    {'/', {0, 1, 2, 4, 8, 16, 0}},       {' ', {0, 0, 0, 0, 0, 0, 0}},        {'A', {14, 17, 17, 31, 17, 17, 17}},
    {'B', {30, 17, 17, 30, 17, 17, 30}}, {'C', {14, 17, 16, 16, 16, 17, 14}}, {'D', {30, 17, 17, 17, 17, 17, 30}},
    {'E', {31, 16, 16, 30, 16, 16, 31}}, {'F', {31, 16, 16, 30, 16, 16, 16}}, {'G', {14, 17, 16, 23, 17, 17, 15}},
    {'H', {17, 17, 17, 31, 17, 17, 17}}, {'I', {14, 4, 4, 4, 4, 4, 14}},     {'J', {7, 2, 2, 2, 2, 18, 12}},
    {'K', {17, 18, 20, 24, 20, 18, 17}}, {'L', {16, 16, 16, 16, 16, 16, 31}}, {'M', {17, 27, 21, 21, 17, 17, 17}},
    {'N', {17, 17, 25, 21, 19, 17, 17}}, {'O', {14, 17, 17, 17, 17, 17, 14}}, {'P', {30, 17, 17, 30, 16, 16, 16}},
    {'Q', {14, 17, 17, 17, 21, 18, 13}}, {'R', {30, 17, 17, 30, 20, 18, 17}}, {'S', {15, 16, 16, 14, 1, 1, 30}},
    {'T', {31, 4, 4, 4, 4, 4, 4}},       {'U', {17, 17, 17, 17, 17, 17, 14}}, {'V', {17, 17, 17, 17, 17, 10, 4}},
    {'W', {17, 17, 17, 21, 21, 21, 10}}, {'X', {17, 17, 10, 4, 10, 17, 17}},  {'Y', {17, 17, 10, 4, 4, 4, 4}},
    {'Z', {31, 1, 2, 4, 8, 16, 31}},
};

void image_text(image *im, int x, int y, const char *text, int scale, const unsigned char c[3])
{
    for (; *text; text++, x += 6 * scale) {
        char ch = *text >= 'a' && *text <= 'z' ? (char)(*text - 'a' + 'A') : *text;
        const glyph *g = NULL;
        for (unsigned k = 0; k < sizeof FONT / sizeof FONT[0]; k++)
            if (FONT[k].c == ch) g = &FONT[k];
        if (!g) continue;
        for (int r = 0; r < 7; r++)
            for (int b = 0; b < 5; b++)
                if (g->rows[r] & (1 << (4 - b)))
                    for (int dy = 0; dy < scale; dy++)
                        for (int dx = 0; dx < scale; dx++) image_set(im, x + b * scale + dx, y + r * scale + dy, c);
    }
}

/* Dark blue-black through purple and orange to pale yellow, piecewise linear between our own control colours,
 * ordered by lightness so that brighter always means denser. */
void colormap(double t, unsigned char out[3])
{
    static const double ctrl[][3] = {{0.02, 0.02, 0.08}, {0.25, 0.05, 0.45}, {0.62, 0.15, 0.45},
                                     {0.90, 0.40, 0.20}, {0.98, 0.75, 0.25}, {0.99, 0.98, 0.75}};
    const int n = sizeof ctrl / sizeof ctrl[0];
    if (!(t > 0)) t = 0;
    if (t > 1) t = 1;
    double x = t * (n - 1);
    int i = (int)x;
    if (i >= n - 1) i = n - 2;
    double f = x - i;
    for (int k = 0; k < 3; k++) out[k] = (unsigned char)(255.0 * ((1 - f) * ctrl[i][k] + f * ctrl[i + 1][k]) + 0.5);
}

void write_png(const image *im, const char *path)
{
    out_file o;
    out_open(&o, path);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) die("cannot write '%s': libpng failed to start", path);
    if (setjmp(png_jmpbuf(png))) die("cannot write '%s': libpng error", path);
    png_init_io(png, o.f);
    png_set_IHDR(png, info, (png_uint_32)im->w, (png_uint_32)im->h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < im->h; y++) png_write_row(png, im->rgb + 3 * (long)y * im->w);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    out_close(&o);
}
