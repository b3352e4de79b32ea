#!/usr/bin/env bash
# Format the C++ sources with clang-format 14 and the top-level .clang-format.
#   usage: bash contrib/indent.sh           rewrite files in place
#          bash contrib/indent.sh --check   change nothing, list offending
#                                           lines, exit non-zero if any
# Files: include/**/*.h source/**/*.cc tests/**/*.cc contrib/**/*.cc
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$top"

mode=(-i)
case "${1:-}" in
  "") ;;
  --check) mode=(--dry-run --Werror) ;;
  *) echo "usage: $0 [--check]" >&2; exit 2 ;;
esac

cf=
for c in clang-format-14 clang-format; do
  command -v "$c" >/dev/null 2>&1 && { cf=$c; break; }
done
[[ -n "$cf" ]] || { echo "indent.sh: clang-format not found (apt-get install clang-format)" >&2; exit 1; }
"$cf" --version | grep -q 'version 14\.' ||
  echo "indent.sh: warning: the style is made for clang-format 14, this is: $("$cf" --version)" >&2

mapfile -d '' files < <(find include source tests contrib \
  \( -name '*.h' -path 'include/*' -o -name '*.cc' \) -type f -print0 2>/dev/null | sort -z)
[[ ${#files[@]} -gt 0 ]] || { echo "indent.sh: no source files found"; exit 0; }

status=0
printf '%s\0' "${files[@]}" | xargs -0 -n 50 -P "$(nproc 2>/dev/null || echo 1)" \
  "$cf" --style=file "${mode[@]}" || status=$?
if [[ ${mode[0]} == -i ]]; then
  echo "indent.sh: ran $cf on ${#files[@]} files"
elif [[ $status -ne 0 ]]; then
  echo "indent.sh: some of ${#files[@]} files are not formatted: run bash contrib/indent.sh" >&2
else
  echo "indent.sh: all ${#files[@]} files formatted"
fi
exit "$status"
