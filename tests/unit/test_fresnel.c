/* Fresnel: the library's real-valued formulas against the complex-amplitude Fresnel equations evaluated here with
 * C99 complex arithmetic, and textbook values. SPDX-License-Identifier: MIT */
#include <complex.h>
#include <math.h>

#include "ggx/ggx_inline.h"
#include "testlib.h"

/* Unpolarised reflectance from the s and p amplitude coefficients with a complex relative index n~:
 * cos_t = sqrt(1 - sin_i^2 / n~^2), r_s = (cos_i - n~ cos_t) / (cos_i + n~ cos_t),
 * r_p = (n~ cos_i - cos_t) / (n~ cos_i + cos_t). */
static double fresnel_complex(double cos_i, double complex n)
{
    double s2 = 1.0 - cos_i * cos_i;
    double complex ct = csqrt(1.0 - s2 / (n * n));
    double complex rs = (cos_i - n * ct) / (cos_i + n * ct);
    double complex rp = (n * cos_i - ct) / (n * cos_i + ct);
    return 0.5 * (creal(rs * conj(rs)) + creal(rp * conj(rp)));
}

static void conductor_matches_complex(void **state)
{
    (void)state;
    rng r = {31};
    for (int i = 0; i < 20000; i++) {
        double eta = exp(rng_range(&r, log(0.05), log(5.0))), k = rng_range(&r, 0.0, 10.0);
        double c = rng_uniform(&r);
        if (i % 10 == 0) c = 1e-8 * rng_uniform(&r); /* grazing */
        CHECK_CLOSE(ggx_fresnel_conductor_eval(c, eta, k), fresnel_complex(c, eta + k * I), 1e-12, 1e-15,
                    "cos %g eta %g k %g", c, eta, k);
    }
    /* Normal incidence ((n-1)^2 + k^2) / ((n+1)^2 + k^2); grazing gives 1. Gold-like and aluminium-like values. */
    const double nk[][2] = {{0.47, 2.4}, {1.2, 7.26}, {0.2, 3.9}};
    for (int i = 0; i < 3; i++) {
        double n = nk[i][0], k = nk[i][1];
        CHECK_CLOSE(ggx_fresnel_conductor_eval(1.0, n, k), ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k),
                    1e-14, 0, "normal incidence %d", i);
        CHECK_CLOSE(ggx_fresnel_conductor_eval(0.0, n, k), 1.0, 1e-15, 0, "grazing %d", i);
    }
    CHECK_CLOSE(ggx_fresnel_conductor_eval(1.0, 1.2, 7.26), 0.9166, 0, 5e-5, "aluminium at 600 nm");
}

static void dielectric(void **state)
{
    (void)state;
    /* Textbook values for glass n = 1.5 (Hecht): 4 % at normal incidence; at 45 degrees R_s = 0.0920 and
     * R_p = 0.0085, so F = 0.0502; at Brewster's angle atan(1.5) R_p = 0 and F = R_s / 2 = 0.0739. */
    CHECK_CLOSE(ggx_fresnel_dielectric_eval(1.0, 1.5), 0.04, 1e-14, 0, "normal");
    CHECK_CLOSE(ggx_fresnel_dielectric_eval(cos(GGX_PI / 4), 1.5), 0.0502, 0, 1e-4, "45 degrees");
    double cb = cos(atan(1.5));
    CHECK_CLOSE(ggx_fresnel_dielectric_eval(cb, 1.5), 0.5 * pow((1.5 * 1.5 - 1) / (1.5 * 1.5 + 1), 2), 1e-12, 0,
                "Brewster");
    CHECK_CLOSE(ggx_fresnel_dielectric_eval(cb, 1.5), 0.0739, 0, 1e-4, "Brewster value");
    /* Total internal reflection from inside glass beyond the critical angle asin(1/1.5) = 41.8 degrees. */
    CHECK(ggx_fresnel_dielectric_eval(cos(0.74), 1 / 1.5) == 1.0, "TIR");
    CHECK(ggx_fresnel_dielectric_eval(cos(0.72), 1 / 1.5) < 1.0, "just below critical");
    rng r = {32};
    for (int i = 0; i < 20000; i++) {
        double eta = exp(rng_range(&r, log(0.2), log(5.0))), c = rng_uniform(&r);
        double want = fresnel_complex(c, eta + 0.0 * I);
        if (1.0 - (1.0 - c * c) / (eta * eta) < 0) want = 1.0;
        CHECK_CLOSE(ggx_fresnel_dielectric_eval(c, eta), want, 1e-12, 1e-15, "cos %g eta %g", c, eta);
        CHECK_CLOSE(ggx_fresnel_dielectric_eval(-c, eta), ggx_fresnel_dielectric_eval(c, eta), 0, 0, "sign");
        if (eta >= 1.0)
            CHECK_CLOSE(ggx_fresnel_conductor_eval(c, eta, 0.0), want, 1e-12, 1e-15, "k = 0 is a dielectric");
        /* Transmittance is the same from both sides for a Snell pair (used by BSDF reciprocity). Recovering the
         * pair from the inside loses eta^2 eps / c^2 relative accuracy in the cosine, so grazing c is left out. */
        double st2 = (1 - c * c) / (eta * eta);
        if (st2 < 1 && c > 0.01) {
            double ct = sqrt(1 - st2);
            CHECK_CLOSE(ggx_fresnel_dielectric_eval(ct, 1 / eta), ggx_fresnel_dielectric_eval(c, eta), 1e-11, 1e-15,
                        "two sides, cos %g eta %g", c, eta);
        }
    }
}

static void schlick_and_setup(void **state)
{
    (void)state;
    CHECK_CLOSE(ggx_fresnel_schlick_eval(1.0, 0.04), 0.04, 1e-15, 0, "f0");
    CHECK_CLOSE(ggx_fresnel_schlick_eval(0.0, 0.04), 1.0, 1e-15, 0, "grazing");
    CHECK_CLOSE(ggx_fresnel_schlick_eval(0.5, 0.04), 0.04 + 0.96 / 32, 1e-15, 0, "half");
    /* Schlick approximates the exact dielectric for glass within 4 % absolute (the worst case, 3.6 %, is near
     * grazing incidence, cos ~ 0.01); a wrong exponent (4 instead of 5) would exceed 4 % near cos = 0.1. */
    for (int i = 0; i <= 100; i++) {
        double c = i / 100.0;
        CHECK_CLOSE(ggx_fresnel_schlick_eval(c, 0.04), ggx_fresnel_dielectric_eval(c, 1.5), 0, 0.04, "cos %g", c);
    }
    ggx_fresnel f = {GGX_FRESNEL_CONDUCTOR, 0, 0, 0};
    CHECK(ggx_fresnel_one(&f) == GGX_OK && ggx_fresnel_eval(&f, 0.3) == 1.0, "one");
    CHECK(ggx_fresnel_dielectric(&f, 1.5) == GGX_OK &&
              ggx_fresnel_eval(&f, 1.0) == ggx_fresnel_dielectric_eval(1.0, 1.5),
          "d");
    CHECK(ggx_fresnel_conductor(&f, 0.2, 3.9) == GGX_OK &&
              ggx_fresnel_eval(&f, 0.7) == ggx_fresnel_conductor_eval(0.7, 0.2, 3.9),
          "c");
    CHECK(ggx_fresnel_schlick(&f, 0.5) == GGX_OK && ggx_fresnel_eval(&f, 1.0) == 0.5, "s");
    ggx_fresnel zero = {0};
    CHECK(ggx_fresnel_eval(&zero, 0.1) == 1.0, "zero-initialised is F = 1");
}

/* Indices far from 1, which every setup function accepts: eta^2 k^2 overflowed above |eta + i k| ~ 1e154 and
 * a^2 + b^2 underflowed to 0 below ~1e-162, and the term fell to 0 there, where the exact F is 1 within
 * 4 / |eta + i k| (above) or 4 |eta + i k| (below). Double against the complex equations from 1e-140 to 1e140 and
 * against 1 beyond; float through ggx_fresnelf_from, whose float eta and k would be 0 or infinite as they stand. */
static void conductor_extreme_indices(void **state)
{
    (void)state;
    rng r = {33};
    for (int i = 0; i < 20000; i++) {
        double eta = exp(rng_range(&r, log(1e-140), log(1e140)));
        double k = i % 4 == 0 ? 0.0 : exp(rng_range(&r, log(1e-140), log(1e140)));
        double c = i % 10 == 0 ? 1.0 : rng_uniform(&r);
        CHECK_CLOSE(ggx_fresnel_conductor_eval(c, eta, k), fresnel_complex(c, eta + k * I), 0, 1e-12,
                    "cos %g eta %g k %g", c, eta, k);
    }
    const double far[][2] = {{1e160, 0},  {0.5, 1e160},     {1e300, 1e300}, {1.7e308, 1.7e308}, {1e200, 1e-200},
                             {1e-163, 0}, {1e-200, 1e-200}, {4.9e-324, 0},  {1e-300, 4.9e-324}};
    for (int i = 0; i < (int)(sizeof far / sizeof far[0]); i++) {
        ggx_fresnel f;
        CHECK(ggx_fresnel_conductor(&f, far[i][0], far[i][1]) == GGX_OK, "setup %d", i);
        ggx_fresnelf ff;
        ggx_fresnelf_from(&ff, &f);
        for (int j = 0; j <= 4; j++) {
            double c = j / 4.0;
            CHECK_CLOSE(ggx_fresnel_eval(&f, c), 1.0, 0, 1e-12, "eta %g k %g cos %g", far[i][0], far[i][1], c);
            CHECK_CLOSE(ggx_fresnel_eval_f(&ff, (float)c), 1.0, 0, 1e-6, "float: eta %g k %g cos %g", far[i][0],
                        far[i][1], c);
        }
    }
    /* a dielectric's index beyond float's range: F is 1 within rounding in double, and in float too */
    const double etas[] = {1e39, 1e300, 1e-39, 1e-300};
    for (int i = 0; i < 4; i++) {
        ggx_fresnel f;
        ggx_fresnelf ff;
        CHECK(ggx_fresnel_dielectric(&f, etas[i]) == GGX_OK, "setup");
        ggx_fresnelf_from(&ff, &f);
        for (int j = 0; j <= 4; j++) {
            double c = j / 4.0;
            CHECK_CLOSE(ggx_fresnel_eval_f(&ff, (float)c), ggx_fresnel_eval(&f, c), 0, 1e-6, "float: eta %g cos %g",
                        etas[i], c);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(conductor_matches_complex),
        cmocka_unit_test(dielectric),
        cmocka_unit_test(schlick_and_setup),
        cmocka_unit_test(conductor_extreme_indices),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
