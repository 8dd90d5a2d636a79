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
               "the crescent factor, the weight bound, ...) for a diagonal shape with your alphas and for your shape\n"
               "(default: alpha 0.3,0.6 skewed by 22.9,-17.2 degrees, rotated 28.6), and prints the verdicts as a\n"
               "Markdown table (docs/audit.md is this table for the defaults). Takes about 10 s.\n");
        return 0;
    }
    int custom = o.have_matrix || o.skew[0] != 0 || o.skew[1] != 0 || o.rotate != 0 ||
                 !(o.alpha[0] == 0.15 && o.alpha[1] == 0.5);
    double A[2][3][3];
    double ax = custom ? o.alpha[0] : 0.3, ay = custom ? o.alpha[1] : 0.6;
    audit_walter_matrix(A[0], ax, ay, 0, 0, 0);
    if (o.have_matrix) memcpy(A[1], o.matrix, sizeof A[1]);
    else if (custom) audit_walter_matrix(A[1], ax, ay, o.skew[0] * DEG, o.skew[1] * DEG, o.rotate * DEG);
    else audit_walter_matrix(A[1], 0.3, 0.6, 0.4, -0.3, 0.5);
    ggx_shape s;
    for (int k = 0; k < 2; k++) {
        ggx_status st = ggx_shape_matrix(&s, (const double(*)[3])A[k]);
        if (st != GGX_OK) die("invalid shape: %s", ggx_status_str(st));
    }
    if (o.have_matrix) { /* the diagonal column uses the alphas of the given matrix when it has them */
        ggx_shape_matrix(&s, (const double(*)[3])A[1]);
        if (s.kind != GGX_SHAPE_SKEWED) audit_walter_matrix(A[0], s.alpha_x, s.alpha_y, 0, 0, 0);
    }
    audit_row rows[AUDIT_MAX_ROWS];
    int progress = o.progress >= 0 ? o.progress : 0;
    int n = audit_run((const double(*)[3][3])A, rows, progress);
    char ld[64], ls[128];
    snprintf(ld, sizeof ld, "diagonal A (%.3g, %.3g)", A[0][0][0], A[0][1][1]);
    if (o.have_matrix) snprintf(ls, sizeof ls, "given matrix");
    else snprintf(ls, sizeof ls, "shape (%.3g, %.3g; %.3g, %.3g, %.3g deg)", ax, ay, custom ? o.skew[0] : 22.918,
                  custom ? o.skew[1] : -17.189, custom ? o.rotate : 28.648);
    out_file out;
    out_open(&out, o.out);
    audit_markdown(out.f, rows, n, ld, ls);
    out_close(&out);
    return 0;
}
