#!/usr/bin/env bash
# Talus performance benchmark (Release build, 1 and 2 MPI ranks).
#
# A neo-Hookean block with a fixed base, released under gravity (see
# block_2d.prm.in / block_3d.prm.in), 2 material points per cell and
# direction, a few implicit time steps, at three sizes in 2D and 3D. The
# TimerOutput tables and time_series.csv files of the runs are turned into
# Markdown tables (results.md) by parse_results.py, together with the deal.II
# "floor" (floor/floor.cc: plain FEM assembly + the same AMG/CG on the same
# block) and the performance targets of the issue.
#
#   usage: bash contrib/benchmark/run_benchmarks.sh [options]
#     --quick          small sizes only (2D 32 63 126, 3D 6 9 17): smoke test
#     --no-build       use the existing executables in the build directory
#     --no-floor       skip the deal.II floor runs
#     --help           this text
#   environment (defaults in brackets):
#     TALUS_BENCH_BUILD    Release build directory [<repo>/build-bench]
#     TALUS_BENCH_OUT      result directory [<build>/benchmark-results]
#     TALUS_BENCH_SIZES_2D cells per direction under the 2D block [63 177 500]
#     TALUS_BENCH_SIZES_3D cells per direction under the 3D block [9 17 34]
#     TALUS_BENCH_RANKS    MPI rank counts [1 2]
#     TALUS_BENCH_STEPS    time steps per run [5]
#     TALUS_BENCH_BUDGET   wall-time budget of all runs [s, 1200]; once it
#                          is spent the remaining runs are skipped (and listed
#                          as skipped in the tables)
#     TALUS_BENCH_TIMEOUT  limit per run [s, 600]
#
# Particle counts: 2D 4 N^2 (63: 15,876; 177: 125,316; 500: 1,000,000),
# 3D 8 N^3 (9: 5,832; 17: 39,304; 34: 314,432). Consecutive sizes grow ~8x.
# The result directory holds one folder per run (input, log, time series)
# and results.md / results.csv. Exit status: non-zero if the build fails or
# a run fails (timeouts and skipped runs are reported, not fatal).
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here="$top/contrib/benchmark"
build=${TALUS_BENCH_BUILD:-$top/build-bench}
sizes2d=${TALUS_BENCH_SIZES_2D:-"63 177 500"}
sizes3d=${TALUS_BENCH_SIZES_3D:-"9 17 34"}
ranks=${TALUS_BENCH_RANKS:-"1 2"}
steps=${TALUS_BENCH_STEPS:-5}
budget=${TALUS_BENCH_BUDGET:-1200}
timeout_run=${TALUS_BENCH_TIMEOUT:-600}
dt=0.01
do_build=1
do_floor=1

while [ $# -gt 0 ]; do
  case "$1" in
    --quick) sizes2d="32 63 126"; sizes3d="6 9 17" ;;
    --no-build) do_build=0 ;;
    --no-floor) do_floor=0 ;;
    --help|-h) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "run_benchmarks.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
out=${TALUS_BENCH_OUT:-$build/benchmark-results}

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
# One thread per rank (deal.II/TBB, OpenMP in Trilinos/BLAS if any).
export OMP_NUM_THREADS=1 DEAL_II_NUM_THREADS=1

SECONDS=0
if [ "$do_build" = 1 ]; then
  echo "run_benchmarks.sh: building talus (Release) in $build"
  mkdir -p "$build"
  (cd "$build" &&
     cmake "$top" -DCMAKE_BUILD_TYPE=Release -DTALUS_ENABLE_TESTS=OFF \
       > cmake.log &&
     make -j"$(nproc)" talus > make.log) ||
    { echo "run_benchmarks.sh: build failed, see $build/make.log" >&2; exit 1; }
  if [ "$do_floor" = 1 ]; then
    echo "run_benchmarks.sh: building the deal.II floor in $build/floor"
    mkdir -p "$build/floor"
    (cd "$build/floor" &&
       cmake "$here/floor" -DCMAKE_BUILD_TYPE=Release > cmake.log &&
       make talus-floor > make.log) ||
      { echo "run_benchmarks.sh: floor build failed" >&2; exit 1; }
  fi
  echo "run_benchmarks.sh: build done after ${SECONDS} s"
fi
talus="$build/talus"
floor="$build/floor/talus-floor"
[ -x "$talus" ] || { echo "run_benchmarks.sh: no $talus" >&2; exit 1; }
if [ "$do_floor" = 1 ] && [ ! -x "$floor" ]; then
  echo "run_benchmarks.sh: no $floor (build it or use --no-floor)" >&2
  exit 1
fi
grep -q 'CMAKE_BUILD_TYPE:STRING=Release' "$build/CMakeCache.txt" 2>/dev/null ||
  echo "run_benchmarks.sh: warning: $build is not a Release build" >&2

rm -rf "$out"
mkdir -p "$out"
start_runs=$SECONDS
status=0

# Machine and revision (for doc/performance.md).
{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "commit: $(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$top" diff --quiet HEAD -- include source 2>/dev/null || echo ' (with local changes in include/ or source/)')"
  echo "nproc: $(nproc)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "memory: $(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo)"
  echo "deal.II: $(sed -n 's/^DEAL_II_PACKAGE_VERSION:[A-Z]*=//p; s/^deal.II_DIR:PATH=//p' "$build/CMakeCache.txt" | head -1)"
  echo "mpirun: $(mpirun --version 2>/dev/null | head -1)"
  echo "steps: $steps"
  echo "dt: $dt"
} > "$out/machine.txt"

# fill <dim> <N> <output dir>: the input file of one run on stdout. The grid
# has N cells per direction under the unit block plus 2 empty cells on the
# sides and on top (room for the Poisson expansion and the motion).
fill() {
  local dim=$1 n=$2 dir=$3
  local h xlo xhi yhi
  h=$(awk -v n="$n" 'BEGIN {printf "%.17g", 1 / n}')
  xlo=$(awk -v h="$h" 'BEGIN {printf "%.17g", -2 * h}')
  xhi=$(awk -v h="$h" 'BEGIN {printf "%.17g", 1 + 2 * h}')
  yhi=$xhi
  sed -e "s/@N@/$n/g" -e "s/@XLO@/$xlo/g" -e "s/@XHI@/$xhi/g" \
      -e "s/@YHI@/$yhi/g" -e "s/@NX@/$((n + 4))/g" -e "s/@NY@/$((n + 2))/g" \
      -e "s/@END@/$(awk -v s="$steps" -v dt="$dt" 'BEGIN {printf "%.10g", s * dt}')/g" \
      -e "s/@DT@/$dt/g" -e "s#@OUT@#$dir#g" \
      "$here/block_${dim}d.prm.in"
}

# run_case <name> <ranks> <command...>: run with /usr/bin/time per rank,
# a time limit and the load average before the run, unless the budget is
# spent.
run_case() {
  local name=$1 np=$2
  shift 2
  local dir="$out/$name"
  mkdir -p "$dir"
  local used=$((SECONDS - start_runs))
  if [ "$used" -ge "$budget" ]; then
    echo "skipped: time budget of $budget s spent" > "$dir/status"
    printf 'run_benchmarks.sh: %-22s skipped (budget spent)\n' "$name"
    return 0
  fi
  cut -d' ' -f1-3 /proc/loadavg > "$dir/load_before"
  local t0=$SECONDS rc=0
  timeout "$timeout_run" mpirun -np "$np" \
    /usr/bin/time -f 'RANKTIME wall=%e user=%U sys=%S maxrss_kb=%M' "$@" \
    > "$dir/log" 2>&1 || rc=$?
  if [ "$rc" = 0 ]; then
    echo ok > "$dir/status"
  elif [ "$rc" = 124 ]; then
    echo "timeout after $timeout_run s" > "$dir/status"
  else
    echo "failed (exit $rc)" > "$dir/status"
    status=1
  fi
  printf 'run_benchmarks.sh: %-22s %s, %d s (load before: %s)\n' \
    "$name" "$(cat "$dir/status")" $((SECONDS - t0)) "$(cat "$dir/load_before")"
}

for dim in 2 3; do
  if [ "$dim" = 2 ]; then sizes=$sizes2d; else sizes=$sizes3d; fi
  for n in $sizes; do
    for np in $ranks; do
      name="${dim}d_N${n}_np${np}"
      mkdir -p "$out/$name"
      fill "$dim" "$n" "$out/$name" > "$out/$name/input.prm"
      run_case "$name" "$np" "$talus" "$out/$name/input.prm"
    done
    if [ "$do_floor" = 1 ]; then
      for np in $ranks; do
        run_case "floor_${dim}d_N${n}_np${np}" "$np" "$floor" "$dim" "$n" 2
      done
    fi
  done
done

python3 "$here/parse_results.py" "$out" || status=1
echo "run_benchmarks.sh: runs took $((SECONDS - start_runs)) s, total ${SECONDS} s"
echo "run_benchmarks.sh: tables in $out/results.md"
exit $status
