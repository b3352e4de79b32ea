#!/usr/bin/env bash
# The 2D flagship analogue (prm/flexible_barrier_2d.prm, ~30 s): build, run,
# draw. Same as bash contrib/run_flexible_barrier.sh 2d.
#   usage: bash contrib/run_flexible_barrier_2d.sh
exec bash "$(dirname "${BASH_SOURCE[0]}")/run_flexible_barrier.sh" 2d
