#!/bin/bash
# Run a Talus variant of a collapse input and print its deposit and volume numbers.
# Usage (from the repository root):
#   contrib/granular/kratos_check/talus_variant.sh BASE.prm NAME 'sed-expr' ...
# writes contrib/granular/kratos_check/lube/NAME.prm (BASE with the sed expressions
# applied and output directory output/lube_check/NAME), runs it with
# $TALUS_BIN (default build/talus; set TALUS_LIB to a directory holding
# libtalus-lib.so to use a copied build), log /tmp/lube_check_NAME.log (or $LOGDIR),
# and prints (L-L0)/L0, H/L0, final and largest V/V0 (sum of V0 det F) and the
# final kinetic energy.
base=$1; name=$2; shift 2
d=contrib/granular/kratos_check/lube
logdir=${LOGDIR:-/tmp}
log=$logdir/lube_check_$name.log
args=()
for e in "$@"; do args+=(-e "$e"); done
sed "${args[@]}" -e "s|set output directory = .*|set output directory = output/lube_check/$name|" "$base" > $d/$name.prm
start=$(date +%s)
if [ -n "$TALUS_LIB" ]; then export LD_LIBRARY_PATH=$TALUS_LIB; fi
${TALUS_BIN:-build/talus} $d/$name.prm > "$log" 2>&1
echo "rc=$? wall=$(( $(date +%s)-start ))" >> "$log"
python3 - output/lube_check/$name <<'PY'
import csv, sys
d = sys.argv[1]
r = list(csv.DictReader(open(d + '/time_series.csv')))
s = list(csv.DictReader(open(d + '/deposit_summary.csv')))[0]
V0 = float(r[0]['volume'])
print(d, 'steps', len(r) - 1, '(L-L0)/L0 %.3f H/L0 %.3f V/V0 %.4f maxV/V0 %.4f KE %.3g' % (
    float(s['runout_normalised']), float(s['height_normalised']), float(r[-1]['volume']) / V0,
    max(float(x['volume']) for x in r) / V0, float(r[-1]['kinetic_energy'])))
PY
tail -1 "$log"
