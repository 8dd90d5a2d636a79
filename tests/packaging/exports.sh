#!/bin/sh
# libggx.so exports exactly the public API: every defined dynamic symbol is a ggx_* name declared in
# include/ggx/*.h, and every function declared there (not the inline kernels of ggx_inline.h) is exported.
# Usage: exports.sh LIBGGX_SO INCLUDE_DIR
set -eu
so=$1 inc=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The per-element functions are GNU ifuncs (baseline and x86-64-v3 clones, src/api/internal.h): GCC exports each one's
# resolver as the weak symbol "<name>.resolver", which no C program can name (the dot); it must belong to an
# exported function.
nm -D --defined-only "$so" | awk '$2 ~ /[TDBRWi]/ {print $3}' | grep -v '^_' | sed 's/@.*//' | sort -u >"$tmp/all"
grep -v '\.resolver$' "$tmp/all" >"$tmp/exported" || true
grep '\.resolver$' "$tmp/all" | sed 's/\.resolver$//' >"$tmp/resolved" || true
# Declarations of exported functions: "ggx_name(" in the non-inline headers (types are never followed by "(").
ls "$inc"/ggx/*.h | grep -v '/ggx_inline\.h$' | xargs cat |
  grep -oE 'ggx_[a-z0-9_]+\(' | tr -d '(' | sort -u >"$tmp/declared"
status=0
extra=$(comm -23 "$tmp/exported" "$tmp/declared")
missing=$(comm -13 "$tmp/exported" "$tmp/declared")
if [ -n "$extra" ]; then echo "exported but not public API:"; echo "$extra"; status=1; fi
if [ -n "$missing" ]; then echo "declared but not exported:"; echo "$missing"; status=1; fi
orphan=$(comm -23 "$tmp/resolved" "$tmp/exported")
if [ -n "$orphan" ]; then echo "ifunc resolvers of no exported function:"; echo "$orphan"; status=1; fi
n=$(wc -l <"$tmp/exported")
[ "$n" -ge 70 ] || { echo "only $n symbols exported"; status=1; }
[ $status -eq 0 ] && echo "exports: $n symbols, all public ggx_* API, all declared functions exported ($(wc -l <"$tmp/resolved") of them with an ifunc resolver)"
exit $status
