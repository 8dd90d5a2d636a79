/* The ggx command's shared parsers: number lists, directions, the shape and the Fresnel term of the options.
 * SPDX-License-Identifier: MIT */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

const char SHAPE_HELP[] =
    "shape (one syntax for every subcommand):\n"
    "  --alpha AX[,AY]       roughness (default 0.15,0.5); one value for isotropic\n"
    "  --skew TX,TY          skew angles theta_x, theta_y in degrees (default 0,0)\n"
    "  --rotate TZ           rotation of the anisotropy in the tangent plane, degrees (default 0)\n"
    "  --matrix a,b,c,d,e,f,g,h,i   any invertible A, row-major (replaces the three above)\n"
    "directions are THETA,PHI in degrees or X,Y,Z (normalised); n = +z, pointing away from the surface\n";


int parse_list(const char *opt, const char *text, double *out, int count)
{
    int max = count < 0 ? -count : count, n = 0;
    const char *p = text;
    if (!text || !*text) die("%s needs a value", opt);
    for (;;) {
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || (*end != ',' && *end != '\0')) die("%s: '%s' is not a list of numbers", opt, text);
        /* strtod's ERANGE: an overflow (HUGE_VAL) or an underflow; a subnormal result is a finite number, kept */
        if (!isfinite(v) && errno != ERANGE) die("%s: '%s' contains a value that is not a finite number", opt, text);
        if (errno == ERANGE && fabs(v) > 1.0)
            die("%s: '%s' contains a value beyond the largest double (1.8e308)", opt, text);
        if (errno == ERANGE && v == 0.0)
            die("%s: '%s' contains a value below the smallest positive double (4.9e-324)", opt, text);
        if (n == max) die("%s: '%s' has more than %d value%s", opt, text, max, max > 1 ? "s" : "");
        out[n++] = v;
        if (*end == '\0') break;
        p = end + 1;
    }
    if (count > 0 && n != count) die("%s: '%s' needs %d values", opt, text, count);
    return n;
}

const char *json_number(double v)
{
    static char bufs[32][32];
    static int next;
    char *buf = bufs[next++ % 32];
    if (isfinite(v)) snprintf(buf, 32, "%.10g", v);
    else snprintf(buf, 32, "null");
    return buf;
}

ggx_vec3 direction_deg(double theta, double phi)
{
    double t = theta * DEG, p = phi * DEG;
    return (ggx_vec3){sin(t) * cos(p), sin(t) * sin(p), cos(t)};
}

int parse_direction(const char *text, ggx_vec3 *v)
{
    double x[3];
    int n = parse_list("direction", text, x, -3);
    if (n == 2) {
        *v = direction_deg(x[0], x[1]);
        return 1;
    }
    if (n != 3) die("direction '%s': give theta,phi in degrees or x,y,z", text);
    /* scaled by the largest component first, so that components near the largest double do not overflow */
    double m = fmax(fabs(x[0]), fmax(fabs(x[1]), fabs(x[2])));
    if (!(m > 0.0)) die("direction '%s' is the zero vector", text);
    for (int k = 0; k < 3; k++) x[k] /= m;
    double l = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    v->x = x[0] / l, v->y = x[1] / l, v->z = x[2] / l;
    return 1;
}

void parse_light_point(const char *text, ggx_vec3 *dir, double v[3])
{
    const char *usage = "give point:THETA,PHI[,E] (degrees; irradiance E >= 0, default 1)";
    if (strncmp(text, "point:", 6) != 0) die("--light '%s': %s", text, usage);
    v[2] = 1.0;
    int n = parse_list("--light", text + 6, v, -3);
    if (n < 2 || !(fabs(v[0]) <= 360 && fabs(v[1]) <= 360 && v[2] >= 0)) die("--light '%s': %s", text, usage);
    *dir = direction_deg(v[0], v[1]);
}

/* The shortest decimal that reads back as v (90.0000001, not 90), in a static buffer. */
static const char *shortest(double v)
{
    static char buf[32];
    for (int p = 1; p <= 17; p++) {
        snprintf(buf, sizeof buf, "%.*g", p, v);
        if (strtod(buf, NULL) == v) break;
    }
    return buf;
}

void shape_from_options(const options *o, ggx_shape *s)
{
    ggx_status st;
    /* the command's own words for what the library would refuse in radians, and a note where it adjusts */
    if (!o->have_matrix) {
        for (int i = 0; i < 2; i++)
            if (!(fabs(o->skew[i]) <= GGX_SKEW_MAX / DEG + 1e-9))
                die("invalid shape: --skew angles must be within [-90, 90] degrees (%s given)", shortest(o->skew[i]));
    }
    if (o->have_matrix) st = ggx_shape_matrix(s, (const double(*)[3])o->matrix);
    else st = ggx_shape_ellipsoid(s, o->alpha[0], o->alpha[1], o->skew[0] * DEG, o->skew[1] * DEG, o->rotate * DEG);
    if (st != GGX_OK) die("invalid shape: %s", ggx_status_str(st));
    for (int i = 0; i < 2 && !o->have_matrix; i++)
        if (o->alpha[i] < GGX_ALPHA_MIN && (i == 0 || o->alpha[1] != o->alpha[0]))
            fprintf(stderr, "ggx: note: alpha %g raised to the smallest accepted roughness, %g\n", o->alpha[i],
                    GGX_ALPHA_MIN);
}

ggx_fresnel fresnel_from_options(const options *o)
{
    ggx_fresnel f;
    ggx_fresnel_one(&f);
    if (!o->fresnel || strcmp(o->fresnel, "one") == 0) return f;
    const char *colon = strchr(o->fresnel, ':');
    if (!colon) die("--fresnel: '%s' is not one, dielectric:ETA, conductor:ETA,K or schlick:F0", o->fresnel);
    double v[2] = {0, 0};
    ggx_status st;
    size_t len = (size_t)(colon - o->fresnel);
    if (len == 10 && strncmp(o->fresnel, "dielectric", len) == 0) {
        parse_list("--fresnel", colon + 1, v, 1);
        st = ggx_fresnel_dielectric(&f, v[0]);
    } else if (len == 9 && strncmp(o->fresnel, "conductor", len) == 0) {
        parse_list("--fresnel", colon + 1, v, 2);
        st = ggx_fresnel_conductor(&f, v[0], v[1]);
    } else if (len == 7 && strncmp(o->fresnel, "schlick", len) == 0) {
        parse_list("--fresnel", colon + 1, v, 1);
        if (!(v[0] >= 0.0 && v[0] <= 1.0))
            die("--fresnel '%s': Schlick's F0 is a reflectance, from 0 to 1 (%s given)", o->fresnel, shortest(v[0]));
        st = ggx_fresnel_schlick(&f, v[0]);
    } else {
        die("--fresnel: unknown kind in '%s' (one, dielectric, conductor, schlick)", o->fresnel);
    }
    if (st != GGX_OK) die("--fresnel '%s': %s", o->fresnel, ggx_status_str(st));
    return f;
}

int phase_is_diffuse(const options *o)
{
    if (o->phase && strcmp(o->phase, "specular") != 0 && strcmp(o->phase, "diffuse") != 0)
        die("--phase: unknown phase function '%s' (specular, diffuse)", o->phase);
    return o->phase && strcmp(o->phase, "diffuse") == 0;
}
