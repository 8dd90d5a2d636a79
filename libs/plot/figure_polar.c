/* The polar figure (ggx plot --figure polar): how a shape scatters light from a few incidence angles, as BRDF
 * Explorer's polar plot: f(wi, wo) |cos theta_o| (the integrand of the directional albedo over wo) in the incidence
 * plane and in the plane across it, against the polar angle of wo, for the BRDF (F = 1) or the rough dielectric's
 * BSDF (radiance). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "figure.h"

enum { POLAR_INCIDENCE = 4, POLAR_STEPS = 720 };
static const double INCIDENCE_DEG[POLAR_INCIDENCE] = {20, 40, 60, 80};

/* wo at the signed polar angle a (radians) in a plane through n: the incidence plane (azimuth of the mirror
 * direction, phi_i + pi, at a > 0) or the plane across it (azimuth phi_i + pi / 2 at a > 0). |a| > pi / 2 is below
 * the surface. */
static ggx_vec3 polar_dir(double phi_i, int across, double a)
{
    double az = phi_i + (across ? (90.0 * DEG) : (180.0 * DEG));
    return (ggx_vec3){sin(a) * cos(az), sin(a) * sin(az), cos(a)};
}

/* The figure's value at wo: f |cos theta_o|, 0 below the surface for the BRDF. */
static double polar_value(const figure_spec *f, ggx_vec3 wi, ggx_vec3 wo)
{
    if (f->eta > 0) return ggx_bsdf_eval(f->s, f->eta, wi, wo, GGX_RADIANCE) * fabs(wo.z);
    return wo.z > 0 ? ggx_brdf_eval(f->s, NULL, wi, wo) * wo.z : 0.0;
}

/* Curve k: incidence angle INCIDENCE_DEG[k / 2] at the view's azimuth, plane k % 2 (0: incidence, 1: across). x is
 * the signed polar angle of wo in degrees, over [-90, 90] (BRDF) or [-180, 180] (BSDF), y the value. */
int polar_curve(const figure_spec *f, int k, double *x, double *y, int max, char *label, size_t n)
{
    if (k < 0 || k >= 2 * POLAR_INCIDENCE) return -1;
    double phi_i = atan2(f->view.y, f->view.x), ti = INCIDENCE_DEG[k / 2] * DEG;
    ggx_vec3 wi = {sin(ti) * cos(phi_i), sin(ti) * sin(phi_i), cos(ti)};
    double span = f->eta > 0 ? 180.0 : 90.0;
    int m = 0;
    for (int i = 0; i <= POLAR_STEPS && m < max; i++) {
        double a = -span + 2.0 * span * i / POLAR_STEPS;
        x[m] = a, y[m++] = polar_value(f, wi, polar_dir(phi_i, k % 2, a * DEG));
    }
    if (label && n) snprintf(label, n, "θi %.0f°%s", INCIDENCE_DEG[k / 2], k % 2 ? ", across" : "");
    return m;
}

void polar_draw(cairo_t *cr, const theme *th, double x, double y, double w, double h, const figure_spec *f)
{
    static double cx[2 * POLAR_INCIDENCE][POLAR_STEPS + 1], cy[2 * POLAR_INCIDENCE][POLAR_STEPS + 1];
    int cn[2 * POLAR_INCIDENCE];
    double top = 0.0;
    for (int k = 0; k < 2 * POLAR_INCIDENCE; k++) {
        cn[k] = polar_curve(f, k, cx[k], cy[k], POLAR_STEPS + 1, NULL, 0);
        for (int i = 0; i < cn[k]; i++)
            if (isfinite(cy[k][i]) && cy[k][i] > top) top = cy[k][i];
    }
    double ticks[16];
    int nt = nice_ticks(0.0, top > 0 ? top : 1.0, 4, ticks, 16);
    double rmax = nt > 0 && ticks[nt - 1] >= top ? ticks[nt - 1] : (top > 0 ? top : 1.0);
    const int full = f->eta > 0;
    double F = figure_font(w, h);
    double cap = figure_draw_caption(cr, th, x, y, w, F, f, 3);
    double legend_w = 9.0 * F;
    /* the plot: a half disk above the surface (BRDF) or a whole disk (BSDF), centred left of the legend */
    double aw = w - legend_w - 2.0 * F, ah = h - cap - 2.5 * F;
    double R = full ? fmin(0.5 * aw, 0.5 * ah) : fmin(0.5 * aw, ah - 0.5 * F);
    double ox = x + F + 0.5 * aw, oy = full ? y + cap + 0.8 * F + 0.5 * ah : y + cap + 0.8 * F + 0.5 * (ah + R);
    /* rings at the radial ticks, labelled; the surface and the normal */
    cairo_set_line_width(cr, fmax(0.4, 0.05 * F));
    text_font(cr, 0.75 * F, 0);
    for (int i = 1; i < nt; i++) {
        double r = R * ticks[i] / rmax;
        if (r > R * 1.0001) continue;
        cairo_set_source_rgba(cr, th->faint[0], th->faint[1], th->faint[2], 0.45);
        cairo_new_path(cr);
        cairo_arc(cr, ox, oy, r, full ? 0 : (180.0 * DEG), (360.0 * DEG));
        cairo_stroke(cr);
        set_rgb(cr, th->fg);
        char b[32];
        format_tick(ticks[i], b, sizeof b);
        text_at(cr, ox + r, oy + 0.3 * F, 0.5, 0, b);
    }
    cairo_set_source_rgba(cr, th->faint[0], th->faint[1], th->faint[2], 0.8); /* the frame, at the scale's top */
    cairo_new_path(cr);
    cairo_arc(cr, ox, oy, R, full ? 0 : (180.0 * DEG), (360.0 * DEG));
    cairo_stroke(cr);
    set_rgb(cr, th->fg);
    cairo_set_line_width(cr, fmax(0.6, 0.08 * F));
    cairo_move_to(cr, ox - R, oy), cairo_line_to(cr, ox + R, oy), cairo_stroke(cr);
    double dn[2] = {0.4 * F, 0.3 * F};
    cairo_set_dash(cr, dn, 2, 0);
    cairo_move_to(cr, ox, oy + (full ? R : 0)), cairo_line_to(cr, ox, oy - R), cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0);
    text_font(cr, 0.8 * F, 0);
    text_at(cr, ox + 0.3 * F, oy - R, 0, 0, "n");
    text_at(cr, ox - R, oy + 1.4 * F, 0, 0, "incidence side");
    text_at(cr, ox + R, oy + 1.4 * F, 1, 0, "mirror side");
    /* the curves: radius value / rmax, at the polar angle of wo (positive toward the mirror side) */
    cairo_save(cr);
    cairo_rectangle(cr, x, y + cap, w, h - cap);
    cairo_clip(cr);
    cairo_set_line_width(cr, fmax(1.0, 0.13 * F));
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (int k = 0; k < 2 * POLAR_INCIDENCE; k++) {
        double dashes[2] = {0.6 * F, 0.35 * F};
        set_rgb(cr, FIGURE_PALETTE[(k / 2) % 6]);
        cairo_set_dash(cr, dashes, k % 2 ? 2 : 0, 0);
        cairo_new_path(cr);
        for (int i = 0; i < cn[k]; i++) {
            double r = isfinite(cy[k][i]) ? R * fmin(cy[k][i] / rmax, 1.05) : 0.0, a = cx[k][i] * DEG;
            double X = ox + r * sin(a), Y = oy - r * cos(a);
            if (i == 0) cairo_move_to(cr, X, Y);
            else cairo_line_to(cr, X, Y);
        }
        cairo_stroke(cr);
    }
    cairo_set_dash(cr, NULL, 0, 0);
    /* the incident directions, as short arrows pointing at the surface's centre from the incidence side */
    for (int k = 0; k < POLAR_INCIDENCE; k++) {
        double a = -INCIDENCE_DEG[k] * DEG, r0 = R, r1 = 0.85 * R;
        set_rgb(cr, FIGURE_PALETTE[k % 6]);
        arrow(cr, ox + r0 * sin(a), oy - r0 * cos(a), ox + r1 * sin(a), oy - r1 * cos(a), 0.5 * F);
    }
    cairo_restore(cr);
    /* legend */
    text_font(cr, 0.8 * F, 0);
    for (int k = 0; k < 2 * POLAR_INCIDENCE; k++) {
        char label[64];
        double dummy_x[1], dummy_y[1];
        polar_curve(f, k, dummy_x, dummy_y, 1, label, sizeof label);
        double lx = x + w - legend_w, ly = y + cap + 1.0 * F + 1.35 * F * k;
        double dashes[2] = {0.6 * F, 0.35 * F};
        set_rgb(cr, FIGURE_PALETTE[(k / 2) % 6]);
        cairo_set_line_width(cr, fmax(1.0, 0.13 * F));
        cairo_set_dash(cr, dashes, k % 2 ? 2 : 0, 0);
        cairo_move_to(cr, lx, ly), cairo_line_to(cr, lx + 2.2 * F, ly), cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0);
        set_rgb(cr, th->fg);
        text_at(cr, lx + 2.7 * F, ly, 0, 0.5, label);
    }
    set_rgb(cr, th->fg);
    text_font(cr, 0.75 * F, 0);
    text_at(cr, x + w - legend_w, y + cap + 1.0 * F + 1.35 * F * (2 * POLAR_INCIDENCE + 0.5), 0, 0.5,
            full ? "radius: f |cos θo| (sr⁻¹)" : "radius: f cos θo (sr⁻¹)");
}
