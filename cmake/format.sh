#!/bin/sh
# The C, CUDA and C++ sources under the project's .clang-format (clang-format 14): `format.sh check` lists every file
# that differs from its formatted self and fails; `format.sh fix` rewrites them. Generated data is left out: the
# shipped tables (src/tables/*.inc), the colour map and the golden values.
set -eu
cd "$(dirname "$0")/.."
CF=${CLANG_FORMAT:-$(command -v clang-format-14 || command -v clang-format || true)}
[ -n "$CF" ] || { echo "format: clang-format not found: apt-get install clang-format" >&2; exit 2; }
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    list() { git ls-files '*.c' '*.h' '*.inc' '*.cu' '*.cpp'; }
else
    list() { find . -name '*.c' -o -name '*.h' -o -name '*.inc' -o -name '*.cu' -o -name '*.cpp' | sed 's|^\./||'; }
fi
files=$(list | grep -v -e '^src/tables/.*\.inc$' -e '^tests/data/' -e '^build' -e 'viridis\.inc$' -e 'golden_values\.inc$')
case "${1:-check}" in
fix)
    for f in $files; do "$CF" -i "$f"; done ;;
check)
    bad=0
    for f in $files; do
        if ! "$CF" "$f" | cmp -s "$f" -; then echo "format: $f differs from clang-format's output (make format)"; bad=1; fi
    done
    [ $bad -eq 0 ] && echo "format: $(echo "$files" | wc -w) files as .clang-format says"
    exit $bad ;;
*) echo "usage: format.sh check|fix" >&2; exit 2 ;;
esac
