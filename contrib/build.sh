#!/usr/bin/env bash
# Configure and build the talus executable.
#   usage: bash contrib/build.sh [Release|Debug] [builddir] [cmake options...]
# Defaults: Release in <repo>/build, Debug in <repo>/build-debug.
# A relative builddir is taken relative to the repository top.
# A build from scratch is a unity build (CMAKE_UNITY_BUILD, 8 sources per
# unit: about half the compile time on 2 cores, doc/testing.md); for
# incremental work configure with cmake directly, without it. Further
# options go to cmake (e.g. -DTALUS_DEBUG_INFO=OFF).
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_type=${1:-Release}
case "$build_type" in
  Release) default_dir=build ;;
  Debug)   default_dir=build-debug ;;
  *) echo "build.sh: build type must be Release or Debug, not '$build_type'" >&2
     exit 2 ;;
esac
build_dir=${2:-$default_dir}
shift $(( $# < 2 ? $# : 2 ))
[[ "$build_dir" = /* ]] || build_dir="$top/$build_dir"

bash "$top/contrib/setup.sh"

# ccache caches sources compiled with a precompiled header only with these
# (CMakeLists.txt, TALUS_PRECOMPILED_HEADERS).
export CCACHE_SLOPPINESS=${CCACHE_SLOPPINESS:-pch_defines,time_macros}

jobs=$(nproc 2>/dev/null || echo 2)
echo "build.sh: $build_type build of talus in $build_dir with $jobs jobs"
cmake -S "$top" -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" \
  -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8 "$@"
make -C "$build_dir" -j"$jobs" talus
echo "build.sh: built $build_dir/talus"
