#!/usr/bin/env bash
# Wall time of coupled inputs for one or more builds in the same run (issue
# 36 §3, the reuse within a coupling window; doc/performance.md "Coupling
# iterations").
#
#   usage (repository top):
#     bash contrib/benchmark/coupling_reuse.sh [-r REPEATS] [-o DIR] \
#       LABEL=BUILD_DIR [LABEL=BUILD_DIR ...] [-- input.prm ...]
#   LABEL=BUILD_DIR  a name and a Release build directory holding talus and
#                    libtalus-lib.so (e.g. base=/work/wt-base/build
#                    new=build); each run loads the library of its own build
#   -r REPEATS       runs per input and build, interleaved (default 2)
#   -o DIR           output root (default output/coupling_reuse)
#   input.prm        default: tests/coupled/block_on_string_contact_rest.prm,
#                    block_drop_on_membrane_contact.prm,
#                    granular_column_on_string.prm
#
# Each input runs as a copy with 'test mode = false' (the TimerOutput
# table is printed), one rank, the builds back to back. Per run: wall time,
# the TimerOutput sections "prepare (P2G)" and "solve (Newton)", the
# "Done:" line; and whether the run's coupling.csv (12 significant digits
# of every step's residual, forces and energies) equals that of the first
# build's first run.
set -uo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$top"
repeats=2; out=output/coupling_reuse
while getopts "r:o:" opt; do
  case $opt in
    r) repeats=$OPTARG ;;
    o) out=$OPTARG ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
builds=(); inputs=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do builds+=("$1"); shift; done
[ $# -gt 0 ] && shift
inputs=("$@")
[ ${#inputs[@]} -eq 0 ] && inputs=(tests/coupled/block_on_string_contact_rest.prm
                                   tests/coupled/block_drop_on_membrane_contact.prm
                                   tests/coupled/granular_column_on_string.prm)
[ ${#builds[@]} -eq 0 ] && { echo "usage: $0 LABEL=BUILD_DIR ... [-- input.prm ...]"; exit 2; }
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
section() { grep -F "| $2 " "$1" | head -1 | awk -F'|' '{gsub(/ /,"",$4); print $4}'; }
printf "| input | build | run | wall [s] | prepare (P2G) [s] | solve (Newton) [s] | coupling.csv as first |\n|---|---|---|---|---|---|---|\n" | tee "$out/results.md"
for input in "${inputs[@]}"; do
  name=$(basename "$input" .prm)
  for r in $(seq 1 "$repeats"); do
    for b in "${builds[@]}"; do
      label=${b%%=*}; dir=$(cd "${b#*=}" && pwd)
      run="$out/$name/$label-$r"; mkdir -p "$run"
      sed 's/set test mode *= *true/set test mode = false/' "$input" > "$run/input.prm"
      start=$(date +%s.%N)
      (cd "$run" && LD_LIBRARY_PATH="$dir" "$dir/talus" input.prm > log 2>&1)
      wall=$(echo "$(date +%s.%N) - $start" | bc)
      csv=$(find "$run" -name coupling.csv | head -1)
      first=$(find "$out/$name/${builds[0]%%=*}-1" -name coupling.csv | head -1)
      same=$(cmp -s "$csv" "$first" && echo yes || echo NO)
      printf "| %s | %s | %s | %.2f | %s | %s | %s |\n" "$name" "$label" "$r" "$wall" \
        "$(section "$run/log" 'prepare (P2G)')" "$(section "$run/log" 'solve (Newton)')" "$same" \
        | tee -a "$out/results.md"
    done
  done
done
