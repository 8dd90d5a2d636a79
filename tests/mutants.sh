#!/bin/sh
# Mutation check: applies one deliberate error at a time to the library (each a plausible mistake, several of them
# the forms the seeds disagree on), rebuilds in a scratch tree and requires the test suite to fail.
# Usage: sh tests/mutants.sh   (from the repository root; about two minutes per mutant on 2 cores)
set -u
root=$(pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
survived=0
mutate() { # file, python-style literal old, new, description
    rm -rf "$work/src" && cp -r "$root" "$work/src" && rm -rf "$work/src/build"*
    if ! grep -qF "$2" "$work/src/$1"; then echo "MUTANT NOT APPLIED: $4"; survived=$((survived + 1)); return; fi
    python3 -c "import sys; p, o, n = sys.argv[1:4]; s = open(p).read(); open(p, 'w').write(s.replace(o, n, 1))" \
        "$work/src/$1" "$2" "$3"
    cmake -S "$work/src" -B "$work/b" -DGGX_WERROR=ON >/dev/null 2>&1 && cmake --build "$work/b" -j 2 >/dev/null 2>&1
    if (cd "$work/b" && GGX_TEST_SCALE=0.2 ctest -j 2 -E "install|cli" >/dev/null 2>&1); then
        echo "SURVIVED: $4"; survived=$((survived + 1))
    else
        echo "killed:   $4 ($(cd "$work/b" && GGX_TEST_SCALE=0.2 ctest -j 2 -E "install|cli" 2>/dev/null | grep -c '\*\*\*Failed') test programs failed)"
    fi
    rm -rf "$work/b"
}
mutate src/shape.c "t.ndf_scale = 1.0 / (GGX_PI * t.det * t.an_len);" "t.ndf_scale = 1.0 / (GGX_PI * t.det);" \
    "D without ||A n|| (eq 1 normalisation)"
mutate src/ndf.c "double num = lune_numerator(mat_mul(s->a, u), s->an, &lv);" \
    "double num = lune_numerator(mat_mul(s->a, u), v3(s->ainv_t[0][2], s->ainv_t[1][2], s->ainv_t[2][2]), &lv);" \
    "masking lune built from A^-T n (blog Part 2 form) instead of A n"
mutate src/ndf.c "return g < 1.0 ? g : 1.0;" "return g;" "G1 without the min of eq 32"
mutate src/ndf.c "return finite_or_zero(s->det * s->det * q * q);" "return finite_or_zero(s->det * q * q);" \
    "Kg with |A| instead of |A|^2"
mutate src/bsdf.c "eta_o * eta_o * T" "T" "BTDF without eta_o^2 (importance form as radiance)"
mutate src/bsdf.c "/ (4.0 * wi.z * wo.z)" "/ (2.0 * wi.z * wo.z)" "BRDF with 2 instead of 4"
mutate src/bsdf.c "return finite_or_zero(eta_o * eta_o * fabs(v3_dot(wo, h)) / (d * d));" \
    "return finite_or_zero(eta_i * eta_i * fabs(v3_dot(wo, h)) / (d * d));" "refraction Jacobian with eta_i^2"
mutate src/fresnel.c "(t1 - t2 + t3) / (t1 + t2 + t3)" "(t1 + t2 + t3) / (t1 + t2 + t3)" "conductor R_p sign"
mutate src/fresnel.c "double rp = (eta * ci - ct) / (eta * ci + ct);" "double rp = (ci - eta * ct) / (ci + eta * ct);" \
    "dielectric R_p = R_s"
mutate src/ndf.c "return finite_or_zero(ggx_ndf(s, m) * mv * 2.0 * s->an_len * s->an_len / num);" \
    "return finite_or_zero(ggx_ndf(s, m) * mv / v.z);" "VNDF pdf with G1 dropped"
mutate src/sample.c "double z = (1.0 - clamp01(u2)) * (1.0 + vs.z) - vs.z;" "double z = (1.0 - clamp01(u2)) * (1.0 + vs.z) - 0.9 * vs.z;" \
    "spherical cap with the wrong lower bound"
mutate src/sample.c "    double sc = 0.5 * (1.0 + vs.z); /* eq 38 with A n / ||A n|| = z */" "    double sc = 0.5 * (1.0 + vs.z * vs.z);" \
    "crescent factor s squared"
mutate src/batch_kernels.inc "float p = 0.25f * ndf1(s, mx, my, mz) * vf;" "float p = 0.5f * ndf1(s, mx, my, mz) * vf;" \
    "batch reflection pdf off by 2"
echo "$survived mutant(s) survived"
[ "$survived" -eq 0 ]
