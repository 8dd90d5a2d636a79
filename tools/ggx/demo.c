/* ggx demo: the seeds' figures for two shapes, then a check of every sampler of normals. SPDX-License-Identifier: MIT */
#include <string.h>
#include <time.h>

#include "chi2.h"
#include "cli.h"

/* The samplers the demo checks on a shape: those of normals, where the shape is in their domain. */
static int checked(const ggx_sampler_info *smp, const ggx_shape *s)
{
    return smp->family != GGX_FAMILY_DIRECTION && sampler_applies(smp, s);
}

int cmd_demo(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 2, &o, "out,n,size");
    if (o.help) {
        printf("usage: ggx demo [--out DIR] [-n N] [--size PX]\n\n"
               "Draws the seeds' figures for alpha = (0.15, 0.5) and for the same shape skewed by theta_x = 15,\n"
               "theta_y = -10 degrees into DIR (default out/): the equal-area grid mapped by NDF sampling (top and\n"
               "side), the NDF pdf (top and side), the VNDF pdf for theta_v = 75 with phi_v = 0 and 90. Then checks\n"
               "every sampler for these shapes (N samples each, default 10^6) and prints the table. --size is the\n"
               "figures' size in pixels (default 384). The figures are written all or none.\n");
        return 0;
    }
    if (o.n > 0) require_check_n(o.n); /* before any figure is drawn */
    clock_t c0 = clock();
    const char *dir = o.out ? o.out : "out";
    ensure_dir(dir);
    int size = o.size ? o.size : 384;
    struct {
        const char *prefix, *label;
        double tx, ty;
    } shapes[2] = {{"", "alpha 0.15,0.5", 0, 0}, {"skewed-", "skewed 15,-10", 15, -10}};
    ggx_vec3 v0, v90;
    parse_direction("75,0", &v0);
    parse_direction("75,90", &v90);
    char path[1024], title[128];
    const ggx_sampler_info *stretch = ggx_sampler_get(GGX_SAMPLER_STRETCH);
    ggx_shape sh[2];
    for (int k = 0; k < 2; k++)
        if (ggx_shape_ellipsoid(&sh[k], 0.15, 0.5, shapes[k].tx * DEG, shapes[k].ty * DEG, 0) != GGX_OK) die("demo shape");
    static const struct {
        figure_kind k;
        const char *name;
        int view;
    } figs[] = {{FIG_GRID, "grid-top.svg", 0},        {FIG_GRID_SIDE, "grid-side.svg", 0},
                {FIG_NDF, "ndf-top.png", 0},          {FIG_NDF_SIDE, "ndf-side.png", 0},
                {FIG_VNDF, "vndf-75-0.png", 0},       {FIG_VNDF, "vndf-75-90.png", 90}};
    printf("ggx demo: figures in %s/\n", dir);
    out_begin_set(); /* all figures or none */
    for (int k = 0; k < 2; k++) {
        for (unsigned f = 0; f < sizeof figs / sizeof figs[0]; f++) {
            snprintf(path, sizeof path, "%s/%s%s", dir, shapes[k].prefix, figs[f].name);
            snprintf(title, sizeof title, "%s %s", shapes[k].label, figs[f].name);
            *strrchr(title, '.') = '\0';
            draw_figure(figs[f].k, &sh[k], figs[f].view ? v90 : v0, stretch, size, 0, title, path);
            printf("  %s\n", path);
        }
    }
    out_commit_set();
    long n = o.n > 0 ? o.n : 1000000;
    /* every sampler of normals of the library, on each shape in its domain */
    int runs = 0;
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < GGX_SAMPLER_COUNT; i++) runs += checked(ggx_sampler_get((ggx_sampler_id)i), &sh[k]);
    double alpha = chi2_sidak(runs);
    printf("\nchecks (%ld samples each; VNDF for theta_v = 75, phi_v = 0; level %.2g per run):\n", n, alpha);
    int all = 1;
    for (int k = 0; k < 2; k++) {
        printf("%s\n", shapes[k].label);
        print_check_header(stdout);
        for (int i = 0; i < GGX_SAMPLER_COUNT; i++) {
            const ggx_sampler_info *smp = ggx_sampler_get((ggx_sampler_id)i);
            if (!checked(smp, &sh[k])) continue;
            check_result r = run_check(&sh[k], v0, smp, n, 100 + (unsigned long long)i, alpha, 0);
            print_check_row(stdout, smp->name, r);
            out_flush_stdout();
            all &= r.pass;
        }
    }
    printf("\n%s in %.1f s. Figures: %s/\n", all ? "all checks pass" : "SOME CHECKS FAILED",
           (double)(clock() - c0) / CLOCKS_PER_SEC, dir);
    return all ? 0 : 1;
}
