#!/bin/sh
# make install works as the README says: `make install PREFIX=...` into a scratch prefix, then the README's example
# (its C block, built with the README's exact command) and a CMake project with find_package(ggx) are built and run
# with no LD_LIBRARY_PATH: a prefix outside the loader's folders gets an rpath through ggx.pc, and CMake's targets
# carry their own. Also checks the installed files (the shared library under its SONAME, libggx.so.MAJOR.MINOR while
# MAJOR is 0), the man page and the version, and that the installed Python package loads the installed libggx.
# Usage: install_test.sh BUILD SRC
set -eu
build=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"
version=$(sed -n 's/^#define GGX_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\)$/\2/p' "$src/include/ggx/ggx_version.h" |
          paste -sd. -)
case $version in
0.*) soname=libggx.so.$(echo "$version" | cut -d. -f1-2) ;;
*) soname=libggx.so.$(echo "$version" | cut -d. -f1) ;;
esac
make -s -C "$src" install BUILD="$build" PREFIX="$prefix" >"$tmp/install.log" 2>&1 || { cat "$tmp/install.log"; exit 1; }
# It says how to reach the pkg-config file of a prefix outside pkg-config's path, and that it used an rpath.
grep -q "export PKG_CONFIG_PATH=$prefix/lib.*/pkgconfig" "$tmp/install.log" ||
  { cat "$tmp/install.log"; echo "install: no PKG_CONFIG_PATH note" >&2; exit 1; }
grep -q "rpath" "$tmp/install.log" || { cat "$tmp/install.log"; echo "install: no rpath note" >&2; exit 1; }
libdir=$(ls -d "$prefix"/lib*/pkgconfig | head -n 1)
libdir=${libdir%/pkgconfig}
tool=
[ -x "$build/ggx" ] && tool="bin/ggx share/man/man1/ggx.1"
for f in include/ggx/ggx.h include/ggx/ggx_version.h include/ggx/ggx_inline.h include/ggx/ggx_batch.h \
         include/ggx/ggx_samplers.h include/ggx/ggx_fit.h include/ggx/ggx_experimental.h include/ggx/ggx_filter.h \
         include/ggx/ggx_sggx.h \
         $tool; do
  test -f "$prefix/$f" || { echo "install: $f missing" >&2; exit 1; }
done
for f in "$soname" libggx.so cmake/ggx/ggxConfig.cmake cmake/ggx/ggxConfigVersion.cmake pkgconfig/ggx.pc; do
  test -e "$libdir/$f" || { echo "install: $libdir/$f missing" >&2; exit 1; }
done
# the library of a shared build only (BUILD_SHARED_LIBS=OFF: tests/packaging/consumer_test.sh)
test ! -e "$libdir/libggx.a" || { echo "install: a shared build installed libggx.a too" >&2; exit 1; }
if [ -n "$tool" ]; then
  [ "$("$prefix/bin/ggx" --version)" = "ggx $version" ] || { echo "install: ggx --version is not ggx $version" >&2; exit 1; }
fi
grep -q "^Version: $version\$" "$libdir/pkgconfig/ggx.pc" || { echo "install: ggx.pc is not version $version" >&2; exit 1; }
grep -q '^prefix='"$prefix"'$' "$libdir/pkgconfig/ggx.pc" || { echo "install: ggx.pc names another prefix" >&2; exit 1; }

# The README's example, with the README's build command, run as is.
readme="$src/README.md"
awk '/^## Example/ {on = 1} on && /^```c$/ {code = 1; next} code && /^```$/ {exit} code {print}' "$readme" \
  > "$tmp/prog.c"
grep -q 'ggx_ndf' "$tmp/prog.c" || { echo "install: no C example found in README.md" >&2; exit 1; }
cmd=$(sed -n 's/^Build it with `\([^`]*\)`.*/\1/p' "$readme" | head -n 1)
[ -n "$cmd" ] || { echo "install: no 'Build it with' command in README.md" >&2; exit 1; }
(cd "$tmp" && PKG_CONFIG_PATH="$libdir/pkgconfig" sh -c "$cmd") ||
  { echo "install: README command failed: $cmd" >&2; exit 1; }
out=$(cd "$tmp" && env -u LD_LIBRARY_PATH ./a.out) || { echo "install: the README example did not run" >&2; exit 1; }
echo "README example: $out"
# Its line gives D, G1, pdf and f_r: each a positive number.
echo "$out" | awk '{ok = NF == 12; for (i = 3; i <= 12; i += 3) ok = ok && $i + 0 > 0} END {exit !ok}' ||
  { echo "install: unexpected example output" >&2; exit 1; }
ldd "$tmp/a.out" | grep -q "$soname => $libdir/" || { ldd "$tmp/a.out"; echo "install: not linked to the installed libggx" >&2; exit 1; }

# A CMake project with find_package(ggx).
mkdir "$tmp/consumer"
cp "$tmp/prog.c" "$tmp/consumer/prog.c"
cat > "$tmp/consumer/CMakeLists.txt" <<'C'
cmake_minimum_required(VERSION 3.16)
project(consumer C)
find_package(ggx 0.1 REQUIRED)
add_executable(prog prog.c)
target_link_libraries(prog PRIVATE ggx::ggx)
C
cmake -S "$tmp/consumer" -B "$tmp/consumer/build" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$tmp/consumer/build" >/dev/null
[ "$(env -u LD_LIBRARY_PATH "$tmp/consumer/build/prog")" = "$out" ] ||
  { echo "install: the find_package consumer printed another line" >&2; exit 1; }

# The Python package, where the install note says, importable with the PYTHONPATH it prints (from another folder).
if [ -f "$build/python/ggx/_ggx_native.so" ]; then
  pyline=$(grep "Python package ggx:" "$tmp/install.log") || { cat "$tmp/install.log"; echo "install: no Python note" >&2; exit 1; }
  pypath=$(echo "$pyline" | sed -n 's/.*export PYTHONPATH=\(.*\)$/\1/p')
  [ -n "$pypath" ] || { echo "install: no PYTHONPATH for a prefix outside python's path: $pyline" >&2; exit 1; }
  case $pypath in "$prefix"/lib/python3.*/dist-packages) ;; *) echo "install: Python package in $pypath" >&2; exit 1;; esac
  test -f "$pypath/ggx/__init__.py" && test -f "$pypath/ggx/_ggx_native.so" || { echo "install: ggx package files missing" >&2; exit 1; }
  py=/usr/bin/python3
  [ -x "$py" ] || py=python3
  d=$(cd "$tmp" && env -u LD_LIBRARY_PATH PYTHONPATH="$pypath" "$py" -c \
      'import ggx; print(ggx.__file__); print(ggx.__version__); print(ggx.ndf(ggx.Shape.iso(0.3), [0, 0, 1]))')
  echo "$d" | head -n 1 | grep -q "^$pypath/ggx/__init__.py$" || { echo "install: imported $d" >&2; exit 1; }
  [ "$(echo "$d" | sed -n 2p)" = "$version" ] || { echo "install: ggx.__version__ is not $version: $d" >&2; exit 1; }
  # the module links the installed libggx (one copy of the library), which it finds by itself
  ldd "$pypath/ggx/_ggx_native.so" | grep -q "$soname => $libdir/" ||
    { ldd "$pypath/ggx/_ggx_native.so"; echo "install: the Python module does not load the installed libggx" >&2; exit 1; }
  # D(n) = 1 / (pi alpha^2) for isotropic GGX
  echo "$d" | tail -n 1 | awk '{exit !($1 > 3.53677 && $1 < 3.53678)}' || { echo "install: ggx.ndf gave $d" >&2; exit 1; }
  echo "Python package: $pypath/ggx"
fi
# A prefix with a space: make install takes it, ggx.pc escapes it (pkg-config keeps each path one argument), the
# notes quote what they ask to export, and the README's example builds with the eval form the note gives.
sp="$tmp/pre fix"
make -s -C "$src" install BUILD="$build" PREFIX="$sp" >"$tmp/install-sp.log" 2>&1 || { cat "$tmp/install-sp.log"; exit 1; }
grep -q "export PKG_CONFIG_PATH='$sp/lib.*/pkgconfig'" "$tmp/install-sp.log" ||
  { cat "$tmp/install-sp.log"; echo "install: PKG_CONFIG_PATH note for a prefix with a space not quoted" >&2; exit 1; }
grep -q 'build with eval "cc prog.c $(pkg-config --cflags --libs ggx)"' "$tmp/install-sp.log" ||
  { cat "$tmp/install-sp.log"; echo "install: no eval note for a prefix with a space" >&2; exit 1; }
splib=$(ls -d "$sp"/lib*/pkgconfig | head -n 1)
(cd "$tmp" && rm -f a.out && PKG_CONFIG_PATH="$splib" sh -c 'eval "cc prog.c $(pkg-config --cflags --libs ggx)"') ||
  { echo "install: the eval build failed for a prefix with a space" >&2; exit 1; }
[ "$(cd "$tmp" && env -u LD_LIBRARY_PATH ./a.out)" = "$out" ] || { echo "install: prefix with a space: other output" >&2; exit 1; }
ldd "$tmp/a.out" | grep -q "$soname => $sp/" || { ldd "$tmp/a.out"; echo "install: not linked to $sp" >&2; exit 1; }
rm -rf "$tmp/consumer/build"
cmake -S "$tmp/consumer" -B "$tmp/consumer/build" -DCMAKE_PREFIX_PATH="$sp" >/dev/null
cmake --build "$tmp/consumer/build" >/dev/null
[ "$(env -u LD_LIBRARY_PATH "$tmp/consumer/build/prog")" = "$out" ] ||
  { echo "install: the find_package consumer of a prefix with a space printed another line" >&2; exit 1; }
if [ -f "$build/python/ggx/_ggx_native.so" ]; then
  # the printed line, run by a shell, sets the folder that holds the package
  export_line=$(sed -n "s/.*\(export PYTHONPATH=.*\)$/\1/p" "$tmp/install-sp.log")
  spy=$(sh -c "$export_line; echo \"\$PYTHONPATH\"")
  test -f "$spy/ggx/__init__.py" || { echo "install: the printed PYTHONPATH line gives '$spy'" >&2; exit 1; }
fi
echo "install test: make install PREFIX=... (also with a space), the README example, a find_package consumer and the Python package built and ran"
