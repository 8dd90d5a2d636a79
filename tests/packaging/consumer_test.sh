#!/bin/sh
# libggx as packagers and other CMake projects use it, from the source tree, in scratch folders:
#  - a library-only build (every optional part off) installs libggx.so with the 0.x SONAME (libggx.so.MAJOR.MINOR)
#    and no lab code, and a program builds against it with pkg-config and with find_package(ggx) (ggx::ggx);
#  - BUILD_SHARED_LIBS=OFF installs libggx.a only, and the same program links it through pkg-config and CMake;
#  - a project that includes the source tree with add_subdirectory keeps its own build type (Debug, or none) and
#    gets the library only, and one that uses FetchContent with a local SOURCE_DIR builds and runs too;
#  - an optional part whose dependency is missing (cairo, hidden from pkg-config; numpy, behind an interpreter that
#    does not exist) turns itself off with one STATUS line, and the same part explicitly ON stops the configure.
# The builds are Debug and leave out the AVX2 and AVX-512 batch loops (their compiles are most of a build's time;
# neither changes which files are installed or how a program links). Usage: consumer_test.sh SRC CMAKE C_COMPILER
set -eu
src=$1
cmake=$2
cc=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
jobs=${GGX_TEST_JOBS:-2}
fail() { echo "consumer: $*" >&2; exit 1; }
# Every optional part off: what a packager of the library alone gets.
parts_off="-DGGX_BUILD_TOOL=OFF -DGGX_BUILD_PYTHON=OFF -DGGX_BUILD_EXAMPLES=OFF -DGGX_BUILD_TESTS=OFF -DGGX_FUZZ=OFF
           -DGGX_CUDA=OFF"
quick="-DCMAKE_BUILD_TYPE=Debug -DGGX_CC_AVX2=OFF -DGGX_CC_AVX512=OFF"
version=$(sed -n 's/^#define GGX_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\)$/\2/p' "$src/include/ggx/ggx_version.h" |
          paste -sd. -)
soname=libggx.so.$(echo "$version" | cut -d. -f1-2)
case $version in 0.*) ;; *) soname=libggx.so.$(echo "$version" | cut -d. -f1) ;; esac

# The user's program: the version it runs with and one evaluation.
cat > "$tmp/prog.c" <<'C'
#include <stdio.h>
#include <string.h>
#include <ggx/ggx.h>
int main(void)
{
    ggx_shape s;
    ggx_vec3 n = {0, 0, 1};
    if (ggx_shape_iso(&s, 0.5) != GGX_OK || strcmp(ggx_version(), GGX_VERSION_STRING) != 0) return 1;
    printf("%s %.6f\n", ggx_version(), ggx_ndf(&s, n));
    return 0;
}
C
# D(n) = 1 / (pi alpha^2) for isotropic GGX
want="$version 1.273240"
run() { # program: runs it with no LD_LIBRARY_PATH and checks its line
    got=$(env -u LD_LIBRARY_PATH "$1") || fail "$1 failed"
    [ "$got" = "$want" ] || fail "$1 printed '$got', '$want' expected"
}
mkdir "$tmp/fp"
cat > "$tmp/fp/CMakeLists.txt" <<'C'
cmake_minimum_required(VERSION 3.16)
project(consumer C)
find_package(ggx 0.1 REQUIRED)
add_executable(prog ../prog.c)
target_link_libraries(prog PRIVATE ggx::ggx)
C
# configure LABEL SOURCE BUILD ARGS...: a configure that must succeed (its output in BUILD.log)
configure() {
    label=$1 s=$2 b=$3
    shift 3
    CC=$cc "$cmake" -S "$s" -B "$b" "$@" >"$b.log" 2>&1 || { cat "$b.log"; fail "$label: the configure failed"; }
}
build() { # LABEL BUILD [ARGS...]
    label=$1 b=$2
    shift 2
    "$cmake" --build "$b" -j "$jobs" "$@" >"$b.build.log" 2>&1 || { tail -n 30 "$b.build.log"; fail "$label: the build failed"; }
}
# consumers PREFIX LIBDIR: the program built with pkg-config and with find_package, each run as built
consumers() {
    prefix=$1 libdir=$2
    rm -f "$tmp/a.out"
    (cd "$tmp" && PKG_CONFIG_PATH="$libdir/pkgconfig" sh -c "$cc prog.c \$(pkg-config --cflags --libs ggx)") ||
        fail "$prefix: the pkg-config build failed"
    run "$tmp/a.out"
    rm -rf "$tmp/fp/build"
    configure "find_package($prefix)" "$tmp/fp" "$tmp/fp/build" -DCMAKE_PREFIX_PATH="$prefix"
    build "find_package($prefix)" "$tmp/fp/build"
    run "$tmp/fp/build/prog"
}

# A library-only build, shared (the default), installed.
configure "library only" "$src" "$tmp/shared" $quick $parts_off
build "library only" "$tmp/shared"
"$cmake" --install "$tmp/shared" --prefix "$tmp/p-shared" >"$tmp/shared.install.log" 2>&1 ||
    { cat "$tmp/shared.install.log"; fail "library only: the install failed"; }
libdir=$(dirname "$(ls "$tmp"/p-shared/lib*/pkgconfig/ggx.pc)")
libdir=${libdir%/pkgconfig}
test -f "$libdir/$soname" || { ls -l "$libdir"; fail "no $soname installed"; }
readelf -d "$libdir/$soname" | grep -q "(SONAME).*\[$soname\]" || { readelf -d "$libdir/$soname"; fail "SONAME is not $soname"; }
test -L "$libdir/libggx.so" || fail "no libggx.so link"
test ! -e "$libdir/libggx.a" || fail "a shared build installed libggx.a"
test ! -e "$tmp/p-shared/bin/ggx" || fail "the tool was installed with GGX_BUILD_TOOL=OFF"
# The lab is not in the product: no symbol of libs/verify/ (or of the tools) in the library, nothing else installed.
if nm -D --defined-only "$libdir/$soname" | awk '{print $3}' | grep -v '^ggx_' | grep -v '^_' | grep -q .; then
    nm -D --defined-only "$libdir/$soname" | grep -v ' ggx_'; fail "the library exports names outside ggx_*"
fi
if nm "$libdir/$soname" | grep -qE ' (chi2_run|quad_adapt|audit_run|verify_pdf_ndf|au_add|rng_uniform)$'; then
    fail "libs/verify/ code in the installed library"
fi
files=$(cd "$tmp/p-shared" && find . -type f | grep -v '^./include/ggx/' | sort | tr '\n' ' ')
case $files in *python*|*bin/*|*man1*) fail "a library-only install has $files" ;; esac
consumers "$tmp/p-shared" "$libdir"
readelf -d "$tmp/fp/build/prog" | grep -q "(NEEDED).*\[$soname\]" || fail "the find_package program does not need $soname"
echo "library only, shared: $soname installed (SONAME $soname), pkg-config and find_package(ggx) programs ran"

# BUILD_SHARED_LIBS=OFF: libggx.a and no shared library; the same programs link it. (The same build folder: the
# objects are the same, position-independent either way, so only the archive is made.)
configure "static" "$src" "$tmp/shared" -DBUILD_SHARED_LIBS=OFF
build "static" "$tmp/shared"
"$cmake" --install "$tmp/shared" --prefix "$tmp/p-static" >"$tmp/static.install.log" 2>&1 ||
    { cat "$tmp/static.install.log"; fail "static: the install failed"; }
slibdir=$(dirname "$(ls "$tmp"/p-static/lib*/pkgconfig/ggx.pc)")
slibdir=${slibdir%/pkgconfig}
test -f "$slibdir/libggx.a" || fail "BUILD_SHARED_LIBS=OFF installed no libggx.a"
if ls "$slibdir"/libggx.so* >/dev/null 2>&1; then fail "BUILD_SHARED_LIBS=OFF installed a shared library"; fi
consumers "$tmp/p-static" "$slibdir"
if readelf -d "$tmp/fp/build/prog" | grep -q 'libggx'; then fail "the static consumer needs a libggx.so"; fi
echo "static: libggx.a installed alone, pkg-config and find_package(ggx) programs ran"

# add_subdirectory: the parent's build type (Debug, or none) stays, the library's compile commands are the build
# type's, its type the parent's BUILD_SHARED_LIBS, and the parent gets the library only (one line says so). Configured
# only: the FetchContent project below builds one (FetchContent_MakeAvailable is add_subdirectory).
mkdir "$tmp/sub"
cat > "$tmp/sub/CMakeLists.txt" <<C
cmake_minimum_required(VERSION 3.16)
project(parent C)
option(BUILD_SHARED_LIBS "shared libraries" ON)
add_subdirectory("$src" ggx)
add_executable(prog ../prog.c)
target_link_libraries(prog PRIVATE ggx::ggx)
C
configure "add_subdirectory" "$tmp/sub" "$tmp/sub/build" $quick -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
grep -q '^CMAKE_BUILD_TYPE:STRING=Debug$' "$tmp/sub/build/CMakeCache.txt" || fail "add_subdirectory changed the build type"
grep -q '^-- ggx: included by another project, so GGX_BUILD_TOOL, .* (AUTO) stay off' "$tmp/sub/build.log" ||
    { cat "$tmp/sub/build.log"; fail "add_subdirectory: no line for the parts left out"; }
grep -q 'src/api/shape\.c' "$tmp/sub/build/compile_commands.json" || fail "add_subdirectory: no compile command for the library"
shape=$(grep '"command".*src/api/shape\.c' "$tmp/sub/build/compile_commands.json")
case $shape in *" -g "*) ;; *) fail "add_subdirectory: the library is not compiled as Debug: $shape" ;; esac
case $shape in *NDEBUG*) fail "add_subdirectory: the library is compiled with NDEBUG: $shape" ;; esac
grep -q 'libggx\.so' "$tmp/sub/build/ggx/CMakeFiles/ggx.dir/link.txt" || fail "add_subdirectory: libggx is not shared"
for t in ggx_tool ggx_python ggx_example ggx_bench test_version; do
    if "$cmake" --build "$tmp/sub/build" --target help 2>/dev/null | grep -qx "\.\.\. $t"; then
        fail "add_subdirectory: target $t in a subproject's build"
    fi
done
mkdir "$tmp/sub-none"
sed 's/project(parent C)/project(parent_none C)/' "$tmp/sub/CMakeLists.txt" > "$tmp/sub-none/CMakeLists.txt"
configure "add_subdirectory, no build type" "$tmp/sub-none" "$tmp/sub-none/build" -DGGX_CC_AVX2=OFF -DGGX_CC_AVX512=OFF
grep -q '^CMAKE_BUILD_TYPE:STRING=$' "$tmp/sub-none/build/CMakeCache.txt" ||
    { grep CMAKE_BUILD_TYPE "$tmp/sub-none/build/CMakeCache.txt"; fail "add_subdirectory set a build type of its own"; }
echo "add_subdirectory: Debug kept (and no build type kept), Debug compile commands, the library only"

# FetchContent with a local source folder (no network); the parent sets no BUILD_SHARED_LIBS, so libggx is static.
mkdir "$tmp/fetch"
cat > "$tmp/fetch/CMakeLists.txt" <<C
cmake_minimum_required(VERSION 3.16)
project(fetcher C)
include(FetchContent)
FetchContent_Declare(ggx SOURCE_DIR "$src")
FetchContent_MakeAvailable(ggx)
add_executable(prog ../prog.c)
target_link_libraries(prog PRIVATE ggx::ggx)
C
configure "FetchContent" "$tmp/fetch" "$tmp/fetch/build" $quick -DFETCHCONTENT_FULLY_DISCONNECTED=ON
build "FetchContent" "$tmp/fetch/build"
run "$tmp/fetch/build/prog"
if readelf -d "$tmp/fetch/build/prog" | grep -q 'libggx'; then fail "FetchContent: the program needs a libggx.so"; fi
echo "FetchContent: built from the local source folder, the program ran"

# A missing dependency: AUTO turns the part off with one line, ON stops. pkg-config searches an empty folder only
# (no cairo), and the Python package's interpreter does not exist (no numpy).
mkdir "$tmp/empty"
export PKG_CONFIG_LIBDIR="$tmp/empty" PKG_CONFIG_PATH=""
missing="-DGGX_PYTHON=$tmp/no-python3"
configure "missing cairo and numpy" "$src" "$tmp/auto" -DGGX_BUILD_TOOL=AUTO -DGGX_BUILD_PYTHON=AUTO \
    -DGGX_BUILD_EXAMPLES=OFF -DGGX_BUILD_TESTS=OFF -DGGX_FUZZ=OFF -DGGX_CUDA=OFF $missing
[ "$(grep -c '^-- ggx command' "$tmp/auto.log")" -eq 1 ] && grep -q '^-- ggx command: off (cairo not found: apt-get install libcairo2-dev' "$tmp/auto.log" ||
    { cat "$tmp/auto.log"; fail "missing cairo: not one 'ggx command: off' line"; }
[ "$(grep -c '^-- Python package' "$tmp/auto.log")" -eq 1 ] && grep -q '^-- Python package: off (.* with numpy not found: apt-get install python3-numpy' "$tmp/auto.log" ||
    { cat "$tmp/auto.log"; fail "missing numpy: not one 'Python package: off' line"; }
grep -q '^GGX_BUILD_TOOL:STRING=AUTO$' "$tmp/auto/CMakeCache.txt" || fail "AUTO was not kept in the cache"
if "$cmake" --build "$tmp/auto" --target help 2>/dev/null | grep -qE '^\.\.\. (ggx_tool|ggx_python)$'; then
    fail "missing cairo and numpy: the tool or the Python module is still a target"
fi
# (the same folder, configured again: each part in turn ON, the other OFF)
for part in "GGX_BUILD_TOOL cairo GGX_BUILD_PYTHON" "GGX_BUILD_PYTHON numpy GGX_BUILD_TOOL"; do
    set -- $part
    if "$cmake" "$tmp/auto" -D"$1"=ON -D"$3"=OFF >"$tmp/on-$1.log" 2>&1; then
        cat "$tmp/on-$1.log"; fail "-D$1=ON configured without $2"
    fi
    grep -q "$1 is ON but .*$2" "$tmp/on-$1.log" || { cat "$tmp/on-$1.log"; fail "-D$1=ON: no message naming $2"; }
done
echo "missing dependencies: one STATUS line each under AUTO, the configure stops under ON"
echo "consumer test: library-only shared and static installs, add_subdirectory, FetchContent and the AUTO parts passed"
