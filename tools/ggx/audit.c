/* ggx audit: the table of the seeds' claims for the default shapes or the user's. SPDX-License-Identifier: MIT */
#include <string.h>

#include "audit.h"
#include "cli.h"

int cmd_audit(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 2, &o, "alpha,skew,rotate,matrix,out,progress,no-progress");
    if (o.help) {
        printf("usage: ggx audit [--alpha AX,AY] [--skew TX,TY] [--rotate TZ] [--matrix ...] [--out FILE]\n\n"
               "Checks each claim of the seeds (normalisation, every sampler's pdf, G1 as a ratio of projected areas,\n"
               "the crescent factor, the weight bound, ...) for two shapes and prints the verdicts as a Markdown table:\n"
               "a diagonal A (default alphas 0.15,0.5) and a skewed A (default alphas 0.3,0.6, skew 22.918,-17.189,\n"
               "rotation 28.648 degrees, i.e. 0.4, -0.3, 0.5 rad). --alpha sets both shapes' alphas; --skew and\n"
               "--rotate the second shape's angles (the defaults for those not given); --matrix replaces the second\n"
               "shape (the first then takes its alphas when it has them). With no shape option the table is\n"
               "docs/audit.md's (written by tests/test_audit.c). Takes about 10 s.\n");
        return 0;
    }
    /* what the user gave, option by option: a default is never guessed from a value */
    double ax0 = o.have_alpha ? o.alpha[0] : 0.15, ay0 = o.have_alpha ? o.alpha[1] : 0.5;
    double ax = o.have_alpha ? o.alpha[0] : 0.3, ay = o.have_alpha ? o.alpha[1] : 0.6;
    double tx = o.have_skew ? o.skew[0] : 22.918311805232928, ty = o.have_skew ? o.skew[1] : -17.188733853924695;
    double tz = o.have_rotate ? o.rotate : 28.64788975654116;
    /* the diagonal column: diag(ax, ay, 1), written out (no rotation, and no limit on the alphas of a given matrix) */
    double A[2][3][3] = {{{ax0, 0, 0}, {0, ay0, 0}, {0, 0, 1}}};
    ggx_status st;
    if (o.have_matrix) memcpy(A[1], o.matrix, sizeof A[1]);
    else if ((st = ggx_ellipsoid_matrix(A[1], ax, ay, tx * DEG, ty * DEG, tz * DEG)) != GGX_OK)
        die("invalid shape: %s", ggx_status_str(st));
    ggx_shape s;
    for (int k = 0; k < 2; k++) {
        st = ggx_shape_matrix(&s, (const double(*)[3])A[k]);
        if (st != GGX_OK) die("invalid shape: %s", ggx_status_str(st));
    }
    if (o.have_matrix) { /* the diagonal column uses the alphas of the given matrix when it has them */
        ggx_shape_matrix(&s, (const double(*)[3])A[1]);
        if (s.kind != GGX_SHAPE_SKEWED) A[0][0][0] = s.alpha_x, A[0][1][1] = s.alpha_y;
    }
    audit_row rows[AUDIT_MAX_ROWS];
    int progress = o.progress >= 0 ? o.progress : 0;
    int n = audit_run((const double(*)[3][3])A, rows, progress);
    char ld[64], ls[128];
    snprintf(ld, sizeof ld, "diagonal A (%.3g, %.3g)", A[0][0][0], A[0][1][1]);
    if (o.have_matrix) snprintf(ls, sizeof ls, "given matrix");
    else if (!o.have_alpha && !o.have_skew && !o.have_rotate) snprintf(ls, sizeof ls, "skewed A (0.3, 0.6; 0.4, -0.3, 0.5 rad)");
    else snprintf(ls, sizeof ls, "shape (%.3g, %.3g; %.4g, %.4g, %.4g deg)", ax, ay, tx, ty, tz);
    out_file out;
    out_open(&out, o.out);
    audit_markdown(out.f, rows, n, ld, ls);
    out_close(&out);
    return 0;
}
