/* ggx plot: one figure for any shape, view and sampler, as PNG, SVG or PDF. SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "figure_out.h"

/* The caption's description of the shape given on the command line. */
void shape_caption(const options *o, char *buf, size_t n)
{
    if (o->have_matrix)
        snprintf(buf, n, "A = [%g %g %g; %g %g %g; %g %g %g]", o->matrix[0][0], o->matrix[0][1], o->matrix[0][2],
                 o->matrix[1][0], o->matrix[1][1], o->matrix[1][2], o->matrix[2][0], o->matrix[2][1], o->matrix[2][2]);
    else figure_shape_caption(buf, n, o->alpha[0], o->alpha[1], o->skew[0], o->skew[1], o->rotate);
}

void plot_help(void)
{
    printf("usage: ggx plot [shape] [--figure NAME] [--view DIR] [--sampler NAME] [--from DEG] [--size W[xH]]\n"
           "                [--log] [--theme light|dark] [--eta E] [--phi-d DEG] [--out FILE]\n\n"
           "Figures (the seeds' hemisphere figures, then line plots):\n"
           "  ndf, ndf-side      the NDF pdf D(m) (m.n), from above / from the side, with a colour bar (sr^-1)\n"
           "  vndf, vndf-side    the visible-normal pdf for --view (default 75,0), with engstad-vndf-proof's grey "
           "region:\n"
           "                     the normals that reflect the view above the horizon\n"
           "  grid, grid-side    the 10 x 10 equal-area grid of the unit square mapped onto the hemisphere by\n"
           "                     --sampler (default stretch; a VNDF sampler maps for --view and shows the region)\n"
           "  g1, lambda         G1(v) and Lambda(v) against the view's polar angle, at several azimuths\n"
           "  ndf-slice          D(m) along the two principal planes through its peak (log scale)\n"
           "  furnace            the weak white furnace G1(v) int D (m.v)+ / (v.n) dm and the albedo E(v); for\n"
           "                     an anisotropic shape also the isotropic E at sqrt(alpha_x alpha_y) that\n"
           "                     renderers use in its place\n"
           "  polar              f cos theta_o, the albedo's integrand over wo, in the incidence plane (at the\n"
           "                     azimuth of --view) and across it, for incidence 20, 40, 60 and 80 degrees:\n"
           "                     the BRDF with F = 1, or with --eta E the rough dielectric's BSDF (radiance)\n"
           "  slice              the BRDF (F = 1) over the half-vector and difference angles (theta_h, theta_d),\n"
           "                     Rusinkiewicz's coordinates, at --phi-d DEG (default 90), the half vector at\n"
           "                     phi_h 0 (--rotate turns the shape), log scale over four decades\n\n"
           "Side views look from the azimuth --from (degrees); by default they show the lobe, which leans toward\n"
           "the view (VNDF) or the NDF peak: in profile from the lean's azimuth - 90 (the view pointing right;\n"
           "from -y for phi_v = 0, as in the seeds), or facing it where the lobe is narrower across the profile\n"
           "plane; the caption states the azimuth. Only the visible half of the hemisphere is drawn.\n"
           "--log: a logarithmic colour scale over four decades.\n"
           "--size W or WxH: the file's size, exactly, in pixels (PNG) or points (SVG, PDF); with W alone the\n"
           "height follows the figure's aspect. Default width 640. --theme: light (default, for print) or dark.\n"
           "--out FILE: its name says the format (.png, .svg, .pdf); default FIGURE.png for hemisphere figures\n"
           "and the slice, FIGURE.svg for line plots and polar; - writes the default format to standard output.\n\n");
}

int cmd_plot(options *o, const ggx_shape *s)
{
    figure_kind k = figure_from_name(o->figure ? o->figure : "ndf");
    int line = k >= FIG_G1 && k != FIG_SLICE; /* line plots default to SVG, images to PNG */
    if (!o->have_view) parse_direction("75,0", &o->view);
    if ((k == FIG_VNDF || k == FIG_VNDF_SIDE) && !(o->view.z > 0))
        die("--view must be above the horizon for a VNDF figure");
    const ggx_sampler_info *smp = o->sampler ? find_sampler(o->sampler) : ggx_sampler_get(GGX_SAMPLER_STRETCH);
    if (k == FIG_GRID || k == FIG_GRID_SIDE) {
        require_domain(smp, s);
        if (!smp->sample) die("sampler '%s' is not a map of the unit square; grids need one", smp->name);
        if (smp->family == GGX_FAMILY_VNDF && !(o->view.z > 0))
            die("--view must be above the horizon for sampler '%s'", smp->name);
    }
    canvas_format deflt = line ? FMT_SVG : FMT_PNG;
    char fallback[64];
    snprintf(fallback, sizeof fallback, "%s%s", figure_name(k), format_ext(deflt));
    const char *path = o->out ? o->out : fallback;
    /* a file name says its format; standard output ("-") and what is not a regular file (a device, a FIFO) take
     * the figure's default format */
    canvas_format fmt = figure_format_of("--out", path, deflt);
    if (o->have_eta && k != FIG_POLAR) die("--eta is for --figure polar (the BSDF)");
    if (k == FIG_POLAR && o->have_eta && o->eta == 1.0) die("--eta 1: no interface, no BSDF to plot");
    figure_spec f = {
        k, s, o->view, smp, o->log_scale, o->dark, o->from * DEG, "", "", o->have_eta ? o->eta : 0.0, o->phi_d * DEG};
    shape_caption(o, f.shape_text, sizeof f.shape_text);
    int w = o->size ? o->size : 640;
    int h = o->size_h ? o->size_h : figure_height(k, w);
    figure_write(&f, path, fmt, w, h);
    if (strcmp(path, "-") != 0) fprintf(stderr, "ggx: wrote %s (%d x %d)\n", path, w, h);
    return 0;
}
