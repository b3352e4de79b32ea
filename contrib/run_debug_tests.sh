#!/usr/bin/env bash
# Debug build (deal.II's debug library, assertions on; <repo>/build-debug)
# and a fast subset of the tests, for CI: the .cc unit tests, the bad-input
# tests (errors/), doc/parameters_up_to_date and one .prm test per module. Assertions
# that the Release suite cannot see (index ranges, vector sizes, deal.II
# preconditions) abort these runs.
#   usage: bash contrib/run_debug_tests.sh
# Exit status is non-zero when the build or any test of the subset fails.
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
SECONDS=0

# Without debug information (-g0): the assertions are what CI needs, and
# the objects compile faster and link in a fraction of the time.
bash "$top/contrib/build.sh" Debug build-debug -DTALUS_DEBUG_INFO=OFF
build_time=$SECONDS
echo "run_debug_tests.sh: Debug build done after ${build_time} s"

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1

# The subset: every .cc test (materials/, solver/, coupling/, structure/elements,
# structure/structure_api, boundaries/external_displacement), every errors/
# test on one rank, doc/parameters_up_to_date, and one .prm test each of
# mpm/, boundaries/, structure/ and coupled/ (seconds in Debug; 20 s for
# the coupled one; doc/testing.md).
# doc/inputs_parse only parses (71 s in Debug): the Release suite runs it.
subset='^(materials/|solver/|coupling/|structure/elements\.|structure/structure_api\.'
subset+='|boundaries/external_displacement\.|errors/|doc/parameters_up_to_date'
subset+='|mpm/incline_slide_mu01\.debug$|boundaries/incline_rotated_30_mu01\.debug$'
subset+='|structure/von_mises_truss\.debug$|coupled/block_on_string_rest\.debug$)'

cd "$top/build-debug"
# two per core, as contrib/run_tests.sh
jobs=$(( 2 * $(nproc 2>/dev/null || echo 2) ))
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
ctest -j"$jobs" --output-on-failure -R "$subset" -E 'mpirun=|_slow' 2>&1 |
  tee "$log" || status=1

awk '/tests passed, [0-9]+ tests? failed out of/ { f = $4; n = $NF }
     END { printf "run_debug_tests.sh: %d tests in %d s (build %d s)\n",
                  n, '"$SECONDS"', '"$build_time"';
           printf "debug: %d passed, %d failed\n", n - f, f }' "$log"
# a report only: it never decides the exit status
bash "$top/contrib/slowest_tests.sh" "$log" || true
exit "$status"
