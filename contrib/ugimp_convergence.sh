#!/bin/bash
# Cell-crossing study of 'shape functions = linear' against 'uGIMP'
# (doc/verification.md, "uGIMP: cell crossing"): the column under self
# weight (tests/mpm/column_small_strain.prm, points settle by up to 1 m) and
# the vibrating bar with v0 = 0.1 m/s (tests/mpm/vibrating_bar_convergence.prm
# with the amplitude of vibrating_bar.prm), each on 4 grids (cells and time
# step halved per level, the talus convergence study), with both shape
# functions. Prints per level the L2 displacement error and the point
# stress error (max and RMS, relative to max |sigma_exact|) and the rates
# log2(e_coarse / e_fine).
#
# A third argument chooses the shape functions (default "linear uGIMP";
# also cpGIMP, cpGIMP-box for 'cpGIMP domain stretch = bounding box', and CPDI).
#
# usage: bash contrib/ugimp_convergence.sh [path/to/talus] [levels] [shapes]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
talus=$(readlink -f "${1:-$here/build/talus}")
levels=${2:-4}
shapes=${3:-linear uGIMP}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run CASE SHAPE: writes $work/CASE-SHAPE.log
run() {
  local case=$1 shape=$2 prm=$work/$1-$2.prm
  local choice="set shape functions = $shape"
  [ "$shape" = cpGIMP-box ] &&
    choice="set shape functions = cpGIMP\n  set cpGIMP domain stretch = bounding box"
  case $case in
    column)
      sed -e "s|set linear solver = direct|set linear solver = direct\n  $choice|" \
          -e "s|set output directory = .*|set output directory = $work/out-$case-$shape|" \
          -e "s|set stress error tolerance = .*|set stress error tolerance = 10\n  set stress error norm = RMS|" \
          -e "s|set displacement error tolerance = .*|set displacement error tolerance = 10|" \
          "$here/tests/mpm/column_small_strain.prm" > "$prm"
      ;;
    bar)
      sed -e "s|v0=0.00001|v0=0.1|g" \
          -e "s|set gravity = 0, 0|set gravity = 0, 0\n  $choice|" \
          -e "s|set output directory = .*|set output directory = $work/out-$case-$shape|" \
          -e "s|set displacement error tolerance = .*|set displacement error tolerance = 10|" \
          -e "/subsection Convergence study/,/^end/d" \
          "$here/tests/mpm/vibrating_bar_convergence.prm" > "$prm"
      ;;
  esac
  printf 'subsection Convergence study\n  set number of levels = %s\n  set minimum rate = 0\nend\n' \
    "$levels" >> "$prm"
  # (a level whose error grows fails the study's rate check: not fatal)
  (cd "$work" && /usr/bin/time -f "wall %e s" "$talus" "$prm") > "$work/$case-$shape.log" 2>&1 ||
    grep -q "Convergence table" "$work/$case-$shape.log" || {
      echo "talus failed on $case $shape:"; tail -20 "$work/$case-$shape.log"; exit 1; }
}

for c in column bar; do
  for s in $shapes; do run $c $s; done
done

python3 - "$work" "$shapes" <<'PY'
import math, re, sys
work, shapes = sys.argv[1], sys.argv[2].split()
def rate(a, b):
    return '-' if a is None or b is None or b <= 0 else '%.2f' % math.log2(a / b)
def table(case, title, pattern, names):
    print('\n%s' % title)
    data = {}
    for s in shapes:
        text = open('%s/%s-%s.log' % (work, case, s)).read()
        data[s] = [tuple(float(x) for x in m) for m in re.findall(pattern, text)]
    header = ['level']
    for s in shapes:
        for n in names:
            header += ['%s %s' % (s, n), 'rate']
    print('| ' + ' | '.join(header) + ' |')
    print('|' + '---|' * len(header))
    for l in range(len(data[shapes[0]])):
        row = [str(l)]
        for s in shapes:
            for j in range(len(names)):
                e = data[s][l][j]
                prev = data[s][l - 1][j] if l > 0 else None
                row += ['%.3e' % e, rate(prev, e)]
        print('| ' + ' | '.join(row) + ' |')
# column: one report time (t = 1), displacement, max and RMS stress error
table('column', 'column under self weight (E = 1 MPa, 20 cells on level 0), t = 1 s',
      r'error at t = 1: displacement (\S+), stress \(relative, max\) (\S+), '
      r'\(relative, RMS\) (\S+)',
      ['u L2 [m]', 'stress max', 'stress RMS'])
# bar: displacement at T/4 and T/2
pattern = r'error at t = 2.5: displacement (\S+)\n\s+error at t = 5: displacement (\S+)'
table('bar', 'vibrating bar, v0 = 0.1 m/s (36 cells on level 0)', pattern,
      ['u(T/4)', 'u(T/2)'])
PY
grep -h "wall" "$work"/*.log | sed 's/^/  /' || true
