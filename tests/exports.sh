#!/bin/sh
# libggx.so exports exactly the public API: every defined dynamic symbol is a ggx_* name declared in
# include/ggx/*.h, and every function declared there (not the inline kernels of ggx_inline.h) is exported.
# Usage: exports.sh LIBGGX_SO INCLUDE_DIR
set -eu
so=$1 inc=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
nm -D --defined-only "$so" | awk '$2 ~ /[TDBRW]/ {print $3}' | grep -v '^_' | sed 's/@.*//' | sort -u >"$tmp/exported"
# Declarations of exported functions: "ggx_name(" in the non-inline headers (types are never followed by "(").
cat "$inc"/ggx/ggx.h "$inc"/ggx/ggx_batch.h "$inc"/ggx/ggx_samplers.h |
  grep -oE 'ggx_[a-z0-9_]+\(' | tr -d '(' | sort -u >"$tmp/declared"
status=0
extra=$(comm -23 "$tmp/exported" "$tmp/declared")
missing=$(comm -13 "$tmp/exported" "$tmp/declared")
if [ -n "$extra" ]; then echo "exported but not public API:"; echo "$extra"; status=1; fi
if [ -n "$missing" ]; then echo "declared but not exported:"; echo "$missing"; status=1; fi
n=$(wc -l <"$tmp/exported")
[ "$n" -ge 70 ] || { echo "only $n symbols exported"; status=1; }
[ $status -eq 0 ] && echo "exports: $n symbols, all public ggx_* API, all declared functions exported"
exit $status
