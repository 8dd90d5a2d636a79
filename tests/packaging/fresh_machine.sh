#!/bin/bash
# shellcheck disable=SC2317 # functions called from the traps
# tests/packaging/fresh_machine.sh: the README on a fresh Debian 12 machine.
#
# Builds a minimal Debian 12 (bookworm) root with `debootstrap --variant=minbase` in a scratch folder, installs only
# git and make in it, clones the repository's committed HEAD (not the working tree) into it with that git, and runs
# as root in a chroot, in the clone, what the README tells a user to run:
#   make run, make test, make install, then the C program under "## Example" built with the README's own command
#   (the line "Build it with `...`": cc prog.c $(pkg-config --cflags --libs ggx)) and run as ./a.out.
# Every other build tool must come from the project itself (make run installs them with apt-get). Each step is timed
# and logged; a summary table ends the run; the exit status is 0 only if every step passed. No LD_LIBRARY_PATH or
# other help is given to the example: if ./a.out cannot find libggx.so.0, make install is at fault.
#
# Not part of `make test`. Requirements:
#   - root (debootstrap, chroot, mounts), on a Debian-like host with apt-get (debootstrap is installed if absent);
#   - network access to the Debian archive: the mirror of the host's apt configuration (the main Debian suite's URIs:
#     in /etc/apt/sources.list.d/*.sources, or /etc/apt/sources.list), else http://deb.debian.org/debian;
#   - about 1.5 GB of disk in the scratch folder and a few minutes (measured on 2 cores with a near mirror: 2.5 min).
#
# Usage: tests/packaging/fresh_machine.sh [--keep] [--dir DIR]
#   --keep     keep the root (DIR/root) afterwards, its mounts undone; default: remove it, keeping only the logs
#   --dir DIR  scratch folder (created if absent; DIR/root must not exist); default: a new mktemp -d folder in /tmp
# Environment:
#   GGX_MIRROR           the Debian mirror (for bookworm and bookworm-updates), instead of the host's
#   GGX_SECURITY_MIRROR  the security archive for bookworm-security (default: the host's, if it has one; none: leave out)
#
# Mounts: the script runs in its own private mount namespace (unshare --mount) where util-linux allows it, so no
# mount is ever seen outside it; in the root it mounts /proc, a read-only /sys, and a small /dev (a tmpfs with the
# host's null, zero, full, random, urandom and tty bound in, a new devpts instance, a tmpfs /dev/shm), never the
# host's /dev itself. On every exit (success, failure, Ctrl-C, SIGTERM, SIGHUP) it stops the running step's
# processes, unmounts everything under the root, checks /proc/self/mountinfo that nothing is left, and only then
# removes the root (rm -rf --one-file-system); if a mount is left it keeps the root and says so.
# Logs: DIR/logs/NN-step.log, one per step, kept in every case; a failing step's last 30 lines are printed.

[ -n "${BASH_VERSION:-}" ] || exec bash "$0" "$@" # run by sh: bash is needed (arrays)
set -u
umask 022
export LC_ALL=C

SUITE=bookworm
CHROOT_PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
SELF=$(readlink -f "$0")
ORIG_ARGS=("$@")

usage() { sed -n '3,/^$/{s/^# \{0,1\}//;p}' "$SELF"; }
say() { printf 'fresh_machine: %s\n' "$*"; }
die() { printf 'fresh_machine: %s\n' "$*" >&2; exit 2; }

KEEP=0
DIR=
while [ $# -gt 0 ]; do
  case $1 in
    --keep) KEEP=1 ;;
    --dir) [ $# -ge 2 ] || die "--dir needs a folder"; DIR=$2; shift ;;
    --dir=*) DIR=${1#--dir=} ;;
    -h|--help) usage; exit 0 ;;
    *) die "unknown option: $1 (try --help)" ;;
  esac
  shift
done

[ "$(id -u)" = 0 ] || die "must run as root (debootstrap, chroot and mounts need it)"
TOP=$(git -C "$(dirname "$SELF")/.." rev-parse --show-toplevel 2>/dev/null) || die "not inside a git repository"

# A private mount namespace: the root's mounts are invisible outside and vanish with this process.
if [ -z "${GGX_FRESH_NS:-}" ]; then
  if command -v unshare >/dev/null 2>&1 && unshare --mount --propagation private true 2>/dev/null; then
    GGX_FRESH_NS=private exec unshare --mount --propagation private -- bash "$SELF" "${ORIG_ARGS[@]}"
  fi
  say "warning: unshare --mount unavailable; mounting in the host's namespace (the root is made a private mount first)"
  GGX_FRESH_NS=host
fi
export GGX_FRESH_NS

SHA=$(git -C "$TOP" rev-parse --verify 'HEAD^{commit}') || die "no commit at HEAD in $TOP"

# ---- scratch folder ----
if [ -n "$DIR" ]; then
  mkdir -p "$DIR" || die "cannot create $DIR"
  SCRATCH=$(readlink -f "$DIR")
else
  SCRATCH=$(mktemp -d /tmp/ggx-fresh.XXXXXX) || die "mktemp failed"
fi
case $SCRATCH/ in "$TOP"/*) die "the scratch folder $SCRATCH must be outside the repository $TOP" ;; esac
[ "$SCRATCH" != / ] || die "refusing / as the scratch folder"
R=$SCRATCH/root
LOGS=$SCRATCH/logs
[ ! -e "$R" ] || die "$R already exists; give another --dir or remove it"
mkdir -p "$LOGS" || die "cannot create $LOGS"
mkdir "$R" || die "cannot create $R"
avail_kb=$(df -Pk "$SCRATCH" | awk 'NR == 2 { print $4 }')
[ "${avail_kb:-0}" -ge 1572864 ] || say "warning: only $((${avail_kb:-0} / 1024)) MB free in $SCRATCH (about 1.5 GB needed)"

# ---- mirrors, from the host's apt configuration ----
# deb822 stanzas: the first URI of an enabled "Types: deb" stanza with a suite matching the regex $1.
uri_deb822() {
  local f
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -r "$f" ] || continue
    awk -v re="$1" '
      function flush(  n, a, i, u) {
        if (types ~ /(^|[ \t])deb([ \t]|$)/ && tolower(enabled) != "no" && uris != "") {
          n = split(suites, a, /[ \t]+/)
          for (i = 1; i <= n; i++) if (a[i] ~ re) { split(uris, u, /[ \t]+/); print u[1]; found = 1; exit }
        }
        types = suites = uris = enabled = ""
      }
      /^[ \t]*#/ { next }
      /^[ \t]*$/ { flush(); next }
      { key = tolower($0); sub(/:.*/, "", key); val = $0; sub(/^[^:]*:[ \t]*/, "", val); sub(/[ \t]+$/, "", val) }
      key == "types" { types = val } key == "suites" { suites = val } key == "uris" { uris = val }
      key == "enabled" { enabled = val }
      END { if (!found) flush() }' "$f"
  done
}
# One-line sources: "deb [options] URI SUITE COMPONENTS...".
uri_oneline() {
  cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null |
    awk -v re="$1" '$1 == "deb" { i = 2; if ($2 ~ /^\[/) { while (i <= NF && $i !~ /\]$/) i++; i++ }
                                  if ($(i + 1) ~ re) { print $i; exit } }'
}
host_uri() { # first http(s)/ftp URI for the suite regexes given, in order of preference
  local re u
  for re in "$@"; do
    for u in $(uri_deb822 "$re") $(uri_oneline "$re"); do
      case $u in http://*|https://*|ftp://*) printf '%s\n' "${u%/}"; return 0 ;; esac
    done
  done
  return 1
}
CODENAMES='^(buster|bullseye|bookworm|trixie|forky|duke|sid|oldoldstable|oldstable|stable|testing|unstable)$'
if [ -n "${GGX_MIRROR:-}" ]; then MIRROR=${GGX_MIRROR%/}; MIRROR_FROM="GGX_MIRROR"
elif MIRROR=$(host_uri "^$SUITE\$" "$CODENAMES"); then MIRROR_FROM="host apt configuration"
else MIRROR=http://deb.debian.org/debian; MIRROR_FROM="default"
fi
if [ -n "${GGX_SECURITY_MIRROR:-}" ]; then SEC_MIRROR=${GGX_SECURITY_MIRROR%/}
else SEC_MIRROR=$(host_uri "^$SUITE-security\$" '-security$') || SEC_MIRROR=none
fi
# An apt proxy of the host is used by debootstrap (environment) and by apt in the root (its apt.conf.d file, copied).
APT_HTTP_PROXY='' APT_HTTPS_PROXY=''
eval "$(apt-config shell APT_HTTP_PROXY Acquire::http::Proxy APT_HTTPS_PROXY Acquire::https::Proxy 2>/dev/null)"
[ -n "$APT_HTTP_PROXY" ] && [ "$APT_HTTP_PROXY" != DIRECT ] && export http_proxy=${http_proxy:-$APT_HTTP_PROXY}
[ -n "$APT_HTTPS_PROXY" ] && [ "$APT_HTTPS_PROXY" != DIRECT ] && export https_proxy=${https_proxy:-$APT_HTTPS_PROXY}

# ---- steps: each in its own session (so a signal to this script can stop all of it), logged and timed ----
NAMES=() STATUS=() SECS=() RCS=() LOGFILES=()
STEP_PID='' CUR_NAME='' CUR_LOG='' CUR_T0=''
T_START=$(date +%s.%N)

elapsed() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }'; }

record() { # name status seconds rc log
  NAMES+=("$1") STATUS+=("$2") SECS+=("$3") RCS+=("$4") LOGFILES+=("$5")
}

# run_step NAME COMMAND...: runs COMMAND (niced) with its output in the step's log; returns its status.
run_step() {
  local name=$1; shift
  local n log t0 rc secs
  n=$(printf '%02d' $((${#NAMES[@]} + 1)))
  log=$LOGS/$n-$name.log
  say "[$n] $name ... (log: $log)"
  t0=$(date +%s.%N)
  CUR_NAME=$name CUR_LOG=$log CUR_T0=$t0
  setsid nice -n 10 "$@" >"$log" 2>&1 </dev/null &
  STEP_PID=$!
  wait "$STEP_PID"; rc=$?
  STEP_PID='' CUR_NAME=''
  secs=$(elapsed "$t0")
  if [ "$rc" = 0 ]; then
    record "$name" PASS "$secs" "$rc" "$log"
    say "[$n] $name: pass, $secs s"
  else
    record "$name" FAIL "$secs" "$rc" "$log"
    say "[$n] $name: FAIL (exit $rc), $secs s; last 30 lines of $log:"
    tail -n 30 "$log" | sed 's/^/    | /'
  fi
  return "$rc"
}
skip_step() { record "$1" SKIP - - -; say "$1: skipped ($2)"; }

# A command in the root, as root, in a clean environment (what a fresh login would have, nothing of this shell's):
# run_step NAME "${IN_ROOT[@]}" 'COMMAND'.
IN_ROOT=(chroot "$R" /usr/bin/env -i HOME=/root PATH="$CHROOT_PATH" TERM=dumb /bin/sh -c)

# ---- mounts and cleanup ----
mounts_under() { # mount points at or under $R, deepest first
  awk -v r="$R" '{ mp = $5; gsub(/\\040/, " ", mp); if (mp == r || index(mp, r "/") == 1) print mp }' \
    /proc/self/mountinfo | sort -r
}
kill_root_procs() { # processes whose root is $R (only ours: $R is this run's new folder), by id
  local p
  for p in /proc/[0-9]*; do
    [ "$(readlink "$p/root" 2>/dev/null)" = "$R" ] && kill "-$1" "${p#/proc/}" 2>/dev/null
  done
}
alive() { # running, not a zombie
  local st
  st=$(sed 's/.*) //' "/proc/$1/stat" 2>/dev/null) || return 1
  [ -n "$st" ] && [ "${st%% *}" != Z ]
}
stop_step() {
  [ -n "$STEP_PID" ] || return 0
  kill -TERM -- "-$STEP_PID" 2>/dev/null || kill -TERM "$STEP_PID" 2>/dev/null
  local i
  for i in 1 2 3 4 5 6 7 8 9 10; do alive "$STEP_PID" || break; sleep 0.5; done
  kill -KILL -- "-$STEP_PID" 2>/dev/null
  wait "$STEP_PID" 2>/dev/null
  STEP_PID=
  [ -n "$CUR_NAME" ] && record "$CUR_NAME" STOPPED "$(elapsed "$CUR_T0")" - "$CUR_LOG"
  CUR_NAME=
}
unmount_all() {
  local try mp left
  for try in 1 2 3 4 5 6; do
    left=$(mounts_under)
    [ -z "$left" ] && return 0
    case $try in 3) kill_root_procs TERM; sleep 1 ;; 4) kill_root_procs KILL; sleep 1 ;; esac
    for mp in $left; do
      if [ "$try" -ge 5 ]; then umount -l "$mp" 2>/dev/null; else umount "$mp" 2>/dev/null; fi
    done
  done
  [ -z "$(mounts_under)" ]
}
setup_mounts() {
  mount -t proc -o nosuid,nodev,noexec proc "$R/proc" || return 1
  mount -t sysfs -o ro,nosuid,nodev,noexec sysfs "$R/sys" || say "warning: cannot mount sysfs on $R/sys"
  mount -t tmpfs -o mode=0755,nosuid,size=16m ggx-dev "$R/dev" || return 1
  local d
  for d in null zero full random urandom tty; do
    : >"$R/dev/$d" && mount --bind "/dev/$d" "$R/dev/$d" || return 1
  done
  ln -s /proc/self/fd "$R/dev/fd" && ln -s fd/0 "$R/dev/stdin" && ln -s fd/1 "$R/dev/stdout" &&
    ln -s fd/2 "$R/dev/stderr" && mkdir -m 0755 "$R/dev/pts" && mkdir -m 1777 "$R/dev/shm" || return 1
  if mount -t devpts -o newinstance,ptmxmode=0666,mode=0620 devpts "$R/dev/pts"; then
    ln -s pts/ptmx "$R/dev/ptmx"
  else
    say "warning: cannot mount a devpts instance on $R/dev/pts (no pseudo-terminals in the root)"
  fi
  mount -t tmpfs -o mode=1777,nosuid,nodev ggx-shm "$R/dev/shm" || return 1
}

SUMMARY_DONE=0
summary() {
  [ "$SUMMARY_DONE" = 1 ] && return 0
  SUMMARY_DONE=1
  local i fails=0
  echo
  echo "fresh_machine: Debian $SUITE minbase, commit $SHA"
  echo "fresh_machine: mirror $MIRROR ($MIRROR_FROM), security $SEC_MIRROR, mount namespace: $GGX_FRESH_NS"
  printf '  %-3s %-16s %-6s %9s %5s  %s\n' '#' step result seconds exit log
  for i in "${!NAMES[@]}"; do
    printf '  %-3s %-16s %-6s %9s %5s  %s\n' "$((i + 1))" "${NAMES[$i]}" "${STATUS[$i]}" "${SECS[$i]}" \
      "${RCS[$i]}" "${LOGFILES[$i]}"
    [ "${STATUS[$i]}" = PASS ] || fails=$((fails + 1))
  done
  for i in "${!NAMES[@]}"; do
    case ${NAMES[$i]} in
      make-run) echo "make run: ${SECS[$i]} s (exit ${RCS[$i]})" ;;
      make-test) echo "make test: ${SECS[$i]} s (exit ${RCS[$i]})" ;;
    esac
  done
  echo "total: $(elapsed "$T_START") s; $fails step(s) not passed; logs in $LOGS"
  [ "$fails" = 0 ]
}

cleanup() {
  local rc=$?
  trap '' INT TERM HUP
  [ -n "${INTERRUPTED:-}" ] && say "interrupted by SIG$INTERRUPTED; cleaning up"
  stop_step
  if ! unmount_all; then
    say "ERROR: still mounted under $R, NOT removing it:"; mounts_under | sed 's/^/    /'
    KEEP=1; rc=1
  fi
  summary || { [ "$rc" = 0 ] && rc=1; }
  if [ "$KEEP" = 1 ]; then
    say "root kept: $R (chroot $R /bin/bash to look around; nothing is mounted)"
  elif [ -d "$R" ]; then
    if rm -rf --one-file-system "$R"; then say "root removed; logs kept in $LOGS"; else say "could not remove $R"; rc=1; fi
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'INTERRUPTED=INT; exit 130' INT
trap 'INTERRUPTED=TERM; exit 143' TERM
trap 'INTERRUPTED=HUP; exit 129' HUP

say "commit $SHA of $TOP; scratch $SCRATCH"
say "mirror $MIRROR ($MIRROR_FROM); security: $SEC_MIRROR"

# The root as a private mount of its own: nothing mounted under it propagates anywhere, even without unshare.
mount --bind "$R" "$R" && mount --make-private "$R" || die "cannot bind-mount $R onto itself"

# ---- 1. debootstrap ----
if ! command -v debootstrap >/dev/null 2>&1; then
  run_step host-debootstrap sh -c 'export DEBIAN_FRONTEND=noninteractive
    apt-get install -y --no-install-recommends debootstrap || { apt-get update && apt-get install -y --no-install-recommends debootstrap; }' ||
    exit 1
fi
INCLUDE=
case $MIRROR$SEC_MIRROR in *https://*) INCLUDE=--include=ca-certificates ;; esac
run_step debootstrap debootstrap --variant=minbase $INCLUDE "$SUITE" "$R" "$MIRROR" || exit 1
# debootstrap mounts and unmounts /proc and /sys itself; leave nothing of it behind before mounting ours.
for mp in $(mounts_under); do [ "$mp" = "$R" ] || umount "$mp" 2>/dev/null; done

# ---- 2. apt configuration, mounts, git and make ----
{
  rm -f "$R/etc/apt/sources.list"
  printf 'Types: deb\nURIs: %s\nSuites: %s %s-updates\nComponents: main\nSigned-By: %s\n' \
    "$MIRROR" "$SUITE" "$SUITE" /usr/share/keyrings/debian-archive-keyring.gpg
  [ "$SEC_MIRROR" = none ] ||
    printf '\nTypes: deb\nURIs: %s\nSuites: %s-security\nComponents: main\nSigned-By: %s\n' \
      "$SEC_MIRROR" "$SUITE" /usr/share/keyrings/debian-archive-keyring.gpg
} >"$R/etc/apt/sources.list.d/debian.sources.new" && mv "$R/etc/apt/sources.list.d/debian.sources.new" \
  "$R/etc/apt/sources.list.d/debian.sources" || die "cannot write the root's apt sources"
# The host's apt settings for reaching its mirror: proxies, TLS, date checks (a snapshot mirror), credentials.
for f in /etc/apt/apt.conf /etc/apt/apt.conf.d/*; do
  [ -f "$f" ] && grep -Eiq 'proxy|check-valid-until|check-date|verify-peer|verify-host|cainfo|sslcert|sslkey' "$f" &&
    { cp "$f" "$R$f" && say "copied $f into the root"; }
done
[ -f /etc/apt/auth.conf ] && cp -p /etc/apt/auth.conf "$R/etc/apt/auth.conf"
for f in /etc/apt/auth.conf.d/*; do [ -f "$f" ] && cp -p "$f" "$R$f"; done
if [ -n "${http_proxy:-}${https_proxy:-}" ] && [ -z "$APT_HTTP_PROXY$APT_HTTPS_PROXY" ]; then
  { [ -n "${http_proxy:-}" ] && printf 'Acquire::http::Proxy "%s";\n' "$http_proxy"
    [ -n "${https_proxy:-}" ] && printf 'Acquire::https::Proxy "%s";\n' "$https_proxy"; } \
    >"$R/etc/apt/apt.conf.d/99fresh-machine-proxy"
fi
rm -f "$R/etc/resolv.conf" && cp -L /etc/resolv.conf "$R/etc/resolv.conf" || die "cannot copy /etc/resolv.conf"
printf '#!/bin/sh\nexit 101\n' >"$R/usr/sbin/policy-rc.d" && chmod 755 "$R/usr/sbin/policy-rc.d" # no daemons
setup_mounts || die "cannot mount /proc and /dev in $R"

PKGS="git make"
case $MIRROR$SEC_MIRROR in *https://*) PKGS="$PKGS ca-certificates" ;; esac
run_step apt-git-make "${IN_ROOT[@]}" "export DEBIAN_FRONTEND=noninteractive; apt-get update &&
  apt-get install -y --no-install-recommends $PKGS" || exit 1

# ---- 3. the committed HEAD, cloned by the root's git from a bundle (the host's path is not visible inside) ----
mkdir -p "$R/work" && git -C "$TOP" bundle create "$R/tmp/libggx.bundle" HEAD >"$LOGS/bundle.log" 2>&1 ||
  { cat "$LOGS/bundle.log"; die "git bundle failed"; }
run_step clone "${IN_ROOT[@]}" "git clone -c advice.detachedHead=false /tmp/libggx.bundle /work/libggx &&
  test \"\$(git -C /work/libggx rev-parse HEAD)\" = $SHA && git -C /work/libggx log --oneline -1" || exit 1
rm -f "$R/tmp/libggx.bundle"
# The project's CI puts ../shared beside the clone; copy it only if the build or the tests refer to it.
if git -C "$TOP" grep -q -e '\.\./shared' "$SHA" -- Makefile CMakeLists.txt cmake tests tools src \
     ':!tests/packaging/fresh_machine.sh' 2>/dev/null; then
  if [ -d "$TOP/../shared" ]; then cp -a "$TOP/../shared" "$R/work/shared" && say "copied ../shared beside the clone"
  else say "warning: the build refers to ../shared but $TOP/../shared does not exist"; fi
else
  say "../shared: not referred to by the build or the tests; not copied"
fi

# ---- 4. the README's commands ----
FAILED=0
run_step make-run "${IN_ROOT[@]}" "cd /work/libggx && make run" || FAILED=1
run_step make-test "${IN_ROOT[@]}" "cd /work/libggx && make test" || FAILED=1
run_step make-install "${IN_ROOT[@]}" "cd /work/libggx && make install" || FAILED=1

# The README's example, its build command taken verbatim from the README.
README=$R/work/libggx/README.md
mkdir -p "$R/work/example"
awk '/^## Example/ { s = 1; next } s == 1 && /^```c/ { s = 2; next } s == 2 && /^```/ { exit } s == 2 { print }' \
  "$README" >"$R/work/example/prog.c"
BUILD_CMD=$(sed -n 's/^Build it with `\([^`]*\)`.*/\1/p' "$README" | head -n 1)
if [ ! -s "$R/work/example/prog.c" ] || [ -z "$BUILD_CMD" ]; then
  say "README.md: no C block under '## Example' or no 'Build it with \`...\`' line"
  record example-build FAIL - - -; skip_step example-run "no example"
  FAILED=1
else
  say "example build command (from README.md): $BUILD_CMD"
  if run_step example-build "${IN_ROOT[@]}" "cd /work/example && $BUILD_CMD"; then
    if run_step example-run "${IN_ROOT[@]}" "cd /work/example && ./a.out"; then
      sed 's/^/    /' "${LOGFILES[${#LOGFILES[@]} - 1]}"
    else
      FAILED=1
      grep -q 'libggx\.so[.0-9]*: cannot open shared object file' "${LOGFILES[${#LOGFILES[@]} - 1]}" &&
        say "FAILURE: ./a.out cannot load libggx.so.0 after the default make install (the loader's cache does not list it: no ldconfig, or no rpath)"
    fi
  else
    FAILED=1
    skip_step example-run "example-build failed"
  fi
fi
exit "$FAILED"
