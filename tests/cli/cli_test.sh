#!/bin/sh
# CLI tests: every subcommand on defaults, outputs parsed back (CSV columns, PNG decoded with the expected size, SVG
# well-formed with the expected size, PDF pages and page size by pdfinfo), `ggx check` failing on a deliberately wrong sampler, and every bad-input case: exit status
# 2, one line on stderr naming the problem, no partial file. Usage: cli_test.sh GGX PNG_INFO
# GGX_WRAP runs every ggx under a wrapper (make valgrind); GGX_CLI_QUICK=1 uses small sample counts there.
set -u
PNG_INFO=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
ROOT=$(cd "$(dirname "$0")/../.." && pwd) # for include/ggx/ggx_samplers.h, the sampler registry
N=""
[ "${GGX_CLI_QUICK:-0}" = 1 ] && N="-n 20000"
. "$ROOT/tests/support/cli_common.sh"

# --- every subcommand on defaults
"$GGX" --help > help.txt && grep -q "commands:" help.txt && ok || bad "ggx --help"
for c in demo eval sample plot check audit; do
    "$GGX" $c --help > h.txt 2>&1 && grep -q "usage: ggx $c" h.txt && ok || bad "ggx $c --help"
done
"$GGX" demo $N > demo.txt 2>&1 && ok || bad "ggx demo: $(tail -3 demo.txt)"
grep -q "all checks pass" demo.txt && ok || bad "demo summary"
# --out - is standard output, which holds no folder of figures: refused before anything is drawn
one_line "demo --out -" "'-' is standard output" 2 "$GGX" demo --out -
[ ! -e ./- ] && ok || bad "demo --out - made a folder named -"
# the demo's figures: each seed figure for both shapes, at 640 wide and each figure's own height
svg_size() { xmllint --xpath 'concat(/*[local-name()="svg"]/@width, " ", /*[local-name()="svg"]/@height)' "$1" 2>/dev/null; }
for p in "" skewed-; do
    for f in grid-top.svg:640pt:640pt grid-side.svg:640pt:435pt vndf-75-0-grid-top.svg:640pt:640pt \
             vndf-75-0-grid-side.svg:640pt:435pt vndf-75-90-grid-top.svg:640pt:640pt vndf-75-90-grid-side.svg:640pt:435pt \
             g1.svg:640pt:397pt lambda.svg:640pt:397pt ndf-slice.svg:640pt:397pt furnace.svg:640pt:397pt; do
        n=${f%%:*} wh=${f#*:}
        xmllint --noout "out/$p$n" && [ "$(svg_size "out/$p$n")" = "${wh%%:*} ${wh#*:}" ] && ok ||
            bad "demo $p$n: not well-formed XML or not ${wh%%:*} x ${wh#*:}: $(svg_size "out/$p$n")"
    done
    for f in ndf-top:550 ndf-side:397 vndf-75-0-top:550 vndf-75-0-side:397 vndf-75-90-top:550 vndf-75-90-side:397; do
        [ "$("$PNG_INFO" "out/$p${f%%:*}.png")" = "640 ${f#*:}" ] && ok || bad "demo $p${f%%:*}.png size $("$PNG_INFO" "out/$p${f%%:*}.png")"
    done
done
[ "$("$PNG_INFO" out/spheres.png)" = "640 248" ] && ok || bad "demo spheres.png size $("$PNG_INFO" out/spheres.png)"
pdftotext -f 17 -l 17 out/figures.pdf - | grep -q "the material, lit" && ok || bad "figures.pdf: no page of lit spheres"
pdfinfo out/figures.pdf > pdf.txt && grep -q "^Pages: *17$" pdf.txt && grep -q "^Page size: *842 x 595 pts" pdf.txt && ok ||
    bad "demo figures.pdf: $(cat pdf.txt)"
# the pages name the seeds (docs/references.md), in their order (Elliptic Stretch's four figures, then the VNDF
# proof's eight)
pdftotext out/figures.pdf - | grep -o "Seed [a-z0-9-]*," | uniq -c | awk '{ print $1, $3 }' | tr '\n' ' ' > seeds.txt
[ "$(cat seeds.txt)" = "4 engstad-stretch, 8 engstad-vndf-proof, " ] && ok || bad "figures.pdf seed order: $(cat seeds.txt)"

"$GGX" eval > eval.csv && ok || bad "ggx eval"
[ "$(wc -l < eval.csv)" -eq 5 ] && [ "$(awk -F, 'NR > 1 && NF != 19 { n++ } END { print n + 0 }' eval.csv)" -eq 0 ] &&
    head -1 eval.csv | grep -q '^wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h_x,h_y,h_z,D,' && ok || bad "eval CSV shape"
"$GGX" eval --wi 30,0 --wo 0.1,0.2,0.97 --eta 1.5 --fresnel conductor:0.2,3.9 --format json > eval.json &&
    grep -q '"bsdf"' eval.json && ok || bad "eval JSON"
# albedo: alpha = 1 has closed forms, 2 (1 - ln 2) / (1 + cos theta) and 1 - mu ln(1 + 1 / mu); E_avg 4 (1 - ln 2)^2
"$GGX" albedo --alpha 1 > alb.csv && [ "$(wc -l < alb.csv)" -eq 16 ] &&
    head -1 alb.csv | grep -qx 'view_theta_deg,view_phi_deg,E,E_height_correlated,E_avg,E_avg_height_correlated' &&
    awk -F, 'NR > 1 { mu = cos($1 * 3.14159265358979 / 180); a = 2 * (1 - log(2)) / (1 + mu); b = 1 - mu * log(1 + 1 / mu)
                      c = 4 * (1 - log(2))^2; if ((a - $3)^2 > 1e-16 || (b - $4)^2 > 1e-16 || (c - $5)^2 > 1e-16) e++ } END { exit e > 0 }' alb.csv &&
    ok || bad "albedo CSV against the closed forms at alpha = 1"
"$GGX" albedo --alpha 0.3 --view 60,30 --rotate 20 --format json > alb.json && grep -q '"E_avg_height_correlated"' alb.json &&
    [ "$(grep -c view_theta_deg alb.json)" -eq 1 ] && ok || bad "albedo JSON, one view"
# albedo --eta: at eta = 1 nothing is reflected and T = G1(v) = 2 / (1 + sqrt(1 + alpha^2 tan^2 theta)); by default
# ten views from both sides, each R + T in (0, 1]
"$GGX" albedo --alpha 0.3 --eta 1 --view 60,0 > ad.csv && head -1 ad.csv | grep -qx 'view_theta_deg,view_phi_deg,R,T,R_plus_T' &&
    awk -F, 'NR == 2 { g = 2 / (1 + sqrt(1 + 0.09 * 3)); if ($3 > 1e-12 || (g - $4)^2 > 1e-12) e++ } END { exit e > 0 }' ad.csv &&
    ok || bad "albedo --eta 1 against T = G1"
"$GGX" albedo --alpha 0.2,0.5 --eta 1.5 > ad.csv && [ "$(wc -l < ad.csv)" -eq 11 ] &&
    awk -F, 'NR > 1 { if (!($5 > 0 && $5 <= 1) || ($3 + $4 - $5)^2 > 1e-18) e++; if ($1 > 90) below++ } END { exit (e > 0 || below != 5) }' ad.csv &&
    ok || bad "albedo --eta 1.5, both sides"
"$GGX" sample > s.csv && [ "$(wc -l < s.csv)" -eq 1001 ] &&
    awk -F, 'NR > 1 { if (NF != 5 || $4 <= 0) e++; l = $1*$1 + $2*$2 + $3*$3; if (l < 0.999999 || l > 1.000001) e++ } END { exit e > 0 }' s.csv &&
    ok || bad "sample CSV (5 columns, unit vectors, pdf > 0)"
"$GGX" sample --sampler bsdf --view 30,0,-1 -n 500 --format f32 --out s.f32 && [ "$(wc -c < s.f32)" -eq 10000 ] && ok || bad "sample f32"
# f32 to stdout (a pipe, or --out -) streams; to a terminal it is refused (script(1) gives the command a terminal)
[ "$("$GGX" sample -n 7 --format f32 | wc -c)" -eq 140 ] && [ "$("$GGX" sample -n 7 --format f32 --out - | wc -c)" -eq 140 ] &&
    ok || bad "sample f32 to stdout"
script -qec "$GGX_BIN sample -n 3 --format f32" /dev/null > tty.txt; rc=$?
[ $rc = 2 ] && grep -q "^ggx: --format f32 is binary" tty.txt && ok || bad "f32 to a terminal: rc $rc, $(cat tty.txt)"
# progress: a bar on a terminal for long runs, nothing when stderr is not a terminal or with --no-progress
PN=1048576
script -qec "$GGX_BIN sample -n $PN --out /dev/null" /dev/null > tty.txt &&
    [ "$(tr '\r' '\n' < tty.txt | grep -c '^  caps  .*%')" -ge 10 ] && tr '\r' '\n' < tty.txt | grep -q '\] 100%' &&
    ok || bad "sample progress on a terminal: $(tail -c 200 tty.txt)"
script -qec "$GGX_BIN sample -n $PN --no-progress --out /dev/null" /dev/null > tty.txt && [ ! -s tty.txt ] &&
    ok || bad "sample --no-progress: $(tail -c 200 tty.txt)"
"$GGX" sample -n $PN --format f32 --out /dev/null 2> err.txt && [ ! -s err.txt ] && ok || bad "sample progress without a terminal"
"$GGX" sample -n 1000 --progress --out /dev/null 2> err.txt && [ ! -s err.txt ] && ok || bad "progress on a short run"
"$GGX" sample --sampler brdf --alpha 0.3 --skew 10,5 -n 200 --seed 7 --out b.csv && [ "$(wc -l < b.csv)" -eq 201 ] && ok || bad "sample brdf"
"$GGX" plot 2> plot.err && [ "$("$PNG_INFO" ndf.png)" = "640 550" ] && ok || bad "plot defaults"
"$GGX" plot --figure vndf-side --view 60,45 --log --size 256 --out v.png && [ "$("$PNG_INFO" v.png)" = "256 159" ] && ok || bad "plot vndf-side"
"$GGX" plot --figure grid --sampler caps --view 70,0 --skew 15,0 --out g.svg && xmllint --noout g.svg && ok || bad "plot grid"
# --size W x H is honoured exactly in every format; the format follows the file name
"$GGX" plot --figure vndf --size 300x500 --theme dark --out d.png 2>/dev/null && [ "$("$PNG_INFO" d.png)" = "300 500" ] && ok || bad "plot --size 300x500"
"$GGX" plot --figure grid-side --size 333x222 --out gs.svg 2>/dev/null && [ "$(svg_size gs.svg)" = "333pt 222pt" ] && ok || bad "plot --size svg: $(svg_size gs.svg)"
"$GGX" plot --figure g1 --size 500x300 --out g1.pdf 2>/dev/null && pdfinfo g1.pdf | grep -q "^Page size: *500 x 300 pts" && ok || bad "plot --size pdf"
for fig in ndf ndf-side vndf vndf-side grid grid-side g1 lambda ndf-slice furnace polar slice; do
    "$GGX" plot --figure $fig --skew 20,-10 --rotate 30 --size 200 --out "f-$fig.pdf" 2>/dev/null && pdfinfo "f-$fig.pdf" | grep -q "^Pages: *1$" &&
        ok || bad "plot --figure $fig as PDF"
done
"$GGX" plot --figure furnace 2>/dev/null && xmllint --noout furnace.svg && ok || bad "plot line figure defaults to SVG"
# extensions in any case, the same in every subcommand (render's below)
"$GGX" plot --size 200 --out UP.PNG 2>/dev/null && [ "$("$PNG_INFO" UP.PNG)" = "200 172" ] && ok || bad "plot --out UP.PNG"
"$GGX" plot --figure g1 --size 200 --out UP.Svg 2>/dev/null && xmllint --noout UP.Svg && ok || bad "plot --out UP.Svg"
"$GGX" plot --figure polar --eta 1.5 --size 500 --out pb.png 2>/dev/null && [ "$("$PNG_INFO" pb.png)" = "500 350" ] && ok ||
    bad "plot --figure polar --eta: $("$PNG_INFO" pb.png)"
"$GGX" plot --figure slice --phi-d 45 2>/dev/null && [ "$("$PNG_INFO" slice.png)" = "640 525" ] && ok || bad "plot --figure slice defaults to PNG: $("$PNG_INFO" slice.png)"
"$GGX" plot --figure ndf --eta 1.5 --out no.png 2>err.txt; [ $? -eq 2 ] && [ ! -e no.png ] && grep -q "eta is for --figure polar" err.txt &&
    ok || bad "plot --eta on another figure: $(cat err.txt)"
"$GGX" check ${N:--n 200000} > check.txt && grep -q "all pass" check.txt && ok || bad "check defaults: $(cat check.txt)"
if [ "${GGX_CLI_QUICK:-0}" = 1 ]; then # 16 chi-square runs of 10^6 samples: minutes under valgrind
    "$GGX" audit --help > audit.txt && ok || bad "audit --help"
else
    # The one audit of the tier: the line of docs/cli.md's Examples, three files from one run. docs/audit.md is the
    # command's output on its defaults, byte for byte; its rows are numbered 1 to the number of claims, which the
    # other formats must match (tests/unit/test_audit.c lists the claims and asserts the count)
    AUDIT_LINE='ggx audit --out audit.md --out audit.csv --out audit.json'
    "$GGX" audit --out audit.md --out audit.csv --out audit.json && CLAIMS=$(grep -c '^| [0-9]' audit.md) &&
        [ "$CLAIMS" -gt 0 ] && [ "$(grep '^| [0-9]' audit.md | tail -1 | cut -d' ' -f2)" = "$CLAIMS" ] &&
        grep -q 'fails' audit.md && cmp -s audit.md "$ROOT/docs/audit.md" &&
        ok || bad "audit: docs/audit.md is not ggx audit's output: $(diff audit.md "$ROOT/docs/audit.md" | head -5)"
    # JSON: a list of the claims, each naming its seeds by their short names and giving three verdicts from the
    # vocabulary
    CLAIMS=$CLAIMS /usr/bin/python3 -c '
import json, os
rows = json.load(open("audit.json"))
words = {"holds", "holds with a correction", "fails", "not claimed"}
seeds = {"walter-ellipsoid", "engstad-stretch", "engstad-vndf-proof", "ellipsoidal-ggx-1", "ellipsoidal-ggx-2"}
assert len(rows) == int(os.environ["CLAIMS"]), len(rows)
for r in rows:
    assert set(r["seed"].split(", ")) <= seeds and len(r["verdicts"]) == 3, r
    assert all(v["verdict"] in words and v["evidence"] for v in r["verdicts"]), r
' && ok || bad "audit json"
    # CSV: a header row, one row per claim and shape, every row naming a seed, the shapes labelled
    head -1 audit.csv | grep -qx 'id,seed,where,scope,claim,shape,verdict,evidence' &&
        [ "$(tail -n +2 audit.csv | grep -Ec '^"[a-z0-9-]*","(walter-ellipsoid|engstad-stretch|engstad-vndf-proof|ellipsoidal-ggx-[12])')" -eq $((3 * CLAIMS)) ] &&
        grep -q '"rotated A (0.3, 0.6; theta_z 28.65 deg)"' audit.csv && grep -q '"skewed A (0.3, 0.6; 22.92, -17.19, 28.65 deg)"' audit.csv &&
        ok || bad "audit csv: $(head -3 audit.csv)"
fi

# --- the samplers of the command are the registry's (in its order) and wrong-s, nothing else. The registry's list
# comes from a program built on include/ggx/ggx_samplers.h alone (its X-macro), the command's from its help.
cat > registry.c <<'EOF_C'
#include <stdio.h>
#include "ggx/ggx_samplers.h"
#define ROW(ID, name, stem, family, domain, inverse, batch, help) printf("%s %s %s\n", name, #family, #domain);
int main(void)
{
    printf("count %d\n", GGX_SAMPLER_COUNT);
    GGX_SAMPLER_LIST(ROW)
    return 0;
}
EOF_C
if ${CC:-cc} -std=c11 -I"$ROOT/include" registry.c -o registry 2> cc.txt && ./registry > registry.txt; then ok; else
    bad "cannot build the registry lister: $(cat cc.txt)"; fi
count=$(awk '$1 == "count" { print $2 }' registry.txt)
awk 'NF == 3 { print $1 }' registry.txt > reg-names.txt
"$GGX" sample --help | awk '/^samplers:/ { on = 1; next } on && NF == 0 { exit } on { print $1 }' > help-names.txt
[ "$(wc -l < help-names.txt)" -eq $((count + 1)) ] && ok ||
    bad "ggx sample --help lists $(wc -l < help-names.txt) samplers, the registry has $count (+ wrong-s)"
{ cat reg-names.txt; echo wrong-s; } | cmp -s - help-names.txt && ok ||
    bad "ggx sample --help samplers $(tr '\n' ' ' < help-names.txt)differ from the registry's $(tr '\n' ' ' < reg-names.txt)+ wrong-s"
"$GGX" check --help | awk '/^samplers:/ { on = 1; next } on && NF == 0 { exit } on { print $1 }' | cmp -s - help-names.txt &&
    ok || bad "ggx check --help lists other samplers than ggx sample --help"
while read -r name; do
    "$GGX" sample --sampler "$name" -n 20 > one.csv 2> err.txt && [ "$(wc -l < one.csv)" -eq 21 ] && [ ! -s err.txt ] &&
        ok || bad "ggx sample --sampler $name -n 20: $(cat err.txt)"
done < help-names.txt
# every sampler of normals of the registry is checked by ggx check (unskewed defaults) and by ggx demo, by name
awk 'NF == 3 && $2 != "DIRECTION" { print $1 }' registry.txt | while read -r name; do
    grep -q "^$name " check.txt || echo "ggx check does not check $name"
    [ "$(grep -c "^$name " demo.txt)" -ge 1 ] || echo "ggx demo does not check $name"
done > missing.txt
[ ! -s missing.txt ] && ok || bad "$(cat missing.txt)"
# a sampler for unskewed shapes given a skewed one: a usage error (exit 2, one line on stderr, nothing on stdout)
awk 'NF == 3 && $3 == "UNSKEWED" { print $1 }' registry.txt | while read -r name; do
    for c in sample check; do
        "$GGX" $c --sampler "$name" --skew 20,0 -n 20 > out.txt 2> err.txt
        rc=$?
        [ $rc -eq 2 ] && [ "$(wc -l < err.txt)" -eq 1 ] && grep -q "^ggx: .*unskewed" err.txt && [ ! -s out.txt ] ||
            echo "ggx $c --sampler $name --skew 20,0: rc $rc, stderr: $(cat err.txt), stdout: $(head -c 80 out.txt)"
    done
done > domain.txt
[ ! -s domain.txt ] && ok || bad "$(cat domain.txt)"

# --- ggx check rejects a deliberately wrong sampler on a skewed shape (exit 1), accepts it when unskewed
"$GGX" check --sampler wrong-s --skew 20,-15 ${N:--n 200000} > wrong.txt; [ $? -eq 1 ] && grep -q FAILED wrong.txt && ok || bad "check wrong-s must fail"
"$GGX" check --sampler wrong-s ${N:--n 200000} > wrong0.txt; [ $? -eq 0 ] && ok || bad "wrong-s is right when unskewed"
[ -z "$(ls chi2_*.csv 2>/dev/null)" ] && ok || bad "ggx check left files in the working folder"

# --- ggx render: sizes and formats, and its bad input
"$GGX" render --size 64 --spp 1 --out RU.PNG 2> /dev/null && [ "$("$PNG_INFO" RU.PNG)" = "64 64" ] && ok || bad "render --out RU.PNG"
"$GGX" render --size 96x64 --spp 2 --out r.png 2> r.err && [ "$("$PNG_INFO" r.png)" = "96 64" ] && [ ! -s r.err ] &&
    ok || bad "render png: $("$PNG_INFO" r.png) $(cat r.err)"
"$GGX" render --size 256x64 --spp 1 --scene plane --light point:30,20 --out rc.png &&
    [ "$("$PNG_INFO" rc.png)" = "256 $((64 + 81))" ] && ok || bad "render png with its caption: $("$PNG_INFO" rc.png)"
"$GGX" render --size 64 --spp 2 --light white --fresnel dielectric:1.5 --out r.pfm &&
    [ "$(head -c 14 r.pfm | tr '\n' ' ')" = "PF 64 64 -1.0 " ] && [ "$(wc -c < r.pfm)" -eq $((14 + 64 * 64 * 12)) ] &&
    ok || bad "render pfm: $(head -c 20 r.pfm | od -c | head -2)"
"$GGX" render --size 64 --spp 2 --light r.pfm --out r2.exr && [ "$(head -c 4 r2.exr | od -An -tx1 | tr -d ' ')" = "762f3101" ] &&
    ok || bad "render exr lit by a pfm environment"
"$GGX" render --size 64 --spp 2 --light r2.exr --threads 1 --out t1.pfm && "$GGX" render --size 64 --spp 2 --light r2.exr --threads 3 --out t3.pfm &&
    cmp -s t1.pfm t3.pfm && ok || bad "render: another thread count gave another image"
"$GGX" render --size 64 --spp 1 --out - > r3.png && [ "$("$PNG_INFO" r3.png)" = "64 64" ] && ok || bad "render to stdout"
printf 'PF\n2 2\n-1.0\n' > nan.pfm; printf '\0\0\300\177%.0s' 1 2 3 4 5 6 7 8 9 10 11 12 >> nan.pfm
printf 'PF\n2 2\n-1.0\n' > black.pfm; printf '\0\0\0\0%.0s' 1 2 3 4 5 6 7 8 9 10 11 12 >> black.pfm
head -c 20 nan.pfm > short.pfm; : > empty.exr; printf 'v/1\001garbage' > bad.exr
printf 'PF\n2 2\n-1.0\n' > neg.pfm; printf '\0\0\200\277%.0s' 1 2 3 4 5 6 7 8 9 10 11 12 >> neg.pfm
"$GGX" render --size 64 --spp 1 --light neg.pfm --out neg.png 2> neg.err; [ $? -eq 2 ] && grep -q "black everywhere" neg.err &&
    grep -q "note: 12 negative values" neg.err && [ ! -e neg.png ] && ok || bad "render: negative environment: $(cat neg.err)"
# bad input: exit 2, exactly one line on stderr starting with "ggx: ", no output file left behind
expect2() { # description, expected-substring, command...
    desc=$1; want=$2; shift 2
    rm -f err.txt
    "$@" > /dev/null 2> err.txt
    rc=$?
    if [ $rc -eq 2 ] && [ "$(wc -l < err.txt)" -eq 1 ] && grep -q "^ggx: .*$want" err.txt; then ok; else bad "$desc: rc $rc, stderr: $(cat err.txt)"; fi
}
expect2 "render --spp 0" "not a number of samples" "$GGX" render --spp 0 --out no.png
expect2 "render --size 0" "is not a size" "$GGX" render --size 0 --out no.png
expect2 "render absurd size" "is not a size" "$GGX" render --size 100000x100000 --out no.png
expect2 "render unknown scene" "unknown scene" "$GGX" render --scene cube --out no.png
expect2 "render unknown strategy" "unknown strategy" "$GGX" render --strategy luck --out no.png
expect2 "render bad format" "give a .png" "$GGX" render --out no.jpg
expect2 "render missing environment" "cannot read" "$GGX" render --light missing.exr --out no.png
expect2 "render empty environment" "is empty" "$GGX" render --light empty.exr --out no.png
expect2 "render corrupt environment" "not a readable OpenEXR" "$GGX" render --light bad.exr --out no.png
expect2 "render truncated environment" "cut short" "$GGX" render --light short.pfm --out no.png
expect2 "render NaN environment" "NaN or infinite" "$GGX" render --light nan.pfm --out no.png
expect2 "render black environment" "black everywhere" "$GGX" render --light black.pfm --out no.png
expect2 "render bad point light" "point:THETA,PHI" "$GGX" render --light point:30 --out no.png
expect2 "render glass with another sampler" "own sampler" "$GGX" render --fresnel dielectric:1.5 --sampler caps --out no.png
expect2 "render compensated with another sampler" "compensation" "$GGX" render --compensate --sampler caps --out no.png
# lights whose image passes the largest float are refused, nothing written (an infinite irradiance at parsing)
printf 'PF\n2 2\n-1.0\n' > bright.pfm; printf '\346\261\141\177%.0s' 1 2 3 4 5 6 7 8 9 10 11 12 >> bright.pfm
expect2 "render point light of 3e38" "exceed the largest float" "$GGX" render --size 64 --spp 1 --light point:0,0,3e38 --out no.pfm
expect2 "render environment of 3e38" "exceed the largest float" "$GGX" render --size 64 --spp 1 --light bright.pfm --out no.exr
expect2 "render infinite point light" "not a finite number" "$GGX" render --size 64 --spp 1 --light point:0,0,inf --out no.pfm
[ ! -e no.pfm ] && [ ! -e no.exr ] && ok || bad "render wrote an image that does not fit single precision"
# a Radiance .hdr (flat, 4 x 2 pixels of radiance 1) cut to half its pixels is refused; whole, it lights
printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n' > env.hdr; cp env.hdr half.hdr
printf '\200\200\200\201%.0s' 1 2 3 4 >> half.hdr; cat half.hdr > env.hdr; printf '\200\200\200\201%.0s' 1 2 3 4 >> env.hdr
"$GGX" render --size 64 --spp 1 --light env.hdr --out hdr.pfm && ok || bad "render: a whole .hdr environment refused"
expect2 "render truncated .hdr" "truncated Radiance .hdr" "$GGX" render --size 64 --spp 1 --light half.hdr --out no.png
# an environment of subnormal radiance renders its light, and says why the PNG is black
printf 'PF\n2 2\n-1.0\n' > dim.pfm; printf '\302\026\001\000%.0s' 1 2 3 4 5 6 7 8 9 10 11 12 >> dim.pfm
"$GGX" render --size 64 --spp 1 --light dim.pfm --out dim.pfm.pfm 2> dim.err && grep -q "note: .* subnormal float" dim.err &&
    [ "$(od -An -tx1 -j 13 dim.pfm.pfm | tr -d ' \n' | tr -d 0)" != "" ] && ok || bad "render dim environment: $(cat dim.err)"
"$GGX" render --size 64 --spp 1 --light dim.pfm --out dim.png 2> dim.err && grep -q "note: the PNG is black" dim.err &&
    ok || bad "render dim environment to PNG: $(cat dim.err)"
# --- the medium of flakes: render --volume, eval --sggx, sample --sggx
"$GGX" render --volume --alpha 0.15,0.5 --skew 20,-10 --density 3 --phase diffuse --albedo 0.9,0.8,0.7 --scatter 4 \
    --size 64 --spp 2 --out vol.png 2> vol.err && [ "$("$PNG_INFO" vol.png)" = "64 64" ] && [ ! -s vol.err ] && ok ||
    bad "render --volume png: $(cat vol.err)"
# no flakes: the furnace's sphere is not there, every value 1
"$GGX" render --volume --density 0 --light white --size 64 --spp 1 --out v0.pfm &&
    [ "$(tail -c 49152 v0.pfm | od -An -tf4 -v | tr -s ' ' '\n' | grep -v '^$' | sort -u)" = "1" ] && ok ||
    bad "render --volume --density 0 in the furnace is not 1 everywhere"
"$GGX" render --volume --albedo 0.5 --scatter 1 --size 64 --spp 2 --threads 1 --out vt1.pfm &&
    "$GGX" render --volume --albedo 0.5 --scatter 1 --size 64 --spp 2 --threads 3 --out vt3.pfm && cmp -s vt1.pfm vt3.pfm &&
    ok || bad "render --volume: another thread count gave another image"
expect2 "render --density without --volume" "the medium of --volume" "$GGX" render --density 2 --out no.png
expect2 "render --volume negative density" "not a flake density" "$GGX" render --volume --density -1 --out no.png
expect2 "render --volume albedo above 1" "not an albedo" "$GGX" render --volume --albedo 1.5 --out no.png
expect2 "render --volume two albedos" "not an albedo" "$GGX" render --volume --albedo 0.5,0.5 --out no.png
expect2 "render --volume unknown phase" "unknown phase function" "$GGX" render --volume --phase glossy --out no.png
expect2 "render --volume --scatter 0" "not a number of scattering events" "$GGX" render --volume --scatter 0 --out no.png
expect2 "render --volume on the plane" "sphere scene only" "$GGX" render --volume --scene plane --out no.png
expect2 "render --volume under a point light" "lit by an environment" "$GGX" render --volume --light point:30,0 --out no.png
expect2 "render --volume with a Fresnel term" "are a surface's" "$GGX" render --volume --fresnel one --out no.png
"$GGX" eval --sggx --alpha 0.2,0.6 --skew 20,-10 --wi 40,0 --wo 30,180 --wo 70,90 > se.csv &&
    head -1 se.csv | grep -qx 'wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h_x,h_y,h_z,sigma_wi,sigma_wo,D,phase_specular,phase_diffuse' &&
    [ "$(awk -F, 'NR > 1 && NF == 14 && $10 > 0 && $12 > 0 && $13 > 0 && $14 > 0 { n++ } END { print n + 0 }' se.csv)" -eq 2 ] &&
    ok || bad "eval --sggx CSV: $(cat se.csv)"
# sigma is |S^(1/2) w|: for S = I (alpha 1) every sigma is 1, D = 1 / pi and the specular phase 1 / (4 pi)
"$GGX" eval --sggx --alpha 1 --wo 30,180 --format json > se.json &&
    grep -q '"sigma_wo": 1, "D": 0.3183098861837906' se.json && grep -q '"phase_specular": 0.079577471545947' se.json &&
    ok || bad "eval --sggx JSON at S = I: $(cat se.json)"
"$GGX" sample --sggx --phase diffuse --alpha 0.2,0.6 -n 200 > ss.csv && [ "$(wc -l < ss.csv)" -eq 201 ] &&
    awk -F, 'NR > 1 { r = $1 * $1 + $2 * $2 + $3 * $3; if ((r - 1)^2 > 1e-20 || !($4 > 0) || $5 != 1) e++ } END { exit e > 0 }' ss.csv &&
    ok || bad "sample --sggx --phase diffuse: unit directions, pdf > 0, weight 1"
"$GGX" sample --sggx -n 5 --format f32 --out ss.f32 && [ "$(wc -c < ss.f32)" -eq 100 ] && ok || bad "sample --sggx f32"
expect2 "sample --phase without --sggx" "phase function of --sggx" "$GGX" sample --phase diffuse
expect2 "sample --sggx unknown phase" "unknown phase function" "$GGX" sample --sggx --phase glossy
expect2 "sample --sggx with a sampler" "give --phase" "$GGX" sample --sggx --sampler caps
expect2 "eval --sggx of an ill-conditioned shape" "too ill-conditioned" "$GGX" eval --sggx --alpha 1e-3,1e3
[ ! -e no.png ] && [ ! -e no.jpg ] && ok || bad "render left a file after an error"

# --- bad input: exit 2, exactly one line on stderr starting with "ggx: ", no output file left behind (expect2,
# defined above its first use)
expect2 "unknown command" "unknown command" "$GGX" frobnicate
expect2 "unknown option" "unknown option '--bogus'" "$GGX" eval --bogus 1
expect2 "option of another command" "unknown option '--figure'" "$GGX" sample --figure ndf
expect2 "malformed number" "not a list of numbers" "$GGX" eval --alpha 0.1x
expect2 "NaN" "not a finite number" "$GGX" eval --alpha nan
expect2 "infinity" "not a finite number" "$GGX" sample --view inf,0
expect2 "beyond the doubles" "beyond the largest double" "$GGX" eval --alpha 1e400
expect2 "below the doubles" "below the smallest positive double" "$GGX" eval --alpha 1e-400
# a subnormal is a finite number: the shape's own words for it
"$GGX" eval --alpha 1e-310 > /dev/null 2> sub.err && grep -q "raised to the smallest accepted roughness" sub.err &&
    ! grep -q "finite" sub.err && ok || bad "a subnormal alpha: $(cat sub.err)"
expect2 "Schlick F0 above 1" "Schlick's F0 is a reflectance, from 0 to 1 (1.5 given)" "$GGX" eval --fresnel schlick:1.5
expect2 "alpha <= 0" "invalid shape" "$GGX" eval --alpha -0.2
expect2 "skew too large" "invalid shape" "$GGX" eval --skew 100,0
expect2 "singular matrix" "singular" "$GGX" eval --matrix 1,2,3,2,4,6,0,0,1
expect2 "short matrix" "needs 9 values" "$GGX" eval --matrix 1,0,0,0,1,0
expect2 "zero direction" "zero vector" "$GGX" eval --wi 0,0,0
expect2 "view below the horizon" "above the horizon" "$GGX" sample --view 100,0
expect2 "vndf figure below" "above the horizon" "$GGX" plot --figure vndf --view 95,0
expect2 "albedo view below" "above the horizon" "$GGX" albedo --view 95,0
expect2 "albedo --eta view on the horizon" "not on the horizon" "$GGX" albedo --eta 1.5 --view 90,0
expect2 "unknown sampler" "unknown sampler" "$GGX" sample --sampler magic
expect2 "unknown figure" "unknown figure" "$GGX" plot --figure pie
expect2 "bad audit format" "is not md, csv or json" "$GGX" audit --format xml
expect2 "audit file of no format" "does not end with .md, .csv or .json" "$GGX" audit --out a.md --out a.txt
expect2 "audit files and --format" "each file's name gives its format" "$GGX" audit --format csv --out a.md --out a.csv
expect2 "five audit files" "at most 4 output files" "$GGX" audit --out 1.md --out 2.md --out 3.md --out 4.md --out 5.md
expect2 "bad count" "not a count" "$GGX" sample -n 0
expect2 "missing value" "needs a value" "$GGX" sample --seed
expect2 "bad fresnel" "fresnel" "$GGX" eval --fresnel gold
expect2 "bad format" "format" "$GGX" eval --format xml
expect2 "no format in the name" "does not name a format" "$GGX" plot --out x.jpg
expect2 "bad --size" "is not a size" "$GGX" plot --size 640x20
expect2 "bad --theme" "is not light or dark" "$GGX" plot --theme blue
expect2 "unwritable folder (demo)" "cannot create output folder" "$GGX" demo --out /proc/ggx-test-out
expect2 "unwritable file (plot)" "cannot write" "$GGX" plot --out /proc/ggx-no/x.png
expect2 "unwritable file (sample)" "cannot write" "$GGX" sample --out /nonexistent-dir/s.csv
mkdir ro && touch ro/keep
expect2 "out is a file (demo)" "not a folder" "$GGX" demo --out ro/keep
# no partial or temporary files anywhere in the work folder after the failures
[ -z "$(find . -name '*.tmp*')" ] && [ ! -e x.jpg ] && [ ! -e x.png ] && ok || bad "temporary files left: $(find . -name '*.tmp*')"
# a failed write leaves an existing file untouched
echo previous > keep.csv
"$GGX" sample --sampler magic --out keep.csv 2>/dev/null
[ "$(cat keep.csv)" = "previous" ] && ok || bad "existing file was modified by a failing command"

# --- output the way users break it: every write checked, devices and FIFOs in place, links kept,
# permissions kept, temporaries removed on errors and signals, figures all or none
if [ -w /dev/full ]; then
    "$GGX" sample -n 100 > /dev/full 2> err.txt; [ $? -eq 2 ] && grep -q "cannot write to standard output" err.txt && ok || bad "sample >/dev/full: $(cat err.txt)"
    "$GGX" audit --help > /dev/full 2> err.txt; [ $? -eq 2 ] && [ "$(wc -l < err.txt)" -eq 1 ] && ok || bad "help >/dev/full"
    "$GGX" check --sampler caps -n 20000 > /dev/full 2> err.txt; [ $? -eq 2 ] && ok || bad "check >/dev/full"
    one_line "--out /dev/full (sample)" "cannot write '/dev/full'" 2 "$GGX" sample -n 100000 --out /dev/full
    one_line "--out /dev/full (png, one line: not libpng's too)" "cannot write '/dev/full'" 2 "$GGX" plot --out /dev/full
fi
# a dead pipe ends the run at once (status 141), also with SIGPIPE ignored (as Python's subprocess does)
sh -c 'trap "" PIPE; "$1" sample -n 1000000000 2>/dev/null | head -1 > /dev/null' sh "$GGX_BIN" && ok || bad "sample into a closed pipe (SIGPIPE ignored)"
rc=$(sh -c 'trap "" PIPE; { "$1" sample -n 1000000000 2>/dev/null; echo $? > rc.txt; } | head -1 > /dev/null; cat rc.txt' sh "$GGX_BIN")
[ "$rc" = 141 ] && ok || bad "closed pipe with SIGPIPE ignored: status $rc, not 141"
# a FIFO is written in place (its reader gets everything) and stays a FIFO; a device is not replaced
mkfifo fifo && { timeout 20 cat fifo > fifo.out & } && timeout 20 "$GGX_BIN" sample -n 50 --out fifo && wait && [ "$(wc -l < fifo.out)" -eq 51 ] && [ -p fifo ] && ok || bad "--out FIFO"
"$GGX" sample -n 10 --out /dev/null && [ -c /dev/null ] && ok || bad "--out /dev/null"
"$GGX" plot --out /dev/null 2>/dev/null && [ -c /dev/null ] && ok || bad "plot --out /dev/null"
# a link to a file: the target is replaced, the link kept; a dangling link: its target created
echo old > target.csv && ln -s target.csv link.csv && "$GGX" sample -n 3 --out link.csv && [ -L link.csv ] &&
    [ "$(wc -l < target.csv)" -eq 4 ] && ok || bad "--out symlink"
ln -s made.csv dangling.csv && "$GGX" sample -n 3 --out dangling.csv && [ -L dangling.csv ] && [ "$(wc -l < made.csv)" -eq 4 ] && ok || bad "--out dangling symlink"
echo old > private.csv && chmod 600 private.csv && "$GGX" sample -n 2 --out private.csv && [ "$(stat -c %a private.csv)" = 600 ] && ok || bad "--out keeps permissions: $(stat -c %a private.csv)"
# --out as a redirect wherever a replacement would lose what a redirect keeps (cli.h states the rules): a plain file
# is replaced (a new inode); the others are written in place (the same inode)
ino() { stat -c %i "$1"; }
echo old > plain.csv && i=$(ino plain.csv) && "$GGX" sample -n 2 --out plain.csv && [ "$(ino plain.csv)" != "$i" ] &&
    [ "$(wc -l < plain.csv)" -eq 3 ] && ok || bad "a plain file is not replaced whole"
# a descriptor named as a file is written as it is open: an appending redirect keeps the log's lines
echo first > log.csv && "$GGX" sample -n 2 --out /dev/stdout >> log.csv && [ "$(head -1 log.csv)" = first ] &&
    [ "$(wc -l < log.csv)" -eq 4 ] && ok || bad "--out /dev/stdout >> log: $(head -2 log.csv)"
echo first > log3.csv && "$GGX" sample -n 2 --out /dev/fd/3 3>> log3.csv && [ "$(head -1 log3.csv)" = first ] &&
    [ "$(wc -l < log3.csv)" -eq 4 ] && ok || bad "--out /dev/fd/3 3>> log: $(head -2 log3.csv)"
ln -s /dev/stdout out-link && echo first > log4.csv && "$GGX" sample -n 2 --out out-link >> log4.csv &&
    [ "$(head -1 log4.csv)" = first ] && [ -L out-link ] && ok || bad "--out a link to /dev/stdout >> log"
"$GGX" plot --out /dev/stdout > dev.png 2>/dev/null && [ "$("$PNG_INFO" dev.png)" = "640 550" ] && ok || bad "plot --out /dev/stdout"
one_line "--out a descriptor not open" "cannot write '/dev/fd/57'" 2 "$GGX" sample -n 2 --out /dev/fd/57
# hard links: every name sees the new content
echo old > h1.csv && ln h1.csv h2.csv && i=$(ino h1.csv) && "$GGX" sample -n 2 --out h1.csv && [ "$(wc -l < h2.csv)" -eq 3 ] &&
    cmp -s h1.csv h2.csv && [ "$(ino h1.csv)" = "$i" ] && ok || bad "--out onto a hard-linked file split it: $(cat h2.csv)"
# extended attributes, an ACL among them, are kept (where the file system has them)
echo old > attr.csv && echo old > acl.csv
if /usr/bin/python3 -c 'import os; os.setxattr("attr.csv", "user.origin", b"kept")' 2>/dev/null; then
    "$GGX" sample -n 2 --out attr.csv && [ "$(wc -l < attr.csv)" -eq 3 ] &&
        /usr/bin/python3 -c 'import os, sys; sys.exit(os.getxattr("attr.csv", "user.origin") != b"kept")' && ok ||
        bad "--out dropped an extended attribute"
else
    echo "cli: no user extended attributes here: not tested"
fi
ACL='import os, struct, sys
acl = struct.pack("<I", 2) + b"".join(struct.pack("<HHI", *e) for e in
      [(1, 6, 2**32 - 1), (2, 4, 65534), (4, 4, 2**32 - 1), (16, 4, 2**32 - 1), (32, 4, 2**32 - 1)])
if sys.argv[1] == "set": os.setxattr("acl.csv", "system.posix_acl_access", acl)
else: sys.exit(os.getxattr("acl.csv", "system.posix_acl_access") != acl)'
if /usr/bin/python3 -c "$ACL" set 2>/dev/null; then
    "$GGX" sample -n 2 --out acl.csv && [ "$(wc -l < acl.csv)" -eq 3 ] && /usr/bin/python3 -c "$ACL" check && ok ||
        bad "--out dropped an ACL"
else
    echo "cli: no ACLs here: not tested"
fi
# names up to the longest the file system takes: the temporary's name is cut to fit (new, then replaced); a longer
# one is the system's refusal, in one line
n254=$(printf 'n%.0s' $(seq 1 250)).csv
for n in "$n254" "${n254%.csv}m.csv"; do
    "$GGX" sample -n 2 --out "$n" && "$GGX" sample -n 3 --out "$n" && [ "$(wc -l < "$n")" -eq 4 ] && ok ||
        bad "--out with a ${#n}-byte name"
done
one_line "--out with a 256-byte name" "File name too long" 2 "$GGX" sample -n 2 --out "${n254%.csv}mm.csv"
[ -z "$(find . -name '*.tmp*')" ] && ok || bad "temporaries of long names left: $(find . -name '*.tmp*')"
# --out as a redirect: a file the user may not write is an error (exit 2, untouched); a replaced file keeps its
# owner where the user could give it, else it is written in place. As an unprivileged user where the test runs as
# root (CI), else as the user running it (the read-only case only).
echo keep > ro.csv && chmod 444 ro.csv
if [ "$(id -u)" = 0 ] && command -v setpriv >/dev/null 2>&1 && id nobody >/dev/null 2>&1; then
    AS="setpriv --reuid=nobody --regid=$(id -g nobody) --clear-groups"
    mkdir perm && chmod 755 . && chown nobody perm && chown nobody ro.csv && mv ro.csv perm/
    # a file the user may write in a folder they may not (no temporary there): written in place; a new file there is
    # refused, as a redirect refuses it
    mkdir rodir && echo root > rodir/open.csv && chmod 666 rodir/open.csv
    $AS "$GGX_BIN" sample -n 2 --out rodir/open.csv && [ "$(wc -l < rodir/open.csv)" -eq 3 ] &&
        [ "$(stat -c %U rodir/open.csv)" = root ] && ok || bad "--out onto a writable file in a read-only folder"
    one_line "--out a new file in a read-only folder" "cannot write 'rodir/new.csv': Permission denied" 2 \
        $AS "$GGX_BIN" sample -n 2 --out rodir/new.csv
    rm -rf rodir
    echo root > perm/rootfile && chmod 644 perm/rootfile
    echo shared > perm/shared && chmod 666 perm/shared
    echo theirs > perm/theirs && chown nobody perm/theirs && chmod 600 perm/theirs
    one_line "--out onto another user's file" "cannot write 'perm/rootfile': Permission denied" 2 $AS "$GGX_BIN" sample -n 2 --out perm/rootfile
    [ "$(cat perm/rootfile)" = root ] && [ "$(stat -c %U perm/rootfile)" = root ] && ok || bad "another user's file was replaced"
    one_line "--out onto the user's read-only file" "Permission denied" 2 $AS "$GGX_BIN" sample -n 2 --out perm/ro.csv
    [ "$(cat perm/ro.csv)" = keep ] && ok || bad "a read-only file was replaced"
    $AS "$GGX_BIN" sample -n 2 --out perm/shared && [ "$(stat -c '%U %a' perm/shared)" = "root 666" ] &&
        [ "$(wc -l < perm/shared)" -eq 3 ] && ok || bad "--out onto a writable file of another user: $(stat -c '%U %a' perm/shared)"
    "$GGX" sample -n 2 --out perm/theirs && [ "$(stat -c '%U %a' perm/theirs)" = "nobody 600" ] && ok ||
        bad "root replacing a user's file changed its owner: $(stat -c '%U %a' perm/theirs)"
    rm -rf perm
elif [ "$(id -u)" != 0 ]; then
    one_line "--out onto a read-only file" "Permission denied" 2 "$GGX" sample -n 2 --out ro.csv
    [ "$(cat ro.csv)" = keep ] && ok || bad "a read-only file was replaced"
    mkdir rodir && echo old > rodir/open.csv && chmod 555 rodir
    "$GGX" sample -n 2 --out rodir/open.csv && [ "$(wc -l < rodir/open.csv)" -eq 3 ] && ok ||
        bad "--out onto a writable file in a read-only folder"
    one_line "--out a new file in a read-only folder" "Permission denied" 2 "$GGX" sample -n 2 --out rodir/new.csv
    chmod 755 rodir && rm -rf rodir
fi
rm -f ro.csv
(umask 027 && "$GGX" sample -n 2 --out fresh.csv) && [ "$(stat -c %a fresh.csv)" = 640 ] && ok || bad "new file mode follows umask: $(stat -c %a fresh.csv)"
# signals: the temporary goes, the signal's status comes back (SIGINT through perl: a background job ignores it)
for sig in TERM HUP INT; do
    rm -f big.csv*
    if [ $sig = INT ]; then perl -e '$SIG{INT} = "DEFAULT"; exec @ARGV' "$GGX_BIN" sample -n 1000000000 --out big.csv &
    else "$GGX_BIN" sample -n 1000000000 --out big.csv & fi
    pid=$!
    i=0; while [ $i -lt 100 ] && [ -z "$(ls big.csv.tmp* 2>/dev/null)" ]; do sleep 0.05; i=$((i + 1)); done
    kill -$sig $pid; wait $pid; rc=$?
    [ -z "$(ls big.csv* 2>/dev/null)" ] && [ $rc -gt 128 ] && ok || bad "SIG$sig during sample --out: status $rc, left $(ls big.csv* 2>/dev/null)"
done
# demo: all figures or none (a folder in the way of one figure fails the demo and leaves nothing)
mkdir -p allnone/skewed-ndf-top.png
one_line "demo with a figure path taken" "it is a folder" 2 "$GGX" demo --out allnone -n 20000
[ "$(find allnone -type f | wc -l)" -eq 0 ] && ok || bad "demo left figures: $(find allnone -type f)"
# (the whole demo again, at another size: outside valgrind, which runs the first demo's code)
if [ -z "${GGX_WRAP:-}" ]; then
    "$GGX" demo --out sized --size 256 -n 20000 > /dev/null && [ "$("$PNG_INFO" sized/ndf-top.png)" = "256 220" ] && ok ||
        bad "demo --size 256: $("$PNG_INFO" sized/ndf-top.png)"
fi
# plot: --out - streams the figure; a long path is written as given (no truncation)
"$GGX" plot --out - > stdout.png && [ "$("$PNG_INFO" stdout.png)" = "640 550" ] && ok || bad "plot --out -"
long=$(printf 'd%.0s' $(seq 1 120)); deep="$long/$long/$long/$long/$long"
mkdir -p "$deep" && "$GGX" plot --figure grid --out "$deep/grid.svg" 2>/dev/null && [ -f "$deep/grid.svg" ] && ok || bad "plot --out with a 600-byte path"
# arguments: GNU --name=value, -V, degrees in messages, a note where the command adjusts, counts that mean something
"$GGX" sample --alpha=0.3 --view=40,0 -n 2 > eq.csv && [ "$(wc -l < eq.csv)" -eq 3 ] && ok || bad "--name=value"
"$GGX" -V | grep -q "^ggx [0-9]" && ok || bad "ggx -V"
one_line "skew out of range, in degrees" "within \[-90, 90\] degrees" 2 "$GGX" eval --skew 95,0
one_line "flag with a value" "takes no value" 2 "$GGX" plot --log=1
# messages that say what is wrong with the value given
"$GGX" sample -n 1 --view 1e300,1e300,1e300 > big.csv && [ "$(wc -l < big.csv)" -eq 2 ] && ok || bad "--view with huge components"
one_line "zero direction" "is the zero vector" 2 "$GGX" sample -n 1 --view 0,0,0
one_line "skew just past 90" "(90.0000001 given)" 2 "$GGX" eval --skew 90.0000001,0
"$GGX" sample -n 1 --seed 9007199254740992 > seed.csv && "$GGX" sample -n 1 --seed 18446744073709551615 > seed2.csv &&
    ! cmp -s seed.csv seed2.csv && ok || bad "--seed above 2^53 refused or ignored"
one_line "seed above 2^64" "larger than the largest seed" 2 "$GGX" sample -n 1 --seed 18446744073709551616
one_line "eta above 1e300" "must be in (0, 1e300]" 2 "$GGX" albedo --eta 1e301
"$GGX" eval --alpha 0.00001 > /dev/null 2> err.txt && grep -q "raised to the smallest" err.txt && ok || bad "alpha below the minimum: no note"
one_line "sampler outside its domain" "unskewed shapes only" 2 "$GGX" sample --sampler inversion --skew 20,0 -n 2
one_line "too few samples for chi-square" "needs at least 10000 samples" 2 "$GGX" check -n 10
one_line "too few samples (demo)" "needs at least 10000 samples" 2 "$GGX" demo -n 100 --out few
[ ! -e few ] || [ -z "$(ls few)" ] && ok || bad "demo -n 100 wrote figures before refusing"
"$GGX" check --alpha 1e4 --sampler caps -n 20000 > nojac.txt && grep -q "(no point)" nojac.txt && ! grep -q "0.00e+00" nojac.txt && ok || bad "check without Jacobian points: $(cat nojac.txt)"
one_line "ill-conditioned matrix" "ill-conditioned" 2 "$GGX" eval --matrix 1e9,0,0,0,1,0,0,0,1
if [ "${GGX_CLI_QUICK:-0}" != 1 ]; then
    # every audit row that docs/seed-claims.md names as covering a claim exists
    grep -o '(covered: [a-z0-9, -]*)' "$ROOT/docs/seed-claims.md" | sed 's/(covered: \(.*\))/\1/' | tr ',' '\n' | tr -d ' ' | sort -u > covered.txt
    cut -d, -f1 audit.csv | tr -d '"' | sort -u > ids.txt
    [ -s covered.txt ] && [ -z "$(comm -23 covered.txt ids.txt)" ] && ok || bad "seed-claims.md names rows the audit lacks: $(comm -23 covered.txt ids.txt)"
    # the README's command lines, run as written (from the ```sh block of "The ggx command"), then those of
    # docs/cli.md's "Examples"
    sed -n '/^## The `ggx` command/,/^## /p' "$ROOT/README.md" | sed -n '/^```sh/,/^```/p' | grep '^ggx ' |
        sed 's/ *#.*//' > readme_cmds.txt
    [ "$(wc -l < readme_cmds.txt)" -ge 6 ] && ok || bad "README command lines not found"
    sed -n '/^## Examples/,/^## /p' "$ROOT/docs/cli.md" | sed -n '/^```sh/,/^```/p' | grep '^ggx ' |
        sed 's/ *#.*//' > cli_doc_cmds.txt
    [ "$(wc -l < cli_doc_cmds.txt)" -ge 10 ] && ok || bad "docs/cli.md example lines not found"
    grep -qxF "$AUDIT_LINE" cli_doc_cmds.txt && ok || bad "docs/cli.md's audit line is not the one run above"
    # each distinct line once, the audit's (run and checked above) left out
    cat readme_cmds.txt cli_doc_cmds.txt | awk '!seen[$0]++' | grep -vxF "$AUDIT_LINE" > doc_cmds.txt
    while read -r line; do
        # shellcheck disable=SC2086
        set -- $line
        shift
        "$GGX" "$@" > readme_out.txt 2>&1 && ok || bad "documented line '$line': $(tail -2 readme_out.txt)"
    done < doc_cmds.txt
fi

echo "cli: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
