#!/usr/bin/env bash
# Build talus (Release), run the 2D flagship analogue prm/flexible_barrier_2d.prm
# (a granular slide into a flexible barrier, coupled MPM + FE, ~30 s) and
# draw its pictures.  Output goes to output/flexible_barrier_2d/ at the
# repository top: snapshots.png (flow and barrier at three instants),
# forces.png (impact force, member forces, brake stroke, energies),
# coupling.csv, structure.csv, and .pvd files for ParaView.
#   usage: bash contrib/run_flexible_barrier_2d.sh
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$top"
out=output/flexible_barrier_2d

bash contrib/build.sh Release build

echo "run_flexible_barrier_2d.sh: running build/talus prm/flexible_barrier_2d.prm"
build/talus prm/flexible_barrier_2d.prm

for f in coupling.csv structure.csv; do
  [[ -f $out/$f ]] || { echo "run_flexible_barrier_2d.sh: talus wrote no $out/$f" >&2; exit 1; }
done

# Debian's matplotlib lives in /usr/bin/python3; a python3 earlier on PATH
# (pyenv, venv) often lacks it.  Take the first interpreter that has it.
python=
for p in /usr/bin/python3 "$(command -v python3 || true)"; do
  if [[ -x "$p" ]] && "$p" -c 'import matplotlib' 2>/dev/null; then python=$p; break; fi
done
[[ -n "$python" ]] || { echo "run_flexible_barrier_2d.sh: no python3 with matplotlib (apt-get install python3-matplotlib)" >&2; exit 1; }
"$python" contrib/plot_flexible_barrier_2d.py "$out"

echo
echo "Output of the 2D flagship analogue in $top/$out:"
echo "  pictures: $out/snapshots.png, $out/forces.png"
echo "  time series: $out/coupling.csv (impact force, iterations, energies),"
echo "               $out/structure.csv (member forces, brake stroke)"
echo "  ParaView: $out/particles.pvd, $out/net.pvd, $out/post.pvd, ..."
