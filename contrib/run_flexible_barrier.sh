#!/usr/bin/env bash
# Build talus (Release), run the flagship and draw its pictures.
#   bash contrib/run_flexible_barrier.sh       prm/flexible_barrier.prm: 25 m^3
#        of granular material sliding into a three-field flexible barrier,
#        3D, coupled MPM + FE, about 5 minutes of CPU time on one core
#   bash contrib/run_flexible_barrier.sh 2d    prm/flexible_barrier_2d.prm: the
#        same event in a longitudinal section per metre of width, ~30 s
# Output goes to output/flexible_barrier[_2d]/ at the repository top:
# snapshots.png (flow and barrier at three instants; 3D: side and plan
# view), forces.png (impact force (3D: per field), member forces (3D: every
# cable, post and anchor, post rotations, net deflection), brake strokes,
# energies), coupling.csv, structure.csv, and .pvd files for ParaView;
# with PyVista installed (PyPI) also render.png and animation.gif (3D).
set -euo pipefail

case "${1:-}" in
  "") name=flexible_barrier ;;
  2d) name=flexible_barrier_2d ;;
  *) echo "usage: $0 [2d]" >&2; exit 2 ;;
esac
me=$(basename "$0")
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$top"
out=output/$name

bash contrib/build.sh Release build

echo "$me: running build/talus prm/$name.prm"
build/talus "prm/$name.prm"

for f in coupling.csv structure.csv; do
  [[ -f $out/$f ]] || { echo "$me: talus wrote no $out/$f" >&2; exit 1; }
done

# Debian's matplotlib lives in /usr/bin/python3; a python3 earlier on PATH
# (pyenv, venv) often lacks it.  Take the first interpreter that has it.
python=
for p in /usr/bin/python3 "$(command -v python3 || true)"; do
  if [[ -x "$p" ]] && "$p" -c 'import matplotlib' 2>/dev/null; then python=$p; break; fi
done
[[ -n "$python" ]] || { echo "$me: no python3 with matplotlib (apt-get install python3-matplotlib)" >&2; exit 1; }
"$python" "contrib/plot_$name.py" "$out"

# 3D renders and an animation need PyVista (PyPI), which Debian does not
# package: draw them when some python3 has it, else say how.
rendered=
if [[ $name == flexible_barrier ]]; then
  for p in "$(command -v python3 || true)" /usr/bin/python3; do
    if [[ -x "$p" ]] && "$p" -c 'import pyvista' 2>/dev/null; then
      "$p" contrib/render_flexible_barrier.py "$out" --animation && rendered=yes
      break
    fi
  done
fi

echo
echo "Output of prm/$name.prm in $top/$out:"
echo "  pictures: $out/snapshots.png, $out/forces.png"
if [[ -n $rendered ]]; then
  echo "  3D render: $out/render.png, animation: $out/animation.gif"
elif [[ $name == flexible_barrier ]]; then
  echo "  3D render and animation: pip install pyvista imageio (in a venv), then"
  echo "    python3 contrib/render_flexible_barrier.py $out --animation"
fi
echo "  time series: $out/coupling.csv (impact force, iterations, energies),"
echo "               $out/structure.csv (member forces, brake strokes; 3D: forces"
echo "               per field, anchor forces, post rotations, net deflection)"
echo "  ParaView: $out/particles.pvd, $out/net.pvd, ..."
