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
#     --quick          small sizes only (2D 28 60 124, 3D 4 8 12): smoke test
#     --no-build       use the existing executables in the build directory
#     --no-floor       skip the deal.II floor runs
#     --help           this text
#   environment (defaults in brackets; an empty size list runs none):
#     TALUS_BENCH_BUILD    Release build directory [<repo>/build-bench]
#     TALUS_BENCH_OUT      result directory [<build>/benchmark-results]
#     TALUS_BENCH_SIZES_2D cells per direction under the 2D block [60 180 508]
#     TALUS_BENCH_SIZES_3D cells per direction under the 3D block [8 18 36]
#     TALUS_BENCH_GEN_SIZES 2D sizes of the particle-generation runs (one
#                          step, single-level grid vs refined grid, 1 rank)
#                          [60 124 180]; empty: none
#     TALUS_BENCH_RANKS    MPI rank counts [1 2]
#     TALUS_BENCH_STEPS    time steps per run [5]
#     TALUS_BENCH_BUDGET   wall-time budget of all runs [s, 1200]; once it
#                          is spent the remaining runs are skipped (and listed
#                          as skipped in the tables)
#     TALUS_BENCH_TIMEOUT  limit per run [s, 600]
#     TALUS_BENCH_COMMIT   revision to state in the results [git rev-parse]
#     TALUS_BENCH_MAX_REFINE  most refinements of the coarse grid [4]; 0 makes
#                          the grid a single level (slow particle generation,
#                          see fill() below)
#
# Particle counts: 2D 4 N^2 (60: 14,400; 180: 129,600; 508: 1,032,256),
# 3D 8 N^3 (8: 4,096; 18: 46,656; 36: 373,248). The two larger sizes of each
# dimension differ by a factor 8 (the AMG growth target); N + 4 has a large
# power of 2 as factor (see fill() below).
# The result directory holds one folder per run (input, log, time series)
# and results.md / results.csv. Exit status: non-zero if the build fails or
# a run fails (timeouts and skipped runs are reported, not fatal).
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here="$top/contrib/benchmark"
build=${TALUS_BENCH_BUILD:-$top/build-bench}
sizes2d=${TALUS_BENCH_SIZES_2D-"60 180 508"}
sizes3d=${TALUS_BENCH_SIZES_3D-"8 18 36"}
gen_sizes=${TALUS_BENCH_GEN_SIZES-"60 124 180"}
ranks=${TALUS_BENCH_RANKS:-"1 2"}
steps=${TALUS_BENCH_STEPS:-5}
budget=${TALUS_BENCH_BUDGET:-1200}
timeout_run=${TALUS_BENCH_TIMEOUT:-600}
max_refine=${TALUS_BENCH_MAX_REFINE:-4}
dt=0.01
do_build=1
do_floor=1

while [ $# -gt 0 ]; do
  case "$1" in
    --quick) sizes2d="28 60 124"; sizes3d="4 8 12" ;;
    --no-build) do_build=0 ;;
    --no-floor) do_floor=0 ;;
    --help|-h) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "run_benchmarks.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
out=${TALUS_BENCH_OUT:-$build/benchmark-results}

# (before OMP_NUM_THREADS is set: nproc honours it)
ncores=$(nproc --all 2>/dev/null || getconf _NPROCESSORS_ONLN)

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
     make -j"$ncores" talus > make.log) ||
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
  if [ -n "${TALUS_BENCH_COMMIT:-}" ]; then
    echo "commit: $TALUS_BENCH_COMMIT"
  elif git -C "$top" rev-parse --short HEAD > /dev/null 2>&1; then
    echo "commit: $(git -C "$top" rev-parse --short HEAD)$(git -C "$top" diff --quiet HEAD -- include source CMakeLists.txt || echo ' + uncommitted changes in include/ or source/')"
  else
    echo "commit: unknown"
  fi
  echo "nproc: $ncores"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//') (family $(grep -m1 'cpu family' /proc/cpuinfo | cut -d: -f2 | tr -d ' ') model $(grep -m1 '^model[[:space:]]*:' /proc/cpuinfo | cut -d: -f2 | tr -d ' '), $(grep -c '^processor' /proc/cpuinfo) logical CPUs, $(lscpu 2>/dev/null | sed -n 's/^Thread(s) per core: *//p') thread(s) per core$(lscpu 2>/dev/null | sed -n 's/^Hypervisor vendor: */, hypervisor /p'))"
  echo "memory: $(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo)"
  dealii_dir=$(sed -n 's/^deal.II_DIR:PATH=//p' "$build/CMakeCache.txt")
  echo "deal.II: $(sed -n 's/^[sS][eE][tT](DEAL_II_PACKAGE_VERSION "\(.*\)")/\1/p' "$dealii_dir/deal.IIConfig.cmake" 2>/dev/null | head -1) ($dealii_dir)"
  echo "mpirun: $(mpirun --version 2>/dev/null | head -1)"
  echo "steps: $steps"
  echo "dt: $dt"
} > "$out/machine.txt"

# fill <dim> <N> <output dir>: the input file of one run on stdout. The grid
# has N cells per direction under the unit block plus empty cells: 2 on the
# sides, 4 on top (room for the Poisson expansion and the motion), N + 4 in
# all. It is made as a coarse grid of (N + 4) / 2^k cells refined k times
# ('Convergence study/first level'), k the largest <= max_refine with
# 2^k | N + 4: with k = 0 the particle generation of Talus (8c62bab) takes
# O(particles x coarse cells) (GridTools::guess_point_owner over one bounding
# box per coarse cell in ParticleHandler::insert_global_particles), minutes
# for 1e6 particles; the refined grid is the same grid with few coarse cells.
fill() {
  local dim=$1 n=$2 dir=$3
  local h xlo xhi yhi k=0 m=$(($2 + 4))
  while [ "$k" -lt "$max_refine" ] && [ $((m % (1 << (k + 1)))) = 0 ] &&
          [ $((m >> (k + 1))) -ge 2 ]; do
    k=$((k + 1))
  done
  h=$(awk -v n="$n" 'BEGIN {printf "%.17g", 1 / n}')
  xlo=$(awk -v h="$h" 'BEGIN {printf "%.17g", -2 * h}')
  xhi=$(awk -v h="$h" 'BEGIN {printf "%.17g", 1 + 2 * h}')
  yhi=$(awk -v h="$h" 'BEGIN {printf "%.17g", 1 + 4 * h}')
  sed -e "s/@N@/$n/g" -e "s/@XLO@/$xlo/g" -e "s/@XHI@/$xhi/g" \
      -e "s/@YHI@/$yhi/g" -e "s/@N0@/$((m >> k))/g" -e "s/@K@/$k/g" \
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

# Particle generation (untimed by Talus: "init" = total - time loop) on a
# single-level grid (max_refine = 0) and on the refined grid, one step.
for n in $gen_sizes; do
  for k in 0 "$max_refine"; do
    name="gen_2d_N${n}_k${k}"
    mkdir -p "$out/$name"
    max_refine=$k steps=1 fill 2 "$n" "$out/$name" > "$out/$name/input.prm"
    run_case "$name" 1 "$talus" "$out/$name/input.prm"
  done
done

python3 "$here/parse_results.py" "$out" || status=1
echo "run_benchmarks.sh: runs took $((SECONDS - start_runs)) s, total ${SECONDS} s"
echo "run_benchmarks.sh: tables in $out/results.md"
exit $status
