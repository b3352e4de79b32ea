#!/usr/bin/env bash
# Print the slowest tests of one or more saved ctest outputs (the lines
# "  12/345 Test  #67: NAME .....   Passed    3.21 sec").
#   usage: bash contrib/slowest_tests.sh CTEST_OUTPUT... [-n N]
set -euo pipefail
n=15
files=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -n) n=$2; shift 2 ;;
    *) files+=("$1"); shift ;;
  esac
done
echo "slowest tests (wall seconds):"
{ grep -h -E '^ *[0-9]+/[0-9]+ Test +#[0-9]+: ' "${files[@]}" || true; } |
  sed -E 's/^ *[0-9]+\/[0-9]+ Test +#[0-9]+: ([^ ]+) .* ([0-9.]+) sec.*$/\2 \1/' |
  { grep -E '^[0-9.]+ ' || true; } | sort -g -r |
  awk -v n="$n" 'NR <= n { printf "  %8.1f  %s\n", $1, $2 }'
