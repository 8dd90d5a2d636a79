#!/bin/sh
# The shipped tables regenerate bit for bit: a share of the lines of src/tables/albedo_iso.inc (every 8th column,
# 17 significant digits: the doubles themselves), of src/tables/bsdf_iso.inc (every 97th line) and of
# src/tables/albedo_aniso.inc (every 69th pair of roughnesses; both with 9 significant digits and a float suffix:
# the floats themselves), recomputed by the generator, must appear in the files character for character, and the
# files must hold the whole grids. The quick tier (GGX_TEST_SCALE below 1) regenerates half as many lines of the two
# albedo tables (every 16th column, every 138th pair). Usage: tables_test.sh GENERATOR ISO_FILE BSDF_FILE ANISO_FILE.
# SPDX-License-Identifier: MIT
set -eu
gen=$1
iso=$2
bsdf=$3
aniso=$4
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT

# check FILE PATTERN GENERATED_LINES TOTAL_LINES WHAT
check() {
    n=$(wc -l < "$tmp")
    [ "$n" -eq "$3" ] || { echo "FAIL: the generator gave $n lines for $1, $3 expected"; exit 1; }
    bad=0
    while IFS= read -r line; do
        if ! grep -qxF -- "$line" "$1"; then
            echo "FAIL: not in $1 as regenerated: $(printf '%s' "$line" | cut -c1-100)..."
            bad=$((bad + 1))
        fi
    done < "$tmp"
    total=$(grep -cE "$2" "$1")
    [ "$total" -eq "$4" ] || { echo "FAIL: $1 has $total lines, $4 expected ($5)"; exit 1; }
    [ "$bad" -eq 0 ] || exit 1
    echo "tables: $3 of $4 lines of $1 regenerated bit for bit"
}

quick=$(awk -v s="${GGX_TEST_SCALE:-1}" 'BEGIN { print (s > 0 && s < 1) ? 1 : 0 }')
if [ "$quick" -eq 1 ]; then iso_every=16 iso_lines=28 aniso_every=138 aniso_lines=66; else
    iso_every=8 iso_lines=52 aniso_every=69 aniso_lines=132; fi

pat='^    /\* (sep|hc) alpha'
"$gen" --every "$iso_every" | grep -E "$pat" > "$tmp"
check "$iso" "$pat" "$iso_lines" 388 "2 x 97 tables, 2 x 97 averages"

pat='^    /\* eta_r [0-9.e+-]+ alpha'
"$gen" --bsdf --every 97 | grep -E "$pat" > "$tmp"
check "$bsdf" "$pat" 17 1584 "2 halves x 24 eta_r x 33 alpha"

pat='^    /\* ax [0-9.e+-]+ ay [0-9.e+-]+ row'
"$gen" --aniso --every "$aniso_every" | grep -E "$pat" > "$tmp"
check "$aniso" "$pat" "$aniso_lines" 9108 "276 pairs of roughnesses x 33 rows"
