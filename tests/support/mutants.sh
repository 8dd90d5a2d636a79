#!/bin/sh
# Mutation check: applies one deliberate error at a time to the library (each a plausible mistake, several of them
# the forms the seeds disagree on, some reaching only one variant: the float kernels, the batch loops, the
# registry), rebuilds in a scratch tree and requires the test suite (at GGX_TEST_SCALE 0.1, the scale of make
# sanitize, without the install, command, man page, Python and CUDA tests, and without the energy tables, the seed
# audit and the figures, whose minutes no mutant below targets) to fail. A mutant whose text is no longer in the
# source counts as survived.
# Usage: sh tests/support/mutants.sh   (from the repository root; about a minute per mutant on 2 cores)
set -u
root=$(pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
survived=0
killed=0
# The sources, copied once (later edits of the tree do not reach a running check).
mkdir "$work/tree" && cp -r "$root/CMakeLists.txt" "$root/.ctags.d" "$root/cmake" "$root/include" "$root/src" "$root/lab" \
    "$root/tests" "$root/tools" "$root/examples" "$work/tree/"
# Builds the scratch tree and prints the names of the test programs that fail, or BUILD FAILED.
build_and_test() {
    if ! { cmake -S "$work/src" -B "$work/b" -DGGX_WERROR=ON -DGGX_BUILD_TOOL=OFF -DGGX_BUILD_EXAMPLES=OFF \
               -DGGX_BUILD_PYTHON=OFF -DGGX_CUDA=OFF \
               >/dev/null 2>&1 && cmake --build "$work/b" -j 2 >/dev/null 2>&1; }; then
        echo "BUILD FAILED"
    else
        (cd "$work/b" && GGX_TEST_SCALE=0.1 ctest -j 2 -E "install|cli|man|energy|audit|figures|tables" 2>/dev/null |
            sed -n 's/.*Test *#[0-9]*: \([a-z_0-9]*\) .*\*\*\*Failed.*/\1/p' | tr '\n' ' ')
    fi
    rm -rf "$work/b"
}
# The control: the unmutated tree passes, or a kill below would mean nothing.
rm -rf "$work/src" && cp -r "$work/tree" "$work/src"
control=$(build_and_test)
if [ -n "$control" ]; then echo "the unmutated tree fails: $control"; exit 1; fi
mutate() { # file, old text, new text, description
    rm -rf "$work/src" && cp -r "$work/tree" "$work/src"
    # (the whole text, lines included: grep -F would accept any one of its lines)
    if ! python3 -c "import sys; sys.exit(sys.argv[2] not in open(sys.argv[1]).read())" "$work/src/$1" "$2"; then
        echo "MUTANT NOT APPLIED: $4"; survived=$((survived + 1)); return
    fi
    python3 -c "import sys; p, o, n = sys.argv[1:4]; s = open(p).read(); open(p, 'w').write(s.replace(o, n, 1))" \
        "$work/src/$1" "$2" "$3"
    failed=$(build_and_test)
    if [ "$failed" = "BUILD FAILED" ]; then
        echo "MUTANT DOES NOT BUILD: $4"; survived=$((survived + 1))
    elif [ -z "$failed" ]; then
        echo "SURVIVED: $4"; survived=$((survived + 1))
    else
        echo "killed:   $4 (failed: $failed)"; killed=$((killed + 1))
    fi
}
K=include/ggx/kernel
mutate src/api/shape.c "t.ndf_scale = 1.0 / (GGX_PI * t.det * t.an_len);" "t.ndf_scale = 1.0 / (GGX_PI * t.det);" \
    "D without ||A n|| (eq 1 normalisation)"
mutate $K/ndf.inc "    int up = au.z >= 0;
    *w = up ? lu + au.z : xy;
    *d = 2 * GGX_A33(s) * (up ? 1 : lu - au.z);" \
    "    ggx_v3 g = GGX_FN(k_normalize)(GGX_FN(k_v3)(s->ainv_t[0][2], s->ainv_t[1][2], s->ainv_t[2][2]));
    *w = lu + GGX_FN(k_dot)(au, g);
    *d = 2 * GGX_A33(s);" \
    "masking lune built from A^-T n (blog Part 2 form) instead of A n"
mutate $K/ndf.inc "return GGX_FN(k_min1)(GGX_FN(g1_smith)(s, u));" "return GGX_FN(g1_smith)(s, u);" \
    "G1 without the min of eq 32"
mutate $K/ndf.inc "return GGX_FN(k_finite0)(s->det * s->det * q * q);" "return GGX_FN(k_finite0)(s->det * q * q);" \
    "Kg with |A| instead of |A|^2"
mutate $K/scatter.inc "GGX_FABS(hi * ho) * eta_o * eta_o * T" "GGX_FABS(hi * ho) * T" \
    "BTDF without eta_o^2 (importance form as radiance)"
mutate $K/scatter.inc "g * fr / (4 * wi.z * wo.z)" "g * fr / (2 * wi.z * wo.z)" "BRDF with 2 instead of 4"
mutate $K/scatter.inc "k_finite0)(eta_o * eta_o * GGX_FABS(GGX_FN(k_dot)(wo, h)) / (d * d))" \
    "k_finite0)(eta_i * eta_i * GGX_FABS(GGX_FN(k_dot)(wo, h)) / (d * d))" "refraction Jacobian with eta_i^2"
mutate $K/fresnel.inc "rs * (t1 - t2 + t3) / (t1 + t2 + t3)" "rs * (t1 + t2 + t3) / (t1 + t2 + t3)" \
    "conductor R_p sign"
mutate $K/fresnel.inc "ggx_r rp = (eta * ci - ct) / (eta * ci + ct);" "ggx_r rp = (ci - eta * ct) / (ci + eta * ct);" \
    "dielectric R_p = R_s"
mutate $K/ndf.inc "GGX_FN(k_finite0)(GGX_FN(ndf)(s, m) * mv * d / w)" \
    "GGX_FN(k_finite0)(GGX_FN(ndf)(s, m) * mv / v.z)" \
    "VNDF pdf with G1 dropped"
mutate $K/lune.inc "ggx_r pz = w * opz;" "ggx_r pz = w * opz + GGX_C(0.1) * av.z;" \
    "spherical cap with the wrong lower bound"
mutate $K/lune.inc "sc = GGX_C(0.5) * opz," "sc = GGX_C(0.5) * (1 + vs.z * vs.z)," \
    "crescent factor s squared"
mutate $K/rejection.inc "ggx_r h = GGX_SQRT(GGX_FN(k_max0)(1 - d.x * d.x - d.y * d.y));" \
    "ggx_r h = GGX_C(0.5) * GGX_SQRT(GGX_FN(k_max0)(1 - d.x * d.x - d.y * d.y));" \
    "rejection (Walter version 2) lifting the silhouette to half height"
mutate src/batch/loops.inc "pdf[i] = uok ? r.pdf : 0.0f;" "pdf[i] = uok ? 0.5f * r.pdf : 0.0f;" \
    "batch reflection pdf off by 2 (fast path)"
mutate src/batch/loops.inc "#define NORMALS_CASE_VNDF_1(ID, stem) NORMALS_CASE_ANY(ID, stem, 1)" \
    "#define NORMALS_CASE_VNDF_1(ID, stem) NORMALS_CASE_ANY(ID, stem, 0)" "batch VNDF samplers of the registry ignoring the view"
mutate $K/traits.h "(x2) * (8.331978694e-03f +" "(x2) * (9.331978694e-03f +" \
    "float sincos polynomial with a wrong coefficient (float variants only)"
mutate include/ggx/ggx_inline.h "out->a_frob2 = (float)f2;" "out->a_frob2 = (float)(f2 / 64);" \
    "float shape's ||A||_F^2 too small: the caps proof claims normals it cannot vouch for"
mutate include/ggx/ggx_inline.h "double k = 1.0 / s->an_len, det = s->det * k * k * k;" \
    "double k = 1.0, det = s->det * k * k * k;" "float shape not normalised by ||A n|| (ggx_shapef_from)"
mutate src/api/registry.c "return ggx_pdf_ndf(s, m);" "return ggx_pdf_vndf(s, v, m);" \
    "registry claiming the VNDF pdf for the NDF samplers (equal at v = n, where the NDF sweep runs)"
mutate $K/traits.h "#define GGX_PROOF_C GGX_C(1.52587890625e-05) /* 2^-16 */" \
    "#define GGX_PROOF_C GGX_C(2.384185791015625e-07) /* 2^-22 */" \
    "float caps proof's C term 64 times too small (its premise fails for views along A's most contracted direction)"
mutate $K/bounded.inc "ggx_rw b = GGX_BOUND_DIVIDE ? 1 : (ggx_rw)GGX_B33(s), b2 = b * b;" "ggx_rw b = 1, b2 = 1;" \
    "bounded plane's fraction in double without its scale (scaled shapes fall to the slow path's u2 kappa at the rim)"
mutate $K/traits.h "#define GGX_FACE_FLOOR(bar, mu2) ((mu2) >= 1e-250)" "#define GGX_FACE_FLOOR(bar, mu2) ((bar) >= 1e-78)" \
    "double facing check's floor on bar instead of mu.mu (small matrices leave the fast path)"
mutate $K/lune.inc "(p.z >= GGX_PROOF_T * k)" "(p.z >= 0)" \
    "scalar caps sampler's proof without the rim bound (returns unchecked normals at the rim)"
mutate $K/disk.inc "*q = 1 - u1; /* exact for u1 >= 1/2 */" "*q = 1 - r * r * (c * c + sn * sn);" \
    "polar disk's 1 - |d|^2 by cancellation (float crescent-polar, Heitz and ellipse samplers off near the rim)"
mutate $K/bounded.inc "    return rt < rc ? rt : rc;" "    return rt < rc ? rc : rt;" \
    "per-azimuth bound stopping at the later of its two quadratics' roots (removes points only one of them bounds)"
mutate $K/bounded.inc "    cur = (two & (ra >= h1)) ? rb : ra;" "    cur = two ? rb : ra;" \
    "per-azimuth bound's second stage taken where the first stopped below the equator"
mutate $K/bounded.inc "    int ok = (wn.z > 0) & (b > start) & (num > 0) & (num < den);" \
    "    int ok = (wn.z > 0) & (b > start - 2) & (num > 0) & (num < den);" \
    "per-azimuth bound in absolute z where the stages leave the plane bound (kappa above the plane's)"
mutate $K/bounded.inc "    ggx_rw P = 1 - t * y, Q = (dy3 - 2 * t * y) + 3;" \
    "    ggx_rw d = (ggx_rw)s->det * (ggx_rw)s->det, P = 1 - t * y, Q = (d * y * y * y + 0 * dy3 - 2 * t * y) + 3;" \
    "sigma2's Newton step from det^2 (subnormal for ill-conditioned matrices near 1e-50)"
# the normal-map filter and the M step it shares with the fits
mutate src/fit/fit.h "    sn[0] = 2.0 * (a[4] / a[1] - dt[0] * dt[0]);" "    sn[0] = (a[4] / a[1] - dt[0] * dt[0]);" \
    "the M step's scale without the factor 2 of nu = 2 (the plain t's scale for Sigma / 2)"
mutate src/filter/filter_lobes.c "        double wq = 0.5 * ws[j] * 2.0 * om / na;" "        double wq = 0.5 * ws[j] / na;" \
    "the lobe's rule without the Jacobian 2 (1 - s) of u = 1 - (1 - s)^2"
mutate src/filter/filter_lobes.c "        double rho = sqrt(s * (2.0 - s)) / om;" "        double rho = sqrt(s * (2.0 - s));" \
    "the lobe's rule with the radius sqrt(u) instead of sqrt(u / (1 - u))"
mutate src/filter/filter_lobes.c "    c[0] = tx, c[1] = ty;" "    c[0] = -tx, c[1] = ty;" \
    "the texel's lobe at the mirrored slope in x (t = +n.x / n.z)"
mutate src/filter/filter_mip.c "filter_lobe_set(&L[n++], c, c + 2, wi / W);" \
    "filter_lobe_set(&L[n++], c, c + 2, 1.0 / (double)(nx * ny));" "a mip level's box ignoring the texels' weights"
echo "$killed mutant(s) killed, $survived survived"
[ "$survived" -eq 0 ]
