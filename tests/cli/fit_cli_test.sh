#!/bin/sh
# ggx fit from the command line: a fit of sampled normals recovers the shape, its printed shape syntax runs in another
# command, height fields in text formats, the three output formats, and every malformed input: exit status 2, one
# line on stderr, no output file. Usage: fit_cli_test.sh GGX
# SPDX-License-Identifier: MIT
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd) # for the README
. "$ROOT/tests/support/cli_common.sh"
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }

"$GGX" fit --help > h.txt && grep -q "usage: ggx fit" h.txt && ok || bad "ggx fit --help"
printf 'x,y,z\n0,0\n' > short.csv

# --- normals of a skewed shape, sampled by the command itself, fitted back
"$GGX" sample --sampler stretch -n 20000 --alpha 0.3,0.1 --skew 20,-10 --rotate 40 --seed 7 | cut -d, -f1-3 > n.csv
"$GGX" fit --normals n.csv --format json > fit.json && ok || bad "fit --normals"
a=$(sed -n 's/.*"alpha": \[\([^,]*\), \([^]]*\)\].*/\1 \2/p' fit.json)
s=$(sed -n 's/.*"skew_deg": \[\([^,]*\), \([^]]*\)\].*/\1 \2/p' fit.json)
r=$(sed -n 's/.*"rotate_deg": \([^}]*\)}.*/\1/p' fit.json)
set -- $a $s $r
[ $# -eq 5 ] && near "$1" 0.3 0.01 && near "$2" 0.1 0.004 && near "$3" 20 1 && near "$4" -10 1 && near "$5" 40 1.5 &&
    ok || bad "recovered shape: alpha $a skew $s rotate $r (want 0.3 0.1, 20 -10, 40)"
grep -q '"best": "ellipsoid"' fit.json && ok || bad "skewed normals: best model $(grep best fit.json)"
# the Markdown's shape line is the command's syntax: it runs as is
"$GGX" fit --normals n.csv > fit.md && ok || bad "fit md"
shape=$(sed -n 's/^shape: `\(.*\)`$/\1/p' fit.md)
[ -n "$shape" ] && "$GGX" eval $shape --wi 30,0 --wo 30,180 > eval.csv && ok || bad "pasting '$shape' into ggx eval"
grep -q "| full ellipsoid (skewed GGX: t and Sigma) \*\*best\*\*" fit.md && ok || bad "md model table"
grep -q "p = " fit.md && ok || bad "md goodness of fit"
"$GGX" fit --normals n.csv --format csv --model isotropic --out fit.csv && ok || bad "fit csv --out"
head -1 fit.csv | grep -q "^quantity,value,std_error$" && grep -q "^sigma_xy,0,0$" fit.csv && ok ||
    bad "csv: $(head -3 fit.csv)"

# --figure: a PNG (or SVG) beside the report, both or neither
"$GGX" fit --normals n.csv --out rep.md --figure fig.png && [ -s rep.md ] &&
    [ "$(head -c 8 fig.png | od -An -c | tr -d ' ')" = "211PNG\r\n032\n" ] && ok || bad "--figure PNG"
"$GGX" fit --normals n.csv --figure fig.svg > /dev/null && grep -q "<svg" fig.svg && ok || bad "--figure SVG"
rm -f fig2.png
"$GGX" fit --normals short.csv --figure fig2.png > /dev/null 2>&1; [ ! -e fig2.png ] && ok || bad "figure left by a failure"
# the figure's name says its format, in any case, as plot's --out: another extension is refused before any work, no
# report and no figure written
"$GGX" fit --normals n.csv --figure FIG.PNG > /dev/null && [ "$(head -c 4 FIG.PNG | od -An -c | tr -d ' ')" = "211PNG" ] &&
    ok || bad "--figure FIG.PNG"
for x in jpg gif tiff; do
    rm -f err.txt rep3.md
    "$GGX" fit --normals n.csv --out rep3.md --figure "fig.$x" > /dev/null 2> err.txt
    rc=$?
    [ $rc -eq 2 ] && [ "$(wc -l < err.txt)" -eq 1 ] && grep -q "^ggx: --figure: 'fig.$x' does not name a format" err.txt &&
        [ ! -e "fig.$x" ] && [ ! -e rep3.md ] && ok || bad "--figure fig.$x: rc $rc, $(cat err.txt), $(ls fig.$x rep3.md 2>&1)"
done

# --- a height field as a Gwyddion text export: separable Gaussian random walks (Gaussian slopes: Beckmann)
awk 'BEGIN { srand(3); n = 120; pi = 3.141592653589793
  for (i = 0; i < n; i++) { F[i] = (i ? F[i-1] : 0) + 0.2 * sqrt(-2 * log(1 - rand())) * cos(2 * pi * rand()) }
  for (j = 0; j < n; j++) { G[j] = (j ? G[j-1] : 0) + 0.1 * sqrt(-2 * log(1 - rand())) * cos(2 * pi * rand()) }
  printf "# Channel: Height\n# Width: 120 um\n# Height: 120 um\n# Value units: um\n"
  for (j = 0; j < n; j++) { for (i = 0; i < n; i++) printf "%s%.9g", (i ? " " : ""), F[i] + G[j]; printf "\n" } }' > h.txt
"$GGX" fit --heightfield h.txt --format json > hf.json && ok || bad "fit --heightfield h.txt"
grep -q '"best": "beckmann"' hf.json && ok || bad "Gaussian slopes: $(grep best hf.json)"
grep -q '"used": 56644' hf.json && ok || bad "facets: $(grep used hf.json)"
# the same heights without the header need --spacing (and then take heights in the spacing's unit)
grep -v '^#' h.txt > plain.txt
"$GGX" fit --heightfield plain.txt --spacing 1 --z-scale 1 --format json > plain.json && ok || bad "plain text"
[ "$(grep '"t"' plain.json)" = "$(grep '"t"' hf.json)" ] && ok || bad "header units differ from --spacing 1e-6 and --z-scale 1e-6"

# --- bad input: exit 2, exactly one line on stderr starting with "ggx: ", no output file
expect2() { # description, expected-substring, command...
    desc=$1; want=$2; shift 2
    rm -f err.txt res.md
    "$@" --out res.md > /dev/null 2> err.txt
    rc=$?
    if [ $rc -eq 2 ] && [ "$(wc -l < err.txt)" -eq 1 ] && grep -q "^ggx: .*$want" err.txt && [ ! -e res.md ]; then ok
    else bad "$desc: rc $rc, stderr: $(cat err.txt), res.md $(ls res.md 2>/dev/null)"; fi
}
: > empty.gsf
printf 'Gwyddion Simple Field 1.0\nXRes = 4\nYRes = 4\n\0\0\0\0' > trunc.gsf
printf 'PK\005\006\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0' > empty.x3p
printf '1 2\n3 nan\n' > nan.txt
printf '5\n' > one.txt
printf '0,0,1\n0,0,1\n0,0,1\n0,0,1\n' > four.csv
expect2 "no input" "give one of" "$GGX" fit
expect2 "two inputs" "give one of" "$GGX" fit --normals n.csv --heightfield h.txt
expect2 "missing file" "cannot read" "$GGX" fit --normals missing.csv
expect2 "empty file" "is empty" "$GGX" fit --heightfield empty.gsf
expect2 "truncated gsf" "truncated" "$GGX" fit --heightfield trunc.gsf
expect2 "empty zip" "main.xml" "$GGX" fit --heightfield empty.x3p
expect2 "NaN height" "not a finite number" "$GGX" fit --heightfield nan.txt --spacing 1 --z-scale 1
expect2 "1 x 1 heights" "at least 2 x 2" "$GGX" fit --heightfield one.txt --spacing 1 --z-scale 1
expect2 "no spacing" "no grid spacing" "$GGX" fit --heightfield plain.txt
expect2 "no height unit" "no height unit" "$GGX" fit --heightfield plain.txt --spacing 1
expect2 "zero spacing" "must be positive" "$GGX" fit --heightfield plain.txt --spacing 0 --z-scale 1
expect2 "four normals" "too few usable samples" "$GGX" fit --normals four.csv
expect2 "short CSV line" "not x,y,z" "$GGX" fit --normals short.csv
expect2 "unknown model" "is not ellipsoid" "$GGX" fit --normals n.csv --model beckmann
expect2 "tilt for normals" "apply to --heightfield" "$GGX" fit --normals n.csv --keep-tilt
expect2 "normals as heights" "holds normals" "$GGX" fit --heightfield n.csv
expect2 "bad format" "is not md, csv or json" "$GGX" fit --normals n.csv --format xml
expect2 "downsample too far" "fewer than 2 x 2" "$GGX" fit --heightfield h.txt --downsample 100

# --- an 8-bit normal map of a lobe near its levels' spacing (alpha 0.006, 0.004; levels 2/255 = 0.0078 apart): fitted
# as cells it recovers alpha; the same texels' decoded normals fitted as points overestimate it (the negative control)
PY=$(command -v /usr/bin/python3 || command -v python3)
"$GGX" sample --sampler stretch -n 20000 --alpha 0.006,0.004 --rotate 30 --seed 5 | cut -d, -f1-3 > m8.csv
if [ -z "$PY" ]; then
    echo "fit CLI: no python3, the 8-bit map is not tested"
elif "$PY" "$ROOT/tests/support/fit_png_map.py" m8.csv 200 100 m8.png m8c.csv && "$GGX" fit --normal-map m8.png --format json \
    > m8.json 2> m8.err; then
    a=$(sed -n 's/.*"alpha": \[\([^,]*\), \([^]]*\)\].*/\1 \2/p' m8.json)
    set -- $a
    [ $# -eq 2 ] && near "$1" 0.006 0.0003 && near "$2" 0.004 0.0002 && ok || bad "8-bit map as cells: alpha $a"
    "$GGX" fit --normal-map m8.png | grep -q "each fitted as its cell of normals" && ok || bad "8-bit map: md says cells"
    "$GGX" fit --normals m8c.csv --format json > m8p.json && a=$(sed -n 's/.*"alpha": \[\([^,]*\), \([^]]*\)\].*/\1 \2/p' m8p.json)
    set -- $a
    [ $# -eq 2 ] && ! near "$2" 0.004 0.0008 && ok || bad "decoded centres as points: alpha $a, not inflated"
elif grep -q "not built" m8.err; then
    echo "fit CLI: PNG support is off, the 8-bit map is not tested"
else
    bad "8-bit map: $(cat m8.err)"
fi

# the README's fitting commands, run as written (the first ```sh block of "Fitting a measured surface"; its ggx
# predict line is predict_cli_test.sh's)
sed -n '/^## Fitting a measured surface/,/^## /p' "$ROOT/README.md" | awk '/^```sh/ { on = 1; next } /^```/ { if (on) exit } on' |
    grep '^ggx ' > cmds.txt
[ "$(wc -l < cmds.txt)" -ge 3 ] && ok || bad "README fit commands not found"
while IFS= read -r line; do
    cmd=$(printf '%s\n' "$line" | sed 's/  *#.*//; s/^ggx /"$GGX" /')
    eval "$cmd" > readme_out.txt 2>&1 && ok || bad "README line '$line': $(tail -2 readme_out.txt)"
done < cmds.txt
[ -s fit.png ] && grep -q "ellipsoid" readme_out.txt && ok || bad "README fit: no figure or no report"

# --- a fit held at the smallest roughness with its lobe away from n: the printed shape line (run by ggx eval) has
# the printed t and Sigma's D at the peak, 1 / (pi sqrt(det Sigma) cos^4), and no alpha below 1e-4
awk 'BEGIN { for (i = 0; i < 200; i++) { x = 0.5 + (i % 7) * 1e-9; y = 0.2 + (i % 5) * 1e-9; l = sqrt(x * x + y * y + 1)
             printf "%.17g,%.17g,%.17g\n", x / l, y / l, 1 / l } }' > tilt.csv
if "$GGX" fit --normals tilt.csv > tilt.md; then
    line=$(sed -n 's/^shape: `\(.*\)`$/\1/p' tilt.md)
    v() { awk -F'|' -v k="$1" '$2 == " " k " " { gsub(/ /, "", $3); print $3 }' tilt.md; }
    tx=$(v t_x) ty=$(v t_y) sxx=$(v sigma_xx) sxy=$(v sigma_xy) syy=$(v sigma_yy)
    peak=$(awk -v x="$tx" -v y="$ty" 'BEGIN { printf "%.9g,%.9g,1\n", -x, -y }')
    grep -q "held at the smallest roughness" tilt.md && [ -n "$line" ] && [ -n "$syy" ] &&
        "$GGX" eval $line --wi "$peak" --wo "$peak" > tilt.out &&
        awk -F, -v a="$sxx" -v b="$sxy" -v c="$syy" -v tx="$tx" -v ty="$ty" -v line="$line" 'NR == 2 {
            c2 = 1 / (1 + tx * tx + ty * ty); want = 1 / (3.14159265358979 * sqrt(a * c - b * b) * c2 * c2)
            split(line, w, /[ ,]/); d = $10 / want - 1; if (d < 0) d = -d
            exit !(d < 1e-3 && w[2] >= 1e-4 && w[3] >= 1e-4) }' tilt.out && ok ||
        bad "a clamped fit's shape line, t and Sigma are not one shape: $line; t $tx $ty; Sigma $sxx $sxy $syy: $(cat tilt.out)"
else
    bad "fit of equal tilted normals"
fi
# a subnormal height is a finite number
printf '0 1e-310 0 0\n1 0 1 0\n0 1 0 1\n1 0 0 0\n' > subh.txt
"$GGX" fit --heightfield subh.txt --spacing 1 --z-scale 1 > /dev/null 2> err.txt && ok ||
    bad "a subnormal height: $(cat err.txt)"
# a negative weight and a spacing beyond the doubles over the height unit are named
printf '0,0,1,1\n0.1,0,1,-1\n0,0.1,1,1\n0.1,0.1,1,1\n0.2,0,1,1\n0,0.2,1,1\n' > negw.csv
one_line "negative weight" "the weight of normal 2 is negative (-1)" 2 "$GGX" fit --normals negw.csv
printf '0 1 0\n1 0 1\n0 1 0\n' > h3.txt
one_line "spacing over z-scale overflows" "beyond the range of a double" 2 "$GGX" fit --heightfield h3.txt \
    --spacing 1e308 --z-scale 0.5

# --- odd inputs (tests/support/fit_odd_inputs.py): W x 1 and 1 x H normal maps alike, 8- and 16-bit maps below the
# plane refused alike, one absurd height left out of the levelling, damaged x3p archives refused in one line, and the
# public x3p files of tests/data/x3p fitted (the point cloud and the one with a stale MD5 refused)
if [ -n "$PY" ] && "$PY" "$ROOT/tests/support/fit_odd_inputs.py"; then
    "$GGX" fit --normal-map row.png --format csv > row.csv && "$GGX" fit --normal-map column.png --format csv > col.csv &&
        ok || bad "64 x 1 and 1 x 64 normal maps"
    expect2 "8-bit map below the plane" "too few usable samples" "$GGX" fit --normal-map below8.png
    expect2 "16-bit map below the plane" "too few usable samples" "$GGX" fit --normal-map below16.png
    "$GGX" fit --heightfield absurd.txt --spacing 1 --z-scale 1 --format json > absurd.json &&
        grep -q '"used": 6068' absurd.json && ok || bad "one absurd height: $(grep used absurd.json)"
    expect2 "--z-scale 1e308" "slopes beyond the range of a double" "$GGX" fit --heightfield h3.txt --spacing 100 \
        --z-scale 1e308
    "$GGX" fit --heightfield good.x3p --format csv > /dev/null && ok || bad "written x3p"
    expect2 "truncated x3p" "zip" "$GGX" fit --heightfield truncated.x3p
    expect2 "x3p CRC" "CRC" "$GGX" fit --heightfield crc.x3p
    expect2 "x3p main.xml MD5" "main.xml's MD5 is" "$GGX" fit --heightfield md5.x3p
    expect2 "x3p data MD5" "MD5ChecksumPointData" "$GGX" fit --heightfield datamd5.x3p
    expect2 "x3p lying sizes" "holds 128 bytes, not the 160" "$GGX" fit --heightfield lying.x3p
    expect2 "x3p profile" "is a profile" "$GGX" fit --heightfield profile.x3p
else
    echo "fit CLI: no python3, the odd inputs are not tested"
fi
for f in ISO5436-sample1 ISO5436-sample1_bin ISO5436-sample3 ISO5436-sample4 ISO5436-sample4_bin \
    KautschukInfiniteFocus sample-land pyramid testing; do
    "$GGX" fit --heightfield "$ROOT/tests/data/x3p/$f.x3p" --format csv > x3p.csv && grep -q "^alpha_x," x3p.csv && ok ||
        bad "public $f.x3p"
done
# the tails of a real scan: the Alicona rubber's slopes are lighter-tailed than GGX's (the flatter peak that made GGX's
# goodness of fit p = 0), many standard errors from nu = 2, in Markdown and JSON; the figure (1100 x 1580: with the
# profile); a synthetic pyramid's nu at the range's end, in Markdown and CSV
# (two fits of 2 million facets: under valgrind the public files' loop above runs the same code on this scan)
if [ -z "${GGX_WRAP:-}" ]; then
    "$GGX" fit --heightfield "$ROOT/tests/data/x3p/KautschukInfiniteFocus.x3p" --figure k.png > k.md &&
        nu=$(sed -n 's/^tails: .* fit nu = \([0-9.]*\) +- \([0-9.e-]*\) .*lighter tails.*/\1 \2/p' k.md) && set -- $nu &&
        [ $# -eq 2 ] && awk -v n="$1" -v e="$2" 'BEGIN { exit !(n > 2 + 20 * e && n < 10) }' &&
        [ "$(od -An -tu1 -j16 -N8 k.png | tr -s " ")" = " 0 0 4 76 0 0 6 44" ] && ok ||
        bad "Kautschuk tails line / figure: $(grep tails k.md)"
    "$GGX" fit --heightfield "$ROOT/tests/data/x3p/KautschukInfiniteFocus.x3p" --format json > k.json &&
        grep -q '"tails": {"nu": 3\.[0-9]*, "nu_std_error": 0\.0' k.json && ok || bad "Kautschuk JSON tails"
fi
"$GGX" fit --heightfield "$ROOT/tests/data/x3p/pyramid.x3p" > p.md && grep -q "^tails: .* at the end of its range" p.md &&
    "$GGX" fit --heightfield "$ROOT/tests/data/x3p/pyramid.x3p" --format csv > p.csv && grep -q "^nu,10000,nan$" p.csv &&
    ok ||
    bad "pyramid: nu at its range's end"
expect2 "public point cloud" "is a point cloud" "$GGX" fit --heightfield "$ROOT/tests/data/x3p/ISO5436-sample2.x3p"
expect2 "public stale MD5" "main.xml's MD5 is" "$GGX" fit --heightfield "$ROOT/tests/data/x3p/csafe-logo.x3p"

echo "fit CLI: $pass passed, $fail failed"
[ $fail -eq 0 ]
