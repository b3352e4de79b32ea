#!/usr/bin/env bash
# Growth of the Krylov iterations per Newton iteration under grid refinement
# (doc/performance.md, "Iterative solver for the plastic contact tangent",
# "Growth with the grid"): the 3D granular block on a grid-friction slope
# (benchmarks/granular_3d/block_on_slope.prm; levels 0-3: 0.2 / 0.1 / 0.05 /
# 0.025 m cells, first END = 0.15 s with steps of 5 ms; case block3d-dt:
# the step halves with the cells, 5 ms at 0.1 m) and the Bui collapse
# (benchmarks/granular_collapse/bui2008_<h>mm.prm; levels 0-3: 20 / 10 / 5 /
# 2.5 mm cells, the inputs' own steps (2.5 mm: 0.25 ms, from the 5 mm
# input), first END = 0.05 s), each with GMRES and the preconditioner
# settings SETTINGS (names below), run one after the other on one rank with
# TALUS_DEBUG_LINEAR=1. LEVELS (environment) selects the levels, default
# "1 2" for block3d and "1 2 3" for bui. Below 2 000 rows ('AMG coarse
# size') ML solves the tangent directly (one Krylov iteration), so the
# coarsest levels say nothing about the multigrid. Prints one Markdown row per run: steps (rejected),
# Newton iterations per step, Krylov iterations per solve (mean / max),
# solves that failed with a fresh preconditioner (the step is then halved),
# failures with a reused preconditioner (rebuilt and solved again), wall
# time. The growth factor is the ratio of the means of two levels.
#   usage: bash contrib/benchmark/amg_growth.sh [talus] [case] [settings...]
#   case: block3d, block3d-dt or bui (default block3d); settings default:
#   klu ilu cheb sgs (names below).
# Run from the repository top; scratch in <talus dir>/amg-growth/.
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
talus=$(realpath "${1:-build/talus}")
case_name=${2:-block3d}
shift $(($# < 2 ? $# : 2))
work=$(dirname "$talus")/amg-growth
mkdir -p "$work"

# preconditioner settings: lines of subsection Solver
setting() {
  case "$1" in
    klu) echo "set linear solver = direct" ;;
    ilu) printf 'set linear solver = GMRES\nset preconditioner = ILU\n' ;;
    cheb) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = Chebyshev\n' ;;
    sgs) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = symmetric Gauss-Seidel\n' ;;
    sgs-ew) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = symmetric Gauss-Seidel\nset linear solver forcing = Eisenstat-Walker\nset maximum forcing term = 0.01\n' ;;
    sgs-t0) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = symmetric Gauss-Seidel\nset AMG aggregation threshold = 0\n' ;;
    sgs-s1) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = symmetric Gauss-Seidel\nset AMG smoother sweeps = 1\n' ;;
    sgs-s3) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = symmetric Gauss-Seidel\nset AMG smoother sweeps = 3\n' ;;
    sgs-w) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = symmetric Gauss-Seidel\nset AMG cycle = W\n' ;;
    sgs-ns) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = symmetric Gauss-Seidel\nset AMG aggregation = non-symmetric\n' ;;
    gs) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = Gauss-Seidel\n' ;;
    amg-ilu) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = ILU\n' ;;
    amg-ilu-w) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = ILU\nset AMG cycle = W\n' ;;
    amg-ilu-ns) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = ILU\nset AMG aggregation = non-symmetric\n' ;;
    amg-ilu-ew) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = ILU\nset linear solver forcing = Eisenstat-Walker\nset maximum forcing term = 0.01\n' ;;
    amg-ilu-fresh) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = ILU\nset reuse preconditioner = false\n' ;;
    amg-ilu-s1) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = ILU\nset AMG smoother sweeps = 1\n' ;;
    amg-ilu-c500) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = ILU\nset AMG coarse size = 500\n' ;;
    sgs-fresh) printf 'set linear solver = GMRES\nset preconditioner = AMG\nset AMG smoother = symmetric Gauss-Seidel\nset reuse preconditioner = false\n' ;;
    ilu-fresh) printf 'set linear solver = GMRES\nset preconditioner = ILU\nset reuse preconditioner = false\n' ;;
    default) printf 'set linear solver = GMRES\n' ;;
    *) echo "unknown setting $1" >&2; exit 1 ;;
  esac
}

# input of level $1 of the case
make_input() {
  case "$case_name" in
    block3d|block3d-dt)
      local sub=("10, 4, 2" "20, 8, 4" "40, 16, 8" "80, 32, 16")
      local dt=0.005
      # block3d-dt: the step halves with the cells (5 ms at 0.1 m)
      [ "$case_name" = block3d-dt ] && dt=$(python3 -c "print(0.01 / 2**$1)")
      sed "s|set subdivisions = .*|set subdivisions = ${sub[$1]}|
           s|set end time = .*|set end time = ${END:-0.15}|
           s|set time step = .*|set time step = $dt|
           s|set format = vtu|set format = none|" \
        "$top/benchmarks/granular_3d/block_on_slope.prm"
      printf 'subsection Verification\n  set energy balance tolerance = 1\n  set maximum final speed = 100\nend\n' ;;
    bui)
      local h=(20 10 5 5)
      sed "s|set end time = .*|set end time = ${END:-0.05}|
           s|set measure deposit = true|set measure deposit = false|
           s|set format = vtu|set format = none|
           s|data/|$top/data/|" \
        "$top/benchmarks/granular_collapse/bui2008_${h[$1]}mm.prm" |
        if [ "$1" = 3 ]; then
          sed "s|set subdivisions = .*|set subdivisions = 240, 48|
               s|set time step = .*|set time step = 0.00025|"
        else cat; fi ;;
    *) echo "unknown case $case_name" >&2; exit 1 ;;
  esac
}

settings=("$@")
[ ${#settings[@]} -gt 0 ] || settings=(klu ilu cheb sgs)
echo "| case | level | setting | steps (rejected) | Newton per step | Krylov per solve (mean / max) | failed solves (fresh / reused) | wall [s] |"
echo "|---|---|---|---|---|---|---|---|"
for s in "${settings[@]}"; do
  default_levels="1 2"; [ "$case_name" = bui ] && default_levels="1 2 3"
  for level in ${LEVELS:-$default_levels}; do
    prm="$work/$case_name-$level-$s.prm"
    { make_input "$level"; echo "subsection Solver"; setting "$s"; echo "end"; } > "$prm"
    log="${prm%.prm}.log"
    err="${prm%.prm}.err"
    start=$(date +%s.%N)
    (cd "$work" && TALUS_DEBUG_LINEAR=1 timeout 900 "$talus" "$prm" > "$log" 2> "$err") || true
    stop=$(date +%s.%N)
    wall=$(python3 -c "print(f'{$stop - $start:.1f}')")
    done_line=$(grep "^Done:" "$log" || echo "Done: failed")
    steps=$(sed -n 's/Done: \([0-9]*\) steps (\([0-9]*\) rejected).*/\1 (\2)/p' <<<"$done_line")
    newton=$(sed -n 's/.* rejected), \([0-9.]*\) Newton.*/\1/p' <<<"$done_line")
    krylov=$(python3 - "$err" <<'EOF'
import re, sys
n = [int(m.group(1)) for m in re.finditer(r'^    Krylov (\d+)$', open(sys.argv[1]).read(), re.M)]
print(f"{sum(n)/len(n):.1f} / {max(n)}" if n else "-")
EOF
)
    fresh=$(grep -c "fresh preconditioner" "$err" || true)
    reused=$(grep -c "reused preconditioner" "$err" || true)
    [ -n "$steps" ] || steps="failed: $(grep -m1 -i "error\|exception" "$log" "$err" | head -c 80)"
    echo "| $case_name | $level | $s | $steps | $newton | $krylov | $fresh / $reused | $wall |"
  done
done
