#!/usr/bin/env bash
# adaptive_grid_study.sh TALUS [WORKDIR] [LEVELS]
# Adaptive against uniform background grids on the Bui et al. 2008 collapse
# (doc/verification.md and doc/performance.md, "Adaptive background
# grids"): the no-slip mu(I) benchmark
# benchmarks/granular_collapse/bui2008_<h>mm_noslip_muI_recoverable.prm on
# the uniform grid of cell size h and on adaptive grids with the same
# finest cell size h (background grid 20 mm or 40 mm, refined to h where
# the points are, one neighbour layer, every step; at 5 mm also two
# layers, every 10 steps). Prints one table row
# per run: finest cell, grid, runout, its error against the experiment's
# 0.43 m, the largest number of DoFs, the cells at the end, steps, Newton
# iterations and the wall time (one rank, format none).
# LEVELS: the finest cell sizes in mm (default "10 5").
set -u
talus=$(readlink -f "$1"); work=${2:-adaptive_grid_study}; levels=${3:-10 5}
src=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mkdir -p "$work"; cd "$work" || exit 1
printf '| finest cell | grid | runout [m] | error | DoFs (max) | cells (end) | steps | Newton per step | run time [s] | wall time [s] |\n'
printf '|---|---|---|---|---|---|---|---|---|---|\n'
run() { # NAME H SUBDIVISIONS ADAPTIVE_LEVEL [LAYERS [EVERY]]
  local name=$1 h=$2 sub=$3 level=$4 layers=${5:-1} every=${6:-1}
  sed -e "s|data/|$src/data/|" \
      -e "s|set subdivisions = .*|set subdivisions = $sub|" \
      -e "s|set format = vtu|set format = none|" \
      -e "s|set output directory = .*|set output directory = out-$name|" \
      "$src/benchmarks/granular_collapse/bui2008_${h}mm_noslip_muI_recoverable.prm" \
      > "$name.prm"
  if [ "$level" -gt 0 ]; then
    printf 'subsection Adaptive grid\n  set enable = true\n  set maximum level = %s\n  set neighbour layers = %s\n  set refine every steps = %s\nend\n' \
      "$level" "$layers" "$every" >> "$name.prm"
  fi
  local t0 t1
  t0=$(date +%s.%N)
  "$talus" "$name.prm" > "$name.log" 2>&1
  local rc=$?
  t1=$(date +%s.%N)
  local runout dofs cells steps newton wall
  runout=$(grep -m1 -oE 'runout L = [0-9.]+' "$name.log" | awk '{print $4}')
  dofs=$(grep -oE '[0-9]+ DoFs' "$name.log" | awk '{print $1}' | sort -n | tail -1)
  cells=$(grep -oE '[0-9]+ cells' "$name.log" | tail -1 | awk '{print $1}')
  steps=$(grep -m1 -oE 'Done: [0-9]+ steps' "$name.log" | awk '{print $2}')
  newton=$(grep -m1 -oE '[0-9.]+ Newton iterations per step' "$name.log" | awk '{print $1}')
  wall=$(grep -m1 -oE 'wall time [0-9.]+ s' "$name.log" | awk '{print $3}')
  local err
  err=$(awk -v r="${runout:-0}" 'BEGIN{printf "%+.1f %%", 100*(r-0.43)/0.43}')
  printf '| %s mm | %s (exit %s) | %s | %s | %s | %s | %s | %s | %s | %.1f |\n' \
    "$h" "$name" "$rc" "${runout:-?}" "$err" "${dofs:-?}" "${cells:-?}" \
    "${steps:-?}" "${newton:-?}" "${wall:-?}" "$(echo "$t1 - $t0" | bc)"
}
for h in $levels; do
  case $h in
    10) run uniform10 10 "60, 12" 0
        run adaptive10_from20 10 "30, 6" 1
        run adaptive10_from40 10 "15, 3" 2 ;;
    5)  run uniform5 5 "120, 24" 0
        run adaptive5_from20 5 "30, 6" 2
        run adaptive5_every10 5 "30, 6" 2 2 10 ;;
  esac
done
