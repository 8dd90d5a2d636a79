#!/bin/sh
# Installs the Debian packages that building and testing libggx need, skipping those already present.
# Run as root (CI and the project's machines are root); otherwise it uses sudo when available.
set -eu
need=""
pkgs="cmake make gcc g++ pkg-config libcmocka-dev libpng-dev libxml2-utils"
[ $# -gt 0 ] && pkgs="$*" # extra packages for the robustness targets (make deps-dev)
for pkg in $pkgs; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || need="$need $pkg"
done
[ -z "$need" ] && exit 0
echo "install-deps: installing$need"
SUDO=""
if [ "$(id -u)" != 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
    echo "install-deps: missing packages:$need (run as root or install them)" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends $need
