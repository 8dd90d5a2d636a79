/* Text formats of measured surfaces: CSV normals, the ASCII matrix of heights (with Gwyddion's text-export header
 * where present) and XYZ points on a regular grid. SPDX-License-Identifier: MIT */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

/* Numbers of one line into v (at most max), separated by blanks, commas or semicolons; returns the count, -1 on a
 * token that is not a finite number in a double's range: not a number, NaN, infinite, or beyond the doubles' range
 * (its text in bad; subnormals are finite numbers). */
static int numbers(const char *line, double *v, int max, char *bad, size_t badn)
{
    int k = 0;
    const char *p = line;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == ',' || *p == ';' || *p == '\r') p++;
        if (!*p) return k;
        char *end;
        errno = 0;
        double x = strtod(p, &end);
        /* an underflow to a subnormal is a finite number (kept); to 0 or an overflow is not the value written */
        int lost = errno == ERANGE && !(x != 0.0 && fabs(x) < 1.0);
        if (end == p || !isfinite(x) || lost || (*end && !strchr(" \t,;\r", *end))) {
            size_t len = strcspn(p, " \t,;\r");
            snprintf(bad, badn, "%.*s", (int)(len > 40 ? 40 : len), p);
            return -1;
        }
        if (k < max) v[k] = x;
        k++;
        p = end;
    }
}

/* A length with a unit ("5.000 µm", "2e-6 m") in metres; 0 when not understood. */
static double metres(const char *text)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || !isfinite(v)) return 0.0;
    while (*end == ' ') end++;
    static const struct {
        const char *u;
        double f;
    } units[] = {{"m", 1.0}, {"mm", 1e-3}, {"\xc2\xb5m", 1e-6}, {"um", 1e-6}, {"nm", 1e-9}, {"pm", 1e-12}};
    for (unsigned i = 0; i < sizeof units / sizeof units[0]; i++) {
        size_t l = strlen(units[i].u);
        if (strncmp(end, units[i].u, l) == 0 && (end[l] == '\0' || end[l] == '\r' || end[l] == ' '))
            return v * units[i].f;
    }
    return 0.0;
}

typedef struct vec {
    double *v;
    size_t n, cap;
} vec;

static int push(vec *a, double x)
{
    if (a->n == a->cap) {
        size_t c = a->cap ? 2 * a->cap : 4096;
        double *nv = realloc(a->v, c * sizeof *nv);
        if (!nv) return -1;
        a->v = nv, a->cap = c;
    }
    a->v[a->n++] = x;
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The regular grid of sorted values v[0..n): its distinct values (values within 1e-9 of the range of each other are
 * one: a coordinate written as 0.3 on one line and 0.30000000000000004 on another), each within 1e-6 of the step
 * from the first; 0 if not regular. */
static size_t grid_axis(double *v, size_t n, double *lo, double *step)
{
    qsort(v, n, sizeof *v, cmp_double);
    double tol = 1e-9 * (v[n - 1] - v[0]);
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (k == 0 || v[i] - v[k - 1] > tol) v[k++] = v[i];
    *lo = v[0];
    *step = k > 1 ? (v[k - 1] - v[0]) / (double)(k - 1) : 0.0;
    for (size_t i = 0; i < k; i++)
        if (fabs(v[i] - (v[0] + (double)i * *step)) > 1e-6 * *step) return 0;
    return k;
}

int surface_parse_text(surface_format f, const unsigned char *data, size_t n, surface *s, char *err, size_t errn)
{
    char *text = malloc(n + 1);
    if (!text) return surface_fail(err, errn, "out of memory");
    memcpy(text, data, n);
    text[n] = '\0';
    if (strlen(text) != n) {
        free(text);
        return surface_fail(err, errn, "a NUL byte in a text file");
    }
    vec a = {0}, b = {0}, c = {0}, w = {0};
    size_t cols = 0, rows = 0, line_no = 0;
    double width = 0, height = 0, zunit = 0;
    int header_seen = 0, rc = 0;
    char bad[48];
    for (char *line = text, *next; line; line = next) {
        next = strchr(line, '\n');
        if (next) *next++ = '\0';
        line_no++;
        const char *p = line;
        while (*p == ' ' || *p == '\t') p++;
        if (*p == '#') {
            if (f == SURFACE_ASCII) {
                if (strncmp(p, "# Width:", 8) == 0) width = metres(p + 8);
                else if (strncmp(p, "# Height:", 9) == 0) height = metres(p + 9);
                else if (strncmp(p, "# Value units:", 14) == 0) {
                    char u[64];
                    snprintf(u, sizeof u, "1 %.50s", p + 14 + strspn(p + 14, " "));
                    zunit = metres(u);
                }
            }
            continue;
        }
        if (!*p || *p == '\r') continue;
        double v[4];
        int k = numbers(p, v, 4, bad, sizeof bad);
        if (k < 0 && f == SURFACE_CSV && !header_seen && a.n == 0) { /* a header line of column names */
            header_seen = 1;
            continue;
        }
        if (k < 0) {
            rc = surface_fail(err, errn,
                              "line %zu: '%s' is not a finite number in a double's range (4.9e-324 to "
                              "1.8e308)",
                              line_no, bad);
            break;
        }
        if (f == SURFACE_CSV) {
            if (k != 3 && k != 4) {
                rc = surface_fail(err, errn, "line %zu: %d values, not x,y,z or x,y,z,weight", line_no, k);
                break;
            }
            if (a.n > 0 && (k == 4) != (w.n > 0)) {
                rc = surface_fail(err, errn, "line %zu: a weight on some lines only", line_no);
                break;
            }
            if (push(&a, v[0]) || push(&b, v[1]) || push(&c, v[2]) || (k == 4 && push(&w, v[3]))) goto oom;
        } else if (f == SURFACE_XYZ) {
            if (k != 3) {
                rc = surface_fail(err, errn, "line %zu: %d values, not x y z", line_no, k);
                break;
            }
            if (push(&a, v[0]) || push(&b, v[1]) || push(&c, v[2])) goto oom;
        } else {
            if (rows == 0) cols = (size_t)k;
            if ((size_t)k != cols) {
                rc = surface_fail(err, errn, "line %zu: %d values where the first row has %zu", line_no, k, cols);
                break;
            }
            /* the row again, in full (numbers() keeps at most 4) */
            const char *q = p;
            for (int i = 0; i < k; i++) {
                char *end;
                while (*q == ' ' || *q == '\t' || *q == ',' || *q == ';') q++;
                if (push(&a, strtod(q, &end))) goto oom;
                q = end;
            }
            rows++;
        }
    }
    if (rc == 0) {
        if (f == SURFACE_CSV) {
            if (a.n == 0) rc = surface_fail(err, errn, "no normals");
            else if (!(s->m = malloc(a.n * sizeof *s->m))) goto oom;
            for (size_t i = 0; rc == 0 && i < a.n; i++) s->m[i] = (ggx_vec3){a.v[i], b.v[i], c.v[i]};
            s->kind = SURFACE_NORMALS, s->nx = a.n, s->ny = 1;
            if (w.n) s->w = w.v, w.v = NULL;
        } else if (f == SURFACE_XYZ) {
            size_t np = a.n;
            double x0, y0, sx, sy;
            double *xs = malloc(np * sizeof *xs), *ys = malloc(np * sizeof *ys);
            if (np && (!xs || !ys)) {
                free(xs), free(ys);
                goto oom;
            }
            if (np) memcpy(xs, a.v, np * sizeof *xs), memcpy(ys, b.v, np * sizeof *ys);
            size_t nx = np ? grid_axis(xs, np, &x0, &sx) : 0, ny = np ? grid_axis(ys, np, &y0, &sy) : 0;
            free(xs), free(ys);
            if (nx < 2 || ny < 2 || nx * ny != np || !(sx > 0) || !(sy > 0)) {
                rc = surface_fail(err, errn,
                                  "%zu points are not a regular grid of at least 2 x 2 (x: %zu values, "
                                  "y: %zu values)",
                                  np, nx, ny);
            } else if (!(s->h = malloc(np * sizeof *s->h))) {
                goto oom;
            } else {
                for (size_t i = 0; i < np; i++) s->h[i] = NAN;
                for (size_t i = 0; rc == 0 && i < np; i++) {
                    size_t ix = (size_t)llround((a.v[i] - x0) / sx), iy = (size_t)llround((b.v[i] - y0) / sy);
                    if (!isnan(s->h[iy * nx + ix]))
                        rc = surface_fail(err, errn, "two points at x = %g, y = %g", a.v[i], b.v[i]);
                    s->h[iy * nx + ix] = c.v[i];
                }
                s->kind = SURFACE_HEIGHTS, s->nx = nx, s->ny = ny, s->dx = sx, s->dy = sy, s->z_scale = 1.0;
            }
        } else {
            if (rows < 2 || cols < 2) {
                rc = surface_fail(err, errn, "%zu x %zu heights: a height field needs at least 2 x 2", cols, rows);
            } else {
                s->kind = SURFACE_HEIGHTS, s->nx = cols, s->ny = rows, s->h = a.v, a.v = NULL;
                if (width > 0 && height > 0) {
                    s->dx = width / (double)cols, s->dy = height / (double)rows;
                    s->z_scale = zunit; /* heights in their unit, dx in metres */
                }
            }
        }
    }
    free(a.v), free(b.v), free(c.v), free(w.v), free(text);
    return rc;
oom:
    free(a.v), free(b.v), free(c.v), free(w.v), free(text);
    return surface_fail(err, errn, "out of memory");
}

int surface_write_text(const char *path, surface_format f, const surface *s, char *err, size_t errn)
{
    FILE *o = fopen(path, "w");
    if (!o) return surface_fail(err, errn, "cannot write '%s': %s", path, strerror(errno));
    size_t n = s->nx * s->ny;
    if (f == SURFACE_CSV) {
        fprintf(o, s->w ? "x,y,z,weight\n" : "x,y,z\n");
        for (size_t i = 0; i < n; i++) {
            fprintf(o, "%.17g,%.17g,%.17g", s->m[i].x, s->m[i].y, s->m[i].z);
            if (s->w) fprintf(o, ",%.17g", s->w[i]);
            fputc('\n', o);
        }
    } else if (f == SURFACE_XYZ) {
        for (size_t j = 0; j < s->ny; j++)
            for (size_t i = 0; i < s->nx; i++)
                fprintf(o, "%.17g %.17g %.17g\n", (double)i * s->dx, (double)j * s->dy, s->h[j * s->nx + i]);
    } else {
        if (s->dx > 0) {
            /* heights are written times z_scale, so that they are in metres beside the widths */
            fprintf(o, "# Channel: Height\n# Width: %.17g m\n# Height: %.17g m\n", s->dx * (double)s->nx,
                    s->dy * (double)s->ny);
            if (s->z_scale > 0) fprintf(o, "# Value units: m\n");
        }
        for (size_t j = 0; j < s->ny; j++)
            for (size_t i = 0; i < s->nx; i++)
                fprintf(o, "%.17g%c", s->h[j * s->nx + i] * (s->dx > 0 && s->z_scale > 0 ? s->z_scale : 1.0),
                        i + 1 < s->nx ? '\t' : '\n');
    }
    if (fclose(o) != 0) return surface_fail(err, errn, "cannot write '%s'", path);
    return 0;
}
