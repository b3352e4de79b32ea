#!/bin/bash
# Cost of 'shape functions = uGIMP' against 'linear' (doc/performance.md,
# "uGIMP"): the elastic block of run_benchmarks.sh (neo-Hookean unit block
# on a fixed base under gravity, N cells across the block, 2 points per
# cell per direction, AMG-CG) in 2D and 3D, both shape functions back to
# back on one rank, test mode off. Prints per run the Newton iterations,
# the wall time of the Newton solve and of its assembly and linear-solve
# phases (TimerOutput) and the time per Newton iteration.
#
# A fifth argument chooses the shape functions (default "linear uGIMP";
# any of linear, uGIMP, cpGIMP, CPDI).
#
# usage: bash contrib/benchmark/ugimp_cost.sh [talus] [N2D] [N3D] [steps] [shapes]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
talus=$(readlink -f "${1:-$here/../../build/talus}")
n2=${2:-48}
n3=${3:-12}
steps=${4:-10}
shapes=${5:-linear uGIMP}
dt=0.005
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

fill() { # dim n shape
  local dim=$1 n=$2 shape=$3 m=$(($2 + 4))
  local h xlo xhi yhi
  h=$(awk -v n="$n" 'BEGIN {printf "%.17g", 1 / n}')
  xlo=$(awk -v h="$h" 'BEGIN {printf "%.17g", -2 * h}')
  xhi=$(awk -v h="$h" 'BEGIN {printf "%.17g", 1 + 2 * h}')
  yhi=$(awk -v h="$h" 'BEGIN {printf "%.17g", 1 + 4 * h}')
  # uGIMP needs the grid boundary away from the body's sides: x from
  # -2h; the base (fixed) is at 0 for both
  sed -e "s/@N@/$n/g" -e "s/@XLO@/$xlo/g" -e "s/@XHI@/$xhi/g" \
      -e "s/@YHI@/$yhi/g" -e "s/@N0@/$m/g" -e "s/@K@/0/g" \
      -e "s/@END@/$(awk -v s="$steps" -v dt="$dt" 'BEGIN {printf "%.10g", s * dt}')/g" \
      -e "s/@DT@/$dt/g" -e "s#@OUT@#$work/out-$dim-$shape#g" \
      -e "s/  set linear solver = CG/  set linear solver = CG\n  set shape functions = $shape/" \
      "$here/block_${dim}d.prm.in"
}

printf '| case | shape functions | steps | Newton it./step | Newton solve [s] | assembly [s] | linear solver + AMG setup [s] | per Newton it. [ms] |\n|---|---|---|---|---|---|---|---|\n'
for dim in 2 3; do
  n=$n2; [ "$dim" = 3 ] && n=$n3
  for shape in $shapes; do
    fill "$dim" "$n" "$shape" > "$work/b$dim-$shape.prm"
    (cd "$work" && "$talus" "b$dim-$shape.prm") > "$work/b$dim-$shape.log" 2>&1 || {
      echo "talus failed:"; tail -20 "$work/b$dim-$shape.log"; exit 1; }
    python3 - "$work/b$dim-$shape.log" "$dim" "$n" "$shape" <<'PY'
import re, sys
log, dim, n, shape = sys.argv[1:]
text = open(log).read()
m = re.search(r'Done: (\d+) steps \((\d+) rejected\), (\S+) Newton iterations per step', text)
steps, its = int(m.group(1)), float(m.group(3))
def section(name):
    m = re.search(r'\|\s*' + re.escape(name) + r'\s*\|\s*(\d+)\s*\|\s*(\S+)s', text)
    return float(m.group(2)) if m else float('nan')
solve = section('solve (Newton)')
asm = section('assembly')
lin = section('linear solver') + section('AMG setup')
print('| %sD, %s^%s cells under the block | %s | %d | %.2f | %.3f | %.3f | %.3f | %.2f |'
      % (dim, n, dim, shape, steps, its, solve, asm, lin, 1000 * solve / (steps * its)))
PY
  done
done
