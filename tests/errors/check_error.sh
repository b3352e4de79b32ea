#!/usr/bin/env bash
# check_error.sh TALUS INPUT [EXPECTED] [NRANKS]
# Passes if talus exits with a non-zero code (not a signal: no crash) and its
# output contains EXPECTED (default: the "# EXPECT:" line of INPUT).
set -u
talus=$1; input=$2; expected=${3:-}; ranks=${4:-1}
if [ -z "$expected" ]; then
  expected=$(sed -n 's/^# EXPECT: *//p' "$input" | head -n 1)
fi
if [ "$ranks" -gt 1 ]; then
  out=$(timeout 120 mpirun -np "$ranks" "$talus" "$input" 2>&1); code=$?
else
  out=$(timeout 120 "$talus" "$input" 2>&1); code=$?
fi
echo "$out"
if [ "$code" -eq 0 ]; then echo "FAIL: talus exited with 0"; exit 1; fi
if [ "$code" -ge 124 ]; then echo "FAIL: exit code $code (crash, signal or timeout)"; exit 1; fi
if ! grep -qF -- "$expected" <<<"$out"; then
  echo "FAIL: the message does not contain: $expected"; exit 1
fi
echo "PASS: exit code $code with the expected message"
