#!/bin/sh
# The man page ggx(1) is complete and well formed: it names every command of `ggx --help` as a section with that
# command's --help text, every sampler of the registry (as `ggx sample --help` lists them) and the exit statuses,
# and groff renders it without a warning. Usage: man_test.sh GGX MANPAGE
set -eu
ggx=$1
page=$2
fail=0
bad() { echo "man: $*" >&2; fail=1; }
warn=$(groff -man -Tutf8 -ww -z "$page" 2>&1) || bad "groff failed"
[ -z "$warn" ] || bad "groff warnings: $warn"
text=$(groff -man -Tutf8 -P-c -P-b -P-u "$page" 2>/dev/null)
for c in $("$ggx" --help | awk '/^commands:$/ {on = 1; next} on && /^$/ {exit} on {print $1}'); do
  printf '%s\n' "$text" | grep -q "^   $c\$" || bad "no section for command '$c'"
  # the command's usage line, as its --help prints it
  usage=$("$ggx" "$c" --help | head -n 1)
  printf '%s\n' "$text" | grep -qF -- "$usage" || bad "'$c --help' usage line missing: $usage"
done
usage=$("$ggx" render --normal-map x --help | head -n 1)
printf '%s\n' "$text" | grep -qF -- "$usage" || bad "'render --normal-map --help' usage line missing: $usage"
for s in $("$ggx" sample --help | awk '/^samplers:$/ {on = 1; next} on && /^$/ {exit} on {print $1}'); do
  printf '%s\n' "$text" | grep -q "^ *$s  " || bad "sampler '$s' missing"
done
for h in NAME SYNOPSIS DESCRIPTION OUTPUT "EXIT STATUS" COMMANDS; do
  printf '%s\n' "$text" | grep -q "^$h\$" || bad "no $h section"
done
printf '%s\n' "$text" | grep -q "141 the reader of stdout" || bad "exit status 141 not described"
# OUTPUT states where --out writes in place instead of renaming a temporary over the file (the roff source, whose
# lines are the help's: the rendered text is filled and hyphenated)
for w in "renamed over it" "written in place" "/dev/stdout" "hard links" "extended attributes" \
         "a folder the user may not write" "in any case"; do
  sed 's/\\-/-/g' "$page" | grep -qF -- "$w" || bad "OUTPUT does not state '$w'"
done
printf '%s\n' "$text" | grep -q "libggx $("$ggx" --version | sed 's/^ggx //')" || bad "version missing"
[ $fail = 0 ] && echo "man page: $(printf '%s\n' "$text" | wc -l) lines, every command and sampler, no groff warning"
exit $fail
