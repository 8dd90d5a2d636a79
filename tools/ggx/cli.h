/* The ggx command: shared declarations. SPDX-License-Identifier: MIT */
#ifndef GGX_CLI_H
#define GGX_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "ggx/ggx.h"
#include "ggx/ggx_samplers.h"
#include "output.h"
#include "verify.h"

/* Degrees to radians: the command's angles are in degrees. */
#define DEG (GGX_PI / 180.0)

/* ---- options ---- */
typedef struct options {
    /* shape */
    double alpha[2], skew[2], rotate; /* degrees */
    double matrix[3][3];
    int have_matrix, have_alpha, have_skew, have_rotate; /* given on the command line */
    /* directions and counts */
    ggx_vec3 view;
    int have_view;
    ggx_vec3 wi, wo[64];
    int have_wi, nwo;
    long n;
    unsigned long long seed;
    const char *out, *format, *sampler, *figure, *fresnel, *claim;
    const char *outs[4]; /* every --out given, in order (out is the last); ggx audit writes each */
    int nout;
    double eta;
    int have_eta, log_scale, size, size_h, dark, help, progress; /* size_h: 0 unless --size W x H */
    double from;                                                 /* --from (degrees), NAN when not given */
    double phi_d;                                                /* --phi-d (degrees), 90 when not given */
    /* ggx fit */
    const char *heightfield, *normal_map, *normals, *model;
    double spacing[2], z_scale;
    int have_spacing, have_z_scale, keep_tilt, downsample, y_down, threads;
    /* ggx mipmap */
    const char *roughness_map;
    int fast, perceptual;
    int level; /* ggx render --normal-map: the chain's level shown; -1 when not given */
    /* ggx microsurface */
    const char *kind;
    double corr, mix;  /* 0 when not given */
    int period;        /* 0 when not given */
    int bounces;       /* ggx microsurface measure: the most reflections of a traced ray; 0 when not given */
    int risers;        /* ggx microsurface: a sawtooth's period; 0 when not given */
    int tilted;        /* ggx microsurface measure --tilted */
    int no_wave;       /* ggx predict --no-wave */
    double wavelength; /* ggx microsurface wave --wavelength (micrometres); 0 when not given */
    int rgb;           /* ggx microsurface wave --rgb */
    /* ggx render */
    const char *scene, *light, *strategy;
    int spp; /* ggx render --spp: whole numbers of OPT_WHOLE are ints */
    int depth, compensate;
    double exposure;
    int have_exposure;
    /* the medium of flakes */
    int volume, sggx, scatter; /* scatter: 0 when not given */
    double density, albedo[3]; /* -1 (density, albedo[0]) when not given */
    const char *phase;
} options;

/* Parses argv[first..] into o (defaults first) from the options named in allowed (comma-separated names of the
 * command's one option table, options.c); unknown options and malformed values die(). */
void parse_options(int argc, char **argv, int first, options *o, const char *allowed);
/* A subcommand's options and its --help: the names it takes, the function that prints its help, and whether it takes
 * a shape (the options of SHAPE_OPTS too, and --help ends with SHAPE_HELP). */
typedef struct command_spec {
    const char *options;
    void (*help)(void);
    int shape;
} command_spec;
/* parse_options over c's options; after --help prints c's help and returns 0 (the subcommand then ends with 0),
 * else returns 1. */
int command_options(const command_spec *c, int argc, char **argv, int first, options *o);
/* Parses exactly count comma-separated finite numbers (count < 0: 1 to -count numbers) for option opt; returns how
 * many; dies on anything else. */
int parse_list(const char *opt, const char *text, double *out, int count);
/* The shape of the options; a bad shape dies with the library's message. */
void shape_from_options(const options *o, ggx_shape *s);
/* Parses "theta,phi" (degrees) or "x,y,z" (normalised) into a direction: the one syntax of every direction. */
int parse_direction(const char *text, ggx_vec3 *v);
/* A number for JSON, which has no NaN or infinity: "%.10g", or null for them. The text lives in one of 32 buffers
 * used in turn, enough for every number of one fprintf (not thread-safe). */
const char *json_number(double v);
/* The unit direction of polar angle theta and azimuth phi, in degrees. */
ggx_vec3 direction_deg(double theta, double phi);
/* --light point:THETA,PHI[,E], the one syntax of a distant light: its direction and v = {theta, phi, E} (E = 1 when
 * not given); dies with one line otherwise (angles within 360 degrees, E >= 0). */
void parse_light_point(const char *text, ggx_vec3 *dir, double v[3]);
ggx_fresnel fresnel_from_options(const options *o);
/* --phase specular (default) or diffuse: 1 for diffuse flakes; dies on another name. */
int phase_is_diffuse(const options *o);
/* The caption's words for the shape of the options (alphas and angles, or the matrix). */
void shape_caption(const options *o, char *buf, size_t n);

/* ---- shape options, shared by the subcommands that take a shape ---- */
#define SHAPE_OPTS "alpha,skew,rotate,matrix"
extern const char SHAPE_HELP[]; /* the help text of the shape syntax */

/* ---- samplers: the library's registry (ggx/ggx_samplers.h) in its order, then the command's one sampler of its
 * own, wrong-s, a deliberately wrong VNDF sampler that `ggx check` must reject on a skewed shape ---- */
int cli_sampler_count(void);                            /* GGX_SAMPLER_COUNT + 1 */
const ggx_sampler_info *cli_sampler(int i);             /* 0 <= i < cli_sampler_count() */
const ggx_sampler_info *find_sampler(const char *name); /* dies on an unknown name */
void print_samplers(FILE *f);                           /* "samplers:" and one line per sampler, for --help */
/* 1 when the shape is in the sampler's domain (an UNSKEWED sampler given a skewed shape: 0). */
int sampler_applies(const ggx_sampler_info *smp, const ggx_shape *s);
/* Dies, as a usage error, when the shape is outside the sampler's domain. */
void require_domain(const ggx_sampler_info *smp, const ggx_shape *s);
/* Dies when the sampler can take no sample from the view (or known direction) at all. */
void require_view(const ggx_sampler_info *smp, ggx_vec3 view);
/* One sample of any sampler: the direction, its pdf and weight (1 for samplers of normals). Returns 0 when invalid.
 * f and eta are used by direction samplers only. */
int draw_sample(const ggx_sampler_info *smp, const ggx_shape *s, ggx_vec3 view, const ggx_fresnel *f, double eta,
                rng *r, ggx_vec3 *w, double *pdf, double *weight);

/* ---- subcommands ----
 * Each runs on the options main.c parsed for it (its command_spec there) and, where it takes one, the shape of the
 * options (NULL otherwise); its help prints its --help. ggx render and ggx microsurface parse their own arguments
 * (their modes take other options). */
int cmd_demo(options *o, const ggx_shape *s);
int cmd_eval(options *o, const ggx_shape *s);
int cmd_albedo(options *o, const ggx_shape *s);
int cmd_sample(options *o, const ggx_shape *s);
int cmd_plot(options *o, const ggx_shape *s);
int cmd_check(options *o, const ggx_shape *s);
int cmd_audit(options *o, const ggx_shape *s);
int cmd_fit(options *o, const ggx_shape *s);
int cmd_mipmap(options *o, const ggx_shape *s);
int cmd_predict(options *o, const ggx_shape *s);
void demo_help(void);
void eval_help(void);
void albedo_help(void);
void sample_help(void);
void plot_help(void);
void check_help(void);
void audit_help(void);
void fit_help(void);
void mipmap_help(void);
void predict_help(void);
int cmd_render(int argc, char **argv);
int cmd_microsurface(int argc, char **argv);
/* --roughness-map of the options as alpha per texel (malloc'd, nx * ny): a grey PNG's levels / (2^bits - 1) or a
 * one-channel OpenEXR's values, squared with --perceptual; dies on another size, a multi-channel OpenEXR or an
 * unreadable file (cmd_mipmap.c). */
double *roughness_map_read(const options *o, size_t nx, size_t ny);

/* ---- checks (also used by demo) ---- */
typedef struct check_result {
    double norm_error; /* |integral of the sampler's pdf - 1| */
    double pvalue;     /* chi-square */
    double jac_error;  /* largest |J pdf - 1| at random u (NaN for rejection samplers, INFINITY if no point
                        * was away from the edges) */
    long zero_hits;
    int pass;
} check_result;
/* The fewest samples for which the chi-square test means something (cells of the smallest grid then expect 50). */
#define CHECK_MIN_N 10000
void require_check_n(long n); /* dies (usage error) below CHECK_MIN_N */
check_result run_check(const ggx_shape *s, ggx_vec3 view, const ggx_sampler_info *smp, long n, unsigned long long seed,
                       double alpha, int progress);
void print_check_header(FILE *f);
void print_check_row(FILE *f, const char *name, check_result r);

#endif
