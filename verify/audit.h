/* The seed audit: one check per claim of the seeds, for a diagonal and a skewed A. Shared by tests/test_audit.c
 * (which asserts the verdicts) and `ggx audit` (which prints them). SPDX-License-Identifier: MIT */
#ifndef GGX_AUDIT_H
#define GGX_AUDIT_H

#include <stdio.h>

#include "chi2.h"

enum { AUDIT_MAX_ROWS = 24, AUDIT_TEXT = 200 };

typedef struct audit_row {
    const char *id, *claim, *seed;
    char text[2][AUDIT_TEXT]; /* evidence for the diagonal and the skewed shape */
    int holds[2];             /* 1 holds, 0 fails, -1 not claimed / not applicable */
} audit_row;

/* Runs every claim. A[0] is a diagonal shape matrix, A[1] a skewed one, both in Walter's form A = S R (the literal
 * forms of the seeds are applied to these matrices as given). Returns the number of rows. progress: dots on stderr.
 * The claims about samplers are found by walking the sampler registry (ggx_samplers.h). No global state: threads
 * may run audits at once. */
int audit_run(const double A[2][3][3], audit_row *rows, int progress);
/* Writes the rows as a Markdown table. */
void audit_markdown(FILE *f, const audit_row *rows, int n, const char *label_diag, const char *label_skew);
/* The crescent sampler with the blog's factor s = (1 + Av.A^-T n / (|Av| |A^-T n|)) / 2 instead of Walter's A n: wrong
 * for skewed shapes, right for unskewed ones. The negative control of the chi-square tests and `ggx check`'s
 * deliberately wrong sampler. */
ggx_vec3 verify_crescent_blog_s(const ggx_shape *s, ggx_vec3 v, double u1, double u2);

#endif
