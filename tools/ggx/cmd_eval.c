/* ggx eval: D, G1, G, the pdfs, the BRDF and the BSDF for a shape and directions, as CSV or JSON.
 * SPDX-License-Identifier: MIT */
#include <string.h>

#include "cli.h"

void eval_help(void)
{
    printf("usage: ggx eval [shape] [--wi DIR] [--wo DIR]... [--fresnel F] [--eta ETA] [--format csv|json] [--out "
           "FILE]\n\n"
           "Evaluates the model for one incident direction wi and one or more outgoing directions wo (defaults:\n"
           "wi = 40,0 and wo = 0,0 40,180 60,180 20,90). Columns: the directions, the half vector h, D(h), G1(wi,h),\n"
           "G1(wo,h), G = G1 G1, the height-correlated G2, Lambda(wi), Lambda(wo), the VNDF pdf of h for wi, the\n"
           "reflection pdf of wo, the BRDF, and with --eta the rough-dielectric BSDF f(wi -> wo) and its pdf.\n"
           "--fresnel one | dielectric:ETA | conductor:ETA,K | schlick:F0 (default one)\n"
           "--sggx: the flakes of S = A^T A instead (ggx_sggx.h): the directions, h, sigma(wi), sigma(wo), D(h) and\n"
           "the specular and diffuse phase functions f(wi, wo), wi the direction the particle came from\n\n");
}

int cmd_eval(options *o, const ggx_shape *s)
{
    ggx_fresnel f = fresnel_from_options(o);
    if (!o->have_wi) parse_direction("40,0", &o->wi);
    if (o->nwo == 0) {
        const char *d[] = {"0,0", "40,180", "60,180", "20,90"};
        for (int i = 0; i < 4; i++) parse_direction(d[i], &o->wo[o->nwo++]);
    }
    int json = 0;
    if (o->format && strcmp(o->format, "json") == 0) json = 1;
    else if (o->format && strcmp(o->format, "csv") != 0) die("--format: '%s' is not csv or json", o->format);
    static const char *cols[] = {"wi_x",      "wi_y",      "wi_z",     "wo_x",     "wo_y",  "wo_z", "h_x",
                                 "h_y",       "h_z",       "D",        "G1_wi",    "G1_wo", "G",    "G2_hc",
                                 "lambda_wi", "lambda_wo", "pdf_vndf", "pdf_brdf", "brdf",  "bsdf", "pdf_bsdf"};
    static const char *sggx_cols[] = {
        "wi_x", "wi_y", "wi_z",     "wo_x",     "wo_y", "wo_z",           "h_x",
        "h_y",  "h_z",  "sigma_wi", "sigma_wo", "D",    "phase_specular", "phase_diffuse"};
    ggx_sggx fl;
    if (o->sggx && ggx_sggx_from_shape(&fl, s) != GGX_OK) die("--sggx: no flakes of this shape (too ill-conditioned)");
    const char **names = o->sggx ? sggx_cols : cols;
    int ncols = o->sggx ? 14 : o->have_eta ? 21 : 19;
    out_file out;
    out_open(&out, o->out);
    if (json) fprintf(out.f, "[\n");
    else
        for (int c = 0; c < ncols; c++) fprintf(out.f, "%s%s", names[c], c + 1 < ncols ? "," : "\n");
    for (int k = 0; k < o->nwo; k++) {
        ggx_vec3 wi = o->wi, wo = o->wo[k], h = ggx_half_reflect(wi, wo);
        double v[21] = {wi.x,
                        wi.y,
                        wi.z,
                        wo.x,
                        wo.y,
                        wo.z,
                        h.x,
                        h.y,
                        h.z,
                        ggx_ndf(s, h),
                        ggx_g1(s, wi, h),
                        ggx_g1(s, wo, h),
                        ggx_g2(s, wi, wo, h),
                        ggx_g2_height_correlated(s, wi, wo, h),
                        ggx_lambda(s, wi),
                        ggx_lambda(s, wo),
                        ggx_pdf_vndf(s, wi, h),
                        ggx_pdf_brdf(s, wi, wo),
                        ggx_brdf_eval(s, &f, wi, wo),
                        0,
                        0};
        if (o->sggx) {
            double sv[5] = {ggx_sggx_sigma(&fl, wi), ggx_sggx_sigma(&fl, wo), ggx_sggx_ndf(&fl, h),
                            ggx_sggx_phase_specular(&fl, wi, wo), ggx_sggx_phase_diffuse(&fl, wi, wo)};
            memcpy(v + 9, sv, sizeof sv);
        } else if (o->have_eta) {
            v[19] = ggx_bsdf_eval(s, o->eta, wi, wo, GGX_RADIANCE);
            v[20] = ggx_pdf_bsdf(s, o->eta, wo, wi);
        }
        if (json) fprintf(out.f, "  {");
        for (int c = 0; c < ncols; c++) {
            if (json) fprintf(out.f, "\"%s\": %.17g%s", names[c], v[c], c + 1 < ncols ? ", " : "");
            else fprintf(out.f, "%.17g%s", v[c], c + 1 < ncols ? "," : "\n");
        }
        if (json) fprintf(out.f, "}%s\n", k + 1 < o->nwo ? "," : "");
    }
    if (json) fprintf(out.f, "]\n");
    out_close(&out);
    return 0;
}
