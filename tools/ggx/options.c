/* The ggx command's options: one table of every option (its name, whether it takes a value, what it sets), and the
 * parser every subcommand runs over its own list of them (command_spec). SPDX-License-Identifier: MIT */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* The option's value as a whole number in [lo, hi]; dies "is not WHAT from LO to HI" otherwise. */
static double whole_number(const char *a, const char *val, double lo, double hi, const char *what)
{
    double v;
    parse_list(a, val, &v, 1);
    if (!(v >= lo && v <= hi) || v != floor(v)) die("%s: '%s' is not %s from %.0f to %.0f", a, val, what, lo, hi);
    return v;
}

/* One number within [-360, 360] degrees. */
static double azimuth(const char *a, const char *val)
{
    double v;
    parse_list(a, val, &v, 1);
    if (!(fabs(v) <= 360)) die("%s: '%s' is not an azimuth in degrees in [-360, 360]", a, val);
    return v;
}

/* ---- the options that check or convert their value: each sets its fields of the options ---- */

static void set_alpha(options *o, const char *a, const char *val)
{
    if (parse_list(a, val, o->alpha, -2) == 1) o->alpha[1] = o->alpha[0];
    o->have_alpha = 1;
}

static void set_skew(options *o, const char *a, const char *val)
{
    parse_list(a, val, o->skew, 2);
    o->have_skew = 1;
}

static void set_rotate(options *o, const char *a, const char *val)
{
    parse_list(a, val, &o->rotate, 1);
    o->have_rotate = 1;
}

static void set_matrix(options *o, const char *a, const char *val)
{
    parse_list(a, val, &o->matrix[0][0], 9);
    o->have_matrix = 1;
}

static void set_view(options *o, const char *a, const char *val)
{
    (void)a;
    parse_direction(val, &o->view);
    o->have_view = 1;
}

static void set_wi(options *o, const char *a, const char *val)
{
    (void)a;
    parse_direction(val, &o->wi);
    o->have_wi = 1;
}

static void set_wo(options *o, const char *a, const char *val)
{
    (void)a;
    if (o->nwo == 64) die("at most 64 --wo directions");
    parse_direction(val, &o->wo[o->nwo++]);
}

static void set_n(options *o, const char *a, const char *val)
{
    double v;
    parse_list(a, val, &v, 1);
    if (!(v >= 1 && v <= 1e10) || v != floor(v)) die("%s: '%s' is not a count between 1 and 1e10", a, val);
    o->n = (long)v;
}

/* any unsigned 64-bit integer in decimal digits; other numerals (1e3) as a double, integers below 2^53 */
static void set_seed(options *o, const char *a, const char *val)
{
    char *end;
    errno = 0;
    unsigned long long u = strtoull(val, &end, 10);
    if (val[0] >= '0' && val[0] <= '9' && *end == '\0') {
        if (errno == ERANGE) die("%s: '%s' is larger than the largest seed, 18446744073709551615", a, val);
        o->seed = u;
        return;
    }
    double v;
    parse_list(a, val, &v, 1);
    if (!(v >= 0) || v != floor(v)) die("%s: '%s' is not a non-negative integer", a, val);
    if (!(v < 9007199254740992.0))
        die("%s: '%s' is too large as a number with an exponent (write it in digits)", a, val);
    o->seed = (unsigned long long)v;
}

/* W or WxH, each a whole number of pixels (points in SVG and PDF) from 64 to 4096 */
static void set_size(options *o, const char *a, const char *val)
{
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
}

static void set_theme(options *o, const char *a, const char *val)
{
    if (strcmp(val, "light") != 0 && strcmp(val, "dark") != 0) die("%s: '%s' is not light or dark", a, val);
    o->dark = strcmp(val, "dark") == 0;
}

static void set_from(options *o, const char *a, const char *val) { o->from = azimuth(a, val); }
static void set_phi_d(options *o, const char *a, const char *val) { o->phi_d = azimuth(a, val); }

static void set_eta(options *o, const char *a, const char *val)
{
    parse_list(a, val, &o->eta, 1);
    if (!(o->eta > 0 && o->eta <= 1e300))
        die("%s: the relative index of refraction must be in (0, 1e300] ('%s' given)", a, val);
    o->have_eta = 1;
}

static void set_out(options *o, const char *a, const char *val)
{
    o->out = val;
    if (o->nout == (int)(sizeof o->outs / sizeof o->outs[0])) die("%s: at most 4 output files", a);
    o->outs[o->nout++] = val;
}

static void set_spacing(options *o, const char *a, const char *val)
{
    if (parse_list(a, val, o->spacing, -2) == 1) o->spacing[1] = o->spacing[0];
    if (!(o->spacing[0] > 0 && o->spacing[1] > 0)) die("%s: the spacing must be positive ('%s' given)", a, val);
    o->have_spacing = 1;
}

static void set_z_scale(options *o, const char *a, const char *val)
{
    parse_list(a, val, &o->z_scale, 1);
    if (!(o->z_scale > 0)) die("%s: the z scale must be positive ('%s' given)", a, val);
    o->have_z_scale = 1;
}

static void set_exposure(options *o, const char *a, const char *val)
{
    parse_list(a, val, &o->exposure, 1);
    if (!(fabs(o->exposure) <= 30)) die("%s: '%s' is not an exposure in stops within [-30, 30]", a, val);
    o->have_exposure = 1;
}

static double positive_length(const char *a, const char *val)
{
    double v;
    parse_list(a, val, &v, 1);
    if (!(v > 0)) die("%s: '%s' is not a positive length", a, val);
    return v;
}

static void set_wavelength(options *o, const char *a, const char *val) { o->wavelength = positive_length(a, val); }

static void set_density(options *o, const char *a, const char *val)
{
    parse_list(a, val, &o->density, 1);
    if (!(o->density >= 0 && o->density <= 1e6)) die("%s: '%s' is not a flake density in [0, 1e6]", a, val);
}

/* A or R,G,B, each in [0, 1] */
static void set_albedo(options *o, const char *a, const char *val)
{
    int n = parse_list(a, val, o->albedo, -3);
    if (n == 1) o->albedo[1] = o->albedo[2] = o->albedo[0];
    for (int k = 0; k < 3; k++)
        if (n == 2 || !(o->albedo[k] >= 0 && o->albedo[k] <= 1))
            die("%s: '%s' is not an albedo A or R,G,B in [0, 1]", a, val);
}

static void set_corr(options *o, const char *a, const char *val) { o->corr = positive_length(a, val); }
static void set_mix(options *o, const char *a, const char *val) { o->mix = positive_length(a, val); }

/* ---- the table ---- */

typedef enum option_kind {
    OPT_FLAG,  /* no value: the int at `field` becomes `flag` */
    OPT_TEXT,  /* the value as given, into the const char * at `field` */
    OPT_WHOLE, /* a whole number in [lo, hi] (else "is not `what` from lo to hi"), into the int at `field` */
    OPT_SET    /* the value through `set` */
} option_kind;

typedef struct option_def {
    const char *name; /* without the leading "--" ("n" is -n) */
    option_kind kind;
    size_t field;
    int flag;
    void (*set)(options *o, const char *a, const char *val);
    double lo, hi;
    const char *what;
} option_def;

/* rows of the table, not blocks: */
// clang-format off
#define FLAG(name, member, value) {name, OPT_FLAG, offsetof(options, member), value, NULL, 0, 0, NULL}
#define TEXT(name, member) {name, OPT_TEXT, offsetof(options, member), 0, NULL, 0, 0, NULL}
#define WHOLE(name, member, lo, hi, what) {name, OPT_WHOLE, offsetof(options, member), 0, NULL, lo, hi, what}
#define SET(name, fn) {name, OPT_SET, 0, 0, fn, 0, 0, NULL}
// clang-format on

static const option_def OPTIONS[] = {
    /* shape */
    SET("alpha", set_alpha),
    SET("skew", set_skew),
    SET("rotate", set_rotate),
    SET("matrix", set_matrix),
    /* directions, counts, output */
    SET("view", set_view),
    SET("wi", set_wi),
    SET("wo", set_wo),
    SET("n", set_n),
    SET("seed", set_seed),
    SET("size", set_size),
    SET("theme", set_theme),
    SET("from", set_from),
    SET("phi-d", set_phi_d),
    SET("eta", set_eta),
    SET("out", set_out),
    TEXT("format", format),
    TEXT("sampler", sampler),
    TEXT("figure", figure),
    TEXT("fresnel", fresnel),
    TEXT("claim", claim),
    FLAG("log", log_scale, 1),
    FLAG("progress", progress, 1),
    FLAG("no-progress", progress, 0),
    /* measured surfaces: fit, mipmap */
    TEXT("heightfield", heightfield),
    TEXT("normal-map", normal_map),
    TEXT("roughness-map", roughness_map),
    TEXT("normals", normals),
    TEXT("model", model),
    SET("spacing", set_spacing),
    SET("z-scale", set_z_scale),
    FLAG("keep-tilt", keep_tilt, 1),
    FLAG("y-down", y_down, 1),
    FLAG("fast", fast, 1),
    FLAG("perceptual", perceptual, 1),
    WHOLE("downsample", downsample, 1, 256, "a whole number"),
    WHOLE("threads", threads, 1, 256, "a whole number"),
    WHOLE("level", level, 0, 64, "a level"),
    /* render */
    TEXT("scene", scene),
    TEXT("light", light),
    TEXT("strategy", strategy),
    WHOLE("spp", spp, 1, 1048576, "a number of samples per pixel"),
    WHOLE("depth", depth, 1, 1024, "a path depth"),
    SET("exposure", set_exposure),
    FLAG("compensate", compensate, 1),
    /* the medium of flakes: render --volume, eval and sample --sggx */
    FLAG("volume", volume, 1),
    FLAG("sggx", sggx, 1),
    SET("density", set_density),
    SET("albedo", set_albedo),
    TEXT("phase", phase),
    WHOLE("scatter", scatter, 1, 1000000, "a number of scattering events"),
    /* microsurface */
    TEXT("kind", kind),
    SET("corr", set_corr),
    SET("mix", set_mix),
    WHOLE("period", period, 2, 4096, "a whole number"),
    WHOLE("risers", risers, 2, 8192, "a sawtooth's period"),
    WHOLE("bounces", bounces, 1, 10000, "a number of bounces"),
    FLAG("tilted", tilted, 1),
    FLAG("no-wave", no_wave, 1),
    SET("wavelength", set_wavelength),
    FLAG("rgb", rgb, 1),
};

static const option_def *option_named(const char *name)
{
    for (size_t i = 0; i < sizeof OPTIONS / sizeof OPTIONS[0]; i++)
        if (strcmp(OPTIONS[i].name, name) == 0) return &OPTIONS[i];
    return NULL;
}

static int allowed_has(const char *allowed, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = allowed; (p = strstr(p, name)) != NULL; p += n)
        if ((p == allowed || p[-1] == ',') && (p[n] == ',' || p[n] == '\0')) return 1;
    return 0;
}

static void option_defaults(options *o)
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
    o->density = o->albedo[0] = -1; /* not given */
}

void parse_options(int argc, char **argv, int first, options *o, const char *allowed)
{
    option_defaults(o);
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        char opt[40];
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
        const char *key = strcmp(a, "-n") == 0 ? "n" : strncmp(a, "--", 2) == 0 ? a + 2 : "";
        const option_def *d = key[0] && allowed_has(allowed, key) ? option_named(key) : NULL;
        if (!d) die("unknown option '%s' (see --help)", a);
        if (d->kind == OPT_FLAG) {
            if (inline_val) die("option '%s' takes no value", a);
            *(int *)((char *)o + d->field) = d->flag;
            continue;
        }
        if (!val) die("option '%s' needs a value", a);
        if (!inline_val) i++;
        if (d->kind == OPT_TEXT) *(const char **)((char *)o + d->field) = val;
        else if (d->kind == OPT_WHOLE)
            *(int *)((char *)o + d->field) = (int)whole_number(a, val, d->lo, d->hi, d->what);
        else d->set(o, a, val);
    }
}

int command_options(const command_spec *c, int argc, char **argv, int first, options *o)
{
    char allowed[512];
    snprintf(allowed, sizeof allowed, "%s%s%s", c->shape ? SHAPE_OPTS : "", c->shape ? "," : "", c->options);
    parse_options(argc, argv, first, o, allowed);
    if (!o->help) return 1;
    c->help();
    if (c->shape) fputs(SHAPE_HELP, stdout);
    return 0;
}
