#!/usr/bin/env bash
# Build talus (Release), run the default example prm/default.prm and plot its
# time series.  Output goes to output/default/ at the repository top.
#   usage: bash contrib/run_default_example.sh
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$top"
out=output/default

bash contrib/build.sh Release build

[[ -f prm/default.prm ]] || { echo "run_default_example.sh: prm/default.prm not found" >&2; exit 1; }
echo "run_default_example.sh: running build/talus prm/default.prm"
build/talus prm/default.prm

csv=$out/time_series.csv
[[ -f $csv ]] || { echo "run_default_example.sh: talus wrote no $csv" >&2; exit 1; }

# Debian's matplotlib lives in /usr/bin/python3; a python3 earlier on PATH
# (pyenv, venv) often lacks it.  Take the first interpreter that has it.
python=
for p in /usr/bin/python3 "$(command -v python3 || true)"; do
  if [[ -x "$p" ]] && "$p" -c 'import matplotlib' 2>/dev/null; then python=$p; break; fi
done
[[ -n "$python" ]] || { echo "run_default_example.sh: no python3 with matplotlib (apt-get install python3-matplotlib)" >&2; exit 1; }
"$python" contrib/plot_time_series.py "$csv" -o "$out/time_series.png" --title "Talus default example"

pvd=$(find "$out" -name '*.pvd' | sort | tr '\n' ' ')
nvtu=$(find "$out" -name '*.vtu' | wc -l)
echo
echo "Output of the default example in $top/$out:"
echo "  ParaView: ${pvd:-no .pvd file found} ($nvtu .vtu files)"
echo "  time series: $csv"
echo "  plot: $out/time_series.png"
