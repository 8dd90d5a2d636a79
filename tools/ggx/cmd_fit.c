/* ggx fit: the shape of a measured surface (a height field, a normal map or a list of normals) by maximum likelihood
 * (ggx_fit.h), printed in the command's own shape syntax with its standard errors, the model comparison and the
 * goodness of fit, as Markdown, CSV or JSON. SPDX-License-Identifier: MIT */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "figure_out.h"
#include "figure_fit.h"
#include "ggx/ggx_fit.h"
#include "surface.h"

/* The samples of the figure: normals as slopes, or the height field's facets through the library. */
typedef struct figure_ctx {
    const surface *s;
    const double *h;
    double dx, dy;
    ggx_heightfield_options ho;
} figure_ctx;

static void read_samples(const void *ctx, size_t at, size_t k, double *x, double *y, double *w)
{
    const figure_ctx *c = ctx;
    if (c->s->kind == SURFACE_NORMALS) {
        for (size_t i = 0; i < k; i++) {
            ggx_vec3 m = c->s->m[at + i];
            int ok = m.z > 0 && isfinite(m.x) && isfinite(m.y);
            x[i] = ok ? -m.x / m.z : 0.0, y[i] = ok ? -m.y / m.z : 0.0;
            w[i] = ok ? (c->s->w ? c->s->w[at + i] : 1.0) : 0.0;
        }
        return;
    }
    /* facets read in blocks of 2^20 (each call levels the whole grid again) */
    enum { BLOCK = 1 << 20 };
    static double *block;
    static size_t first = (size_t)-1, len;
    if (at < first || at + k > first + len) {
        size_t total;
        ggx_heightfield_facets(NULL, 0, 0, c->h, c->s->nx, c->s->ny, c->dx, c->dy, &c->ho, &total);
        first = at, len = total - at < BLOCK ? total - at : BLOCK;
        if (!block && !(block = malloc(2 * BLOCK * sizeof *block))) die("out of memory");
        if (ggx_heightfield_facets(block, first, len, c->h, c->s->nx, c->s->ny, c->dx, c->dy, &c->ho, NULL) != GGX_OK)
            die("--figure: the facets could not be read");
    }
    const double *sl = block + 2 * (at - first);
    for (size_t i = 0; i < k; i++) x[i] = sl[2 * i], y[i] = sl[2 * i + 1], w[i] = isnan(sl[2 * i]) ? 0.0 : 1.0;
}

static const char *const MODEL_NAMES[GGX_FIT_MODELS] = {"ellipsoid", "anisotropic", "isotropic", "beckmann"};
static const char *const MODEL_WORDS[GGX_FIT_MODELS] = {
    "full ellipsoid (skewed GGX: t and Sigma)", "rotated anisotropic GGX (t = 0)",
    "isotropic GGX (t = 0, Sigma = a^2 I)", "Beckmann (Gaussian slopes, mean and covariance)"};
static const char *const PARAM_NAMES[5] = {"t_x", "t_y", "sigma_xx", "sigma_xy", "sigma_yy"};

static int show_progress(void *ctx, int it, double ll)
{
    (void)ll;
    if (*(int *)ctx) progress_show("fit", it < 199 ? it : 199, 200);
    return 0;
}

void fit_help(void)
{
    printf(
        "usage: ggx fit (--heightfield FILE | --normal-map FILE | --normals FILE.csv) [--spacing DX[,DY]]\n"
        "               [--z-scale Z] [--keep-tilt] [--downsample K] [--y-down]\n"
        "               [--model ellipsoid|anisotropic|isotropic] [--threads N] [--format md|csv|json] [--out FILE]\n"
        "\n"
        "Fits the ellipsoid NDF to a measured surface by maximum likelihood: the slopes of its micro-normals follow\n"
        "GGX's P22 with a location t (the skew) and a scale Sigma (docs/design/fit.md). Prints the shape in the\n"
        "command's syntax (--alpha AX,AY --skew TX,TY --rotate TZ, to paste into every other command), the matrix\n"
        "A, t and Sigma with standard errors (observed information; lower bounds for a height field, whose facets\n"
        "are correlated), the comparison of isotropic GGX, anisotropic GGX, the full ellipsoid and Beckmann by BIC,\n"
        "a chi-square goodness of fit, and how far the slopes' tails are from GGX's: the Student t of free nu\n"
        "(GGX is nu = 2, Beckmann nu -> infinity) fitted with nu's standard error (not for 8-bit normal maps).\n"
        "\n"
        "inputs (the format from the file's first bytes, else its extension):\n"
        "  --heightfield FILE   heights on a regular grid: .x3p (ISO 25178-72), .gsf (Gwyddion), .txt/.asc (a\n"
        "                       matrix, one row per line; Gwyddion's text header gives the widths and units), .xyz\n"
        "                       (x y z points of a grid), grey .png (8 or 16 bit levels), .exr (one float channel).\n"
        "                       The facets of both triangulations of each cell, weighted by projected area.\n"
        "  --normal-map FILE    a tangent-space normal map: .png (RGB, 8 or 16 bit: n = 2 c / max - 1; grey+alpha\n"
        "                       or blue 0 everywhere: two channels, z rebuilt) or .exr (R, G[, B] in [-1, 1]);\n"
        "                       an 8-bit map's texels are fitted as the cells of normals their levels stand for\n"
        "  --normals FILE.csv   x,y,z[,weight] per line (a header line of names is skipped)\n"
        "options:\n"
        "  --spacing DX[,DY]    grid spacing, where the file has none (x3p, gsf, xyz and Gwyddion text have it)\n"
        "  --z-scale Z          height per unit of the file's values where it has no units (PNG: per level)\n"
        "  --keep-tilt          keep the height field's mean plane (its tilt becomes the skew t); by default the\n"
        "                       least-squares plane is removed first, as surface metrology does\n"
        "  --downsample K       average the heights over K x K blocks first (the NDF depends on the scale)\n"
        "  --y-down             the normal map's green channel points down (DirectX); default up (OpenGL)\n"
        "  --model M            the family of the printed shape (default ellipsoid); all four are compared\n"
        "  --threads N          threads for the fit's passes (results do not depend on N)\n"
        "  --format md|csv|json (default md)\n"
        "  --figure FILE        also draw the measured NDF beside the fitted one (top views, one colour scale) with\n"
        "                       their difference, the slopes' histogram with the fitted contours, and the NDF's\n"
        "                       radial profile in the fit's standardised slopes (GGX flat at 1 / pi) beside the\n"
        "                       fitted Student t's, on a log scale (.png, .svg, .pdf); a height field's facets are\n"
        "                       read back in blocks, once per block\n");
}

/* The samples of the input, fitted. */
/* 8-bit levels are as coarse as a fine lobe: such a map's texels are fitted as the cells of normals they stand for. */
static int fit_as_cells(const surface *s) { return s->kind == SURFACE_NORMALS && s->uv && s->bits == 8; }

static void fit_input(const options *o, const surface *s, const ggx_fit_options *fo, ggx_shape *out, ggx_fit_info *info,
                      const char **what, double *spacing_used, const double **heights)
{
    ggx_status st;
    if (fit_as_cells(s)) {
        /* the cells' fit reads red and green only: texels whose normal (blue included) points at or below the plane
         * are left out here and counted at the horizon, as the fit of 16-bit texels counts them */
        size_t n = s->nx * s->ny, kept = 0;
        double *uv = malloc(2 * n * sizeof *uv + 1);
        if (!uv) die("out of memory");
        for (size_t i = 0; i < n; i++)
            if (s->m[i].z > 0.0) uv[2 * kept] = s->uv[2 * i], uv[2 * kept + 1] = s->uv[2 * i + 1], kept++;
        st = ggx_fit_normal_cells(out, uv, NULL, kept, 2.0 / 255.0, fo, info);
        free(uv);
        info->ignored_horizon += n - kept;
        *what = "normal-map texels (8-bit: each fitted as its cell of normals)";
    } else if (s->kind == SURFACE_NORMALS) {
        for (size_t i = 0; s->w && i < s->nx * s->ny; i++)
            if (s->w[i] < 0.0)
                die("the weight of normal %zu is negative (%g): a weight is a share of area, 0 or more", i + 1,
                    s->w[i]);
        st = ggx_fit_normals(out, s->m, s->w, s->nx * s->ny, fo, info);
        *what = s->format != SURFACE_CSV ? "normal-map texels" : "normals";
    } else {
        double dx = o->have_spacing ? o->spacing[0] : s->dx, dy = o->have_spacing ? o->spacing[1] : s->dy;
        double zs = o->have_z_scale ? o->z_scale : s->z_scale;
        if (!(dx > 0 && dy > 0))
            die("--heightfield: the file gives no grid spacing: give --spacing DX[,DY] (in the heights' unit)");
        if (!(zs > 0))
            die("--heightfield: the file gives no height unit: give --z-scale Z (the height of one unit of its "
                "values, in the spacing's unit)");
        if (o->downsample >= 2 && (s->nx / (size_t)o->downsample < 2 || s->ny / (size_t)o->downsample < 2))
            die("--downsample %d leaves fewer than 2 x 2 heights of the %zu x %zu", o->downsample, s->nx, s->ny);
        /* slopes are z_scale h / dx: the file's heights with the spacing divided by z_scale, no copy; a quotient
         * beyond the doubles' normal range has no slopes to fit */
        double q[2] = {dx / zs, dy / zs};
        for (int k = 0; k < 2; k++)
            if (!(q[k] >= DBL_MIN && q[k] <= DBL_MAX))
                die("--heightfield: the grid spacing %g over the height unit %g is %g, beyond the range of a double "
                    "(%g to %g): give --spacing and --z-scale in nearer units",
                    k ? dy : dx, zs, q[k], DBL_MIN, DBL_MAX);
        ggx_heightfield_options ho = {o->keep_tilt, o->downsample};
        st = ggx_fit_heightfield(out, s->h, s->nx, s->ny, dx / zs, dy / zs, &ho, fo, info);
        /* facets left out for slopes beyond a double, or for a missing height (NaN or outside the fence of
         * ggx_fit_heightfield): said with the units that made them, where they leave too few */
        if (st == GGX_ERR_DATA && info->ignored_nonfinite > 0)
            die("--heightfield: %zu of the %zu facets have a missing height or slopes beyond the range of a double "
                "(height differences x %g / spacing %g x %g), %zu are left: too few to fit%s",
                info->ignored_nonfinite, info->ignored_nonfinite + info->used + info->ignored_horizon, zs, dx, dy,
                info->used, info->used ? "" : "; give --spacing and --z-scale in nearer units");
        *heights = s->h;
        *what = "facets";
        spacing_used[0] = dx, spacing_used[1] = dy, spacing_used[2] = dx / zs, spacing_used[3] = dy / zs;
    }
    if (st != GGX_OK) die("fit: %s", ggx_status_str(st));
}

/* What ggx fit found, for its report. */
typedef struct fit_report {
    const char *path, *what;
    const surface *s;
    const ggx_fit_info *info;
    const ggx_fit_model_result *mr;
    ggx_fit_model model;
    double ax, ay, tx, ty, tz, A[3][3], val[5], spacing[2], best_bic;
    int keep_tilt, cells;
    size_t ignored;
    char shape[200], qnote[400];
} fit_report;

static void report_md(FILE *f, const fit_report *r)
{
    fprintf(f, "# ggx fit: %s\n\n", r->path);
    fprintf(f, "%s, %zu x %zu; %zu %s used", surface_format_name(r->s->format), r->s->nx, r->s->ny, r->info->used,
            r->what);
    if (r->ignored)
        fprintf(f, ", %zu ignored (%zu at or below the horizon, %zu not finite, %zu of weight 0)", r->ignored,
                r->info->ignored_horizon, r->info->ignored_nonfinite, r->info->ignored_weight);
    if (r->spacing[0] > 0)
        fprintf(f, "; spacing %.6g x %.6g%s", r->spacing[0], r->spacing[1], r->keep_tilt ? "" : "; levelled");
    fprintf(f, "\n\nshape: `%s`\n\n", r->shape);
    fprintf(f, "A = [[%.6g, %.6g, %.6g], [%.6g, %.6g, %.6g], [%.6g, %.6g, %.6g]]\n\n", r->A[0][0], r->A[0][1],
            r->A[0][2], r->A[1][0], r->A[1][1], r->A[1][2], r->A[2][0], r->A[2][1], r->A[2][2]);
    fprintf(f, "| parameter | value | standard error |\n|---|---|---|\n");
    for (int i = 0; i < 5; i++)
        fprintf(f, "| %s | %.6g | %s%.3g |\n", PARAM_NAMES[i], r->val[i], r->info->std_error[i] > 0 ? "" : "fixed ",
                r->info->std_error[i]);
    fprintf(f, "\n| model | parameters | log-likelihood per sample | BIC | BIC - best |\n|---|---|---|---|---|\n");
    for (int k = 0; k < GGX_FIT_MODELS; k++)
        fprintf(f, "| %s%s | %d | %.6f | %.1f | %.1f |\n", MODEL_WORDS[k], k == (int)r->info->best ? " **best**" : "",
                r->mr[k].parameters, r->mr[k].log_likelihood, r->mr[k].bic, r->mr[k].bic - r->best_bic);
    const ggx_fit_tails *tl = &r->info->tails;
    if (isfinite(tl->nu) && !isfinite(tl->nu_std_error))
        fprintf(f,
                "\ntails: the Student-t slopes of free nu fit nu at the end of its range, %g (%s; BIC %.1f against "
                "GGX's %.1f)\n",
                tl->nu, tl->nu > 2.0 ? "slopes as light-tailed as Beckmann's Gaussian" : "tails heavier than any nu",
                tl->bic, r->mr[GGX_FIT_ELLIPSOID].bic);
    else if (isfinite(tl->nu))
        fprintf(
            f,
            "\ntails: the Student-t slopes of free nu (GGX: nu = 2, Beckmann: nu -> infinity) fit nu = %.4g +- %.2g "
            "(%.1f standard errors from GGX's%s; BIC %.1f against GGX's %.1f)%s\n",
            tl->nu, tl->nu_std_error, (tl->nu - 2.0) / tl->nu_std_error,
            tl->nu < 2.0 ? ": heavier tails" : ": lighter tails, a flatter peak", tl->bic, r->mr[GGX_FIT_ELLIPSOID].bic,
            tl->subsample ? "; on the fit's subsample of 2^20" : "");
    else fprintf(f, "\ntails: not fitted (%s)\n", r->cells ? "texels fitted as cells" : "Sigma at its floor");
    fprintf(f, "\ngoodness of fit (%s): ", MODEL_NAMES[r->model]);
    if (r->info->gof_dof > 0)
        fprintf(f, "chi-square %.1f on %d x %d equal-probability cells, %d degrees of freedom, p = %.3g\n",
                r->info->gof_chi2, r->info->gof_cells, r->info->gof_cells, r->info->gof_dof, r->info->gof_pvalue);
    else if (r->cells)
        fprintf(f, "not computed for texels fitted as cells (a texel's cell straddles the test's cells)\n");
    else fprintf(f, "too few samples for the cells (n_eff %.0f)\n", r->info->effective_n);
    if (r->qnote[0]) fprintf(f, "\nquantisation: %s\n", r->qnote);
    fprintf(f, "\nEM: %d iterations, %s (Newton decrement %.2g); effective sample size %.0f%s\n", r->info->iterations,
            r->info->converged ? "converged" : "NOT converged", r->info->stationarity, r->info->effective_n,
            !r->info->clamped ? ""
            : r->cells        ? "; Sigma held at the levels' floor"
                              : "; Sigma held at the smallest roughness (all slopes nearly equal)");
}

static void report_csv(FILE *f, const fit_report *r)
{
    fprintf(f, "quantity,value,std_error\n");
    fprintf(f, "alpha_x,%.10g,\nalpha_y,%.10g,\nskew_x_deg,%.10g,\nskew_y_deg,%.10g,\nrotate_deg,%.10g,\n", r->ax,
            r->ay, r->tx, r->ty, r->tz);
    for (int i = 0; i < 5; i++) fprintf(f, "%s,%.10g,%.10g\n", PARAM_NAMES[i], r->val[i], r->info->std_error[i]);
    for (int k = 0; k < GGX_FIT_MODELS; k++)
        fprintf(f, "log_likelihood_%s,%.10g,\nbic_%s,%.10g,\n", MODEL_NAMES[k], r->mr[k].log_likelihood, MODEL_NAMES[k],
                r->mr[k].bic);
    fprintf(f, "nu,%.10g,%.10g\nlog_likelihood_tails,%.10g,\nbic_tails,%.10g,\n", r->info->tails.nu,
            r->info->tails.nu_std_error, r->info->tails.log_likelihood, r->info->tails.bic);
    fprintf(f,
            "best_model_index,%d,\ngof_chi2,%.10g,\ngof_dof,%d,\ngof_pvalue,%.10g,\nused,%zu,\nignored,%zu,\n"
            "effective_n,%.10g,\niterations,%d,\nconverged,%d,\nclamped,%d,\n",
            (int)r->info->best, r->info->gof_chi2, r->info->gof_dof, r->info->gof_pvalue, r->info->used, r->ignored,
            r->info->effective_n, r->info->iterations, r->info->converged, r->info->clamped);
}

static void report_json(FILE *f, const fit_report *r)
{
#define J(v) json_number(v)
    fprintf(f, "{\n  \"input\": \"");
    for (const char *p = r->path; *p; p++) {
        if (*p == '"' || *p == '\\') fputc('\\', f);
        if ((unsigned char)*p < 0x20) fprintf(f, "\\u%04x", *p);
        else fputc(*p, f);
    }
    fprintf(f, "\",\n  \"shape\": {\"alpha\": [%s, %s], \"skew_deg\": [%s, %s], \"rotate_deg\": %s},\n", J(r->ax),
            J(r->ay), J(r->tx), J(r->ty), J(r->tz));
    fprintf(f, "  \"matrix\": [[%s, %s, %s], [%s, %s, %s], [%s, %s, %s]],\n", J(r->A[0][0]), J(r->A[0][1]),
            J(r->A[0][2]), J(r->A[1][0]), J(r->A[1][1]), J(r->A[1][2]), J(r->A[2][0]), J(r->A[2][1]), J(r->A[2][2]));
    fprintf(f, "  \"t\": [%s, %s], \"sigma\": [%s, %s, %s],\n", J(r->val[0]), J(r->val[1]), J(r->val[2]), J(r->val[3]),
            J(r->val[4]));
    fprintf(f, "  \"std_error\": [%s, %s, %s, %s, %s],\n", J(r->info->std_error[0]), J(r->info->std_error[1]),
            J(r->info->std_error[2]), J(r->info->std_error[3]), J(r->info->std_error[4]));
    fprintf(f, "  \"models\": {");
    for (int k = 0; k < GGX_FIT_MODELS; k++)
        fprintf(f, "%s\"%s\": {\"parameters\": %d, \"log_likelihood\": %s, \"bic\": %s}", k ? ", " : "", MODEL_NAMES[k],
                r->mr[k].parameters, J(r->mr[k].log_likelihood), J(r->mr[k].bic));
    fprintf(f, "},\n  \"tails\": {\"nu\": %s, \"nu_std_error\": %s, \"log_likelihood\": %s, \"bic\": %s},\n",
            J(r->info->tails.nu), J(r->info->tails.nu_std_error), J(r->info->tails.log_likelihood),
            J(r->info->tails.bic));
    fprintf(f, "  \"best\": \"%s\",\n", MODEL_NAMES[r->info->best]);
    fprintf(f, r->qnote[0] ? "  \"quantisation_note\": \"%s\",\n" : "%s", r->qnote);
    if (r->info->gof_dof > 0)
        fprintf(f, "  \"gof\": {\"chi2\": %s, \"dof\": %d, \"pvalue\": %s},\n", J(r->info->gof_chi2), r->info->gof_dof,
                J(r->info->gof_pvalue));
    else fprintf(f, "  \"gof\": null,\n");
    fprintf(f,
            "  \"used\": %zu, \"ignored\": %zu, \"effective_n\": %s, \"iterations\": %d, \"converged\": %s, "
            "\"clamped\": %s\n}\n",
            r->info->used, r->ignored, J(r->info->effective_n), r->info->iterations,
            r->info->converged ? "true" : "false", r->info->clamped ? "true" : "false");
#undef J
}

int cmd_fit(options *o, const ggx_shape *no_shape)
{
    (void)no_shape;
    int inputs = (o->heightfield != NULL) + (o->normal_map != NULL) + (o->normals != NULL);
    if (inputs != 1) die("give one of --heightfield, --normal-map or --normals (see ggx fit --help)");
    const char *fmt = o->format ? o->format : "md";
    if (strcmp(fmt, "md") != 0 && strcmp(fmt, "csv") != 0 && strcmp(fmt, "json") != 0)
        die("--format: '%s' is not md, csv or json", fmt);
    ggx_fit_options fo;
    memset(&fo, 0, sizeof fo);
    if (o->model) {
        int k = 0;
        while (k < 3 && strcmp(o->model, MODEL_NAMES[k]) != 0) k++;
        if (k == 3) die("--model: '%s' is not ellipsoid, anisotropic or isotropic", o->model);
        fo.model = (ggx_fit_model)k;
    }
    if ((o->keep_tilt || o->downsample || o->have_z_scale) && !o->heightfield)
        die("--keep-tilt, --downsample and --z-scale apply to --heightfield");
    if (o->y_down && !o->normal_map) die("--y-down applies to --normal-map");
    /* the figure's name says its format, as plot's --out does: refused before any work */
    canvas_format figure_fmt = o->figure ? figure_format_of("--figure", o->figure, FMT_PNG) : FMT_PNG;
    fo.threads = o->threads;
    int bar = progress_wanted(o->progress);
    fo.progress = show_progress;
    fo.progress_ctx = &bar;

    const char *path = o->heightfield ? o->heightfield : o->normal_map ? o->normal_map : o->normals;
    surface_read_options ro = {o->heightfield ? SURFACE_HEIGHTS : SURFACE_NORMALS, o->y_down};
    surface s;
    char err[512];
    if (bar) progress_show("read", 0, 1);
    if (surface_read(path, &ro, &s, err, sizeof err) != 0) die("%s", err);
    /* a list of normals is a CSV file, a normal map an image of any size (W x 1 and 1 x H alike) */
    if (o->normals && s.format != SURFACE_CSV) die("--normals: '%s' is not a CSV list of normals", path);
    if (o->normal_map && s.format == SURFACE_CSV) die("--normal-map: '%s' is a list of normals (use --normals)", path);
    ggx_shape fit;
    ggx_fit_info info;
    const char *what = "";
    double spacing[4] = {0, 0, 0, 0}; /* the grid's spacing; the spacing the fit took (over z_scale) */
    const double *heights = NULL;
    fit_input(o, &s, &fo, &fit, &info, &what, spacing, &heights);
    if (bar) progress_end("fit", 200);
    fit_report r;
    memset(&r, 0, sizeof r);
    r.path = path, r.what = what, r.s = &s, r.info = &info, r.mr = info.models, r.model = fo.model;
    r.spacing[0] = spacing[0], r.spacing[1] = spacing[1], r.keep_tilt = o->keep_tilt;
    /* An 8-bit map is fitted as cells (fit_input), which holds Sigma at (0.4 q)^2 (1 + |t|^2)^3: say so when that
     * binds. */
    r.cells = fit_as_cells(&s);
    if (r.cells && info.clamped) {
        snprintf(r.qnote, sizeof r.qnote,
                 "the lobe is narrower than the map's 8-bit levels resolve: its narrowest alpha is held at %.2g "
                 "(0.4 of the levels' spacing %.2g, times (1 + |t|^2)^1.5 for a lobe away from n); a 16-bit map "
                 "resolves it",
                 0.4 * 2.0 / 255.0 * pow(1.0 + info.t[0] * info.t[0] + info.t[1] * info.t[1], 1.5), 2.0 / 255.0);
        fprintf(stderr, "ggx: note: %s\n", r.qnote);
    }
    ggx_shape_ellipsoid_params(&fit, &r.ax, &r.ay, &r.tx, &r.ty, &r.tz);
    ggx_ellipsoid_matrix(r.A, r.ax, r.ay, r.tx, r.ty, r.tz);
    r.tx = r.tx / DEG + 0.0, r.ty = r.ty / DEG + 0.0, r.tz = r.tz / DEG + 0.0; /* degrees; + 0.0 turns -0 into 0 */
    snprintf(r.shape, sizeof r.shape, "--alpha %.6g,%.6g --skew %.6g,%.6g --rotate %.6g", r.ax, r.ay, r.tx, r.ty, r.tz);
    const double val[5] = {info.t[0], info.t[1], info.sigma[0], info.sigma[1], info.sigma[2]};
    memcpy(r.val, val, sizeof val);
    r.best_bic = info.models[info.best].bic;
    r.ignored = info.ignored_horizon + info.ignored_nonfinite + info.ignored_weight;

    out_file out;
    out_open(&out, o->out);
    FILE *f = out.f;
    if (strcmp(fmt, "md") == 0) report_md(f, &r);
    else if (strcmp(fmt, "csv") == 0) report_csv(f, &r);
    else report_json(f, &r);
    if (o->figure) out_begin_set(); /* the report and the figure appear together or not at all */
    out_close(&out);
    if (o->figure) {
        figure_ctx fc = {&s, heights, spacing[2], spacing[3], {o->keep_tilt, o->downsample}};
        size_t nsamp = s.nx * s.ny;
        if (s.kind == SURFACE_HEIGHTS)
            ggx_heightfield_facets(NULL, 0, 0, heights, s.nx, s.ny, spacing[2], spacing[3], &fc.ho, &nsamp);
        fit_samples fs = {read_samples, &fc, nsamp, r.cells};
        char title[300];
        snprintf(title, sizeof title, "ggx fit: %s", path);
        canvas c;
        canvas_open_file(&c, o->figure, figure_fmt, FIGURE_FIT_W, FIGURE_FIT_H, 0);
        if (figure_fit_draw(&c, &fs, &fit, &info, MODEL_NAMES[fo.model], title) != 0) die("out of memory");
        canvas_close_file(&c);
        out_commit_set();
    }
    surface_free(&s);
    return 0;
}
