#!/bin/sh
# The shipped tables regenerate bit for bit: every 8th column of src/tables/albedo_iso.inc, recomputed by the
# generator, must appear in the file character for character (17 significant digits: the doubles themselves), and
# the file must hold the whole grid. Usage: tables_test.sh GENERATOR TABLE_FILE. SPDX-License-Identifier: MIT
set -eu
gen=$1
file=$2
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
"$gen" --every 8 | grep -E '^    /\* (sep|hc) alpha' > "$tmp"
n=$(wc -l < "$tmp")
[ "$n" -eq 52 ] || { echo "FAIL: the generator gave $n columns, 52 expected"; exit 1; }
bad=0
while IFS= read -r line; do
    if ! grep -qxF -- "$line" "$file"; then
        echo "FAIL: not in $file as regenerated: $(printf '%s' "$line" | cut -c1-100)..."
        bad=$((bad + 1))
    fi
done < "$tmp"
total=$(grep -cE '^    /\* (sep|hc) alpha' "$file")
[ "$total" -eq 388 ] || { echo "FAIL: $file has $total columns, 388 expected (2 x 97 tables, 2 x 97 averages)"; exit 1; }
[ "$bad" -eq 0 ] || exit 1
echo "tables: 52 of 388 columns regenerated bit for bit"
