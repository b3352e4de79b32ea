#!/usr/bin/env bash
# Timing of the standard barrier structure (doc/performance.md, "Barrier
# structure"): builds barrier-timing in a Release build directory and runs it
# at net cell sizes 0.25 m and 0.1 m, serially, one run after the other.
#
#   usage: bash contrib/benchmark/structure/run_barrier_timing.sh [BUILD_DIR]
#   BUILD_DIR: a configured Release build of Talus [<repo>/build]
# Output: one block of "key = value" lines per size, preceded by the machine,
# the revision and the date (also written to BUILD_DIR/barrier-timing.txt).
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
build=${1:-$top/build}
make -C "$build" barrier-timing >/dev/null
out="$build/barrier-timing.txt"
{
  echo "date = $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "revision = $(git -C "$top" rev-parse --short HEAD)"
  echo "cpu = $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
  echo "nproc = $(nproc)"
  echo "load_average_before = $(cut -d' ' -f1-3 /proc/loadavg)"
  # H  time_steps  dt  static_load_steps
  for run in "0.25 10 0.005 5" "0.1 5 0.005 0"; do
    set -- $run
    echo "--- net cell size $1 m"
    "$build/barrier-timing" "$1" "$2" "$3" "$4"
  done
} | tee "$out"
