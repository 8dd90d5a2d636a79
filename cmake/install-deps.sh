#!/bin/sh
# Installs the given Debian packages (the Makefile's lists), skipping those already present. Run as root (CI and
# the project's machines are root); otherwise it uses sudo when available. apt's output goes to a log that is shown
# only when the installation fails.
set -eu
if ! command -v dpkg-query >/dev/null 2>&1; then
  echo "install-deps: not a Debian system; the build needs the equivalents of: $*" >&2
  exit 0 # CMake's configure step names whatever is missing
fi
need=""
for pkg in "$@"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || need="$need $pkg"
done
[ -z "$need" ] && exit 0
log=$(mktemp "${TMPDIR:-/tmp}/ggx-apt.XXXXXX")
trap 'rm -f "$log"' EXIT
echo "install-deps: installing$need (apt-get)"
SUDO=""
if [ "$(id -u)" != 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
    echo "install-deps: missing packages:$need (run as root or install them)" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
if ! { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq --no-install-recommends $need; } >"$log" 2>&1; then
  tail -n 30 "$log" >&2
  echo "install-deps: apt-get failed; install these Debian packages:$need" >&2
  exit 1
fi
