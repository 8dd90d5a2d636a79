#!/bin/sh
# ggx microsurface generate from the command line: a Gaussian field written as x3p and as OpenEXR is read back by
# ggx fit, which prefers Beckmann to every GGX model by BIC; V-grooves give two facet normals; bad input exits 2 with
# one line and no file. Usage: microsurface_cli_test.sh GGX   SPDX-License-Identifier: MIT
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
. "$ROOT/tests/support/cli_common.sh"
PY=/usr/bin/python3

"$GGX" microsurface --help > h.txt && grep -q "usage: ggx microsurface generate" h.txt && ok || bad "--help"
"$GGX" microsurface generate --help > g.txt && grep -q "kind beckmann|ggx|vgroove" g.txt && ok || bad "generate --help"
if "$GGX" microsurface generate --kind beckmann --alpha 0.3 --corr 8 --size 256 --seed 3 --out b.x3p > b.txt 2> err.txt; then
    grep -q "heights' sigma 1.2," b.txt && ok || bad "sigma: $(cat b.txt)"
    "$GGX" fit --heightfield b.x3p > fit.txt && grep -q "Beckmann.*\*\*best\*\*" fit.txt && ok ||
        bad "fit of the x3p field: $(grep -i beckmann fit.txt)"
    "$GGX" microsurface generate --kind beckmann --alpha 0.2,0.4 --rotate 30 --corr 8 --size 256 --out b.exr > /dev/null &&
        "$GGX" fit --heightfield b.exr --spacing 1 --z-scale 1 > fe.txt && grep -q "Beckmann.*\*\*best\*\*" fe.txt &&
        ok || bad "fit of the OpenEXR field: $(grep -i beckmann fe.txt)"
    # the name's extension in any case, as every subcommand reads it
    "$GGX" microsurface generate --kind beckmann --alpha 0.3 --corr 4 --size 64 --out UP.EXR > /dev/null &&
        [ "$(head -c 4 UP.EXR | od -An -tx1 | tr -d ' ')" = 762f3101 ] &&
        "$GGX" microsurface generate --kind beckmann --alpha 0.3 --corr 4 --size 64 --out UP.X3P > /dev/null &&
        [ "$(head -c 2 UP.X3P)" = PK ] && ok || bad "generate --out UP.EXR, UP.X3P"
    # measure a Gaussian field at 80 degrees: Smith's G1 for Beckmann slopes of the facets' covariance is the facets'
    # G1 to 1e-2 (the ensemble is exactly Gaussian)
    if "$GGX" microsurface measure --heightfield b.x3p --view 80,30 -n 40000 --threads 2 --format json > bm.json 2> err.txt; then
        "$PY" -c "
import json; d = json.load(open('bm.json')); g = d['g1']
assert d['missed'] == 0 and abs(g['facets'] - g['smith_beckmann']) < 1e-2, g" && ok || bad "measure, Beckmann: $(head -c 400 bm.json)"
    elif ! grep -q "not built" err.txt; then
        bad "measure: $(cat err.txt)"
    fi
    # GGX slopes: ggx fit prefers a GGX model to Beckmann, and reads back the roughness within 5 %
    "$GGX" microsurface generate --kind ggx --alpha 0.3 --corr 8 --size 512 --out g.x3p > /dev/null &&
        "$GGX" fit --heightfield g.x3p --model isotropic --format json > gf.json && "$PY" -c "
import json; d = json.load(open('gf.json'))
assert d['best'] != 'beckmann', d['best']
assert abs(d['shape']['alpha'][0] / 0.3 - 1) < 0.05, d['shape']" && ok || bad "GGX field: $(head -c 400 gf.json)"
    # its visible normals: from the normal no facet is masked, and eq 33 of the fitted shape is near (chi-square
    # under 3 per degree of freedom at 20,000 rays); at 80 degrees Smith's masking misses them many times more
    "$GGX" microsurface measure --heightfield g.x3p --view 0,0 -n 20000 --format json > g0.json &&
        "$GGX" microsurface measure --heightfield g.x3p --view 80,20 -n 20000 --format json > g80.json && "$PY" -c "
import json; a = json.load(open('g0.json'))['vndf_chi2']; b = json.load(open('g80.json'))['vndf_chi2']
assert a['stat'] / a['dof'] < 3 and b['stat'] / b['dof'] > 5 * a['stat'] / a['dof'], (a, b)" && ok ||
        bad "visible normals: $(grep vndf g0.json g80.json)"
    # the BRDF with F = 1: the white furnace of all bounces keeps every ray (none lost, none left bouncing), at
    # normal incidence the single-scattering BRDF is ggx_brdf_eval's within 10 % in L2, and at 80 degrees the
    # height-correlated G2 puts the lobe nearer the traced one than eq 5's
    "$PY" -c "
import json; a = json.load(open('g0.json'))['brdf']; b = json.load(open('g80.json'))['brdf']
for r in (a, b):
    assert r['lost'] == 0 and r['capped'] == 0 and abs(r['albedo_all'] - 1) < 1e-12 and r['albedo_single'] < 1, r
assert a['l2_single'] < 0.1 and abs(a['albedo_single'] - a['albedo_model']) < 0.02, a
assert b['l2_single_height_correlated'] < 0.9 * b['l2_single'], b" && ok ||
        bad "BRDF: $(grep brdf g0.json g80.json)"
    # skewed GGX (docs/design/microsurface.md, "Skewed surfaces"): a tilted patch is refused as periodic; traced as
    # an infinite tilted patch its G1 is the tilted base's within 3 % and eq 6 misses it by over 20 %; as a sawtooth
    # the ramps' G1 is the sawtooth form's within 3 %, the vertical-facet form off by over 10 %, the risers seen
    "$GGX" microsurface generate --kind ggx --alpha 0.3 --skew 20,0 --size 512 --out tp.exr > tp.txt &&
        grep -q "location t = (0, -0.327" tp.txt && grep -q "measure --tilted" tp.txt && ok ||
        bad "generate --skew: $(cat tp.txt)"
    "$GGX" microsurface generate --kind ggx --alpha 0.3 --skew 20,0 --risers 256 --size 512 --out sw.exr > sw.txt &&
        grep -q "risers in the columns and rows 255 mod 256" sw.txt && ok || bad "generate --risers: $(cat sw.txt)"
    # without --tilted or --risers neither wraps: each is traced as a patch, saying why and what to give instead
    # (near the normal: the GGX field's tallest spike spans 1800 spacings, the margin the band's fall times tan 10)
    for f in tp sw; do
        "$GGX" microsurface measure --heightfield $f.exr --spacing 1 --z-scale 1 --view 10,90 -n 400 --format json \
            > ${f}p.json && "$PY" -c "
import json; p = json.load(open('${f}p.json'))['patch']
assert 'not periodic along y' in p['why'] and '--tilted' in p['why'] and p['left'] == 0, p" && ok ||
            bad "$f.exr as a patch: $(grep patch ${f}p.json)"
    done
    if "$GGX" microsurface measure --heightfield tp.exr --spacing 1 --z-scale 1 --tilted --view 60,270 -n 40000 \
        --threads 2 --format json > tp.json 2> err.txt; then
        "$PY" -c "
import json; d = json.load(open('tp.json')); g = d['skewed_g1']
assert abs(d['tilt'][0]) < 1e-3 and abs(d['tilt'][1] + 0.327) < 2e-3 and d['brdf'] is None, d['tilt']
assert abs(g['traced'] / g['tilted_base'] - 1) < 0.03 and abs(g['eq6'] / g['traced'] - 1) > 0.2, g" && ok ||
            bad "measure --tilted: $(head -c 600 tp.json)"
        "$GGX" microsurface measure --heightfield sw.exr --spacing 1 --z-scale 1 --risers 256 --view 60,270 \
            -n 40000 --threads 2 --format json > sw.json && "$PY" -c "
import json; d = json.load(open('sw.json')); g = d['skewed_g1']
assert d['risers'] == [0, 256] and g['risers_visible'] > 0.95 and d['brdf']['lost'] == 0, (d['risers'], g)
assert abs(g['traced'] / g['sawtooth'] - 1) < 0.03 and abs(g['vertical_facets'] / g['traced'] - 1) > 0.1, g" &&
            ok || bad "measure --risers: $(head -c 600 sw.json)"
        "$GGX" microsurface measure --heightfield sw.exr --spacing 1 --z-scale 1 --risers 256 --view 60,270 -n 4000 \
            --alpha 0.3 --skew 20,0 > swg.txt && grep -q "Smith, GGX given" swg.txt &&
            grep -q "| sawtooth (ggx_g1_risers) |" swg.txt && ok ||
            bad "measure with a given shape: $(head -20 swg.txt)"
    elif ! grep -q "not built" err.txt; then
        bad "measure --tilted: $(cat err.txt)"
    fi
    one_line "risers not dividing" "a period that divides the size 512" 2 "$GGX" microsurface generate --kind ggx \
        --skew 20,0 --risers 100 --size 512 --out n.x3p
    one_line "risers without skew" "give the skew" 2 "$GGX" microsurface generate --kind ggx --risers 64 --size 512 \
        --out n.x3p
    one_line "skew of a Beckmann field" "apply to --kind ggx" 2 "$GGX" microsurface generate --kind beckmann \
        --skew 20,0 --size 512 --out n.x3p
    one_line "tilted and risers" "one or the other" 2 "$GGX" microsurface measure --heightfield sw.exr --spacing 1 \
        --z-scale 1 --tilted --risers 256 --view 60,90
    one_line "measure, risers not dividing" "a period that divides" 2 "$GGX" microsurface measure --heightfield \
        sw.exr --spacing 1 --z-scale 1 --risers 100 --view 60,90
    one_line "measure, another period's risers" "not a sawtooth of period 128" 2 "$GGX" microsurface measure \
        --heightfield sw.exr --spacing 1 --z-scale 1 --risers 128 --view 60,90 -n 1000
    one_line "measure, risers of a plain tile" "no risers of period 64" 2 "$GGX" microsurface measure \
        --heightfield g.x3p --risers 64 --view 60,90 -n 1000
    one_line "measure, a view grazing the tilted plane" "0.06 degrees above the tilted plane" 2 "$GGX" \
        microsurface measure --heightfield tp.exr --spacing 1 --z-scale 1 --tilted --view 71.87,270 -n 1000
    one_line "measure, a view grazing the plane" "0.06 degrees above the plane" 2 "$GGX" microsurface measure \
        --heightfield g.x3p --view 89.99,0 -n 1000
    one_line "figure, no format" "does not name a format" 2 "$GGX" microsurface figure --heightfield g.x3p \
        --out f.txt
    [ ! -e f.txt ] && ok || bad "a refused figure left f.txt"
    one_line "generate, alpha out of range" "a GGX surface takes alphas in" 2 "$GGX" microsurface generate --kind ggx \
        --alpha 1e-6 --skew 10,5 --size 64 --out n.exr
    "$GGX" microsurface measure --heightfield g.x3p --view 30,0 -n 1 > m1.txt && grep -q "too few for a chi-square" \
        m1.txt && ! grep -q nan m1.txt && ok || bad "measure -n 1: $(grep -i 'visible\|nan' m1.txt)"
    # surfaces too large for the memory given: one line, exit 2, no file (not under a wrapper or a sanitizer, which
    # reserve more address space than the limit leaves)
    if [ -z "${GGX_WRAP:-}" ] && [ -z "${ASAN_OPTIONS:-}" ] && [ -z "${TSAN_OPTIONS:-}" ]; then
        # (one_line in a subshell, for the limit: its verdict comes back as the subshell's status)
        f0=$fail
        (ulimit -v 300000 && one_line "generate, out of memory" "out of memory" 2 "$GGX" microsurface generate \
            --kind ggx --size 4096 --out big.exr && [ $fail -eq $f0 ]) && [ ! -e big.exr ] && ok ||
            bad "generate without memory"
        "$GGX" microsurface generate --kind vgroove --size 4096 --out big.exr > /dev/null &&
            (ulimit -v 900000 && one_line "measure, out of memory" "out of memory" 2 "$GGX" microsurface measure \
                --heightfield big.exr --spacing 1 --z-scale 1 --view 45,0 -n 1000 && [ $fail -eq $f0 ]) && ok ||
            bad "measure without memory"
        rm -f big.exr
    fi
    # the figure: a PNG of the size asked and an SVG; bad input refused with one line
    "$GGX" microsurface figure --heightfield sw.exr --spacing 1 --z-scale 1 --risers 256 -n 2000 --size 600x360 \
        --out f.png 2> /dev/null && "$PY" -c "
import struct; b = open('f.png', 'rb').read(24)
assert b[:8] == b'\\x89PNG\\r\\n\\x1a\\n' and struct.unpack('>II', b[16:24]) == (600, 360), b" && ok || bad "figure PNG"
    "$GGX" microsurface figure --heightfield g.x3p -n 2000 --out f.svg 2> /dev/null && grep -q "<svg" f.svg && ok ||
        bad "figure SVG"
    one_line "figure, no output" "--out FILE.png|svg|pdf is required" 2 "$GGX" microsurface figure --heightfield g.x3p
    # generate's OpenEXR states its grid spacing: measure and fit read it without --spacing, as its x3p
    "$GGX" microsurface measure --heightfield b.exr --view 60,30 -n 4000 > /dev/null 2> err.txt && ok ||
        bad "measure of generate's OpenEXR without --spacing: $(cat err.txt)"
    "$GGX" fit --heightfield b.exr > fe2.txt 2> err.txt && [ "$(sed 1d fe.txt)" = "$(sed 1d fe2.txt)" ] && ok ||
        bad "fit of generate's OpenEXR without --spacing: $(cat err.txt)"
    # the measurement does not depend on the threads
    for t in 1 2 3; do
        "$GGX" microsurface measure --heightfield g.x3p --view 70,30 -n 20000 --threads $t --format json > th$t.json
    done
    cmp -s th1.json th2.json && cmp -s th1.json th3.json && ok || bad "measure: --threads 1, 2, 3 differ"
    # one tall spike: the work is bounded; a spike that would make the rays walk too far is refused at once
    "$PY" -c "
import random
random.seed(1)
for H in ('1e4', '1e9'):
    with open('spike' + H + '.txt', 'w') as f:
        for y in range(64):
            f.write(' '.join(H if (x, y) == (10, 20) else '%.3f' % random.gauss(0, 0.3) for x in range(64)) + '\\n')"
    "$GGX" microsurface measure --heightfield spike1e4.txt --spacing 1 --z-scale 1 --view 60,30 -n 10000 \
        > /dev/null 2> err.txt && ok || bad "measure of a spike of 1e4: $(cat err.txt)"
    one_line "measure, a spike of 1e9" "crosses about 2.71e+07 tiles" 2 "$GGX" microsurface measure \
        --heightfield spike1e9.txt --spacing 1 --z-scale 1 --view 60,30
    # Embree that cannot start says why in words (where this limit stops Embree and not the loader)
    if [ -z "${GGX_WRAP:-}" ] && [ -z "${ASAN_OPTIONS:-}" ] && [ -z "${TSAN_OPTIONS:-}" ]; then
        (ulimit -v 200000 && "$GGX" microsurface measure --heightfield spike1e4.txt --spacing 1 --z-scale 1 \
            --view 60,30 -n 100 > /dev/null 2> emb.txt)
        if grep -q "Embree" emb.txt; then
            grep -q "Embree did not start (out of memory)" emb.txt && ok || bad "Embree's error: $(cat emb.txt)"
        fi
    fi
    # the same seed, the same file
    "$GGX" microsurface generate --kind beckmann --alpha 0.3 --corr 8 --size 256 --seed 3 --out b2.x3p > /dev/null &&
        "$GGX" fit --heightfield b2.x3p > fit2.txt && [ "$(sed 1d fit.txt)" = "$(sed 1d fit2.txt)" ] && ok ||
        bad "the seed does not repeat"
elif grep -q "not built" err.txt; then
    echo "microsurface CLI: $(cat err.txt): the Gaussian fields are not tested"
else
    bad "generate: $(cat err.txt)"
fi
if "$GGX" microsurface generate --kind vgroove --alpha 0.5 --period 8 --size 64 --out v.x3p > v.txt 2> err.txt; then
    grep -q "26.56" v.txt && ok || bad "V-grooves: $(cat v.txt)"
    # 63 x 63 cells, four facets each; no slope along y: Sigma_yy at the floor (the lobe off n by the grooves'
    # mean slope: at the shape of alpha_y = 1e-4)
    "$GGX" fit --heightfield v.x3p --format json > vf.json && grep -q '"used": 15876' vf.json &&
        grep -q '"sigma": \[[0-9.e-]*, 0, 1\.00[0-9]*e-08\]' vf.json &&
        grep -q '"alpha": \[[0-9.e-]*, 0.0001\]' vf.json && ok ||
        bad "fit of the V-grooves: $(head -c 300 vf.json)"
    # measure: V-grooves of slope 0.5 at 70 degrees hide the facets facing away (back-facing) and show of those
    # facing v the Torrance-Sparrow share: G1 = 2 / (1 + s tan 70) = 0.842553, the same in their bin. The model
    # compared with is given (--alpha): the fitted shape's 1:5000 anisotropy costs seconds of quadrature, minutes
    # under valgrind, and this check reads only the trace.
    if "$GGX" microsurface measure --heightfield v.x3p --view 70,0 -n 40000 --alpha 0.5 --format json > vm.json 2> err.txt; then
        "$PY" - <<'EOF_PY' && ok || bad "measure, V-grooves: $(cat vm.json)"
import json, math
d = json.load(open("vm.json"))
want = 2 / (1 + 0.5 * math.tan(math.radians(70)))
assert d["missed"] == 0 and abs(d["g1"]["facets"] - want) < 1e-6, d["g1"]
bins = [b for b in d["bins"] if b["area"] > 0.01]
assert len(bins) == 1 and abs(bins[0]["g1"] - want) < 0.01, bins
EOF_PY
    elif grep -q "not built" err.txt; then
        echo "microsurface CLI: $(cat err.txt): measure is not tested"
    else
        bad "measure: $(cat err.txt)"
    fi
elif grep -q "not built" err.txt; then
    echo "microsurface CLI: x3p support is off, the V-grooves are not written"
else
    bad "V-grooves: $(cat err.txt)"
fi
one_line "no kind" "--kind beckmann|ggx|vgroove is required" 2 "$GGX" microsurface generate --size 64 --out n.x3p
one_line "unknown kind" "unknown kind 'gauss'" 2 "$GGX" microsurface generate --kind gauss --size 64 --out n.x3p
one_line "odd size" "an even size" 2 "$GGX" microsurface generate --kind vgroove --size 65 --out n.x3p
one_line "mix with beckmann" "--mix applies to --kind ggx" 2 "$GGX" microsurface generate --kind beckmann --mix 64 \
    --size 256 --out n.x3p
one_line "mix too long" "the mixing length" 2 "$GGX" microsurface generate --kind ggx --corr 16 --size 256 --out n.x3p
one_line "period with beckmann" "--period applies to --kind vgroove" 2 "$GGX" microsurface generate --kind beckmann \
    --period 8 --size 64 --out n.x3p
one_line "png out" "give a .exr or .x3p name" 2 "$GGX" microsurface generate --kind vgroove --size 64 --out n.png
one_line "short correlation" "correlation length must be in" 2 "$GGX" microsurface generate --kind beckmann \
    --corr 2 --size 64 --out n.x3p
# --bounces: one reflection leaves the rays that need more counted as still bouncing, none lost
if [ -e g.x3p ] && "$GGX" microsurface measure --heightfield g.x3p --view 80,20 -n 20000 --bounces 1 --format json > g1b.json 2>/dev/null; then
    "$PY" -c "
import json; b = json.load(open('g1b.json'))['brdf']
assert b['lost'] == 0 and b['capped'] > 0 and abs(b['albedo_all'] - b['albedo_single']) < 1e-7, b
assert abs(b['albedo_all'] + b['capped'] / b['rays'] - 1) < 1e-7, b  # (8 digits in the JSON)" && ok || bad "--bounces 1: $(grep brdf g1b.json)"
fi
one_line "bad bounces" "not a number of bounces" 2 "$GGX" microsurface measure --heightfield v.x3p --view 30,0 --bounces 0
one_line "measure, no view" "--view THETA,PHI is required" 2 "$GGX" microsurface measure --heightfield v.x3p
one_line "measure, no file" "--heightfield FILE is required" 2 "$GGX" microsurface measure --view 30,0
# a ramp is not periodic: the tracer would tile a cliff
"$PY" - <<'EOF_PY'
import struct, zlib
raw = b"".join(b"\0" + bytes(4 * i for i in range(32)) for j in range(32))
ch = lambda k, b: struct.pack(">I", len(b)) + k + b + struct.pack(">I", zlib.crc32(k + b) & 0xFFFFFFFF)
open("ramp.png", "wb").write(b"\x89PNG\r\n\x1a\n" + ch(b"IHDR", struct.pack(">IIBBBBB", 32, 32, 8, 0, 0, 0, 0)) +
                             ch(b"IDAT", zlib.compress(raw)) + ch(b"IEND", b""))
EOF_PY
if [ -e ramp.png ] && "$GGX" fit --heightfield ramp.png --spacing 1 --z-scale 0.01 > /dev/null 2>&1; then
    "$GGX" microsurface measure --heightfield ramp.png --spacing 1 --z-scale 0.01 --view 30,0 -n 400 > ramp.txt \
        2> err.txt && grep -q "traced as a patch (not periodic along x" ramp.txt && ok ||
        bad "a ramp as a patch: $(head -3 ramp.txt) $(cat err.txt)"
fi
# measured scans (tests/data/x3p, docs/design/microsurface.md "Measured patches"): traced as patches, not square,
# with missing points; the rays from the window never leave at 60 degrees, every BRDF ray is binned, lost (through
# a hole), left or capped. Kautschuk at --downsample 4 (215 x 158), sample-land at full resolution (at 4 under a
# wrapper, and Kautschuk's full resolution only outside one). (v.x3p exists where x3p is read and written.)
X3P="$ROOT/tests/data/x3p"
if [ -e v.x3p ]; then
    runs="KautschukInfiniteFocus:4 sample-land:4"
    [ -z "${GGX_WRAP:-}" ] && runs="KautschukInfiniteFocus:4 sample-land:1 KautschukInfiniteFocus:1"
    for run in $runs; do
        f=${run%:*} k=${run#*:}
        "$GGX" microsurface measure --heightfield "$X3P/$f.x3p" --downsample $k --view 60,0 -n 2000 --threads 2 \
            --format json > scan.json 2> err.txt
        if grep -q "not built" err.txt; then echo "microsurface CLI: $(cat err.txt): scans not traced"; break; fi
        "$PY" -c "
import json; d = json.load(open('scan.json')); p = d['patch']; b = d['brdf']
assert p['why'] == 'not square' and p['edge'] == 'window' and p['left'] == 0 and p['missing_points'] > 0, p
assert d['rays'] == 2025 and d['missed'] == p['holes'] and 0 < d['g1']['facets'] <= 1, d['g1']
assert abs(b['albedo_all'] + (b['lost'] + p['brdf_left'] + b['capped']) / b['rays'] - 1) < 1e-7, (b, p)
if '$f' == 'sample-land': assert p['holes'] > 0 and b['lost'] > 0 and ($k > 1 or p['missing_points'] == 25292), p
if '$run' == 'KautschukInfiniteFocus:4': assert (p['nx'], p['ny'], p['downsample']) == (215, 158, 4), p" && ok ||
            bad "measure $run: $(cat err.txt) $(grep -A1 patch scan.json)"
    done
    "$GGX" microsurface figure --heightfield "$X3P/KautschukInfiniteFocus.x3p" --downsample 8 -n 200 --out k.svg \
        2> /dev/null && grep -q "<svg" k.svg && ok || bad "figure of a scan"
    one_line "a scan too small for a grazing view" "leaves a window of one cell" 2 "$GGX" microsurface measure \
        --heightfield "$X3P/sample-land.x3p" --downsample 4 --view 85,90 -n 100
    one_line "an absurd z scale" "beyond the tracer's single precision" 2 "$GGX" microsurface measure \
        --heightfield "$X3P/KautschukInfiniteFocus.x3p" --z-scale 1e300 --view 30,0 -n 100
fi
"$PY" -c "
import struct
open('nan.pfm', 'wb').write(b'Pf\\n4 4\\n-1.0\\n' + struct.pack('<16f', *[float('nan')] * 16))"
if "$GGX" fit --heightfield nan.pfm --spacing 1 --z-scale 1 2>&1 | grep -q "ggx:"; then
    one_line "a scan of missing points only" "all 4 x 4 heights are missing" 2 "$GGX" microsurface measure \
        --heightfield nan.pfm --spacing 1 --z-scale 1 --view 30,0
fi
printf "0 1\n2 3\n" > two.txt
printf "0 1 2\n2 3 1\n1 0 2\n" > three.txt
one_line "a 2 x 2 scan" "2 x 2 heights: at least 3 x 3 are needed" 2 "$GGX" microsurface measure \
    --heightfield two.txt --spacing 1 --z-scale 1 --view 30,0
one_line "unequal spacings" "equal spacings are needed" 2 "$GGX" microsurface measure --heightfield three.txt \
    --spacing 1,2 --z-scale 1 --view 30,0
one_line "no subcommand" "give a subcommand" 2 "$GGX" microsurface
one_line "bad subcommand" "unknown subcommand 'trace'" 2 "$GGX" microsurface trace
[ ! -e n.x3p ] && [ ! -e n.png ] && ok || bad "a failed generate left a file"

echo "microsurface CLI: $pass passed, $fail failed"
[ $fail -eq 0 ]
