/* Seed audit: runs libs/verify/audit.c for the command's three default shapes (diagonal, theta_z-rotated, skewed) and
 * asserts every verdict, so that docs/audit.md (the command's output, compared by tests/cli/cli_test.sh) stays true: a
 * claim recorded as failing must keep failing. SPDX-License-Identifier: MIT */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "audit.h"
#include "audit_internal.h"
#include "testlib.h"

#define H AUDIT_HOLDS
#define F AUDIT_FAILS
#define C AUDIT_CORRECTED
#define N AUDIT_NOT_CLAIMED

/* Expected verdicts for [diagonal, rotated, skewed]. */
static const struct {
    const char *id;
    audit_verdict v[AUDIT_SHAPES];
} EXPECT[] = {
    {"norm", {H, H, H}},
    {"ggx", {H, N, N}},
    {"area", {H, H, H}},
    {"lune", {H, H, H}},
    {"g1-blog", {H, H, F}},
    {"g1-walter", {H, H, H}},
    {"stretch", {H, N, N}},
    {"ellipse", {H, H, H}},
    {"inversion", {C, N, N}},
    {"vndf-g1", {H, H, F}},
    {"crescent", {H, H, H}},
    {"heitz", {H, N, N}},
    {"crescent-blog", {H, H, F}},
    {"jacobian-blog", {F, F, F}},
    {"weight", {H, H, H}},
    {"below", {H, N, N}},
    {"rejection", {H, H, H}},
    {"p22", {H, N, N}},
    {"unit-norms", {H, H, F}},
    {"sm-lt-su", {H, H, F}},
    {"su", {H, H, F}},
    {"invariance", {H, H, H}},
    {"rotate-z", {H, H, N}},
    {"min-inactive", {H, H, N}},
    {"mean-normal", {H, H, H}},
    {"reciprocity", {H, H, H}},
    {"energy", {H, H, H}},
    {"stretch-omega", {C, N, N}},
    {"disk-concentric", {C, C, C}},
    {"vndf-support", {C, N, N}},
    {"lambda-zz", {H, N, N}},
    {"curvature", {H, H, H}},
    {"dof", {H, H, H}},
    {"vndf-phi90", {H, N, N}},
    {"cosine-jacobian", {H, H, H}},
    {"slope-jacobian", {H, H, H}},
    {"squish-jacobian", {H, H, H}},
    {"stretch-jacobian", {H, N, N}},
    {"reflect-jacobian", {H, H, H}},
    {"cross-product", {H, H, H}},
    {"sphere-normal", {H, H, H}},
    {"half-cut", {H, H, H}},
    {"g1-pdf-identity", {H, H, H}},
    {"vndf-frame", {H, N, N}},
    {"vndf-eq33", {H, H, H}},
    {"sggx", {H, H, H}},
    {"hessian", {H, H, H}},
    {"normalize-derivative", {H, H, H}},
    {"stretch-inverse", {H, N, N}},
    {"equal-area-grid", {H, N, N}},
    {"inversion-forms", {H, N, N}},
    {"spherical-form", {H, N, N}},
    {"det-sr", {H, H, H}},
    {"an-is-n", {H, H, N}},
    /* libs/verify/audit_ellipsoid.c */
    {"normal-point", {H, H, H}},
    {"gauss-map", {H, H, H}},
    {"silhouette", {H, H, H}},
    {"surface-integrals", {H, H, H}},
    {"lune-sphere", {H, H, H}},
    {"ce-cancels", {H, H, H}},
    {"semi-axes", {H, N, N}},
    {"skew-max", {H, H, H}},
    {"ndf-along-u", {H, N, N}},
    {"sin-jacobian", {H, H, H}},
    {"ellipsoid-map", {H, N, N}},
    /* libs/verify/audit_sampling.c */
    {"lift", {H, N, N}},
    {"sphere-disk", {H, H, H}},
    {"crescent-sphere", {H, H, H}},
    {"concentric-walter", {H, H, H}},
    {"squeeze-walter", {H, H, H}},
    {"frame-eq42", {H, H, H}},
    {"lune-point", {H, H, H}},
    {"walter-v1", {H, H, H}},
    {"pm-blog", {H, H, H}},
    {"vndf-total-jacobian", {H, N, N}},
    {"project-jacobian", {H, H, H}},
    /* libs/verify/audit_scattering.c */
    {"smith-integral", {C, C, F}},
    {"eq7-transmission", {H, H, H}},
    {"weight-formula", {H, H, H}},
    {"g-approx", {H, N, N}},
    {"brdf-form", {H, N, N}},
    {"reflect-below", {H, N, N}},
    /* libs/verify/audit_stretch.c */
    {"vector-identities", {H, H, H}},
    {"det-scale", {H, N, N}},
    {"stretch-total-jacobian", {H, N, N}},
    {"slope-stretch", {H, N, N}},
    {"d-slope", {H, N, N}},
    {"iso", {H, N, N}},
};

static void default_shapes(double A[AUDIT_SHAPES][3][3])
{
    CHECK(ggx_ellipsoid_matrix(A[0], 0.15, 0.5, 0, 0, 0) == GGX_OK, "diagonal");
    CHECK(ggx_ellipsoid_matrix(A[1], 0.3, 0.6, 0, 0, 0.5) == GGX_OK, "rotated");
    CHECK(ggx_ellipsoid_matrix(A[2], 0.3, 0.6, 0.4, -0.3, 0.5) == GGX_OK, "skewed");
}

/* A row's seed field: one or more of the five short names, separated by ", " and nothing else. */
static int names_seeds(const char *list)
{
    static const char *const NAMES[] = {SEED_WALTER, SEED_STRETCH, SEED_VNDF, SEED_BLOG1, SEED_BLOG2};
    const char *p = list;
    for (;;) {
        size_t len = strcspn(p, ",");
        int known = 0;
        for (size_t k = 0; k < sizeof NAMES / sizeof NAMES[0]; k++)
            known |= strlen(NAMES[k]) == len && strncmp(p, NAMES[k], len) == 0;
        if (!known) return 0;
        if (p[len] == '\0') return 1;
        if (strncmp(p + len, ", ", 2) != 0) return 0;
        p += len + 2;
    }
}

static void audit(void **state)
{
    (void)state;
    double A[AUDIT_SHAPES][3][3];
    default_shapes(A);
    audit_row rows[AUDIT_MAX_ROWS];
    remove("chi2_audit.csv");
    long before = chi2_runs_made();
    int n = audit_run_at((const double(*)[3][3])A, rows, 0, test_chi2_level());
    chi2_budget_spend(chi2_runs_made() - before);
    /* claims that fail are answers: the audit's chi-square runs are quiet and leave no histogram behind */
    FILE *dump = fopen("chi2_audit.csv", "r");
    CHECK(dump == NULL, "the audit wrote chi2_audit.csv");
    if (dump) fclose(dump);
    const char *const labels[AUDIT_SHAPES] = {"diagonal", "rotated", "skewed"};
    audit_write(stdout, AUDIT_MD, rows, n, labels);
    CHECK(n == (int)(sizeof EXPECT / sizeof EXPECT[0]), "%d rows", n);
    for (int i = 0; i < n; i++) {
        CHECK(strcmp(rows[i].id, EXPECT[i].id) == 0, "row %d is %s", i, rows[i].id);
        /* every row names its seed(s), by the short names of docs/references.md */
        CHECK(names_seeds(rows[i].seed), "%s names no seed or an unknown one: %s", rows[i].id, rows[i].seed);
        for (int k = 0; k < AUDIT_SHAPES; k++)
            CHECK(rows[i].verdict[k] == EXPECT[i].v[k], "claim '%s' (%s), %s A: verdict %s, expected %s: %s",
                  rows[i].id, rows[i].seed, labels[k], audit_verdict_name(rows[i].verdict[k]),
                  audit_verdict_name(EXPECT[i].v[k]), rows[i].text[k]);
    }
    /* a seed's formula that fails as written says which form holds, with that form's own passing chi-square; a claim
     * applied outside its scope says what happens */
    for (int i = 0; i < n; i++)
        for (int k = 0; k < AUDIT_SHAPES; k++) {
            const char *h = strstr(rows[i].text[k], "holds as ");
            if (h && strstr(h, "(p = ")) /* a sampler's corrected form, with its own chi-square */
                CHECK(atof(strstr(h, "(p = ") + 5) >= test_chi2_level(), "%s: %s", rows[i].id, rows[i].text[k]);
            if (rows[i].verdict[k] == AUDIT_CORRECTED) /* a correction is stated */
                CHECK(h || strstr(rows[i].text[k], " with "), "%s: %s", rows[i].id, rows[i].text[k]);
            if (rows[i].verdict[k] == AUDIT_NOT_CLAIMED)
                CHECK(strncmp(rows[i].text[k], "applied anyway", 14) == 0 ||
                          strncmp(rows[i].text[k], "cannot be applied", 17) == 0,
                      "%s, %s: %s", rows[i].id, labels[k], rows[i].text[k]);
        }
    /* the blog's Jacobian is wrong, yet its final pdf is the VNDF's up to the constant |A|^2: the D(m, v) step of the
     * same derivation errs by the inverse factor */
    for (int i = 0; i < n; i++)
        if (strcmp(rows[i].id, "jacobian-blog") == 0)
            for (int k = 0; k < AUDIT_SHAPES; k++) {
                const char *t = strstr(rows[i].text[k], "VNDF to ");
                CHECK(t && atof(t + 8) < 1e-9, "jacobian-blog: %s", rows[i].text[k]);
            }
    /* the literal five steps fail when applied to the rotated and the skewed shape, and Engstad's stretch to the skewed */
    for (int i = 0; i < n; i++)
        if (strcmp(rows[i].id, "heitz") == 0)
            CHECK(strstr(rows[i].text[1], "it fails") && strstr(rows[i].text[2], "it fails"), "heitz: %s | %s",
                  rows[i].text[1], rows[i].text[2]);
}

/* A claim about every view is checked at a grid of views: for the skewed shape of the seed audit's issue (0.1, 0.8;
 * 0.6, 0.5, 1.0 rad) both G1 claims fail, though at the one view the audit used before they held. */
static void view_grid(void **state)
{
    (void)state;
    double A[AUDIT_SHAPES][3][3];
    CHECK(ggx_ellipsoid_matrix(A[0], 0.1, 0.8, 0, 0, 0) == GGX_OK, "diagonal");
    CHECK(ggx_ellipsoid_matrix(A[1], 0.1, 0.8, 0, 0, 1.0) == GGX_OK, "rotated");
    CHECK(ggx_ellipsoid_matrix(A[2], 0.1, 0.8, 0.6, 0.5, 1.0) == GGX_OK, "skewed");
    audit_row rows[AUDIT_MAX_ROWS];
    long before = chi2_runs_made();
    int n = audit_run_at((const double(*)[3][3])A, rows, 0, test_chi2_level()), found = 0;
    chi2_budget_spend(chi2_runs_made() - before);
    for (int i = 0; i < n; i++) {
        if (strcmp(rows[i].id, "g1-blog") != 0 && strcmp(rows[i].id, "vndf-g1") != 0) continue;
        found++;
        CHECK(rows[i].verdict[0] == AUDIT_HOLDS && rows[i].verdict[1] == AUDIT_HOLDS &&
                  rows[i].verdict[2] == AUDIT_FAILS,
              "%s: %s | %s | %s", rows[i].id, rows[i].text[0], rows[i].text[1], rows[i].text[2]);
        CHECK(strstr(rows[i].text[2], "worst of 48 views") != NULL, "%s: %s", rows[i].id, rows[i].text[2]);
    }
    CHECK(found == 2, "rows g1-blog and vndf-g1: %d found", found);
}

/* Claims about every shape of a kind: a failure is reported with the failing shape nearest to a diagonal one (the
 * smallest counterexample), and a claim that holds everywhere holds. The synthetic claim fails where A^T A's
 * off-diagonal share exceeds the bound (the family's median share). */
static double share_bound;
static double offdiag_err(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)g, (void)ctx;
    snprintf(at, nat, "share %.6f", K->offdiag);
    return K->offdiag > share_bound ? K->offdiag : 0;
}
static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
static void kin_counterexample(void **state)
{
    (void)state;
    double A[3][3], shares[AU_KIN];
    ggx_shape s;
    CHECK(ggx_ellipsoid_matrix(A, 0.3, 0.6, 0.4, -0.3, 0.5) == GGX_OK &&
              ggx_shape_matrix(&s, (const double(*)[3])A) == GGX_OK,
          "skewed shape");
    for (int i = 0; i < AU_KIN; i++) {
        au_kin K;
        au_kin_shape(&s, (const double(*)[3])A, i, 0x5eed, &K);
        CHECK(K.s.kind == GGX_SHAPE_SKEWED && K.offdiag > 0, "shape %d of the skewed family: kind %d", i,
              (int)K.s.kind);
        shares[i] = K.offdiag;
    }
    qsort(shares, AU_KIN, sizeof shares[0], cmp_d);
    share_bound = shares[AU_KIN / 2];
    double least = shares[AU_KIN / 2 + 1]; /* the smallest failing share */
    audit_row row;
    memset(&row, 0, sizeof row);
    au_verdict_kin(&row, 0, &s, (const double(*)[3])A, offdiag_err, NULL, 3, 0, "synthetic:");
    char want[64];
    snprintf(want, sizeof want, "share %.6f", least);
    CHECK(row.verdict[0] == AUDIT_FAILS && strstr(row.text[0], want), "expected the counterexample %s: %s", want,
          row.text[0]);
    /* the diagonal family: every share 0, so the same claim holds */
    ggx_shape d;
    double D[3][3] = {{0.2, 0, 0}, {0, 0.7, 0}, {0, 0, 1}};
    CHECK(ggx_shape_matrix(&d, (const double(*)[3])D) == GGX_OK, "diagonal shape");
    au_verdict_kin(&row, 1, &d, (const double(*)[3])D, offdiag_err, NULL, 3, 0, "synthetic:");
    CHECK(row.verdict[1] == AUDIT_HOLDS, "%s", row.text[1]);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(audit), cmocka_unit_test(view_grid),
                                       cmocka_unit_test(kin_counterexample)};
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    return rc | chi2_budget_end("audit", argc, argv);
}
