#!/usr/bin/env bash
# Time to solution of the Bui et al. 2008 collapse (t = 1 s), Talus against
# the explicit MPM code CB-Geo (https://github.com/cb-geo/mpm), both pinned
# to the same core and run back to back (issue 41, doc/performance.md).
#
#   usage (repository top):
#     bash contrib/benchmark/cbgeo_bui.sh (-s CBGEO_SRC | -m MPM_BINARY) \
#       [-b CBGEO_BUILD] [-t TALUS_BUILD] [-c "5 10"] [-r REPEATS] [-k CORE] \
#       [-i INPUT_PATTERN] [-d DT] [-p Section/parameter=value ...] \
#       [-e CBGEO_DT] [-v pic|flip] [-o DIR]
#   -s CBGEO_SRC    CB-Geo source tree: configured and built (Release, serial:
#                   no MPI, KaHIP, VTK, Partio, MKL, tests) in CBGEO_BUILD
#                   (default CBGEO_SRC/../cbgeo-build) unless its 'mpm' is
#                   there already; needs Eigen 3, Boost filesystem, HDF5
#   -m MPM_BINARY   an existing CB-Geo 'mpm' instead
#   -t TALUS_BUILD  Talus Release build dir holding talus (default build)
#   -c CELLS        cell edges in mm (default "5 10"; 5, 10 or 20)
#   -r REPEATS      rounds over all cases (default 1)
#   -k CORE         the core both codes are pinned to (taskset -c; default 1)
#   -i PATTERN      Talus input, %H replaced by the cell edge in mm (default
#                   benchmarks/granular_collapse/bui2008_%Hmm_muI_recoverable.prm)
#   -d DT           Talus' 'time step' (largest step) [s] (default: the input's)
#   -p SETTING      a Talus parameter, Section/parameter=value (repeatable):
#                   replaced where the input sets it (the name must be
#                   unique in the input), else added to the top-level
#                   subsection, e.g. -p "Solver/residual tolerance=1e-3"
#   -e CBGEO_DT     CB-Geo's explicit step [s] (default 5e-5)
#   -v UPDATE       CB-Geo's velocity update, pic (default) or flip
#   -o DIR          output root (default output/cbgeo_bui)
#
# CB-Geo's case (contrib/benchmark/cbgeo_bui.py generate): the same grid,
# column, 2 x 2 points per cell, density, E, nu, floor friction 0.36 and
# smooth wall as the Talus input, rate-independent Mohr-Coulomb phi = 19.8
# deg, c = 0, psi = 0 (CB-Geo has no mu(I)), USF, PIC velocity update,
# explicit steps of 5e-5 s, geostatic initial stresses (K0 = nu/(1 - nu);
# CB-Geo's Mohr-Coulomb gives NaN from a zero stress). Its runout: final particle positions from its
# last HDF5 particle file, front as in Talus' deposit profile
# (cbgeo_bui.py runout). Wall time: the whole process (input reading,
# output included) from the shell; CPU: its user + system time
# (/usr/bin/time), less sensitive to other jobs on the core. Table to
# stdout and DIR/results.md; ratios = Talus / CB-Geo of the same round.
set -uo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$top"
src=""; mpm=""; cbuild=""; tbuild=build; cells="5 10"; repeats=1; core=1
pattern='benchmarks/granular_collapse/bui2008_%Hmm_muI_recoverable.prm'
dt=""; edt=5e-5; vupdate=pic; out=output/cbgeo_bui; settings=()
while getopts "s:m:b:t:c:r:k:i:d:p:e:v:o:h" opt; do
  case $opt in
    s) src=$OPTARG ;; m) mpm=$OPTARG ;; b) cbuild=$OPTARG ;;
    t) tbuild=$OPTARG ;; c) cells=$OPTARG ;; r) repeats=$OPTARG ;;
    k) core=$OPTARG ;; i) pattern=$OPTARG ;; d) dt=$OPTARG ;;
    p) settings+=("$OPTARG") ;; e) edt=$OPTARG ;; v) vupdate=$OPTARG ;; o) out=$OPTARG ;;
    *) sed -n '2,41p' "$0"; exit 2 ;;
  esac
done
[[ -n $src || -n $mpm ]] || { sed -n '2,41p' "$0"; exit 2; }
# a python with h5py (Debian's python3-h5py lives in /usr/bin/python3)
py=""
for p in python3 /usr/bin/python3; do
  if "$p" -c "import h5py" 2>/dev/null; then py=$p; break; fi
done
[[ -n $py ]] || { echo "cbgeo_bui.sh: no python3 with h5py (apt-get install python3-h5py)" >&2; exit 1; }
if [[ -z $mpm ]]; then
  cbuild=${cbuild:-$(cd "$src/.." && pwd)/cbgeo-build}
  mpm=$cbuild/mpm
  if [[ ! -x $mpm ]]; then
    cmake -S "$src" -B "$cbuild" -DCMAKE_BUILD_TYPE=Release -DMPM_BUILD_TESTING=OFF \
      -DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON -DCMAKE_DISABLE_FIND_PACKAGE_VTK=ON \
      -DCMAKE_DISABLE_FIND_PACKAGE_Partio=ON -DCMAKE_DISABLE_FIND_PACKAGE_MKL=ON ||
      exit 1
    nice make -C "$cbuild" -j1 mpm || exit 1
  fi
fi
mpm=$(cd "$(dirname "$mpm")" && pwd)/$(basename "$mpm")
[[ -x $mpm ]] || { echo "cbgeo_bui.sh: no CB-Geo binary <$mpm>" >&2; exit 1; }
[[ -x $tbuild/talus ]] || { echo "cbgeo_bui.sh: no talus in <$tbuild>" >&2; exit 1; }
tbuild=$(cd "$tbuild" && pwd)
export OMP_NUM_THREADS=1
mkdir -p "$out"
table=$out/results.md
{
  echo "| round | code | cells | points | steps (rejected) | Newton/step | wall [s] | CPU [s] | runout L [m] | error | Talus/CB-Geo wall | CPU |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} > "$table"
cat "$table"
now() { date +%s.%N; }
for round in $(seq 1 "$repeats"); do
  for H in $cells; do
    h=$("$py" -c "print($H / 1000)")
    # CB-Geo
    run=$out/r${round}_${H}mm_cbgeo
    rm -rf "$run"
    read -r ncells npoints nsteps < <("$py" contrib/benchmark/cbgeo_bui.py generate "$run" --cell "$h" --dt "$edt" --velocity-update "$vupdate")
    start=$(now)
    /usr/bin/time -f "%U %S" -o "$run/cpu" taskset -c "$core" "$mpm" -f "$(cd "$run" && pwd)/" -i mpm.json -p 1 > "$run/cbgeo.log" 2>&1
    rc=$?
    cwall=$("$py" -c "print('%.1f' % ($(now) - $start))")
    ccpu=$("$py" -c "print('%.1f' % sum(map(float, open('$run/cpu').read().split()[-2:])))")
    read -r cL cn _ < <("$py" contrib/benchmark/cbgeo_bui.py runout "$run" --cell "$h" 2>/dev/null || echo "? ? ?")
    cerr=$("$py" -c "print('%+.1f %%' % (100 * ($cL / 0.43 - 1)))" 2>/dev/null || echo "?")
    [[ $rc -eq 0 ]] || cerr="$cerr (exit $rc)"
    printf '| %s | CB-Geo (explicit, USF, %s, Δt %s s) | %s | %s | %s | – | %s | %s | %s | %s | | |\n' \
      "$round" "${vupdate^^}" "$edt" "$ncells" "$cn" "$nsteps" "$cwall" "$ccpu" "$cL" "$cerr" | tee -a "$table"
    # Talus on the same core right after
    input=${pattern//%H/$H}
    run=$out/r${round}_${H}mm_talus
    rm -rf "$run"; mkdir -p "$run"
    sed -e "s|^\( *set output directory = \).*|\1$run|" \
        -e "s|^\( *set format = \).*|\1none|" "$input" > "$run/input.prm"
    [[ -n $dt ]] && sed -i "s|^\( *set time step = \).*|\1$dt|" "$run/input.prm"
    for setting in "${settings[@]}"; do
      section=${setting%%/*}; assignment=${setting#*/}
      [[ $setting == */*=* ]] || { echo "cbgeo_bui.sh: -p <$setting>: Section/parameter=value" >&2; exit 2; }
      name=${assignment%%=*}; value=${assignment#*=}
      if grep -q "^ *set $name = " "$run/input.prm"; then
        # assumes the name is unique in the input
        sed -i "s|^\( *set $name = \).*|\1$value|" "$run/input.prm"
      elif grep -q "^subsection $section\$" "$run/input.prm"; then
        sed -i "/^subsection $section\$/a\\  set ${assignment%%=*} = ${assignment#*=}" "$run/input.prm"
      else
        printf 'subsection %s\n  set %s = %s\nend\n' "$section" "${assignment%%=*}" "${assignment#*=}" >> "$run/input.prm"
      fi
    done
    start=$(now)
    LD_LIBRARY_PATH=$tbuild /usr/bin/time -f "%U %S" -o "$run/cpu" taskset -c "$core" "$tbuild/talus" "$run/input.prm" > "$run/talus.log" 2>&1
    rc=$?
    twall=$("$py" -c "print('%.1f' % ($(now) - $start))")
    tcpu=$("$py" -c "print('%.1f' % sum(map(float, open('$run/cpu').read().split()[-2:])))")
    "$py" - "$run/talus.log" "$round" "$H" "$twall" "$cwall" "$rc" "$run/input.prm" "$tcpu" "$ccpu" <<'EOF' | tee -a "$table"
import re, sys
log, rnd, H, twall, cwall, rc, prm, tcpu, ccpu = sys.argv[1:]
text = open(log).read()
done = re.search(r"Done: (\d+) steps \((\d+) rejected\), ([\d.]+) Newton", text)
runout = re.search(r"runout L \[m\]\s+(\S+)\s+(\S+)\s+(\S+)", text)
points = re.search(r"material points: (\d+)", text)
cells = 0.6 * 0.12 / (float(H) / 1000) ** 2
step = re.findall(r"^ *set time step = *(\S+)", open(prm).read(), re.M)
L = "%.4f" % float(runout.group(1)) if runout else "?"
err = "%+.1f %%" % (100 * (float(runout.group(1)) / 0.43 - 1)) if runout else "?"
if rc != "0":
    err += " (exit %s)" % rc
print("| %s | Talus (implicit, largest Δt %s s) | %d | %s | %s | %s | %s | %s | %s | %s | %.2f | %.2f |"
      % (rnd, step[-1] if step else "?", round(cells),
         points.group(1) if points else "?",
         "%s (%s)" % (done.group(1), done.group(2)) if done else "?",
         done.group(3) if done else "?", twall, tcpu, L, err,
         float(twall) / float(cwall), float(tcpu) / float(ccpu)))
EOF
  done
done
