/* ggx plot: one figure (PNG density or SVG grid) for any shape, view and sampler. SPDX-License-Identifier: MIT */
#include <string.h>
#include <sys/stat.h>

#include "cli.h"

static const char *default_ext(figure_kind k) { return (k == FIG_GRID || k == FIG_GRID_SIDE) ? "svg" : "png"; }

int cmd_plot(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 2, &o, SHAPE_OPTS ",figure,view,sampler,size,log,out");
    if (o.help) {
        printf("usage: ggx plot [shape] [--figure NAME] [--view DIR] [--sampler NAME] [--size PX] [--log] [--out FILE]\n\n"
               "Figures: ndf, ndf-side (pdf D(m) m.n from above / from the side, PNG with a colour bar), vndf,\n"
               "vndf-side (the visible-normal pdf for --view, default 75,0), grid, grid-side (the 10 x 10 equal-area\n"
               "grid of the unit square mapped onto the hemisphere by --sampler, default stretch, SVG). --log uses a\n"
               "logarithmic colour scale over four decades (for sharp lobes). --size in pixels (default 512).\n"
               "--out defaults to FIGURE.png or FIGURE.svg in the current folder.\n\n%s", SHAPE_HELP);
        return 0;
    }
    ggx_shape s;
    shape_from_options(&o, &s);
    figure_kind k = figure_from_name(o.figure ? o.figure : "ndf");
    if (!o.have_view) parse_direction("75,0", &o.view);
    if ((k == FIG_VNDF || k == FIG_VNDF_SIDE) && !(o.view.z > 0)) die("--view must be above the horizon for a VNDF figure");
    const ggx_sampler_info *smp = o.sampler ? find_sampler(o.sampler) : ggx_sampler_get(GGX_SAMPLER_STRETCH);
    require_domain(smp, &s);
    if (smp->family == GGX_FAMILY_VNDF && !(o.view.z > 0))
        die("--view must be above the horizon for sampler '%s'", smp->name);
    char fallback[64], title[128];
    snprintf(fallback, sizeof fallback, "%s.%s", o.figure ? o.figure : "ndf", default_ext(k));
    const char *path = o.out ? o.out : fallback;
    /* a file name says its format: a PNG figure is not written to x.svg. Standard output ("-") and what is not a
     * regular file (a device, a FIFO) take the figure's own format. */
    const char *want = (k == FIG_GRID || k == FIG_GRID_SIDE) ? ".svg" : ".png";
    size_t pl = strlen(path);
    struct stat st;
    int stream = strcmp(path, "-") == 0 || (stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode));
    if (!stream && (pl < 4 || strcmp(path + pl - 4, want) != 0))
        die("--out: figure '%s' is written as %s (or give - for standard output)", o.figure ? o.figure : "ndf", want);
    snprintf(title, sizeof title, "%s  alpha %.3g,%.3g", o.figure ? o.figure : "ndf", o.alpha[0], o.alpha[1]);
    draw_figure(k, &s, o.view, smp, o.size ? o.size : 512, o.log_scale, title, path);
    if (strcmp(path, "-") != 0) fprintf(stderr, "ggx: wrote %s\n", path);
    return 0;
}
