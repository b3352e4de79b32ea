#!/bin/bash
# Time-step convergence of the granular collapse benchmarks (issue 3).
# Usage (from the repository top):
#   contrib/granular/dt_convergence/run_dt.sh INPUT.prm DT [DT ...]
# For every DT: writes output/dt_check/<input>_dt<DT>/<input>_dt<DT>.prm, a
# copy of INPUT.prm with 'time step = DT' (the largest step of the adaptive
# stepping; everything else unchanged, 'time series interval' kept at 0.01 s)
# and its own output directory, runs it with $TALUS (default build/talus) on
# one rank, and writes the log and the wall time (last line 'rc=... wall=...')
# to talus.log there. collect_dt.py tabulates the runs.
set -u
input=$1; shift
base=$(basename "$input" .prm)
for dt in "$@"; do
  name=${base}_dt$dt
  dir=output/dt_check/$name
  mkdir -p "$dir"
  series=$(python3 -c "print(max(1, round(0.01 / $dt)))")
  sed -e "s|^\( *set time step = \).*|\1$dt|" \
      -e "s|^\( *set time series interval = \).*|\1$series|" \
      -e "s|^\( *set output directory = \).*|\1$dir|" "$input" > "$dir/$name.prm"
  start=$(date +%s.%N)
  ${TALUS:-build/talus} "$dir/$name.prm" > "$dir/talus.log" 2>&1
  rc=$?
  wall=$(python3 -c "print('%.0f' % ($(date +%s.%N) - $start))")
  echo "rc=$rc wall=$wall" >> "$dir/talus.log"
  echo "$name: rc=$rc wall=${wall}s"
done
