/* ggx: evaluate, sample, verify and draw the ellipsoid NDF model. Dispatches to the subcommands, one file each.
 * SPDX-License-Identifier: MIT */
#include <stdio.h>
#include <string.h>

#include "cli.h"

/* The one list of subcommands: dispatch, the options each takes and the usage text all come from it. A command
 * with run_argv parses its own arguments. */
static const struct command {
    const char *name;
    command_spec spec;
    int (*run)(options *o, const ggx_shape *s);
    int (*run_argv)(int argc, char **argv);
    const char *summary;
} COMMANDS[] = {
    {"demo",
     {"out,n,size,theme", demo_help, 0},
     cmd_demo,
     NULL,
     "draw the seeds' figures into out/ and check every sampler (what `make run` runs)"},
    {"eval",
     {"wi,wo,fresnel,eta,format,out,sggx", eval_help, 1},
     cmd_eval,
     NULL,
     "D, G1, G, pdfs, BRDF and BSDF for a shape and directions, as CSV or JSON"},
    {"albedo",
     {"view,eta,format,out", albedo_help, 1},
     cmd_albedo,
     NULL,
     "directional and average albedo E(v), E_avg (separable and height-correlated G)"},
    {"sample",
     {"sampler,view,n,seed,format,out,fresnel,eta,progress,no-progress,sggx,phase", sample_help, 1},
     cmd_sample,
     NULL,
     "N samples of a chosen sampler, as CSV or float32, with pdf and weight"},
    {"plot",
     {"figure,view,sampler,size,log,theme,from,eta,phi-d,out", plot_help, 1},
     cmd_plot,
     NULL,
     "one figure (PNG, SVG or PDF) for any shape, view and sampler: the seeds' figures and line plots"},
    {"check",
     {"sampler,view,n,seed,progress,no-progress", check_help, 1},
     cmd_check,
     NULL,
     "chi-square, normalisation and Jacobian checks; exit status 0 only if all pass"},
    {"audit",
     {"alpha,skew,rotate,matrix,format,out,progress,no-progress", audit_help, 0},
     cmd_audit,
     NULL,
     "the table of the seeds' claims for default or given shapes"},
    {"render",
     {NULL, NULL, 0},
     NULL,
     cmd_render,
     "an image of a sphere or plane of the material under a sky, an environment map or a light"},
    {"fit",
     {"heightfield,normal-map,normals,spacing,z-scale,keep-tilt,downsample,y-down,model,threads,format,out,figure,"
      "progress,no-progress",
      fit_help, 0},
     cmd_fit,
     NULL,
     "the shape A of a measured height field, normal map or list of normals, by maximum likelihood"},
    {"mipmap",
     {"normal-map,alpha,roughness-map,perceptual,fast,y-down,threads,out,format", mipmap_help, 0},
     cmd_mipmap,
     NULL,
     "a normal map filtered into a mip chain of per-texel ellipsoids (OpenEXR per level)"},
    {"predict",
     {"heightfield,spacing,z-scale,downsample,n,bounces,no-wave,size,exposure,threads,out,progress,no-progress",
      predict_help, 0},
     cmd_predict,
     NULL,
     "a measured surface's BRDF traced and by wave optics beside its fitted model, on one sheet"},
    {"microsurface",
     {NULL, NULL, 0},
     NULL,
     cmd_microsurface,
     "height fields with a chosen NDF, traced against the model's masking"},
};
enum { NCOMMANDS = sizeof COMMANDS / sizeof COMMANDS[0] };

static void usage(FILE *f)
{
    fprintf(f, "usage: ggx <command> [options]   (ggx <command> --help for each)\n\ncommands:\n");
    for (int i = 0; i < NCOMMANDS; i++) fprintf(f, "  %-12s %s\n", COMMANDS[i].name, COMMANDS[i].summary);
    fputs("\n"
          "options: --name VALUE or --name=VALUE; -n N counts; --out PATH (- or absent: stdout; demo and mipmap\n"
          "write a folder and refuse -); --seed S; --help on every command; -V (--version) prints the version.\n"
          "\n"
          "output: --out writes what a shell redirect (> PATH) would. A new file, or a regular file (or the target\n"
          "of a link to one) of one name and no extended attributes, is written under a temporary name in its\n"
          "folder and renamed over it when complete, keeping its permissions and owner: no partial or temporary\n"
          "file is left by an error, a full disk, SIGINT, SIGTERM, SIGHUP or SIGPIPE. It is written in place,\n"
          "as a redirect writes it, where a rename would lose what a redirect keeps: /dev/stdout, /dev/stderr,\n"
          "/dev/fd/N (the descriptor as opened: >> appends); a device, FIFO or socket; a file with hard links\n"
          "or extended attributes (ACLs); a file in a folder the user may not write, or whose owner the user\n"
          "cannot give. File names' extensions (.png, .PNG) are read in any case.\n"
          "\n"
          "exit status: 0 success; 1 a check failed (ggx check); 2 bad input or a failed write, with one line\n"
          "\"ggx: ...\" on stderr; 141 the reader of stdout went away (also where SIGPIPE is ignored).\n",
          f);
    fprintf(f, "\nlibggx %d.%d.%d, MIT licence\n", GGX_VERSION_MAJOR, GGX_VERSION_MINOR, GGX_VERSION_PATCH);
}

/* Every write to stdout is checked: a full disk or a closed pipe is an error, not a silent success. */
static int finish(int rc)
{
    out_flush_stdout();
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *c = argv[1];
    if (strcmp(c, "--help") == 0 || strcmp(c, "-h") == 0 || strcmp(c, "help") == 0) {
        usage(stdout);
        return finish(0);
    }
    if (strcmp(c, "--version") == 0 || strcmp(c, "-V") == 0) {
        printf("ggx %d.%d.%d\n", GGX_VERSION_MAJOR, GGX_VERSION_MINOR, GGX_VERSION_PATCH);
        return finish(0);
    }
    for (int i = 0; i < NCOMMANDS; i++) {
        const struct command *k = &COMMANDS[i];
        if (strcmp(c, k->name) != 0) continue;
        if (k->run_argv) return finish(k->run_argv(argc, argv));
        options o;
        ggx_shape s;
        if (!command_options(&k->spec, argc, argv, 2, &o)) return finish(0); /* --help */
        if (k->spec.shape) shape_from_options(&o, &s);
        return finish(k->run(&o, k->spec.shape ? &s : NULL));
    }
    die("unknown command '%s' (see ggx --help)", c);
}
