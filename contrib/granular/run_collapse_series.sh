#!/usr/bin/env bash
# Run granular column collapse inputs and collect their deposits in one CSV.
#   usage: bash contrib/granular/run_collapse_series.sh [-n NP] [-o results.csv]
#                                                       [-t talus] input.prm...
#   -n NP   run each input with `mpirun -np NP` (default: one rank)
#   -o CSV  collected results (default output/granular/collapse_series.csv)
#   -t EXE  talus executable (default build/talus)
# Runs from the repository top (the inputs name data/ and output/ relative to
# it). For every input: the talus log goes to <output directory>/talus.log,
# and one line is appended to the CSV with the input, talus' exit code
# (0 passed, 3 missed its references, else failed) and the numbers of
# <output directory>/deposit_summary.csv (runout, maximum height, L0, H0, a,
# normalised values and Lube predictions) plus the path of its
# deposit_profile.csv. contrib/granular/plot_collapse.py plots the CSV.
# Example (the Bui resolutions and the Lube series, 2 ranks):
#   bash contrib/granular/run_collapse_series.sh -n 2 \
#     benchmarks/granular_collapse/bui2008_*.prm benchmarks/granular_collapse/lube2005/*.prm
set -uo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$top"
np=1; csv=output/granular/collapse_series.csv; talus=build/talus
while getopts "n:o:t:h" opt; do
  case $opt in
    n) np=$OPTARG ;;
    o) csv=$OPTARG ;;
    t) talus=$OPTARG ;;
    *) sed -n '2,8p' "$0"; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[[ $# -gt 0 ]] || { echo "run_collapse_series.sh: no input files (see -h)" >&2; exit 2; }
[[ -x "$talus" ]] || { echo "run_collapse_series.sh: no talus executable at <$talus>" >&2; exit 1; }
if [[ $np -gt 1 && $(id -u) -eq 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi

mkdir -p "$(dirname "$csv")"
header="input,exit_code,L0,H0,a,runout,max_height,runout_normalised,height_normalised,lube_runout,lube_height,mass,profile"
[[ -s "$csv" ]] || echo "$header" > "$csv"

status=0
for input in "$@"; do
  [[ -r "$input" ]] || { echo "run_collapse_series.sh: cannot read <$input>" >&2; status=1; continue; }
  # Output directory as set in the input (subsection Output).
  dir=$(awk '/^[ \t]*subsection[ \t]+Output[ \t]*$/{o=1} o&&/^[ \t]*end[ \t]*$/{o=0}
             o&&/^[ \t]*set[ \t]+output directory[ \t]*=/{sub(/^[^=]*=[ \t]*/,""); sub(/[ \t]*(#.*)?$/,""); d=$0}
             END{print (d==""?"output":d)}' "$input")
  mkdir -p "$dir"
  echo "== $input  ->  $dir/ ($np rank(s))"
  start=$(date +%s)
  if [[ $np -gt 1 ]]; then
    mpirun -np "$np" "$talus" "$input" > "$dir/talus.log" 2>&1; code=$?
  else
    "$talus" "$input" > "$dir/talus.log" 2>&1; code=$?
  fi
  echo "   exit code $code after $(( $(date +%s) - start )) s; log $dir/talus.log"
  summary="$dir/deposit_summary.csv"
  if [[ -s "$summary" && $(stat -c %Y "$summary") -ge $start ]]; then
    values=$(sed -n 2p "$summary")
    echo "$input,$code,$values,$dir/deposit_profile.csv" >> "$csv"
    sed -n '/^Deposit profile/,/^  (errors/p' "$dir/talus.log" | sed 's/^/   /'
  else
    echo "$input,$code,,,,,,,,,,,," >> "$csv"
    echo "   no deposit summary (run failed or 'measure deposit' is off); see the log" >&2
    tail -n 5 "$dir/talus.log" | sed 's/^/   /' >&2
  fi
  [[ $code -eq 0 ]] || status=1
done
echo "results in $csv"
exit $status
