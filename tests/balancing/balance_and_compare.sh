#!/usr/bin/env bash
# balance_and_compare.sh TALUS INPUT MODE WORKDIR
# Load balancing tests (doc/verification.md, "Load balancing"). INPUT is run
# as it is (subsection Load balancing on) and with load balancing off; both
# write their final material points in full precision
# (TALUS_DEBUG_DUMP_POINTS) next to their time_series.csv.
#   ranks2  2 ranks: the run repartitions at the start (log line), the
#           imbalance of the material points drops from 1.5 to below 1.1
#           (also after every later repartition), and
#           the results agree with the run without load balancing to 1e-6
#           (compare_runs.py of tests/checkpoint: CSV rows and points)
#   coupled1, coupled2  the coupled problem (INPUT
#           tests/coupled/block_on_string_rest.prm, load balancing added
#           here) on 1 rank: output and coupling.csv bitwise identical; on 2
#           ranks: the output agrees to the coupling tolerance
#   ranks1  1 rank: the repartitions carry the state through
#           Triangulation::repartition(); the CSV and the points must be
#           bitwise identical to the run without
set -u
talus=$1; input=$2; mode=$3; work=$4
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
cp "$input" balanced.prm
sed 's/set repartition every steps = .*/set repartition every steps = 0/;
     s/set imbalance threshold = .*/set imbalance threshold = 0/' \
  "$input" > plain.prm

fail() { echo "FAIL: $*"; exit 1; }

# run NAME RANKS: talus on NAME.prm in directory NAME
run() {
  mkdir -p "$1"
  ( cd "$1" && TALUS_DEBUG_DUMP_POINTS=output/points.txt \
      timeout 300 mpirun -np "$2" "$talus" "../$1.prm" > log.txt 2>&1 ) ||
    { cat "$1/log.txt"; fail "the run $1 on $2 rank(s) failed"; }
}

case $mode in
  ranks2)
    run plain 2
    run balanced 2
    grep -q "load balancing" plain/log.txt &&
      fail "the run without load balancing repartitioned"
    grep "load balancing" balanced/log.txt ||
      fail "the run with load balancing did not repartition"
    # the start: 120 of the 160 points on rank 0 (imbalance 1.5); after
    # every repartition below the threshold 1.1
    line=$(grep "load balancing at step 0: repartitioned" balanced/log.txt) ||
      fail "no repartition at the start"
    before=$(sed 's/.*(largest rank \/ mean) \([0-9.e+-]*\) -> .*/\1/' <<<"$line")
    after=$(sed 's/.* -> \([0-9.e+-]*\) (points.*/\1/' <<<"$line")
    echo "imbalance at the start: $before -> $after"
    python3 -c "import sys; sys.exit(0 if $before >= 1.5 and $after < 1.1 else 1)" ||
      fail "the imbalance did not drop from 1.5 or more to below 1.1"
    python3 - balanced/log.txt <<'PY' || fail "an imbalance after a repartition is 1.1 or more"
import re, sys
after = [float(m.group(1)) for m in
         re.finditer(r" -> ([0-9.e+-]+) \(points", open(sys.argv[1]).read())]
print(f"{len(after)} repartitions, largest imbalance after one: {max(after):.4g}")
sys.exit(0 if after and max(after) < 1.1 else 1)
PY
    python3 "$here/../checkpoint/compare_runs.py" plain/output \
      balanced/output 1e-6 "2 ranks, with and without load balancing" 18,19 ||
      fail "the runs with and without load balancing differ"
    ;;
  ranks1)
    run plain 1
    run balanced 1
    grep "load balancing" balanced/log.txt ||
      fail "the run with load balancing did not repartition"
    cmp plain/output/time_series.csv balanced/output/time_series.csv ||
      fail "time_series.csv differs"
    cmp plain/output/points.txt balanced/output/points.txt ||
      fail "the final material points differ"
    diff <(sed -n '/^Summary/,$p' plain/log.txt) \
         <(sed -n '/^Summary/,$p' balanced/log.txt) ||
      fail "the summaries differ"
    echo "1 rank: time series, points and summary bitwise identical"
    ;;
  coupled2)
    # the coupled problem (INPUT: tests/coupled/block_on_string_rest.prm,
    # load balancing added here): 2 ranks; the coupling converges to its
    # interface tolerance, and the partition changes the MPM's sums at
    # round-off, so the runs agree to the coupling tolerance: the test-mode
    # output without the load balancing lines to 1e-5 relative or absolute
    # (numdiff), the same steps and rejections, the coupling iterations
    # per step within 5 %
    printf 'subsection Load balancing\n  set repartition every steps = 10\n  set imbalance threshold = 1.1\nend\n' \
      >> balanced.prm
    run plain 2
    run balanced 2
    grep "load balancing" balanced/log.txt ||
      fail "the coupled run with load balancing did not repartition"
    grep -q "load balancing at step 0: repartitioned" balanced/log.txt ||
      fail "no repartition at the start"
    grep -v "load balancing at" balanced/log.txt | grep -v "^Done:" \
      > balanced/summary.txt
    grep -v "^Done:" plain/log.txt > plain/summary.txt
    diff plain/summary.txt balanced/summary.txt
    numdiff -q -r 1e-5 -a 1e-5 plain/summary.txt balanced/summary.txt ||
      fail "the coupled runs with and without load balancing differ"
    a=$(grep "^Done:" plain/log.txt); b=$(grep "^Done:" balanced/log.txt)
    echo "without: $a"; echo "with:    $b"
    [ "${a%%),*}" = "${b%%),*}" ] || fail "other steps or rejections"
    python3 -c "import re, sys; f = lambda s: float(re.search(r'([0-9.]+) coupling iterations', s).group(1)); sys.exit(0 if abs(f('$a') - f('$b')) <= 0.05 * f('$a') else 1)" ||
      fail "the coupling iterations per step differ by more than 5 %"
    echo "coupled, 2 ranks: same output within 1e-5, iterations within 5 %"
    ;;
  coupled1)
    # the coupled problem on 1 rank, repartitioned every 10 steps: the
    # output (without the load balancing lines) and coupling.csv bitwise
    # those of the run without
    printf 'subsection Load balancing\n  set repartition every steps = 10\nend\n' \
      >> balanced.prm
    run plain 1
    run balanced 1
    grep -q "load balancing at step 10: repartitioned" balanced/log.txt ||
      fail "the coupled run with load balancing did not repartition"
    diff plain/log.txt <(grep -v "load balancing at" balanced/log.txt) ||
      fail "the outputs differ"
    cmp plain/output-block_on_string_rest/coupling.csv \
        balanced/output-block_on_string_rest/coupling.csv ||
      fail "coupling.csv differs"
    echo "coupled, 1 rank: output and coupling.csv bitwise identical"
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo PASS
