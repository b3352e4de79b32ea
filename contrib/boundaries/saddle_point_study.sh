#!/bin/bash
# Lagrange multiplier boundaries: the saddle-point solvers compared in one
# run (doc/performance.md, "Saddle-point solve"). Each case is a test input
# with the linear solver, the saddle-point solver and the penalty factor
# changed; printed: wall time, steps, rejected steps, Newton iterations,
# linear iterations per Newton iteration, the displacement errors of the
# test and its verdict.
#
#   usage: contrib/boundaries/saddle_point_study.sh [path/to/talus] [ranks]
#
# Run from the repository top; about 6 minutes on 1 rank. As root, mpirun
# needs OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1.
set -u
TALUS=$(realpath "${1:-build/talus}")
RANKS=${2:-1}
TOP=$(pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
RUN="$TALUS"
[ "$RANKS" -gt 1 ] && RUN="mpirun -np $RANKS $TALUS"

# case: name input linear-solver saddle-point-solver penalty-factor
run_case() {
  local name=$1 input=$2 solver=$3 saddle=$4 factor=$5
  python3 - "$input" "$WORK/$name.prm" "$TOP/tests/boundaries" "$solver" \
    "$saddle" "$factor" "$WORK/out-$name" <<'EOF'
import re, sys
src, dst, sdir, solver, saddle, factor, out = sys.argv[1:]
lines = []
for l in open(src).read().replace("@SOURCE_DIR@", sdir).splitlines():
    if re.match(r"\s*set (method|penalty factor|saddle-point solver) =", l):
        continue
    if re.match(r"\s*set friction coefficient =", l):
        lines += [l, "    set method = Lagrange multiplier",
                  f"    set penalty factor = {factor}"]
    elif re.match(r"\s*set linear solver =", l):
        lines += [f"  set linear solver = {solver}",
                  f"  set saddle-point solver = {saddle}"]
    elif re.match(r"\s*set output directory =", l):
        lines.append(f"  set output directory = {out}")
    else:
        lines.append(l)
open(dst, "w").write("\n".join(lines) + "\n")
EOF
  local start end
  start=$(date +%s.%N)
  (cd "$WORK" && timeout 900 $RUN "$name.prm" > "$name.log" 2>&1)
  local rc=$?
  end=$(date +%s.%N)
  python3 - "$WORK" "$name" "$rc" "$start" "$end" <<'EOF'
import csv, sys, os, re
work, name, rc, start, end = sys.argv[1:]
wall = float(end) - float(start)
rows = []
f = f"{work}/out-{name}/time_series.csv"
if os.path.exists(f):
    rows = list(csv.DictReader(open(f)))[1:]
newton = sum(int(r["newton_iterations"]) for r in rows)
linear = sum(int(r["linear_iterations"]) for r in rows)
log = open(f"{work}/{name}.log").read()
rejected = log.count("rejected (dt")
errors = " / ".join(re.findall(r"error at t = \S+: displacement (\S+)", log))
t_end = rows[-1]["time"] if rows else "0"
verdict = "ok" if rc == "0" else f"exit {rc}"
print(f"| {name} | {wall:.1f} | {t_end} | {len(rows)} | {rejected} | "
      f"{newton} | {linear / max(newton, 1):.1f} | {errors} | {verdict} |")
EOF
}

echo "talus: $TALUS, $RANKS rank(s), $(date -u +%Y-%m-%dT%H:%MZ), $(git -C "$TOP" rev-parse --short HEAD)"
echo "| case | wall [s] | reached t [s] | steps | rejected | Newton | linear per Newton | error [m] | result |"
echo "|---|---|---|---|---|---|---|---|---|"
I2=$TOP/tests/boundaries/incline_rotated_30_mu01_lagrange.prm
I3=$TOP/tests/boundaries/incline_plane_3d_20_mu01_slow.prm.in
run_case 2d_direct_schur "$I2" direct "Schur complement" 100
run_case 2d_direct_block "$I2" direct "block preconditioned" 100
run_case 2d_gmres_schur "$I2" GMRES "Schur complement" 100
run_case 2d_gmres_block "$I2" GMRES "block preconditioned" 100
run_case 2d_gmres_block_f1 "$I2" GMRES "block preconditioned" 1
run_case 3d_direct_schur "$I3" direct "Schur complement" 100
run_case 3d_direct_block "$I3" direct "block preconditioned" 100
run_case 3d_gmres_schur_f1 "$I3" GMRES "Schur complement" 1
run_case 3d_gmres_block_f1 "$I3" GMRES "block preconditioned" 1
