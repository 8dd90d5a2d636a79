/* The seed audit: one check per claim of the seeds, for a diagonal, a theta_z-rotated and a skewed A. Shared by
 * tests/unit/test_audit.c (which asserts the verdicts) and `ggx audit` (which prints them). SPDX-License-Identifier: MIT */
#ifndef GGX_AUDIT_H
#define GGX_AUDIT_H

#include <stdio.h>

#include "chi2.h"

enum { AUDIT_SHAPES = 3, AUDIT_MAX_ROWS = 128, AUDIT_TEXT = 720 };

/* The shapes a seed states a claim for: a diagonal A = diag(ax, ay, 1); A = S Rz (anisotropy rotated in the tangent
 * plane, "rotated"); any A (skewed included). */
typedef enum audit_scope { AUDIT_SCOPE_DIAGONAL, AUDIT_SCOPE_ROTATED, AUDIT_SCOPE_ANY } audit_scope;

/* One vocabulary for every row: the claim holds as the seed writes it; it holds with a correction the evidence
 * states (the seed's formula fails as written); it fails (the evidence gives the counterexample found); or the seed
 * does not claim it for this shape (the evidence says what happens when it is applied anyway). */
typedef enum audit_verdict { AUDIT_FAILS, AUDIT_HOLDS, AUDIT_CORRECTED, AUDIT_NOT_CLAIMED } audit_verdict;

typedef struct audit_row {
    const char *id, *claim, *seed, *where; /* seed: the seed's short name(s), docs/references.md */
    audit_scope scope;
    audit_verdict verdict[AUDIT_SHAPES];
    char text[AUDIT_SHAPES][AUDIT_TEXT]; /* the evidence, with the figure measured */
} audit_row;

/* Runs every claim for the three shapes A[k] (Walter's form A = S R; the seeds' literal forms are applied to these
 * matrices as given): A[0] diagonal, A[1] rotated by theta_z only, A[2] skewed by default, though any shapes may
 * be given (scope is decided by each shape's kind). Returns the number of rows, 0 if a matrix is invalid.
 * progress: dots on stderr. The claims about samplers are found by walking the sampler registry (ggx_samplers.h).
 * No global state: threads may run audits at once. */
int audit_run(const double A[AUDIT_SHAPES][3][3], audit_row *rows, int progress);
/* audit_run judging each chi-square run at the per-run level alpha instead of the command's
 * chi2_sidak(CHI2_SUITE_RUNS): the test suite's own level (tests/support/testlib.h). */
int audit_run_at(const double A[AUDIT_SHAPES][3][3], audit_row *rows, int progress, double alpha);

const char *audit_verdict_name(audit_verdict v); /* "holds", "holds with a correction", "fails", "not claimed" */
const char *audit_scope_name(audit_scope s);     /* "diagonal A", "A = S Rz", "any A" */

/* The rows as a document: md (docs/audit.md: its introduction, then one table), csv (a header row, one row per
 * claim and shape) or json (an array of claims, each with its verdicts). labels name the three shapes. */
typedef enum audit_format { AUDIT_MD, AUDIT_CSV, AUDIT_JSON } audit_format;
void audit_write(FILE *f, audit_format fmt, const audit_row *rows, int n, const char *const labels[AUDIT_SHAPES]);

/* The crescent sampler with the blog's factor s = (1 + Av.A^-T n / (|Av| |A^-T n|)) / 2 instead of Walter's A n: wrong
 * for skewed shapes, right for unskewed ones. The negative control of the chi-square tests and `ggx check`'s
 * deliberately wrong sampler. */
ggx_vec3 verify_crescent_blog_s(const ggx_shape *s, ggx_vec3 v, double u1, double u2);

#endif
