#!/bin/sh
# ggx render --normal-map: the rendered ground truth of the filter on the synthetic maps shipped in
# tests/data/normal_maps (regenerated here and compared byte for byte). Level 0 of our chain is the truth exactly,
# a constant tilted map is filtered exactly at every level, and on the bump, scratch and sawtooth maps our RMSE is
# below every engine filter's at every level; the figure is written; bad input exits 2 with one line and no file.
# Prints the tables. Usage: render_mip_test.sh GGX   SPDX-License-Identifier: MIT
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
MAPS=$ROOT/tests/data/normal_maps
. "$ROOT/tests/support/cli_common.sh"
PY=/usr/bin/python3

mkdir fresh && "$PY" "$MAPS/make_maps.py" fresh && ok || bad "make_maps.py"
for m in bumps checker scratches sawtooth; do
    cmp -s "fresh/$m.png" "$MAPS/$m.png" && ok || bad "$m.png differs from what make_maps.py writes"
done
# rows of the first table (against the model's truth): "| level | size | ours | fast | none | Toksvig | variance |
# unskewed |"; awk fields: $2 level, $4 ours, $5 fast, $6 none, $7 Toksvig, $8 variance, $9 unskewed
table() { awk '/^\| [0-9]/ { print } /^$/ && n++ >= 1 { exit }' "$1"; }
if "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1 --out bumps.png > bumps.txt 2> err.txt; then
    for m in bumps checker scratches sawtooth; do
        [ "$m" = bumps ] || "$GGX" render --normal-map "$MAPS/$m.png" --alpha 0.1 --out "$m.png" > "$m.txt" ||
            bad "$m: $(cat err.txt)"
        echo "$m, alpha 0.1:"
        table "$m.txt"
        table "$m.txt" | awk -F'|' '$2 + 0 == 0 { exit !($4 + 0 == 0 && $5 + 0 == 0) }' && ok ||
            bad "$m: level 0 of the chain is not the truth"
        [ "$(grep -c '^| 0 ' "$m.txt")" -eq 2 ] && grep '^| 0 ' "$m.txt" | tail -1 |
            awk -F'|' '{ exit !($6 + 0 == 0) }' && ok || bad "$m: no filtering at level 0 is not the engines' truth"
        [ -s "$m.png" ] && ok || bad "$m: no figure"
    done
    for m in bumps scratches sawtooth; do
        table "$m.txt" | awk -F'|' '$2 + 0 > 0 && !($4 < $6 && $4 < $7 && $4 < $8) { bad = 1 } END { exit bad }' &&
            ok || bad "$m: an engine filter is below ours: $(table "$m.txt")"
    done
    # the bimodal checker: no single lobe is near the two tilts; ours is within 15 % of the best engine filter
    table checker.txt | awk -F'|' '$2 + 0 >= 2 { b = $7 < $8 ? $7 : $8; if (!($4 < 1.15 * b && $4 < $6)) bad = 1 }
        END { exit bad }' && ok || bad "checker: $(table checker.txt)"
    # a constant tilted map, 12 x 10 texels (not a power of two): every level exact, the engines' filters not
    "$PY" - <<'EOF_PY'
import struct, zlib
n = (0.3, -0.2, (1 - 0.13) ** 0.5)
raw = b"".join(b"\0" + b"".join(struct.pack(">HHH", *[round((c + 1) / 2 * 65535) for c in n]) for i in range(12))
               for j in range(10))
ch = lambda k, b: struct.pack(">I", len(b)) + k + b + struct.pack(">I", zlib.crc32(k + b) & 0xFFFFFFFF)
open("const.png", "wb").write(b"\x89PNG\r\n\x1a\n" + ch(b"IHDR", struct.pack(">IIBBBBB", 12, 10, 16, 2, 0, 0, 0)) +
                              ch(b"IDAT", zlib.compress(raw)) + ch(b"IEND", b""))
grey = b"".join(b"\0" + bytes([51] * 12) for j in range(10))
open("rough.png", "wb").write(b"\x89PNG\r\n\x1a\n" + ch(b"IHDR", struct.pack(">IIBBBBB", 12, 10, 8, 0, 0, 0, 0)) +
                              ch(b"IDAT", zlib.compress(grey)) + ch(b"IEND", b""))
EOF_PY
    "$GGX" render --normal-map const.png --alpha 0.2 --level 2 --out const_fig.png > const.txt &&
        [ "$(table const.txt | wc -l)" -eq 5 ] &&
        table const.txt | awk -F'|' '!($4 + 0 < 1e-4 && $5 + 0 < 1e-4 && $6 + 0 > 0.01) { bad = 1 } END { exit bad }' &&
        ok || bad "constant map: $(cat const.txt)"
    # a roughness map of 51 / 255 = 0.2 everywhere is --alpha 0.2
    "$GGX" render --normal-map const.png --roughness-map rough.png --level 2 --out rough_fig.png > rough.txt &&
        [ "$(table rough.txt)" = "$(table const.txt)" ] && ok || bad "roughness map: $(cat rough.txt)"
    # one light and eye: the table is for that pair
    "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1 --light point:30,90 --view 10,0 --level 1 --out one.png \
        > one.txt && grep -q "at the given light and eye" one.txt && ok || bad "--light, --view: $(head -1 one.txt)"
    # rough lobes beyond alpha 1, where Toksvig and variance widening leave alpha as it is
    "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 5 --level 1 --out a5.png > a5.txt && ok ||
        bad "alpha 5: $(cat a5.txt)"
    # the figure on standard output, the table on standard error
    "$GGX" render --normal-map "$MAPS/checker.png" --alpha 0.1 --out - > fig_stdout.png 2> tab.txt &&
        [ "$(head -c 4 fig_stdout.png | od -An -c | tr -d ' ')" = "211PNG" ] && grep -q "^| 0 " tab.txt && ok ||
        bad "--out -: $(head -c 80 fig_stdout.png | od -c | head -2)"
    one_line "not a png" "give a .png name" 2 "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1 --out none.exr
    one_line "eye on the horizon" "--view" 2 "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1 --view 90,0 \
        --out none.png
    one_line "level too deep" "levels 0 to 6" 2 "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1 --level 7 \
        --out none.png
    one_line "eye below the plane" "--view" 2 "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1 --view 100,0 \
        --out none.png
    one_line "light below the plane" "--light" 2 "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1 \
        --light point:95,0 --out none.png
    # --light as ggx render takes it: an irradiance scales the truth and the levels alike (the same table); the
    # direction alone, without point:, is no light
    "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1 --light point:30,90,2.5 --view 10,0 --level 1 \
        --out one_e.png > one_e.txt && [ "$(table one_e.txt)" = "$(table one.txt)" ] && ok ||
        bad "--light point:30,90,2.5: $(head -3 one_e.txt)"
    one_line "light without point:" "point:THETA,PHI" 2 "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1 \
        --light 30,90 --out none.png
    one_line "light of one angle" "point:THETA,PHI" 2 "$GGX" render --light point:30 --size 64 --out none.png
    one_line "no roughness" "give the base roughness" 2 "$GGX" render --normal-map "$MAPS/bumps.png" --out none.png
    one_line "anisotropic alpha" "isotropic" 2 "$GGX" render --normal-map "$MAPS/bumps.png" --alpha 0.1,0.2 \
        --out none.png
    one_line "roughness map of another size" "12 x 10 texels, the normal map 64 x 64" 2 "$GGX" render \
        --normal-map "$MAPS/bumps.png" --roughness-map rough.png --out none.png
    [ ! -e none.png ] && [ ! -e none.exr ] && ok || bad "a failed render left its figure"
elif grep -q "not built" err.txt; then
    echo "render --normal-map: PNG support is off, the maps are not tested"
else
    bad "render --normal-map: $(cat err.txt)"
fi

echo "render --normal-map: $pass passed, $fail failed"
[ $fail -eq 0 ]
