#!/usr/bin/env bash
# Configure and build the talus executable.
#   usage: bash contrib/build.sh [Release|Debug] [builddir]
# Defaults: Release in <repo>/build, Debug in <repo>/build-debug.
# A relative builddir is taken relative to the repository top.
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
[[ "$build_dir" = /* ]] || build_dir="$top/$build_dir"

bash "$top/contrib/setup.sh"

jobs=$(nproc 2>/dev/null || echo 2)
echo "build.sh: $build_type build of talus in $build_dir with $jobs jobs"
cmake -S "$top" -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type"
make -C "$build_dir" -j"$jobs" talus
echo "build.sh: built $build_dir/talus"
