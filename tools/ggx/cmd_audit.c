/* ggx audit: the seeds' claims checked for three shapes, as Markdown (docs/audit.md), CSV or JSON.
 * SPDX-License-Identifier: MIT */
#include <string.h>

#include "audit.h"
#include "cli.h"

void audit_help(void)
{
    printf("usage: ggx audit [--alpha AX,AY] [--skew TX,TY] [--rotate TZ] [--matrix ...] [--format md|csv|json]\n"
           "                 [--out FILE]...\n\n"
           "Checks each claim of the seeds (normalisation, every sampler's pdf, G1 as a ratio of projected areas,\n"
           "the crescent factor, the weight bound, ...) for three shapes and prints its verdict for each: holds,\n"
           "holds with a correction, fails, or not claimed (the seed restricts the claim to other shapes; the\n"
           "evidence says what happens when it is applied anyway). A claim about every shape is also checked on\n"
           "23 random shapes of each one's kind, and a failure names the smallest counterexample found. The\n"
           "shapes, by default:\n"
           "  diagonal  A = diag(0.15, 0.5, 1)\n"
           "  rotated   alphas 0.3,0.6 rotated by theta_z = 28.648 degrees (0.5 rad)\n"
           "  skewed    alphas 0.3,0.6, skew 22.918,-17.189 and rotation 28.648 degrees (0.4, -0.3, 0.5 rad)\n"
           "--alpha sets the three shapes' alphas; --skew the skewed shape's angles and --rotate both the rotated\n"
           "and the skewed one's (the defaults for those not given); --matrix replaces the skewed shape (the\n"
           "diagonal one then takes its alphas when it has them). --format md (default: the document\n"
           "docs/audit.md, which is this command's output on its defaults), csv (a header row, one row per claim\n"
           "and shape, each naming its seeds) or json. --out may be given up to four times: one run then writes\n"
           "every file, each in the format its name ends with (.md, .csv or .json), all or none.\n");
}

int cmd_audit(options *o, const ggx_shape *no_shape)
{
    (void)no_shape;
    /* one output in the format of --format, or several, each in the format its name ends with */
    const char *names[4] = {o->out};
    audit_format fmts[4] = {AUDIT_MD};
    int nout = o->nout > 1 ? o->nout : 1;
    if (o->nout > 1) {
        if (o->format) die("--format: with several --out files each file's name gives its format");
        for (int i = 0; i < nout; i++) {
            names[i] = o->outs[i];
            if (path_has_ext(names[i], ".md")) fmts[i] = AUDIT_MD;
            else if (path_has_ext(names[i], ".csv")) fmts[i] = AUDIT_CSV;
            else if (path_has_ext(names[i], ".json")) fmts[i] = AUDIT_JSON;
            else die("--out: '%s' does not end with .md, .csv or .json", o->outs[i]);
        }
    } else if (o->format && strcmp(o->format, "csv") == 0) fmts[0] = AUDIT_CSV;
    else if (o->format && strcmp(o->format, "json") == 0) fmts[0] = AUDIT_JSON;
    else if (o->format && strcmp(o->format, "md") != 0) die("--format: '%s' is not md, csv or json", o->format);
    /* what the user gave, option by option: a default is never guessed from a value */
    double ax0 = o->have_alpha ? o->alpha[0] : 0.15, ay0 = o->have_alpha ? o->alpha[1] : 0.5;
    double ax = o->have_alpha ? o->alpha[0] : 0.3, ay = o->have_alpha ? o->alpha[1] : 0.6;
    double tx = o->have_skew ? o->skew[0] : 22.918311805232928, ty = o->have_skew ? o->skew[1] : -17.188733853924695;
    double tz = o->have_rotate ? o->rotate : 28.64788975654116;
    /* the diagonal column: diag(ax, ay, 1), written out (no rotation, and no limit on the alphas of a given matrix) */
    double A[AUDIT_SHAPES][3][3] = {{{ax0, 0, 0}, {0, ay0, 0}, {0, 0, 1}}};
    ggx_status st;
    if ((st = ggx_ellipsoid_matrix(A[1], ax, ay, 0, 0, tz * DEG)) != GGX_OK)
        die("invalid shape: %s", ggx_status_str(st));
    if (o->have_matrix) memcpy(A[2], o->matrix, sizeof A[2]);
    else if ((st = ggx_ellipsoid_matrix(A[2], ax, ay, tx * DEG, ty * DEG, tz * DEG)) != GGX_OK)
        die("invalid shape: %s", ggx_status_str(st));
    ggx_shape s;
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        st = ggx_shape_matrix(&s, (const double(*)[3])A[k]);
        if (st != GGX_OK) die("invalid shape: %s", ggx_status_str(st));
    }
    if (o->have_matrix) { /* the diagonal column uses the alphas of the given matrix when it has them */
        ggx_shape_matrix(&s, (const double(*)[3])A[2]);
        if (s.kind != GGX_SHAPE_SKEWED) A[0][0][0] = s.alpha_x, A[0][1][1] = s.alpha_y;
    }
    audit_row rows[AUDIT_MAX_ROWS];
    int progress = o->progress >= 0 ? o->progress : 0;
    int n = audit_run((const double(*)[3][3])A, rows, progress);
    char label[AUDIT_SHAPES][96];
    snprintf(label[0], sizeof label[0], "diagonal A (%.4g, %.4g)", A[0][0][0], A[0][1][1]);
    snprintf(label[1], sizeof label[1], "rotated A (%.4g, %.4g; theta_z %.4g deg)", ax, ay, tz);
    if (o->have_matrix) snprintf(label[2], sizeof label[2], "given matrix");
    else snprintf(label[2], sizeof label[2], "skewed A (%.4g, %.4g; %.4g, %.4g, %.4g deg)", ax, ay, tx, ty, tz);
    const char *const labels[AUDIT_SHAPES] = {label[0], label[1], label[2]};
    if (nout > 1) out_begin_set();
    for (int i = 0; i < nout; i++) {
        out_file out;
        out_open(&out, names[i]);
        audit_write(out.f, fmts[i], rows, n, labels);
        out_close(&out);
    }
    if (nout > 1) out_commit_set();
    return 0;
}
