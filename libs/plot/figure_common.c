/* What every figure shares (figure.h): the figures' names, the grey region's rule, the captions, the font size
 * and the palette. The hemisphere and line figures (figures.c), the polar plot and the slice call down into this
 * file only. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figure.h"

static const char *const FIGURE_NAMES[] = {"ndf", "ndf-side", "vndf",      "vndf-side", "grid",  "grid-side",
                                           "g1",  "lambda",   "ndf-slice", "furnace",   "polar", "slice"};
_Static_assert(sizeof FIGURE_NAMES / sizeof FIGURE_NAMES[0] == FIG_COUNT, "a name for every figure_kind");

const char *figure_name(figure_kind k) { return k >= 0 && k < FIG_COUNT ? FIGURE_NAMES[k] : ""; }

int figure_kind_of(const char *name)
{
    for (int i = 0; i < FIG_COUNT; i++)
        if (name && strcmp(name, FIGURE_NAMES[i]) == 0) return i;
    return -1;
}

int figure_has_grey(const figure_spec *f)
{
    return figure_is_vndf(f->kind) || (figure_is_grid(f->kind) && f->sampler && f->sampler->family == GGX_FAMILY_VNDF);
}

void figure_direction_name(ggx_vec3 d, char *buf, size_t n)
{
    static const struct {
        double x, y;
        const char *name;
    } axes[] = {{1, 0, "x"}, {-1, 0, "−x"}, {0, 1, "y"}, {0, -1, "−y"}};
    for (unsigned i = 0; i < 4; i++)
        if (d.x * axes[i].x + d.y * axes[i].y > 1 - 1e-9) {
            snprintf(buf, n, "%s", axes[i].name);
            return;
        }
    snprintf(buf, n, "φ %.0f°", fmod(atan2(d.y, d.x) / DEG + 360.0, 360.0));
}

double figure_azimuth_deg(double rad)
{
    double d = fmod(rad / DEG, 360.0);
    if (d > 180) d -= 360;
    if (d <= -180) d += 360;
    return fabs(d) < 1e-9 ? 0.0 : d;
}

static void view_text(ggx_vec3 v, char *buf, size_t n)
{
    snprintf(buf, n, "view v: θ %.4g°, φ %.4g°", acos(fmax(-1, fmin(1, v.z))) / DEG,
             figure_azimuth_deg(atan2(v.y, v.x)));
}

static int caption_lines(const figure_spec *f, char lines[FIGURE_CAPTION_LINES][400])
{
    const char *what;
    char where[96] = "", view[96];
    switch (f->kind) {
    case FIG_NDF:
    case FIG_NDF_SIDE: what = "NDF pdf D(m) (m·n)"; break;
    case FIG_VNDF:
    case FIG_VNDF_SIDE:
        /* for skewed shapes Walter's clamped G1 does not normalise the G1 form: name eq 33 */
        what = f->s->kind == GGX_SHAPE_SKEWED ? "VNDF pdf D(m) (m·v)⁺ / ∫ D (m'·v)⁺ dm' (Walter eq 33)"
                                              : "VNDF pdf G1(v) D(m) (m·v)⁺ / (v·n)";
        break;
    case FIG_GRID:
    case FIG_GRID_SIDE: what = "Equal-area 10 × 10 grid of the unit square"; break;
    case FIG_G1: what = "Masking G1(v) against the view's polar angle"; break;
    case FIG_LAMBDA: what = "Smith Λ(v) against the view's polar angle"; break;
    case FIG_NDF_SLICE: what = "D(m) along the principal planes through its peak"; break;
    case FIG_POLAR:
        what = f->eta > 0 ? "BSDF f |cos θo| in the incidence plane (solid) and across it (dashed), radiance"
                          : "BRDF f cos θo (F = 1) in the incidence plane (solid) and across it (dashed)";
        break;
    case FIG_SLICE: what = "BRDF f_r (F = 1) over (θh, θd), Rusinkiewicz's coordinates, log scale"; break;
    default: what = "Weak white furnace and directional albedo (F = 1)"; break;
    }
    int n = 0;
    if (figure_is_side(f->kind))
        snprintf(where, sizeof where, ", from the side (seen from φ %.4g°)", figure_azimuth_deg(f->from));
    else if (!figure_is_line(f->kind)) snprintf(where, sizeof where, ", from above");
    snprintf(lines[n++], 400, "%s%s", what, where);
    view_text(f->view, view, sizeof view);
    if (figure_is_grid(f->kind))
        snprintf(lines[n++], 400, "%s  ·  mapped by sampler '%s'%s%s", f->shape_text, f->sampler->name,
                 f->sampler->family == GGX_FAMILY_VNDF ? "  ·  " : "",
                 f->sampler->family == GGX_FAMILY_VNDF ? view : "");
    else if (figure_is_vndf(f->kind)) snprintf(lines[n++], 400, "%s  ·  %s", f->shape_text, view);
    else if (f->kind == FIG_SLICE)
        snprintf(lines[n++], 400, "%s  ·  φd %.4g°, half vector at φh 0°", f->shape_text, f->phi_d / DEG);
    else if (f->kind == FIG_POLAR && f->eta > 0) snprintf(lines[n++], 400, "%s  ·  η %.4g", f->shape_text, f->eta);
    else snprintf(lines[n++], 400, "%s", f->shape_text);
    if (figure_has_grey(f))
        snprintf(lines[n++], 400, "%s: normals m that reflect v above the horizon (2 (m·v) m·n > v·n)%s",
                 figure_is_grid(f->kind) ? "grey" : "hatched grey",
                 figure_is_grid(f->kind) ? "; blank: m·v < 0, never sampled" : "");
    if (f->log_scale && !figure_is_grid(f->kind) && !figure_is_line(f->kind))
        snprintf(lines[n++], 400, "log scale: blank where the pdf is 0");
    if (f->note[0]) snprintf(lines[n++], 400, "%s", f->note);
    return n;
}

/* Draws the caption at the top of the rectangle; returns its height. */
double figure_draw_caption(cairo_t *cr, const theme *th, double x, double y, double w, double F, const figure_spec *f,
                           int max_lines)
{
    char lines[FIGURE_CAPTION_LINES][400];
    int n = caption_lines(f, lines);
    if (n > max_lines) n = max_lines;
    set_rgb(cr, th->fg);
    double yy = y + 0.7 * F;
    for (int i = 0; i < n; i++) {
        text_font(cr, i == 0 ? 1.05 * F : 0.86 * F, i == 0);
        /* shrink a line that would not fit the width */
        double tw = text_width(cr, lines[i]);
        if (tw > w - F) text_font(cr, (i == 0 ? 1.05 * F : 0.86 * F) * (w - F) / tw, i == 0);
        text_at(cr, x + 0.5 * F, yy, 0, 0, lines[i]);
        yy += (i == 0 ? 1.5 : 1.3) * F;
    }
    return yy - y + 0.2 * F;
}

double figure_font(double w, double h) { return fmax(6.0, fmin(26.0, 0.021 * fmin(w, 1.6 * h))); }

/* Okabe and Ito's colour-blind-safe palette, with dashes so that print in grey still tells the curves apart. */
const double FIGURE_PALETTE[6][3] = {{0.0, 0.447, 0.698}, {0.835, 0.369, 0.0},   {0.0, 0.62, 0.451},
                                     {0.8, 0.475, 0.655}, {0.337, 0.706, 0.914}, {0.902, 0.624, 0.0}};
