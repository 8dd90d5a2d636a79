#!/bin/sh
# make install works: installs into a scratch prefix, then builds a user's program with
# `cc prog.c $(pkg-config --cflags --libs ggx)` and a CMake project with find_package(ggx), and runs both.
set -eu
build=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
libdir=$(ls -d "$tmp"/prefix/lib*/pkgconfig | head -n 1)
libdir=${libdir%/pkgconfig}
test -f "$tmp/prefix/include/ggx/ggx.h"
test -f "$libdir/cmake/ggx/ggxConfig.cmake"
"$tmp/prefix/bin/ggx" --version | grep -q '^ggx [0-9]'
# The pkg-config file is generated for the configured prefix; point it at the scratch prefix.
sed "s|^prefix=.*|prefix=$tmp/prefix|" "$libdir/pkgconfig/ggx.pc" > "$tmp/ggx.pc"
cat > "$tmp/prog.c" <<'C'
#include <ggx/ggx.h>
#include <stdio.h>
int main(void)
{
    ggx_shape s;
    ggx_vec3 m = {0.0, 0.0, 1.0};
    if (ggx_shape_aniso(&s, 0.2, 0.4) != GGX_OK) return 1;
    double d = ggx_ndf(&s, m); /* 1 / (pi 0.2 0.4) */
    printf("%.6f\n", d);
    return d > 3.978 && d < 3.979 ? 0 : 1;
}
C
PKG_CONFIG_PATH="$tmp" cc "$tmp/prog.c" -o "$tmp/prog" $(PKG_CONFIG_PATH="$tmp" pkg-config --cflags --libs ggx)
LD_LIBRARY_PATH="$libdir" "$tmp/prog"
mkdir "$tmp/consumer"
cat > "$tmp/consumer/CMakeLists.txt" <<'C'
cmake_minimum_required(VERSION 3.16)
project(consumer C)
find_package(ggx 0.1 REQUIRED)
add_executable(prog ../prog.c)
target_link_libraries(prog PRIVATE ggx::ggx)
C
cmake -S "$tmp/consumer" -B "$tmp/consumer/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" >/dev/null
cmake --build "$tmp/consumer/build" >/dev/null
LD_LIBRARY_PATH="$libdir" "$tmp/consumer/build/prog"
echo "install test: pkg-config and find_package consumers built and ran"
