/* ggx albedo: the directional albedo E(v) and the average E_avg of a shape, separable and height-correlated G; or,
 * with --eta, the reflected and transmitted albedo of the rough dielectric from both sides; as CSV or JSON.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "cli.h"

/* A row of numbers, CSV or JSON (the JSON's brackets around the rows are the caller's). */
static void put_row(FILE *f, int json, const char *const *cols, const double *row, int n, int last)
{
    if (json) fprintf(f, "  {");
    for (int c = 0; c < n; c++) {
        if (json) fprintf(f, "\"%s\": %.10g%s", cols[c], row[c], c + 1 < n ? ", " : "");
        else fprintf(f, "%.10g%s", row[c], c + 1 < n ? "," : "\n");
    }
    if (json) fprintf(f, "}%s\n", last ? "" : ",");
}

static void put_header(FILE *f, int json, const char *const *cols, int n)
{
    if (json) {
        fprintf(f, "[\n");
        return;
    }
    for (int c = 0; c < n; c++) fprintf(f, "%s%s", cols[c], c + 1 < n ? "," : "\n");
}

/* --eta: R and T of the rough dielectric for light from each view, on either side. */
static int dielectric(const options *o, const ggx_shape *s, int json)
{
    ggx_vec3 views[10];
    int nv = 0;
    if (o->have_view) {
        if (!(fabs(o->view.z) > 1e-12)) die("--view: with --eta the view may be on either side, not on the horizon");
        views[nv++] = o->view;
    } else {
        const double th[] = {0, 30, 60, 80, 89, 180, 150, 120, 100, 91};
        for (int i = 0; i < 10; i++) {
            double t = th[i] * DEG;
            ggx_vec3 v = {sin(t), 0.0, cos(t)};
            views[nv++] = v;
        }
    }
    static const char *const cols[] = {"view_theta_deg", "view_phi_deg", "R", "T", "R_plus_T"};
    out_file out;
    out_open(&out, o->out);
    put_header(out.f, json, cols, 5);
    for (int k = 0; k < nv; k++) {
        ggx_vec3 v = views[k];
        double r, t, e = ggx_bsdf_albedo(s, o->eta, v, &r, &t);
        double l = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        double row[5] = {acos(v.z / l) / DEG, atan2(v.y, v.x) / DEG, r, t, e};
        put_row(out.f, json, cols, row, 5, k + 1 == nv);
    }
    if (json) fprintf(out.f, "]\n");
    out_close(&out);
    return 0;
}

void albedo_help(void)
{
    printf("usage: ggx albedo [shape] [--view DIR] [--eta ETA] [--format csv|json] [--out FILE]\n\n"
           "The directional albedo E(v) of the BRDF with F = 1 (the energy that single scattering keeps), for the\n"
           "view DIR or, by default, for theta = 0, 15, 30, 45, 60, 75, 85 and 89 degrees at phi = 0 and 90; and\n"
           "the average E_avg = (1/pi) int E(v) v.z dv. Columns: view_theta_deg, view_phi_deg, E (separable G,\n"
           "eq 5, as ggx_brdf_eval), E_height_correlated (the height-correlated G2 most renderers use), E_avg,\n"
           "E_avg_height_correlated (the same on every row). Deterministic quadrature, absolute error <= 1e-6;\n"
           "the averages of a skewed shape take about half a minute.\n\n"
           "With --eta ETA (the index below the surface relative to above, as for the rough dielectric): the\n"
           "albedo of ggx_bsdf_eval for light arriving from the view, which may be on either side (theta > 90:\n"
           "from below), by default theta = 0, 30, 60, 80, 89 and 180, 150, 120, 100, 91 at phi = 0. Columns:\n"
           "view_theta_deg, view_phi_deg, R (reflected), T (transmitted), R_plus_T (the rest is lost to multiple\n"
           "scattering). Absolute error <= 1e-4.\n\n");
}

int cmd_albedo(options *o, const ggx_shape *s)
{
    int json = 0;
    if (o->format && strcmp(o->format, "json") == 0) json = 1;
    else if (o->format && strcmp(o->format, "csv") != 0) die("--format: '%s' is not csv or json", o->format);
    if (o->have_eta) return dielectric(o, s, json);
    ggx_vec3 views[16];
    int nv = 0;
    if (o->have_view) {
        if (!(o->view.z > 0)) die("--view: the view must be above the horizon (theta < 90)");
        views[nv++] = o->view;
    } else {
        const double th[] = {0, 15, 30, 45, 60, 75, 85, 89};
        for (int p = 0; p < 2; p++)
            for (int i = 0; i < 8; i++) {
                if (th[i] == 0 && p == 1) continue;
                double t = th[i] * DEG, ph = 90.0 * p * DEG;
                ggx_vec3 v = {sin(t) * cos(ph), sin(t) * sin(ph), cos(t)};
                views[nv++] = v;
            }
    }
    double avg = ggx_albedo_avg(s), avg_hc = ggx_albedo_avg_height_correlated(s);
    static const char *const cols[] = {"view_theta_deg",      "view_phi_deg", "E",
                                       "E_height_correlated", "E_avg",        "E_avg_height_correlated"};
    out_file out;
    out_open(&out, o->out);
    put_header(out.f, json, cols, 6);
    for (int k = 0; k < nv; k++) {
        ggx_vec3 v = views[k];
        double row[6] = {
            acos(v.z) / DEG, atan2(v.y, v.x) / DEG, ggx_albedo(s, v), ggx_albedo_height_correlated(s, v), avg, avg_hc};
        put_row(out.f, json, cols, row, 6, k + 1 == nv);
    }
    if (json) fprintf(out.f, "]\n");
    out_close(&out);
    return 0;
}
