#!/usr/bin/env bash
# Time to solution of the granular collapse benchmarks, with their accuracy,
# for one or more builds in the same run (issue 3, doc/performance.md).
#
#   usage (repository top):
#     bash contrib/granular/time_to_solution.sh [-n "1 2"] [-d DT] [-o DIR] \
#       LABEL=BUILD_DIR[%Section/parameter=value] [LABEL=... ...] -- input.prm ...
#   LABEL=BUILD_DIR  a name and a Release build directory holding talus and
#                    libtalus-lib.so (e.g. base=/work/wt-base/build
#                    new=build); each run loads the library of its own build
#                    (LD_LIBRARY_PATH, which precedes talus' RUNPATH).
#                    LABEL=BUILD_DIR%Section/parameter=value sets a
#                    parameter of a top-level subsection for this label's
#                    runs (A/B of a setting with one build, e.g.
#                    zero=build%Solver/predictor=zero predicted=build)
#   -n RANKS         MPI rank counts (default "1")
#   -d DT            override the inputs' 'time step' (largest step) [s]
#   -o DIR           output root (default output/time_to_solution)
#
# Every (input, build, ranks) runs once, in the order input > ranks > build,
# so that the builds of one input run back to back on the same machine
# state. Per run: wall time, steps (rejected), Newton iterations per step
# (the "Done:" line), runout L and its error against the input's
# 'reference runout', the largest |h - h_ref| (talus' deposit table), and
# talus' exit code (0 = every reference met, 3 = a reference missed). The
# table goes to stdout and to DIR/results.md.
set -uo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$top"
ranks="1"; dt=""; out=output/time_to_solution
while getopts "n:d:o:h" opt; do
  case $opt in
    n) ranks=$OPTARG ;;
    d) dt=$OPTARG ;;
    o) out=$OPTARG ;;
    *) sed -n '2,25p' "$0"; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
builds=()
while [[ $# -gt 0 && $1 != "--" ]]; do builds+=("$1"); shift; done
[[ $# -gt 0 ]] && shift
[[ ${#builds[@]} -gt 0 && $# -gt 0 ]] || { sed -n '2,25p' "$0"; exit 2; }
for b in "${builds[@]}"; do
  dir=${b#*=}; dir=${dir%%%*}
  [[ -x $dir/talus && -e $dir/libtalus-lib.so ]] ||
    { echo "time_to_solution.sh: no talus / libtalus-lib.so in <$dir>" >&2; exit 1; }
done
if [[ $(id -u) -eq 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
export OMPI_MCA_rmaps_base_oversubscribe=1
mkdir -p "$out"
table=$out/results.md
{
  echo "| input | build | ranks | largest Δt [s] | wall [s] | steps (rejected) | Newton/step | runout L [m] | error | max abs(h − h_ref) [m] | exit |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
} > "$table"
cat "$table"
for input in "$@"; do
  name=$(basename "$input" .prm)
  for np in $ranks; do
    for b in "${builds[@]}"; do
      label=${b%%=*}; spec=${b#*=}; dir=$(cd "${spec%%%*}" && pwd)
      run=$out/${name}_${label}_np$np
      mkdir -p "$run"
      sed -e "s|^\( *set output directory = \).*|\1$run|" \
          -e "s|^\( *set format = \).*|\1none|" "$input" > "$run/input.prm"
      if [[ $spec == *%* ]]; then
        setting=${spec#*%}; section=${setting%%/*}; assignment=${setting#*/}
        if [[ $setting != */*=* ]]; then
          echo "time_to_solution.sh: <$b>: the override must read Section/parameter=value" >&2
          exit 2
        fi
        if grep -q "^subsection $section\$" "$run/input.prm"; then
          sed -i "/^subsection $section\$/a\\  set ${assignment%%=*} = ${assignment#*=}" "$run/input.prm"
        else
          printf 'subsection %s\n  set %s = %s\nend\n' "$section" \
            "${assignment%%=*}" "${assignment#*=}" >> "$run/input.prm"
        fi
      fi
      [[ -n $dt ]] && sed -i "s|^\( *set time step = \).*|\1$dt|" "$run/input.prm"
      step=$(sed -n 's|^ *set time step = *||p' "$run/input.prm")
      start=$(date +%s.%N)
      if [[ $np -gt 1 ]]; then
        LD_LIBRARY_PATH=$dir mpirun -np "$np" -x LD_LIBRARY_PATH "$dir/talus" "$run/input.prm" > "$run/talus.log" 2>&1
      else
        LD_LIBRARY_PATH=$dir "$dir/talus" "$run/input.prm" > "$run/talus.log" 2>&1
      fi
      rc=$?
      wall=$(python3 -c "print('%.1f' % ($(date +%s.%N) - $start))")
      python3 - "$run/talus.log" "$name" "$label" "$np" "$step" "$wall" "$rc" >> "$table" <<'EOF'
import re, sys
log, name, label, np_, step, wall, rc = sys.argv[1:]
text = open(log).read()
done = re.search(r"Done: (\d+) steps \((\d+) rejected\), ([\d.]+) Newton", text)
runout = re.search(r"runout L \[m\]\s+(\S+)\s+(\S+)\s+(\S+)", text)
heights = [float(m.group(1)) for m in
           re.finditer(r"h\([\d.]+\) \[m\]\s+\S+\s+\S+\s+(\S+)", text)]
L = "%.4f" % float(runout.group(1)) if runout else "?"
err = "%+.1f %%" % (100 * (float(runout.group(1)) / float(runout.group(2)) - 1)) if runout else "?"
h = "%.4f" % max(heights) if heights else "?"
steps = "%s (%s)" % (done.group(1), done.group(2)) if done else "?"
newton = done.group(3) if done else "?"
print("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |"
      % (name, label, np_, step, wall, steps, newton, L, err, h, rc))
EOF
      tail -1 "$table"
    done
  done
done
