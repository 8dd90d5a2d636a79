#!/bin/sh
# Writes the man page ggx(1) from the command's own --help texts, so that it cannot drift from them: NAME and
# SYNOPSIS, the commands with their summaries, the paragraphs of `ggx --help` headed "word:" (options, output, exit
# status) as sections, then each command's full --help. Usage: man.sh GGX OUT (built and installed by CMake).
# SPDX-License-Identifier: MIT
set -eu
ggx=$1
out=$2
tmp="$out.tmp.$$"
trap 'rm -f "$tmp"' EXIT INT TERM

# roff escapes: backslash, hyphen-minus (as \- so options copy and paste), a leading . or ' (a request otherwise)
esc() { sed -e 's/\\/\\e/g' -e 's/-/\\-/g' -e "s/^[.']/\\\\\&&/"; }

version=$("$ggx" --version | sed 's/^ggx //')
help=$("$ggx" --help)
commands=$(printf '%s\n' "$help" | awk '/^commands:$/ {on = 1; next} on && /^$/ {exit} on {print $1}')
[ -n "$commands" ] || { echo "man.sh: no commands in '$ggx --help'" >&2; exit 1; }

{
  printf '.TH GGX 1 "" "libggx %s" "User Commands"\n' "$version"
  printf '.SH NAME\nggx \\- evaluate, sample, verify and draw GGX as the normal distribution of a truncated ellipsoid\n'
  printf '.SH SYNOPSIS\n.B ggx\n.I command\n.RI [ options ]\n.br\n.B ggx \\-\\-help\n.br\n.B ggx \\-V\n'
  printf '.SH DESCRIPTION\n'
  printf '%s\n' "$help" | awk '/^commands:$/ {on = 1; next} on && /^$/ {exit} on {print}' | esc |
    awk '{name = $1; $1 = ""; sub(/^ +/, ""); printf ".TP\n.B %s\n%s\n", name, $0}'
  # Paragraphs headed "word[ word]: text" become sections (EXIT STATUS, OUTPUT, OPTIONS).
  printf '%s\n' "$help" | awk '
    /^$/ {on = 0; next}
    /^[a-z]+( [a-z]+)?: / && !/^usage:/ {
      i = index($0, ": "); head = toupper(substr($0, 1, i - 1))
      rest = substr($0, i + 2); printf ".SH %s\n%s\n", head, toupper(substr(rest, 1, 1)) substr(rest, 2)
      on = 1; next }
    on {print}' | esc | sed 's/^\\&\.SH/.SH/'
  printf '.SH COMMANDS\n'
  for c in $commands; do
    printf '.SS %s\n.nf\n' "$c"
    "$ggx" "$c" --help | esc
    printf '.fi\n'
    if [ "$c" = render ]; then # its second form, a normal map's chain against its ground truth
      printf '.SS render \\-\\-normal\\-map\n.nf\n'
      "$ggx" render --normal-map x --help | esc
      printf '.fi\n'
    fi
  done
  printf '.SH SEE ALSO\nThe library'"'"'s headers\n.IR ggx/ggx.h ,\n.IR ggx/ggx_inline.h ,\n.I ggx/ggx_batch.h\n'
  printf 'and its README, which give the conventions (n = +z, unit directions pointing away from the surface)\n'
  printf 'and the seeds'"'"' equations behind every function.\n'
  printf '.SH LICENSE\nMIT.\n'
} > "$tmp"
mv "$tmp" "$out"
trap - EXIT INT TERM
