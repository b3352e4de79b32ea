#!/usr/bin/env bash
# Regenerate doc/parameters.md, the reference of all input parameters, from
# `talus --print-parameters`.  Run it after adding or changing a parameter.
#   usage: bash contrib/generate_parameter_doc.sh [talus binary]
# The binary defaults to build/talus; a relative path is taken relative to the
# current directory, the default relative to the repository top.
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
talus=${1:-$top/build/talus}
out=$top/doc/parameters.md

[[ -x "$talus" ]] || { echo "generate_parameter_doc.sh: no talus executable at <$talus> (build it with contrib/build.sh or pass its path)" >&2; exit 1; }

listing=$(mktemp)
trap 'rm -f "$listing" "$out.tmp"' EXIT
"$talus" --print-parameters > "$listing"
[[ -s "$listing" ]] || { echo "generate_parameter_doc.sh: <$talus --print-parameters> printed nothing" >&2; exit 1; }

# A fence longer than any run of backticks at the start of a listing line.
fence='```'
while grep -q "^$fence" "$listing"; do fence="$fence\`"; done

mkdir -p "$top/doc"
{
  cat <<'EOF'
# Talus input parameters

This file is generated: do not edit it by hand. After changing a parameter,
regenerate it with

    bash contrib/generate_parameter_doc.sh [path/to/talus]

which stores the output of `talus --print-parameters` below: every parameter
of the input file, by subsection, with its default value, the values it
accepts and its meaning (units in square brackets). Range conditions that a
pattern cannot express (e.g. density > 0, Poisson's ratio in (-1, 0.5)) are
stated in the meaning and checked when the file is read.
`talus --print-parameters prm` prints a complete input file with every
parameter at its default value, a good starting point for a new input file.

The listing shows the 2D declarations (`set dimension = 2`, the default). With
`set dimension = 3`, points and vectors (corners, gravity, subdivisions,
initial velocity, body force, exact displacement) have three components, the
exact stress has six (xx yy zz xy yz xz instead of xx yy xy), and the body
geometry `polygon` is not available.

An input file only needs the entries that differ from the defaults. A
misspelled name, an unknown subsection or a value that does not fit the
pattern shown here stops talus with a message naming the line of the file.

EOF
  echo "${fence}text"
  cat "$listing"
  echo "$fence"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "generate_parameter_doc.sh: wrote $out ($(wc -l < "$listing") lines of listing)"
