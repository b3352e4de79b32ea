#!/usr/bin/env bash
# Bui et al. 2008 collapse: runout against the velocity transfer, in one run.
#   usage: bash contrib/granular/transfer_study.sh [-t talus] [-c "20mm 10mm 5mm"]
#                                                  [-s "FLIP APIC XPIC2 XPIC4"] [-d DT]
#   -t EXE      talus executable (default build/talus)
#   -c CELLS    inputs benchmarks/granular_collapse/bui2008_<CELL>.prm
#   -s SCHEMES  FLIP, APIC, PIC (FLIP fraction 0) or XPIC<m> (XPIC order m)
#   -d DT       largest time step [s] for every run (default: the input's)
# Runs from the repository top, one rank each, and writes the variants to
# output/granular/transfer/<cell>_<scheme>/ (input.prm, talus.log and the
# deposit files), then prints a Markdown table: runout L, its error against
# the experiment's toe (0.43 m), the largest |h - h_exp| of the surface
# stations (target 0.01 m), the transfer dissipation (kinetic energy the
# update removes relative to FLIP), steps and wall time. The benchmark
# inputs themselves keep FLIP (doc/verification.md, "Bui
# collapse, rate-independent Mohr-Coulomb and other models").
set -uo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$top"
talus=build/talus; cells="20mm 10mm 5mm"; schemes="FLIP APIC XPIC2 XPIC4"; dt=""
while getopts "t:c:s:d:h" opt; do
  case $opt in
    t) talus=$OPTARG ;;
    c) cells=$OPTARG ;;
    s) schemes=$OPTARG ;;
    d) dt=$OPTARG ;;
    *) sed -n '2,8p' "$0"; exit 2 ;;
  esac
done
[[ -x "$talus" ]] || { echo "transfer_study.sh: no talus executable at <$talus>" >&2; exit 1; }

rows=()
for cell in $cells; do
  base=benchmarks/granular_collapse/bui2008_$cell.prm
  [[ -r $base ]] || { echo "transfer_study.sh: cannot read <$base>" >&2; exit 1; }
  for scheme in $schemes; do
    case $scheme in
      FLIP) lines="  set velocity update = FLIP" ;;
      APIC) lines="  set velocity update = APIC" ;;
      PIC) lines="  set FLIP fraction = 0" ;;
      XPIC[0-9]*) lines="  set velocity update = XPIC\n  set XPIC order = ${scheme#XPIC}" ;;
      *) echo "transfer_study.sh: unknown scheme <$scheme>" >&2; exit 2 ;;
    esac
    dir=output/granular/transfer/${cell}_$scheme${dt:+_dt$dt}
    mkdir -p "$dir"
    step="set time step = ${dt}"
    [[ -n $dt ]] || step='&'
    sed -e "s|^subsection Solver\$|subsection Solver\n$lines|" \
        -e "s|set time step = .*|$step|" \
        -e "s|set output directory = .*|set output directory = $dir|" \
        -e "s|set output interval = .*|set output interval = 1|" "$base" > "$dir/input.prm"
    start=$(date +%s.%N)
    "$talus" "$dir/input.prm" > "$dir/talus.log" 2>&1; code=$?
    wall=$(python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.0f}')" "$start" "$(date +%s.%N)")
    row=$(python3 - "$dir" "$cell" "$scheme" "$code" "$wall" <<'PYEOF'
import csv, sys
d, cell, scheme, code, wall = sys.argv[1:]
try:
    s = next(csv.DictReader(open(f"{d}/deposit_summary.csv")))
    L = float(s["runout"])
    rows = list(csv.DictReader(open(f"{d}/time_series.csv")))
    last = rows[-1]
    # largest surface error of the run's own check (talus.log table)
    dh = 0.
    log = open(f"{d}/talus.log").read().splitlines()
    for line in log:
        if line.strip().startswith("h(") and "[m]" in line:
            dh = max(dh, float(line.split()[4]))
    dt = next(l.split("=")[1].strip() for l in open(f"{d}/input.prm") if "set time step =" in l)
    print(f"| {cell} | {scheme} | {dt} | {L:.4f} | {100 * (L - 0.43) / 0.43:+.1f} % | {dh:.4f} | "
          f"{float(last['transfer_dissipation']):.3g} | {last['step']} | {wall} s | {code} |")
except Exception as e:
    print(f"| {cell} | {scheme} | | failed ({e}) | | | | | {wall} s | {code} |")
PYEOF
)
    echo "$row"
    rows+=("$row")
  done
done
echo
echo "| cells | transfer | largest step [s] | runout L [m] | error vs 0.43 m | largest abs(h - h_exp) [m] | transfer dissipation [J] | steps | wall | exit |"
echo "|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
