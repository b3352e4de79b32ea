#!/usr/bin/env bash
# Load balancing benchmark (doc/performance.md, "Load balancing"): one
# granular collapse input on 1 rank, on 2 ranks with deal.II's default
# partition (cells balanced) and on 2 ranks with load balancing (subsection
# Load balancing: imbalance threshold 1.1, the default weights), back to
# back, REPEAT times each; prints a Markdown table with the wall time, the
# steps, the imbalance of the material points and the 1-minute load
# average before each run (other jobs on the machine).
#   usage: bash contrib/benchmark/load_balancing.sh [talus] [input] [end time] [repeat]
# Defaults: build/talus, benchmarks/granular_collapse/bui2008_10mm.prm,
# 0.5 s (the deposit measurement is switched off: a shortened run has no
# deposit), 2. Run from the repository top; scratch in
# build/load-balancing-benchmark/.
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
talus=$(realpath "${1:-build/talus}")
input=$(realpath "${2:-benchmarks/granular_collapse/bui2008_10mm.prm}")
end=${3:-0.5}
repeat=${4:-2}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
work=$(dirname "$talus")/load-balancing-benchmark
rm -rf "$work"; mkdir -p "$work"; cd "$work"

# the input with its data paths from the repository top, shortened
sed "s|set end time = .*|set end time = $end|;
     s|set measure deposit = true|set measure deposit = false|;
     s|set output interval = .*|set output interval = 100|;
     s|set format = vtu|set format = none|;
     s|data/|$top/data/|" "$input" > plain.prm
cp plain.prm balanced.prm
printf 'subsection Load balancing\n  set imbalance threshold = 1.1\nend\n' \
  >> balanced.prm

echo "| run | ranks | wall time [s] | steps | Newton per step | imbalance (mean / largest / end) | repartitions | load before |"
echo "|---|---|---|---|---|---|---|---|"
for r in $(seq "$repeat"); do
  for c in "1 plain" "2 plain" "2 balanced"; do
    set -- $c
    log="$2-np$1-$r.log"
    load=$(cut -d' ' -f1 /proc/loadavg)   # other jobs on the machine
    start=$(date +%s.%N)
    mpirun -np "$1" "$talus" "$2.prm" > "$log" 2>&1 ||
      { tail "$log"; echo "run $2 on $1 rank(s) failed"; exit 1; }
    stop=$(date +%s.%N)
    wall=$(python3 -c "print(f'{$stop - $start:.1f}')")
    done_line=$(grep "^Done:" "$log")
    steps=$(sed 's/Done: \([0-9]*\) steps.*/\1/' <<<"$done_line")
    newton=$(sed 's/.* rejected), \([0-9.]*\) Newton.*/\1/' <<<"$done_line")
    imb=$(grep "imbalance of the material points (largest rank / mean) at the start" "$log" |
          sed 's/.*mean \([0-9.]*\), largest \([0-9.]*\), at the end \([0-9.]*\); \([0-9]*\) rep.*/\1 \/ \2 \/ \3|\4/' || true)
    [ -n "$imb" ] || imb="1 / 1 / 1|0"
    echo "| $2 ($r) | $1 | $wall | $steps | $newton | ${imb%|*} | ${imb#*|} | $load |"
  done
done
