/* ggx sample: N samples of any sampler, with pdf and weight, as CSV or float32. SPDX-License-Identifier: MIT */
#include <string.h>
#include <unistd.h>

#include "cli.h"

enum { SAMPLE_PROGRESS_MIN = 1 << 20 };

void sample_help(void)
{
    printf("usage: ggx sample [shape] [--sampler NAME] [--view DIR] [-n N] [--seed S] [--format csv|f32] [--out "
           "FILE]\n"
           "                  [--progress|--no-progress]\n\n"
           "Draws N samples (default 1000) with columns x,y,z,pdf,weight. For normal samplers the weight is 1;\n"
           "for samplers of directions it is f |w.n| / pdf. Invalid samples are written as 0,0,0,0,0. --format f32\n"
           "writes 5 little-endian float32 per sample (to a file or a pipe, not to a terminal). --view is the\n"
           "view / known direction (default 40,0). Runs of %d samples or more show a progress bar on a terminal.\n"
           "--sggx --phase specular|diffuse: directions wo drawn from the flakes' phase function f(wi, .) of\n"
           "S = A^T A, wi = --view (ggx_sggx.h), pdf f(wi, wo), weight 1.\n\n",
           SAMPLE_PROGRESS_MIN);
    print_samplers(stdout);
    printf("\n");
}

int cmd_sample(options *o, const ggx_shape *s)
{
    if (o->sggx && o->sampler) die("--sggx samples the flakes' phase function: give --phase, not --sampler");
    if (o->phase && !o->sggx) die("--phase is the flakes' phase function of --sggx");
    int diffuse = phase_is_diffuse(o);
    ggx_sggx fl;
    if (o->sggx && ggx_sggx_from_shape(&fl, s) != GGX_OK) die("--sggx: no flakes of this shape (too ill-conditioned)");
    const ggx_sampler_info *smp = o->sampler ? find_sampler(o->sampler) : ggx_sampler_get(GGX_SAMPLER_CAPS);
    require_domain(smp, s);
    if (!o->have_view) parse_direction("40,0", &o->view);
    require_view(smp, o->view);
    ggx_fresnel f = fresnel_from_options(o);
    int f32 = 0;
    if (o->format && strcmp(o->format, "f32") == 0) f32 = 1;
    else if (o->format && strcmp(o->format, "csv") != 0) die("--format: '%s' is not csv or f32", o->format);
    int to_stdout = !o->out || strcmp(o->out, "-") == 0;
    if (f32 && to_stdout && isatty(1)) die("--format f32 is binary: give --out FILE or redirect standard output");
    long n = o->n > 0 ? o->n : 1000;
    rng r = {o->seed};
    int progress = progress_wanted(o->progress) && n >= SAMPLE_PROGRESS_MIN;
    out_file out;
    out_open(&out, o->out);
    if (!f32) fprintf(out.f, "x,y,z,pdf,weight\n");
    for (long i = 0; i < n; i++) {
        ggx_vec3 w;
        double pdf, weight;
        if (o->sggx) {
            double u1 = rng_uniform(&r), u2 = rng_uniform(&r);
            w = diffuse ? ggx_sggx_sample_diffuse(&fl, o->view, u1, u2, rng_uniform(&r), rng_uniform(&r))
                        : ggx_sggx_sample_specular(&fl, o->view, u1, u2);
            pdf = diffuse ? ggx_sggx_phase_diffuse(&fl, o->view, w) : ggx_sggx_phase_specular(&fl, o->view, w);
            weight = 1;
        } else if (!draw_sample(smp, s, o->view, &f, o->eta, &r, &w, &pdf, &weight))
            w = t_vec(0, 0, 0), pdf = 0, weight = 0;
        if (f32) {
            float v[5] = {(float)w.x, (float)w.y, (float)w.z, (float)pdf, (float)weight};
            fwrite(v, sizeof v, 1, out.f);
        } else {
            fprintf(out.f, "%.17g,%.17g,%.17g,%.17g,%.17g\n", w.x, w.y, w.z, pdf, weight);
        }
        if ((i & 1023) == 1023) out_check(&out); /* a full disk or a dead pipe stops the run */
        if (progress && (i & 0xFFFF) == 0xFFFF) progress_show(smp->name, i + 1, n);
    }
    if (progress) progress_end(smp->name, n);
    out_close(&out);
    return 0;
}
