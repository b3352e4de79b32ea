#!/bin/bash
# Large-deformation cantilever swinging under its own weight (doc/
# verification.md, "Cantilever swinging under its own weight"; Sadeghirad,
# Brannon & Burghardt 2011): the MPM beam of tests/mpm/cantilever_neo_hookean
# (2 x 2 points per cell, neo-Hookean, dt = 0.01 s) on grids h = 0.25 m
# times 2^-level, with 'shape functions = linear' and 'uGIMP' (or cpGIMP,
# --shapes), against the
# FE reference tests/mpm/cantilever_fe_reference.csv (the mean deflection of
# x >= 3.75 m). Prints per run the peak deflection and its time, the
# relative L2-in-time error of the history and its rate, the rejected
# steps, the energy lost over the run (kinetic + strain + gravitational,
# per released gravitational energy), what the energy accounts book of it
# and the wall time.
# With --reference it first reruns the FE study (contrib/reference/
# cantilever_fe.prm: Q1 on 32 x 8 and 64 x 16 cells, Q2 on 16 x 4), prints
# its convergence and rewrites the reference file from Q1 64 x 16.
#
# Options (after the levels): --reference; --root-clamp fixes only the
# nodes of the root face (x = 0, 0 <= y <= 1: 'fixed region lower/upper
# corner') instead of the whole wall x = 0, in a grid that extends to
# x = -1 m so that the beam can swing past the plane of the root; --from-forces starts each step
# from the acceleration of the forces ('start acceleration = from forces')
# instead of the projected one; --shapes "linear uGIMP" chooses the shape
# functions (default linear and uGIMP; also cpGIMP, 'cpGIMP domain stretch
# = diagonal', cpGIMP-box, 'bounding box', and CPDI). For cpGIMP the
# table's last column gives the share of point evaluations whose domain
# was capped at the cell size, for CPDI of those whose parallelogram was
# scaled down to keep its corners in the node patch and the grid.
#
# usage: bash contrib/cantilever_convergence.sh [path/to/talus] [levels] [options]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
talus=$(readlink -f "${1:-$here/build/talus}")
levels=${2:-3}
reference=
extra=()
shapes="linear uGIMP"
nx=20
shift $(($# < 2 ? $# : 2))
while [ $# -gt 0 ]; do
  case $1 in
    --reference) reference=--reference ;;
    --root-clamp) nx=24; extra+=(-e "s|set lower corner = 0, -5|set lower corner = -1, -5|"
                    -e "s|set fixed boundaries = 0|set fixed region lower corner = 0, 0\n  set fixed region upper corner = 0, 1|") ;;
    --from-forces) extra+=(-e "s|set linear solver = direct|set linear solver = direct\n  set start acceleration = from forces|") ;;
    --shapes) shift; shapes=$1 ;;
    *) echo "unknown option $1"; exit 1 ;;
  esac
  shift
done
ref_csv=$here/tests/mpm/cantilever_fe_reference.csv
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if [ "$reference" = "--reference" ]; then
  sed -e "s|set output directory = .*|set output directory = $work/fe|" \
    "$here/contrib/reference/cantilever_fe.prm" > "$work/fe.prm"
  sed -e "s|set output directory = .*|set output directory = $work/fe-q2|" \
      -e "s|set degree = 1|set degree = 2|" -e "s|set subdivisions = 32, 8, 1|set subdivisions = 16, 4, 1|" \
      -e "s|set number of levels = 2|set number of levels = 1|" \
    "$here/contrib/reference/cantilever_fe.prm" > "$work/fe-q2.prm"
  for p in fe fe-q2; do
    (cd "$work" && /usr/bin/time -f "wall %e s" nice "$talus" $p.prm) > "$work/$p.log" 2>&1 || {
      echo "talus failed on the FE reference $p:"; tail -20 "$work/$p.log"; exit 1; }
  done
  python3 - "$work" "$ref_csv" <<'PY'
import csv, math, sys
work, out = sys.argv[1], sys.argv[2]
def load(name):
    rows = list(csv.DictReader(open(name)))
    return ([0.] + [float(r['time']) for r in rows],
            [0.] + [float(r['end_region_u_y']) for r in rows],
            [float(r['total_energy']) for r in rows],
            max(float(r['kinetic_energy']) for r in rows))
runs = [('Q1 32 x 8', load(work + '/fe/load_steps_level0.csv')),
        ('Q2 16 x 4', load(work + '/fe-q2/load_steps.csv')),
        ('Q1 64 x 16', load(work + '/fe/load_steps_level1.csv'))]
t2, u2 = runs[-1][1][0], runs[-1][1][1]
print('FE (consistent mass, trapezoidal rule, dt = 0.005 s): mean deflection of x >= 3.75 m')
print('| mesh | peak [m] | t_peak [s] | u(2 s) [m] | L2-in-time difference to Q1 64 x 16 (rel.) | energy drift / peak kinetic energy |')
print('|---|---|---|---|---|---|')
for label, (t, u, e, kmax) in runs:
    k = min(range(len(u)), key=lambda i: u[i])
    num = den = 0.
    for i in range(1, len(t)):
        dt = t[i] - t[i - 1]
        num += dt * (u[i] - u2[i]) ** 2
        den += dt * u2[i] ** 2
    drift = max(abs(x - e[0]) for x in e)
    print('| %s | %.5f | %.3f | %.5f | %.2e | %.1e |' % (
        label, u[k], t[k], u[-1], math.sqrt(num / den), drift / kmax))
t, u = t2, u2
with open(out, 'w') as f:
    f.write('# FE reference of tests/mpm/cantilever_neo_hookean*.prm: mean\n'
            '# deflection u_y [m] of the cells x >= 3.75 m of the neo-Hookean\n'
            '# cantilever (contrib/reference/cantilever_fe.prm, Q1 64 x 16 cells,\n'
            '# consistent mass, trapezoidal rule, dt = %g s); rebuilt by\n'
            '# contrib/cantilever_convergence.sh --reference.\n'
            'time,u_y\n' % (t[1] - t[0]))
    for a, b in zip(t, u):
        f.write('%.6g,%.10g\n' % (a, b))
print('reference written to %s' % out)
PY
  grep -h "wall" "$work/fe.log" "$work/fe-q2.log" | sed 's/^/  FE wall time /'
fi

# run SHAPE LEVEL: writes $work/SHAPE-LEVEL.log and its output directory
run() {
  local shape=$1 level=$2 f=$((1 << $2)) prm=$work/$1-$2.prm
  local choice="set shape functions = $shape"
  [ "$shape" = cpGIMP-box ] &&
    choice="set shape functions = cpGIMP\n  set cpGIMP domain stretch = bounding box"
  sed -e "s|set subdivisions = 20, 26|set subdivisions = $((nx * f)), $((26 * f))|" \
      -e "s|set shape functions = linear|$choice|" \
      -e "s|set output directory = .*|set output directory = $work/out-$shape-$level|" \
      -e "s|set test mode = true|set test mode = false|" \
      -e "s|set tolerance = .*||" -e "s|set peak tolerance = .*||" \
      -e "s|@SOURCE_DIR@|$here/tests/mpm|" ${extra[@]+"${extra[@]}"} \
      "$here/tests/mpm/cantilever_neo_hookean.prm.in" > "$prm"
  (cd "$work" && /usr/bin/time -f "wall %e s" nice "$talus" "$prm") > "$work/$shape-$level.log" 2>&1 || {
    echo "talus failed on $shape level $level:"; tail -20 "$work/$shape-$level.log"; exit 1; }
}

for s in $shapes; do
  for l in $(seq 0 $((levels - 1))); do run $s $l; done
done

python3 - "$work" "$levels" "$ref_csv" "$shapes" <<'PY'
import bisect, csv, math, re, sys
work, levels, ref_csv = sys.argv[1], int(sys.argv[2]), sys.argv[3]
shapes = sys.argv[4].split()
ref = [tuple(float(x) for x in l.split(',')) for l in open(ref_csv)
       if l[0].isdigit()]
rt = [r[0] for r in ref]
def u_ref(t):
    i = min(max(bisect.bisect_right(rt, t), 1), len(ref) - 1)
    (a, ua), (b, ub) = ref[i - 1], ref[i]
    return ua + (ub - ua) * (t - a) / (b - a)
def window_error(name, T):
    """relative L2-in-time error over [0, T] (trapezoidal rule)"""
    h = [(float(r['time']), float(r['u_y'])) for r in csv.DictReader(open(name))]
    h = [x for x in h if x[0] <= T + 1e-9]
    e = n = 0.
    for (t0, u0), (t1, u1) in zip(h, h[1:]):
        e += 0.5 * (t1 - t0) * ((u0 - u_ref(t0)) ** 2 + (u1 - u_ref(t1)) ** 2)
        n += 0.5 * (t1 - t0) * (u_ref(t0) ** 2 + u_ref(t1) ** 2)
    return math.sqrt(e / n)
def rate(a, b):
    return '-' if a is None or b <= 0 else '%.2f' % math.log2(a / b)
print('\nMPM, 2 x 2 points per cell, dt = 0.01 s: mean deflection of the points of x >= 3.75 m')
print('| shape | h [m] | peak [m] | t_peak [s] | peak error | L2 error [0, 1 s] | rate | L2 error [0, 2 s] | rate | u(2 s) [m] | rejected steps | energy lost | booked | unbooked | wall [s] | Newton it./step | per Newton it. [ms] | capped domains |')
print('|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|')
for s in shapes:
    prev = prev1 = None
    for l in range(levels):
        log = open('%s/%s-%d.log' % (work, s, l)).read()
        peak = re.search(r'peak (\S+) m at t = (\S+) s\n', log)
        err = re.search(r'relative peak error (\S+), relative L2-in-time error (\S+)', log)
        rej = re.search(r'steps \((\d+) rejected\)', log)
        wall = re.findall(r'^wall (\S+) s', log, re.M)
        its = re.search(r'rejected\), (\S+) Newton iterations per step', log)
        steps = re.search(r'Done: (\d+) steps', log)
        newton = re.search(r'\|\s*solve \(Newton\)\s*\|\s*(\d+)\s*\|\s*(\S+)s', log)
        per_it = '-' if not (its and steps and newton) else '%.1f' % (
            1000. * float(newton.group(2)) /
            (int(steps.group(1)) * float(its.group(1))))
        cap = re.search(r'capped[^:\n]*: (\d+) of (\d+)', log)
        capped = '-' if cap is None else '%.2f %%' % (
            100. * int(cap.group(1)) / max(1, int(cap.group(2))))
        out = '%s/out-%s-%d' % (work, s, l)
        rows = list(csv.DictReader(open(out + '/time_series.csv')))
        f = lambda r, k: float(r[k])
        g0 = f(rows[0], 'gravitational_energy')
        released = max(g0 - f(r, 'gravitational_energy') for r in rows)
        lost = f(rows[0], 'total_energy') - f(rows[-1], 'total_energy')
        booked = sum(f(rows[-1], k) - f(rows[0], k) for k in (
            'plastic_dissipation', 'friction_dissipation', 'reset_dissipation',
            'transfer_dissipation', 'integrator_dissipation'))
        unbooked = f(rows[0], 'energy_balance') - f(rows[-1], 'energy_balance')
        l2 = float(err.group(2))
        l1 = window_error(out + '/probe_history.csv', 1.)
        u_end = list(csv.DictReader(open(out + '/probe_history.csv')))[-1]['u_y']
        print('| %s | %g | %s | %s | %s | %.3e | %s | %.3e | %s | %.3f | %s | %.1f %% | %.1f %% | %.1f %% | %s | %s | %s | %s |' % (
            s, 0.25 / 2 ** l, peak.group(1), peak.group(2), err.group(1), l1,
            rate(prev1, l1), l2, rate(prev, l2), float(u_end), rej.group(1),
            100 * lost / released, 100 * booked / released,
            100 * unbooked / released, wall[-1],
            its.group(1) if its else '-', per_it, capped))
        prev, prev1 = l2, l1
print('(energy: of the largest released gravitational energy; lost = '
      'K + S + G at 0 minus at the end; booked = the dissipation columns of '
      'time_series.csv; unbooked = the change of energy_balance)')
PY
