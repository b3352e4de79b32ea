#!/usr/bin/env bash
# Check that every tracked C++ file (*.h, *.cc) is formatted with the
# repository's .clang-format (clang-format 14, as on Debian 12). Changes
# nothing; lists the offending lines and exits non-zero if any file is not
# formatted. To format: bash contrib/indent.sh
#   usage: bash contrib/check_format.sh
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$top"

cf=
for c in clang-format-14 clang-format; do
  command -v "$c" >/dev/null 2>&1 && { cf=$c; break; }
done
if [[ -z "$cf" ]]; then
  echo "check_format.sh: clang-format not found (bash contrib/setup.sh installs it)" >&2
  exit 1
fi
"$cf" --version | grep -q 'version 14\.' ||
  echo "check_format.sh: warning: the style is made for clang-format 14, this is: $("$cf" --version)" >&2

# Tracked files only (a git checkout); otherwise every *.h/*.cc of the tree.
if git -C "$top" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -d '' files < <(git -C "$top" ls-files -z -- '*.h' '*.cc')
else
  mapfile -d '' files < <(find include source tests contrib \
    \( -name '*.h' -o -name '*.cc' \) -type f -print0 | sort -z)
fi
if [[ ${#files[@]} -eq 0 ]]; then
  echo "check_format.sh: no C++ files found" >&2
  exit 1
fi

log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
printf '%s\0' "${files[@]}" |
  xargs -0 -n 20 "$cf" --style=file --dry-run --Werror >"$log" 2>&1 || status=$?
if [[ $status -ne 0 ]]; then
  cat "$log"
  mapfile -t bad < <(grep -o '^[^:]*\.\(h\|cc\):[0-9]*:[0-9]*: error' "$log" |
                       cut -d: -f1 | sort -u)
  echo "check_format.sh: ${#bad[@]} of ${#files[@]} files are not formatted:" >&2
  printf '  %s\n' "${bad[@]}" >&2
  echo "check_format.sh: run bash contrib/indent.sh and commit the result" >&2
  exit 1
fi
echo "check_format.sh: all ${#files[@]} tracked C++ files are formatted ($cf)"
