#!/bin/sh
# The inline API compiles warning-free wherever a user includes it: tests/packaging/headers/user.c as C99, C11 and C17 and as
# C++11, C++17 and C++20 under gcc/g++ and clang/clang++ with -Wall -Wextra -Wpedantic -Werror, and
# tests/packaging/headers/user.cu under nvcc (where it is installed) with each host compiler found, host warnings errors.
# A compiler that is not installed is named and skipped; GGX_REQUIRE_CLANG=1 makes a missing clang a failure (CI).
# SPDX-License-Identifier: MIT
set -u
src=$(cd "$(dirname "$0")" && pwd)
inc="$src/../../include"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0 ran=0
flags="-Wall -Wextra -Wpedantic -Werror"
try() { # label, command...
    label=$1
    shift
    if "$@" >"$tmp/log" 2>&1; then
        ran=$((ran + 1))
        echo "ok   $label"
    else
        fail=$((fail + 1))
        echo "FAIL $label"
        sed 's/^/     /' "$tmp/log" | head -20
    fi
}
for cc in gcc clang; do
    if ! command -v $cc >/dev/null 2>&1; then
        echo "skip $cc (not installed)"
        [ "$cc" = clang ] && [ "${GGX_REQUIRE_CLANG:-0}" = 1 ] && fail=$((fail + 1))
        continue
    fi
    for std in c99 c11 c17; do
        try "$cc -std=$std" $cc -std=$std $flags -I"$inc" -c "$src/headers/user.c" -o "$tmp/u.o"
    done
done
for cxx in g++ clang++; do
    if ! command -v $cxx >/dev/null 2>&1; then
        echo "skip $cxx (not installed)"
        [ "$cxx" = clang++ ] && [ "${GGX_REQUIRE_CLANG:-0}" = 1 ] && fail=$((fail + 1))
        continue
    fi
    for std in c++11 c++17 c++20; do
        try "$cxx -std=$std" $cxx -x c++ -std=$std $flags -I"$inc" -c "$src/headers/user.c" -o "$tmp/u.o"
    done
done
nvcc=$(command -v nvcc || { [ -x /usr/local/cuda/bin/nvcc ] && echo /usr/local/cuda/bin/nvcc; } || true)
if [ -z "$nvcc" ]; then
    echo "skip nvcc (not installed)"
else
    for host in g++ clang++; do
        command -v $host >/dev/null 2>&1 || { echo "skip nvcc -ccbin $host (not installed)"; continue; }
        try "nvcc -ccbin $host" "$nvcc" -ccbin $host -std=c++17 -Werror=all-warnings -Xcompiler=-Wall,-Wextra,-Werror \
            -I"$inc" -c "$src/headers/user.cu" -o "$tmp/u.o"
    done
fi
echo "$ran compiled, $fail failed"
[ $fail -eq 0 ]
