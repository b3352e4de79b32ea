#!/usr/bin/env bash
# Build talus (Release), run the flagship prm/flexible_barrier.prm (25 m^3
# of granular material sliding into a three-field flexible barrier, 3D,
# coupled MPM + FE, about 15 minutes on one core) and draw its pictures.
# Output goes to output/flexible_barrier/ at the repository top:
# snapshots.png (side and plan view of flow and barrier at three instants),
# forces.png (impact force per field, cable, post and anchor forces, post
# rotations, net deflection, brake strokes, energies), coupling.csv,
# structure.csv, and .pvd files for ParaView.
#   usage: bash contrib/run_flexible_barrier.sh
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$top"
out=output/flexible_barrier

bash contrib/build.sh Release build

echo "run_flexible_barrier.sh: running build/talus prm/flexible_barrier.prm"
build/talus prm/flexible_barrier.prm

for f in coupling.csv structure.csv; do
  [[ -f $out/$f ]] || { echo "run_flexible_barrier.sh: talus wrote no $out/$f" >&2; exit 1; }
done

# Debian's matplotlib lives in /usr/bin/python3; a python3 earlier on PATH
# (pyenv, venv) often lacks it.  Take the first interpreter that has it.
python=
for p in /usr/bin/python3 "$(command -v python3 || true)"; do
  if [[ -x "$p" ]] && "$p" -c 'import matplotlib' 2>/dev/null; then python=$p; break; fi
done
[[ -n "$python" ]] || { echo "run_flexible_barrier.sh: no python3 with matplotlib (apt-get install python3-matplotlib)" >&2; exit 1; }
"$python" contrib/plot_flexible_barrier.py "$out"

echo
echo "Output of the flagship in $top/$out:"
echo "  pictures: $out/snapshots.png, $out/forces.png"
echo "  time series: $out/coupling.csv (impact force, iterations, energies),"
echo "               $out/structure.csv (forces per field, member and anchor forces,"
echo "               post rotations, brake strokes, net deflection)"
echo "  ParaView: $out/particles.pvd, $out/net.pvd, $out/posts.pvd, ..."
