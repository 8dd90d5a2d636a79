/* The suite's one chi-square budget: the share of each ctest entry, the level derived from their sum, and the count
 * each program checks against its share (tests/support/testlib.h). SPDX-License-Identifier: MIT */
#include <stdio.h>
#include <string.h>

#include "chi2.h"
#include "testlib.h"

/* Each entry: a test program and its argument (as ctest runs it, tests/CMakeLists.txt), and the most chi-square
 * checks that must pass it may make, at either tier. A new sampler, variant or sweep that needs more raises its
 * entry's share here, which lowers every run's level a little. */
static const struct {
    const char *entry;
    int share;
} SHARES[] = {
    {"sample_vndf 0", 124}, {"sample_vndf 1", 100}, {"sample_ndf", 36},
    {"sample_dir 1", 112},  {"sample_dir 2", 42},   {"variants inline", 96},
    {"variants batch", 92}, {"energy 2", 16},       {"energy 3", 14},
    {"energy_bsdf 2", 28},  {"audit", 84},          {"fit", 20},
    {"slopes", 12},         {"render", 1},          {"sggx", 9},
};
enum { NSHARES = sizeof SHARES / sizeof SHARES[0] };

static int budget_total(void)
{
    int total = 0;
    for (int i = 0; i < NSHARES; i++) total += SHARES[i].share;
    return total;
}

double test_chi2_level(void) { return chi2_sidak(budget_total()); }

static long checks;
int chi2_accepts(double p)
{
    checks++;
    return p >= test_chi2_level();
}
void chi2_budget_spend(long runs) { checks += runs; }

int chi2_budget_end(const char *program, int argc, char **argv)
{
    char entry[96];
    snprintf(entry, sizeof entry, "%s%s%s", program, argc > 1 ? " " : "", argc > 1 ? argv[1] : "");
    /* the entry's share; a program run without its argument runs every part: the sum of its entries */
    int share = 0, found = 0;
    size_t lp = strlen(program);
    for (int i = 0; i < NSHARES; i++)
        if (strcmp(SHARES[i].entry, entry) == 0 ||
            (argc <= 1 && strncmp(SHARES[i].entry, program, lp) == 0 && SHARES[i].entry[lp] == ' '))
            share += SHARES[i].share, found = 1;
    printf("chi-square checks in '%s': %ld of its share %d (suite budget %d runs, per-run level %.3g)\n", entry, checks,
           share, budget_total(), test_chi2_level());
    if (!found && checks > 0) {
        printf("FAIL: '%s' made chi-square checks but has no share in tests/support/chi2_budget.c\n", entry);
        return 1;
    }
    if (checks > share) {
        printf("FAIL: '%s' made %ld chi-square checks, more than its share %d (tests/support/chi2_budget.c)\n", entry,
               checks, share);
        return 1;
    }
    return 0;
}
