/* Option parsing for the ggx command: one syntax for every subcommand. SPDX-License-Identifier: MIT */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

jmp_buf *cli_die_jump;

const char SHAPE_HELP[] =
    "shape (one syntax for every subcommand):\n"
    "  --alpha AX[,AY]       roughness (default 0.15,0.5); one value for isotropic\n"
    "  --skew TX,TY          skew angles theta_x, theta_y in degrees (default 0,0)\n"
    "  --rotate TZ           rotation of the anisotropy in the tangent plane, degrees (default 0)\n"
    "  --matrix a,b,c,d,e,f,g,h,i   any invertible A, row-major (replaces the three above)\n"
    "directions are THETA,PHI in degrees or X,Y,Z (normalised); n = +z, pointing away from the surface\n";

void die(const char *fmt, ...)
{
    if (cli_die_jump) longjmp(*cli_die_jump, 1);
    va_list ap;
    va_start(ap, fmt);
    fputs("ggx: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(2);
}


/* Parses exactly `count` comma-separated finite numbers (count < 0: 1 to -count numbers); returns how many. */
static int parse_list(const char *opt, const char *text, double *out, int count)
{
    int max = count < 0 ? -count : count, n = 0;
    const char *p = text;
    if (!text || !*text) die("%s needs a value", opt);
    for (;;) {
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || (*end != ',' && *end != '\0')) die("%s: '%s' is not a list of numbers", opt, text);
        if (!isfinite(v) || errno == ERANGE) die("%s: '%s' contains a value that is not a finite number", opt, text);
        if (n == max) die("%s: '%s' has more than %d value%s", opt, text, max, max > 1 ? "s" : "");
        out[n++] = v;
        if (*end == '\0') break;
        p = end + 1;
    }
    if (count > 0 && n != count) die("%s: '%s' needs %d values", opt, text, count);
    return n;
}

int parse_direction(const char *text, ggx_vec3 *v)
{
    double x[3];
    int n = parse_list("direction", text, x, -3);
    if (n == 2) {
        double t = x[0] * DEG, p = x[1] * DEG;
        v->x = sin(t) * cos(p), v->y = sin(t) * sin(p), v->z = cos(t);
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

/* The option's value as a whole number in [lo, hi]; dies "is not WHAT from LO to HI" otherwise. */
static double whole_number(const char *a, const char *val, double lo, double hi, const char *what)
{
    double v;
    parse_list(a, val, &v, 1);
    if (!(v >= lo && v <= hi) || v != floor(v)) die("%s: '%s' is not %s from %.0f to %.0f", a, val, what, lo, hi);
    return v;
}

static int allowed_has(const char *allowed, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = allowed; (p = strstr(p, name)) != NULL; p += n)
        if ((p == allowed || p[-1] == ',') && (p[n] == ',' || p[n] == '\0')) return 1;
    return 0;
}

void parse_options(int argc, char **argv, int first, options *o, const char *allowed)
{
    memset(o, 0, sizeof *o);
    o->alpha[0] = 0.15, o->alpha[1] = 0.5;
    o->n = -1;
    o->seed = 1;
    o->size = 0; /* not given: each command has its default */
    o->from = NAN;
    o->phi_d = 90.0;
    o->level = -1;
    o->eta = 1.5;
    o->progress = -1;
    o->spp = 64;
    o->depth = 32;
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        char key[32] = "", opt[40];
        /* --name=value (GNU syntax) is --name value */
        const char *eq = strncmp(a, "--", 2) == 0 ? strchr(a, '=') : NULL;
        int inline_val = 0;
        if (eq && (size_t)(eq - a) < sizeof opt) {
            snprintf(opt, sizeof opt, "%.*s", (int)(eq - a), a);
            val = eq + 1;
            a = opt;
            inline_val = 1;
        }
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            o->help = 1;
            continue;
        }
        if (strcmp(a, "-n") == 0) snprintf(key, sizeof key, "n");
        else if (strncmp(a, "--", 2) == 0 && strlen(a) < sizeof key + 2) snprintf(key, sizeof key, "%s", a + 2);
        if (!key[0] || !allowed_has(allowed, key) || strcmp(key, "help") == 0)
            die("unknown option '%s' (see --help)", a);
        /* flags */
        int flag = strcmp(key, "log") == 0 || strcmp(key, "progress") == 0 || strcmp(key, "no-progress") == 0 ||
                   strcmp(key, "keep-tilt") == 0 || strcmp(key, "y-down") == 0 || strcmp(key, "compensate") == 0 ||
                   strcmp(key, "fast") == 0 || strcmp(key, "perceptual") == 0 || strcmp(key, "tilted") == 0;
        if (flag && inline_val) die("option '%s' takes no value", a);
        if (strcmp(key, "keep-tilt") == 0) {
            o->keep_tilt = 1;
            continue;
        }
        if (strcmp(key, "y-down") == 0) {
            o->y_down = 1;
            continue;
        }
        if (strcmp(key, "compensate") == 0) {
            o->compensate = 1;
            continue;
        }
        if (strcmp(key, "fast") == 0) {
            o->fast = 1;
            continue;
        }
        if (strcmp(key, "perceptual") == 0) {
            o->perceptual = 1;
            continue;
        }
        if (strcmp(key, "tilted") == 0) {
            o->tilted = 1;
            continue;
        }
        if (strcmp(key, "log") == 0) {
            o->log_scale = 1;
            continue;
        }
        if (strcmp(key, "progress") == 0) {
            o->progress = 1;
            continue;
        }
        if (strcmp(key, "no-progress") == 0) {
            o->progress = 0;
            continue;
        }
        if (!val) die("option '%s' needs a value", a);
        if (!inline_val) i++;
        if (strcmp(key, "alpha") == 0) {
            int k = parse_list(a, val, o->alpha, -2);
            if (k == 1) o->alpha[1] = o->alpha[0];
            o->have_alpha = 1;
        } else if (strcmp(key, "skew") == 0) {
            parse_list(a, val, o->skew, 2);
            o->have_skew = 1;
        } else if (strcmp(key, "rotate") == 0) {
            parse_list(a, val, &o->rotate, 1);
            o->have_rotate = 1;
        } else if (strcmp(key, "matrix") == 0) {
            parse_list(a, val, &o->matrix[0][0], 9);
            o->have_matrix = 1;
        } else if (strcmp(key, "view") == 0) {
            parse_direction(val, &o->view);
            o->have_view = 1;
        } else if (strcmp(key, "wi") == 0) {
            parse_direction(val, &o->wi);
            o->have_wi = 1;
        } else if (strcmp(key, "wo") == 0) {
            if (o->nwo == 64) die("at most 64 --wo directions");
            parse_direction(val, &o->wo[o->nwo++]);
        } else if (strcmp(key, "n") == 0) {
            double v;
            parse_list(a, val, &v, 1);
            if (!(v >= 1 && v <= 1e10) || v != floor(v)) die("%s: '%s' is not a count between 1 and 1e10", a, val);
            o->n = (long)v;
        } else if (strcmp(key, "seed") == 0) {
            /* any unsigned 64-bit integer in decimal digits; other numerals (1e3) as a double, integers below 2^53 */
            char *end;
            errno = 0;
            unsigned long long u = strtoull(val, &end, 10);
            if (val[0] >= '0' && val[0] <= '9' && *end == '\0') {
                if (errno == ERANGE) die("%s: '%s' is larger than the largest seed, 18446744073709551615", a, val);
                o->seed = u;
            } else {
                double v;
                parse_list(a, val, &v, 1);
                if (!(v >= 0) || v != floor(v)) die("%s: '%s' is not a non-negative integer", a, val);
                if (!(v < 9007199254740992.0))
                    die("%s: '%s' is too large as a number with an exponent (write it in digits)", a, val);
                o->seed = (unsigned long long)v;
            }
        } else if (strcmp(key, "size") == 0) {
            /* W or WxH, each a whole number of pixels (points in SVG and PDF) from 64 to 4096 */
            char wbuf[64];
            const char *x = strchr(val, 'x');
            double v[2] = {0, 0};
            if (x && (size_t)(x - val) < sizeof wbuf) {
                snprintf(wbuf, sizeof wbuf, "%.*s", (int)(x - val), val);
                parse_list(a, wbuf, &v[0], 1);
                parse_list(a, x + 1, &v[1], 1);
            } else {
                parse_list(a, val, &v[0], 1);
            }
            for (int k = 0; k < (x ? 2 : 1); k++)
                if (!(v[k] >= 64 && v[k] <= 4096) || v[k] != floor(v[k]))
                    die("%s: '%s' is not a size W or WxH with W and H between 64 and 4096", a, val);
            o->size = (int)v[0], o->size_h = (int)v[1];
        } else if (strcmp(key, "theme") == 0) {
            if (strcmp(val, "light") != 0 && strcmp(val, "dark") != 0) die("%s: '%s' is not light or dark", a, val);
            o->dark = strcmp(val, "dark") == 0;
        } else if (strcmp(key, "from") == 0) {
            parse_list(a, val, &o->from, 1);
            if (!(fabs(o->from) <= 360)) die("%s: '%s' is not an azimuth in degrees in [-360, 360]", a, val);
        } else if (strcmp(key, "phi-d") == 0) {
            parse_list(a, val, &o->phi_d, 1);
            if (!(fabs(o->phi_d) <= 360)) die("%s: '%s' is not an azimuth in degrees in [-360, 360]", a, val);
        } else if (strcmp(key, "eta") == 0) {
            parse_list(a, val, &o->eta, 1);
            if (!(o->eta > 0 && o->eta <= 1e300))
                die("%s: the relative index of refraction must be in (0, 1e300] ('%s' given)", a, val);
            o->have_eta = 1;
        } else if (strcmp(key, "out") == 0) {
            o->out = val;
            if (o->nout == (int)(sizeof o->outs / sizeof o->outs[0])) die("%s: at most 4 output files", a);
            o->outs[o->nout++] = val;
        } else if (strcmp(key, "format") == 0) {
            o->format = val;
        } else if (strcmp(key, "sampler") == 0) {
            o->sampler = val;
        } else if (strcmp(key, "figure") == 0) {
            o->figure = val;
        } else if (strcmp(key, "fresnel") == 0) {
            o->fresnel = val;
        } else if (strcmp(key, "claim") == 0) {
            o->claim = val;
        } else if (strcmp(key, "heightfield") == 0) {
            o->heightfield = val;
        } else if (strcmp(key, "normal-map") == 0) {
            o->normal_map = val;
        } else if (strcmp(key, "roughness-map") == 0) {
            o->roughness_map = val;
        } else if (strcmp(key, "normals") == 0) {
            o->normals = val;
        } else if (strcmp(key, "model") == 0) {
            o->model = val;
        } else if (strcmp(key, "spacing") == 0) {
            if (parse_list(a, val, o->spacing, -2) == 1) o->spacing[1] = o->spacing[0];
            if (!(o->spacing[0] > 0 && o->spacing[1] > 0)) die("%s: the spacing must be positive ('%s' given)", a, val);
            o->have_spacing = 1;
        } else if (strcmp(key, "z-scale") == 0) {
            parse_list(a, val, &o->z_scale, 1);
            if (!(o->z_scale > 0)) die("%s: the z scale must be positive ('%s' given)", a, val);
            o->have_z_scale = 1;
        } else if (strcmp(key, "scene") == 0) {
            o->scene = val;
        } else if (strcmp(key, "light") == 0) {
            o->light = val;
        } else if (strcmp(key, "strategy") == 0) {
            o->strategy = val;
        } else if (strcmp(key, "spp") == 0) {
            o->spp = (long)whole_number(a, val, 1, 1048576, "a number of samples per pixel");
        } else if (strcmp(key, "depth") == 0) {
            o->depth = (int)whole_number(a, val, 1, 1024, "a path depth");
        } else if (strcmp(key, "bounces") == 0) {
            o->bounces = (int)whole_number(a, val, 1, 10000, "a number of bounces");
        } else if (strcmp(key, "exposure") == 0) {
            parse_list(a, val, &o->exposure, 1);
            if (!(fabs(o->exposure) <= 30)) die("%s: '%s' is not an exposure in stops within [-30, 30]", a, val);
        } else if (strcmp(key, "kind") == 0) {
            o->kind = val;
        } else if (strcmp(key, "corr") == 0 || strcmp(key, "mix") == 0) {
            double *dst = key[0] == 'c' ? &o->corr : &o->mix;
            parse_list(a, val, dst, 1);
            if (!(*dst > 0)) die("%s: '%s' is not a positive length", a, val);
        } else if (strcmp(key, "period") == 0) {
            o->period = (int)whole_number(a, val, 2, 4096, "a whole number");
        } else if (strcmp(key, "risers") == 0) {
            o->risers = (int)whole_number(a, val, 2, 8192, "a sawtooth's period");
        } else if (strcmp(key, "level") == 0) {
            o->level = (int)whole_number(a, val, 0, 64, "a level");
        } else if (strcmp(key, "downsample") == 0 || strcmp(key, "threads") == 0) {
            double v = whole_number(a, val, 1, 256, "a whole number");
            if (key[0] == 'd') o->downsample = (int)v;
            else o->threads = (int)v;
        } else {
            die("unknown option '%s' (see --help)", a);
        }
    }
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
        st = ggx_fresnel_schlick(&f, v[0]);
    } else {
        die("--fresnel: unknown kind in '%s' (one, dielectric, conductor, schlick)", o->fresnel);
    }
    if (st != GGX_OK) die("--fresnel '%s': %s", o->fresnel, ggx_status_str(st));
    return f;
}
