#!/bin/sh
# ggx predict from the command line: the README's line on the public rubber scan (KautschukInfiniteFocus.x3p) gives every file of the
# sheet at its size, a fit near ggx fit's, traced and wave albedos near 1 and a model within its measured distance of
# the trace; the bullet land with its missing points (sample-land.x3p) goes through without wave optics; a generated
# field under the wrapper (valgrind); bad input exits 2 with one line and leaves no folder.
# Usage: predict_cli_test.sh GGX [PNG_INFO]   SPDX-License-Identifier: MIT
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PNG_INFO=${2:-}
. "$ROOT/tests/support/cli_common.sh"
PY=/usr/bin/python3
X3P=$ROOT/tests/data/x3p

"$GGX" predict --help > h.txt && grep -q "usage: ggx predict" h.txt && ok || bad "--help"
png_size() { if [ -n "$PNG_INFO" ]; then "$PNG_INFO" "$1"; else echo "${2:-?}"; fi; }
if [ -z "${GGX_WRAP:-}" ]; then
    # the README's line, run as written from a folder that sees the source tree's tests/: the rubber scan at the
    # defaults, about 15 s, most of it the wave optics
    ln -s "$ROOT/tests" tests
    line=$(sed -n '/^## Fitting a measured surface/,/^## /p' "$ROOT/README.md" | grep '^ggx predict ')
    cmd=$(printf '%s\n' "$line" | sed 's/  *#.*//; s/^ggx /"$GGX" /')
    case $line in *"--out predict"*) ;; *) bad "the README's ggx predict line: '$line'" ;; esac
    if eval "$cmd" > kp.md 2> err.txt && mv predict kp; then
        for f in sheet.pdf sheet.png spheres.png predict.csv predict.json; do
            [ -s "kp/$f" ] && ok || bad "kp/$f missing"
        done
        [ "$(png_size kp/sheet.png '1200 1560')" = "1200 1560" ] && ok || bad "sheet.png $(png_size kp/sheet.png)"
        [ "$(png_size kp/spheres.png '768 256')" = "768 256" ] && ok || bad "spheres.png $(png_size kp/spheres.png)"
        if command -v pdfinfo > /dev/null; then
            pdfinfo kp/sheet.pdf > pi.txt 2>&1 && grep -q "Pages: *1" pi.txt && ok || bad "sheet.pdf: $(cat pi.txt)"
        fi
        [ "$(grep -c '^| [0-9]' kp.md)" -eq 5 ] && [ "$(wc -l < kp/predict.csv)" -eq 21 ] && ok ||
            bad "table: $(cat kp.md) $(wc -l < kp/predict.csv) CSV lines"
        # the fit is ggx fit's (alpha 0.0719, 0.0753; nu 3.49); the rubber's BRDF is near its model (0.20 to 0.22
        # measured) and both optics agree within 0.13 (the wave optics on a 775 x 571 window upsampled 3 times)
        "$PY" - << 'EOF_PY' && ok || bad "predict.json: $(head -c 900 kp/predict.json)"
import json
d = json.load(open("kp/predict.json"))
f = d["fit"]
assert abs(f["alpha"][0] - 0.0719) < 2e-3 and abs(f["alpha"][1] - 0.0753) < 2e-3 and abs(f["nu"] - 3.49) < 0.05, f
assert d["points"] == [860, 634] and abs(d["spacing_um"] - 2.27998) < 1e-3, d["points"]
assert d["traced"]["lost"] == 0 and d["traced"]["left"] < 0.01 * d["traced"]["rays"], d["traced"]
inc = d["incidences"]
assert len(inc) == 20 and [i["theta_i"] for i in inc[::4]] == [0, 20, 40, 60, 75], inc
for i in inc:
    assert 0.96 < i["albedo_traced"] <= 1 and abs(i["albedo_traced_all"] - 1) < 1e-4, i
    assert 0.1 < i["l2_model_traced"] < 0.3, i
    if d["wave"] is not None:
        assert all(0.97 < a <= 1 + 1e-3 for a in i["albedo_wave"]), i
        assert i["l2_traced_wave"] < 0.2, i
EOF_PY
    elif grep -q "not built" err.txt; then
        echo "predict CLI: $(cat err.txt): the scan is not predicted"
    else
        bad "predict of the rubber scan: $(cat err.txt)"
    fi
    # missing points (the land's NaN), no wave optics: the traced rays that fall through the holes are counted; the
    # narrow land's band of heights leaves no window for the rays at 75 degrees, nor at 60 across it: those are null
    if "$GGX" predict --heightfield "$X3P/sample-land.x3p" --downsample 2 -n 20000 --no-wave --size 64 --out land \
        > land.md 2> err.txt; then
        "$PY" -c "
import json; d = json.load(open('land/predict.json'))
t = d['traced']
assert d['wave'] is None and d['missing_share'] > 0.05 and t['lost'] > 0 and 0 < t['untraced_incidences'] < 20, t
assert all(i['albedo_traced'] is not None or i['theta_i'] >= 60 for i in d['incidences']), d['incidences']
assert sum(i['albedo_traced'] is None for i in d['incidences']) == t['untraced_incidences'], d['incidences']" && ok ||
            bad "land: $(head -c 600 land/predict.json)"
    elif ! grep -q "not built" err.txt; then
        bad "predict of the land: $(cat err.txt)"
    fi
fi
# a generated field, small enough for the wrapper: every file written
if "$GGX" microsurface generate --kind beckmann --alpha 0.3 --corr 4 --size 64 --out g.x3p > /dev/null 2> err.txt; then
    "$GGX" predict --heightfield g.x3p -n 2000 --no-wave --size 64 --out small > small.md 2> err.txt &&
        [ -s small/sheet.pdf ] && [ -s small/spheres.png ] && [ -s small/predict.json ] && ok ||
        bad "predict of a generated field: $(cat err.txt)"
elif ! grep -q "not built" err.txt; then
    bad "generate: $(cat err.txt)"
fi
# (outside the wrapper: each run samples the model's 17 lobes, 4.5 million samples, a minute under valgrind)
if [ -z "${GGX_WRAP:-}" ]; then
    # a mirror (zeros): the fit's alpha 1e-4 lobe lies in one cell, which the model's table holds as the trace does
    "$PY" -c "
for y in range(40): print(' '.join(['0'] * 48))" > flat.txt
    "$GGX" predict --heightfield flat.txt --spacing 1 -n 2000 --no-wave --size 64 --out flat > /dev/null 2> err.txt &&
        "$PY" -c "
import json; d = json.load(open('flat/predict.json'))
for i in d['incidences']:
    assert abs(i['albedo_traced'] - 1) < 1e-6 and i['albedo_model'] > 0.99 and i['l2_model_traced'] < 0.05, i" && ok ||
        bad "flat: $(cat err.txt) $(head -c 900 flat/predict.json)"
    # an OpenEXR whose spacing has no unit: --spacing D (micrometres) alone takes its heights in D's unit, as ggx fit
    if "$GGX" microsurface generate --kind beckmann --alpha 0.3 --corr 4 --size 64 --out g.exr > /dev/null 2> err.txt
    then
        "$GGX" predict --heightfield g.exr --spacing 2 -n 2000 --no-wave --size 64 --out e1 > /dev/null 2> err.txt &&
            "$GGX" predict --heightfield g.exr --spacing 2 --z-scale 1 -n 2000 --no-wave --size 64 --out e2 > /dev/null &&
            cmp -s e1/predict.csv e2/predict.csv && ok || bad "OpenEXR with --spacing alone: $(cat err.txt)"
    fi
fi
# bad input: one line, status 2, no folder left
"$PY" -c "print('0 1\n2 3')" > two.txt
one_line "no heightfield" "--heightfield FILE is required" 2 "$GGX" predict
one_line "unknown option" "unknown option" 2 "$GGX" predict --heightfield two.txt --frobnicate
one_line "a 2 x 2 scan" "at least 3 x 3" 2 "$GGX" predict --heightfield two.txt --spacing 1 --out bad1
"$PY" -c "
import struct
open('none.pfm', 'wb').write(b'Pf\n4 4\n-1.0\n' + struct.pack('<16f', *([float('nan')] * 16)))"
one_line "only missing points" "missing" 2 "$GGX" predict --heightfield none.pfm --spacing 1 --out bad2
"$PY" -c "
for y in range(8): print(' '.join(str((x * y) % 5) for x in range(8)))" > eight.txt
one_line "absurd z scale" "" 2 "$GGX" predict --heightfield eight.txt --spacing 1 --z-scale 1e300 --out bad3
one_line "unwritable folder" "" 2 "$GGX" predict --heightfield eight.txt --spacing 1 -n 100 --no-wave --out /proc/ggx-predict
one_line "two sizes" "one number" 2 "$GGX" predict --heightfield eight.txt --spacing 1 --size 100x200 --out bad4
# standard output that cannot be written: the files go with it (all or none; a whole run: outside the wrapper)
if [ -z "${GGX_WRAP:-}" ]; then
    "$GGX" predict --heightfield eight.txt --spacing 1 -n 100 --no-wave --size 64 --out bad5 > /dev/full 2> err.txt
    rc=$?
    [ $rc -eq 2 ] && [ "$(wc -l < err.txt)" -eq 1 ] && ok || bad "stdout full: rc $rc, $(cat err.txt)"
fi
[ ! -e bad1 ] && [ ! -e bad2 ] && [ ! -e bad3 ] && [ ! -e bad4 ] && [ ! -e bad5 ] && ok ||
    bad "a refused run left a folder: $(ls -d bad* 2>/dev/null)"
echo "predict CLI: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
