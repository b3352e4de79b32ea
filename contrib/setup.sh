#!/usr/bin/env bash
# Install what Talus needs to build and test on Debian 12 (bookworm).
# Idempotent: does nothing (but say so) when every package is already there.
# Needs root only when something is missing.
#   usage: bash contrib/setup.sh
set -euo pipefail

packages=(libdeal.ii-dev numdiff openmpi-bin cmake python3-matplotlib g++ make
          clang-format)

if ! command -v dpkg-query >/dev/null 2>&1; then
  echo "setup.sh: dpkg-query not found: this script is for Debian 12 only." >&2
  exit 1
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Abbrev}' "$p" 2>/dev/null || true)
  [[ "$status" == ii* ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup.sh: all Debian packages present (${packages[*]}), nothing to install."
  exit 0
fi

echo "setup.sh: missing Debian packages: ${missing[*]}"
if [[ $(id -u) -ne 0 ]]; then
  echo "setup.sh: not root, cannot install them. Run as root:" >&2
  echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
  exit 1
fi

# Recommended packages are kept on purpose: the deal.II stack has only been
# exercised here with them (gmsh, libcoarrays-openmpi-dev, ...).
apt-get update
DEBIAN_FRONTEND=noninteractive apt-get install -y "${missing[@]}"
echo "setup.sh: installed ${missing[*]}"
