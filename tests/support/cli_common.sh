# Shared by the command's shell tests (cli_test.sh, fit_cli_test.sh, mipmap_cli_test.sh), sourced with the ggx binary as $1: the binary
# by absolute path, ggx_run (under GGX_WRAP, e.g. valgrind, when set), a scratch folder made the working folder and
# removed on exit, and the pass/fail counters ok and bad. Compute paths relative to the caller's folder first.
# SPDX-License-Identifier: MIT
GGX_BIN=$(command -v "$1") || GGX_BIN=$1
case $GGX_BIN in /*) ;; *) GGX_BIN=$(pwd)/$GGX_BIN ;; esac
GGX="ggx_run"
ggx_run() { ${GGX_WRAP:-} "$GGX_BIN" "$@"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
# description, expected substring, expected status, command...: the command exits with that status and prints one
# line "ggx: ...<substring>..." on stderr
one_line() {
    desc=$1; want=$2; st=$3; shift 3
    rm -f err.txt
    "$@" > /dev/null 2> err.txt
    rc=$?
    if [ $rc -eq "$st" ] && [ "$(wc -l < err.txt)" -eq 1 ] && grep -q "^ggx: .*$want" err.txt; then ok; else bad "$desc: rc $rc, stderr: $(cat err.txt)"; fi
}
