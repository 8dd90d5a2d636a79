#!/bin/sh
# The public headers as a reader finds them: every public inline kernel is declared by its full name in
# include/ggx/ggx_inline.h (the index that lab/gen_inline_index.py derives from the kernels is current), ctags finds
# a tag for every ggx_*_f and ggx_*_d kernel and every batch function (with the repository's .ctags.d options), and
# no public header holds a date.
# Usage: sh tests/packaging/header_index.sh SOURCE_DIR C_COMPILER PYTHON
set -u
cd "$1" || exit 1
CC=$2
PY=$3
fail=0
bad() { echo "FAIL: $*"; fail=1; }

"$PY" lab/gen_inline_index.py --check --cc "$CC" || bad "the function index of ggx_inline.h"

# the kernels' public names, from the index itself (its declarations are checked against the kernels above)
names=$(sed -n '/^\/\* ---- function index/,/^\/\* ---- end of the function index/p' include/ggx/ggx_inline.h |
        grep -o 'ggx_[a-z0-9_]*_[fd](' | tr -d '(')
[ "$(echo "$names" | wc -l)" -ge 100 ] || bad "the index declares only $(echo "$names" | wc -l) kernels"
batch=$(grep -o 'ggx_batch_[a-z0-9_]*(' include/ggx/ggx_batch.h | tr -d '(' | sort -u)
[ -n "$batch" ] || bad "no batch function found in ggx_batch.h"

if command -v ctags >/dev/null 2>&1 && ctags --version 2>/dev/null | grep -q Universal; then
    tags=$(mktemp)
    ctags -R -f "$tags" include || bad "ctags failed"
    missing=0
    for n in $names $batch; do
        grep -q "^$n	" "$tags" || { echo "no tag for $n"; missing=$((missing + 1)); }
    done
    if [ "$missing" -eq 0 ]; then
        echo "ctags: a tag for each of $(echo $names $batch | wc -w) public inline and batch names"
    else
        bad "$missing public names without a tag"
    fi
    rm -f "$tags"
else
    echo "universal-ctags not installed (Debian: universal-ctags): the tag check is skipped"
fi

dates=$(grep -rnE '(19|20)[0-9][0-9]-[01][0-9]-[0-3][0-9]|(19|20)[0-9][0-9]-[01][0-9]\b' include/)
[ -z "$dates" ] || bad "a public header holds a date: $dates"

[ "$fail" -eq 0 ] && echo "header index: ok"
exit "$fail"
