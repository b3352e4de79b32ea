#!/usr/bin/env bash
# check_hdf5_output.sh TALUS INPUT NRANKS
# Runs INPUT (HDF5 output) on NRANKS MPI ranks with a 120 s limit (deal.II
# 9.4's parallel HDF5 writer hangs when a rank of its communicator has no
# data) and checks the XDMF indices it wrote: every output time of
# particles.xdmf and grid.xdmf names an .h5 file that exists, and every
# particle entry has the number of points of the input's "# POINTS:" line.
set -u
talus=$1; input=$2; ranks=$3
points=$(sed -n 's/^# POINTS: *//p' "$input" | head -n 1)
dir=$(sed -n 's/^ *set output directory *= *//p' "$input" | head -n 1)
rm -rf "$dir"
out=$(timeout 120 mpirun -np "$ranks" "$talus" "$input" 2>&1); code=$?
echo "$out" | grep -E "^Talus|material points:|mass:|lost mass"
if [ "$code" -ne 0 ]; then echo "FAIL: exit code $code (124: hang)"; exit 1; fi
fail=0
for name in particles grid; do
  index=$dir/$name.xdmf
  [ -f "$index" ] || { echo "FAIL: $index missing"; exit 1; }
  n=$(grep -c "<Time " "$index")
  echo "$name.xdmf: $n output times"
  for h5 in $(sed -n "s/^ *\($name-[0-9]*\.h5\):\/nodes.*/\1/p" "$index"); do
    [ -s "$dir/$h5" ] || { echo "FAIL: $dir/$h5 missing or empty"; fail=1; }
  done
done
sizes=$(sed -n 's/.*<Topology TopologyType="Polyvertex" NumberOfElements="\([0-9]*\)".*/\1/p' \
  "$dir/particles.xdmf" | sort -u)
echo "points per particle entry: $sizes (expected $points)"
[ "$sizes" = "$points" ] || fail=1
[ $fail -eq 0 ] && echo PASS || { echo FAIL; exit 1; }
