#!/usr/bin/env bash
# memory_long_run.sh TALUS [STEPS...] [-- WORKDIR]
# Memory over long runs (doc/performance.md, "Memory over long runs"):
# runs two small cases for each number of steps (default 1000 and 10000)
# on one rank and reports the peak resident set size (VmHWM, measured
# by /usr/bin/time; the summary prints it as "memory: peak resident
# set") and the resident set sampled every 2 s against the step reached
# (all of it, VmRSS, and its anonymous part, RssAnon: the heap and the
# stacks, without the pages of the shared libraries), so that growth over
# the run shows:
#   mpm      tests/checkpoint/block_floor.prm (Mohr-Coulomb block, grid
#            friction, a wall of boundary particles, 400 points), 5 ms
#   coupled  tests/checkpoint/coupled_string.prm on a coarser grid (35 x 15
#            cells, 50 points) and 10 string elements, IQN-ILS, 5 ms
# Both write a checkpoint every 1000 steps (keep 2; the environment
# variable CHECKPOINT_EVERY sets another interval, 0: none) and VTU
# output every 500 steps, so that these paths are part of the measurement; the
# coupled case has no verification (its energy balance drifts beyond
# 1 % over 10^4 steps, which is not what is measured here).
# 10^4 steps take about 3 min (mpm) and 6 min (coupled) on one core.
set -u
talus=$(readlink -f "$1"); shift
steps_list=()
work=${TMPDIR:-/tmp}/talus_memory_long_run
while [ $# -gt 0 ]; do
  if [ "$1" = "--" ]; then work=$2; shift 2; else steps_list+=("$1"); shift; fi
done
[ ${#steps_list[@]} -gt 0 ] || steps_list=(1000 10000)
every=${CHECKPOINT_EVERY:-1000}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
tests=$here/../../tests/checkpoint
mkdir -p "$work"

# make_case NAME STEPS: the parameter file of NAME for STEPS steps of 5 ms
make_case() {
  local name=$1 steps=$2 end
  end=$(python3 -c "print($steps * 0.005)")
  local interval
  interval=$(python3 -c "print(500 * 0.005)")
  if [ "$name" = mpm ]; then
    sed "s/set end time = .*/set end time = $end/;
         s/set output interval = .*/set output interval = $interval/;
         s/set test mode = true/set test mode = false/;
         s/set every steps = 10/set every steps = $every/" "$tests/block_floor.prm"
  else
    sed "s/set end time = .*/set end time = $end/;
         s/set output interval = .*/set output interval = $interval/;
         s/set test mode = true/set test mode = false/;
         s/set subdivisions = 70, 30/set subdivisions = 35, 15/;
         s/set elements per member = 20/set elements per member = 10/;
         s/set every steps = 10/set every steps = $every/;
         /subsection Verification/,/^  end/d" "$tests/coupled_string.prm"
  fi
}

printf '%-8s %7s %10s %12s %12s %s\n' case steps "wall [s]" "VmHWM [MB]" \
  "last RSS [MB]" "(sampled VmRSS [MB] at step: ...)"
for steps in "${steps_list[@]}"; do
  for name in mpm coupled; do
    dir=$work/$name-$steps
    rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
    make_case $name "$steps" > case.prm
    csv=output/time_series.csv
    [ $name = coupled ] && csv=output/coupling.csv
    start=$(date +%s.%N)
    /usr/bin/time -f %M -o maxrss.txt "$talus" case.prm > log.txt 2>&1 &
    tpid=$!
    pid=""
    while [ -z "$pid" ] && kill -0 $tpid 2>/dev/null; do
      pid=$(pgrep -P $tpid | head -n 1); sleep 0.2
    done
    samples=""; anon_samples=""; rss=0
    while [ -n "$pid" ] && kill -0 $pid 2>/dev/null; do
      r=$(awk '/VmRSS/ {print $2}' /proc/$pid/status 2>/dev/null)
      a=$(awk '/RssAnon/ {print $2}' /proc/$pid/status 2>/dev/null)
      n=$(($(cat $csv 2>/dev/null | wc -l) - 1))
      if [ -n "$r" ] && [ -n "$a" ] && [ $n -gt 0 ]; then
        rss=$r; samples+="$n:$r "; anon_samples+="$n:$a "
      fi
      sleep 2
    done
    wait $tpid; code=$?
    hwm=$(tail -n 1 maxrss.txt)
    wall=$(python3 -c "import time; print(round(time.time() - $start, 1))")
    echo "$samples" > rss_samples.txt
    echo "$anon_samples" > rss_anon_samples.txt
    # thin the samples to about 8, in MB
    thin() {
      python3 - "$1" <<'PY'
import sys
s = [tuple(map(int, x.split(':'))) for x in sys.argv[1].split()]
s = [x for x in s if x[0] > 0]
if s:
    k = max(1, len(s) // 8)
    t = s[::k]
    if t[-1] != s[-1]:
        t.append(s[-1])
    print(' '.join('%d:%.1f' % (n, r / 1024.) for n, r in t))
PY
    }
    printf '%-8s %7s %10s %12.1f %12.1f %s\n' $name "$steps" "$wall" \
      "$(echo "$hwm / 1024" | bc -l)" "$(echo "$rss / 1024" | bc -l)" \
      "$(thin "$samples")"
    printf '%52s anonymous (heap): %s\n' "" "$(thin "$anon_samples")"
    grep "memory:" log.txt | sed 's/^/         /'
    [ $code -eq 0 ] || { echo "  $name-$steps failed (exit $code):"; tail -n 5 log.txt; }
  done
done
