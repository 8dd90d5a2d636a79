/* ggx albedo: the directional albedo E(v) and the average E_avg of a shape, separable and height-correlated G,
 * as CSV or JSON. SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "cli.h"

int cmd_albedo(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 2, &o, SHAPE_OPTS ",view,format,out");
    if (o.help) {
        printf("usage: ggx albedo [shape] [--view DIR] [--format csv|json] [--out FILE]\n\n"
               "The directional albedo E(v) of the BRDF with F = 1 (the energy that single scattering keeps), for the\n"
               "view DIR or, by default, for theta = 0, 15, 30, 45, 60, 75, 85 and 89 degrees at phi = 0 and 90; and\n"
               "the average E_avg = (1/pi) int E(v) v.z dv. Columns: view_theta_deg, view_phi_deg, E (separable G,\n"
               "eq 5, as ggx_brdf_eval), E_height_correlated (the height-correlated G2 most renderers use), E_avg,\n"
               "E_avg_height_correlated (the same on every row). Deterministic quadrature, absolute error <= 1e-6;\n"
               "the averages of a skewed shape take about half a minute.\n\n%s",
               SHAPE_HELP);
        return 0;
    }
    ggx_shape s;
    shape_from_options(&o, &s);
    int json = 0;
    if (o.format && strcmp(o.format, "json") == 0) json = 1;
    else if (o.format && strcmp(o.format, "csv") != 0) die("--format: '%s' is not csv or json", o.format);
    ggx_vec3 views[16];
    int nv = 0;
    if (o.have_view) {
        if (!(o.view.z > 0)) die("--view: the view must be above the horizon (theta < 90)");
        views[nv++] = o.view;
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
    double avg = ggx_albedo_avg(&s), avg_hc = ggx_albedo_avg_height_correlated(&s);
    static const char *cols[] = {"view_theta_deg", "view_phi_deg", "E", "E_height_correlated", "E_avg",
                                 "E_avg_height_correlated"};
    out_file out;
    out_open(&out, o.out);
    if (json) fprintf(out.f, "[\n");
    else fprintf(out.f, "%s,%s,%s,%s,%s,%s\n", cols[0], cols[1], cols[2], cols[3], cols[4], cols[5]);
    for (int k = 0; k < nv; k++) {
        ggx_vec3 v = views[k];
        double row[6] = {acos(v.z) / DEG, atan2(v.y, v.x) / DEG, ggx_albedo(&s, v),
                         ggx_albedo_height_correlated(&s, v), avg, avg_hc};
        if (json) fprintf(out.f, "  {");
        for (int c = 0; c < 6; c++) {
            if (json) fprintf(out.f, "\"%s\": %.10g%s", cols[c], row[c], c + 1 < 6 ? ", " : "");
            else fprintf(out.f, "%.10g%s", row[c], c + 1 < 6 ? "," : "\n");
        }
        if (json) fprintf(out.f, "}%s\n", k + 1 < nv ? "," : "");
    }
    if (json) fprintf(out.f, "]\n");
    out_close(&out);
    return 0;
}
