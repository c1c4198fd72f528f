#!/usr/bin/env bash
# Installs the Debian 12 packages Kiln builds with, only those that are missing.
set -euo pipefail
pkgs=(build-essential cmake libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev libpng-dev
      libtinyobjloader-dev zlib1g-dev libxxhash-dev libgtest-dev libbenchmark-dev libpugixml-dev nlohmann-json3-dev
      libcli11-dev)
# Participating media read .nvdb grids with NanoVDB (header-only).
pkgs+=(libnanovdb-dev)
# libFuzzer (the Fuzz.LoadersRunClean test, .ci/fuzz.sh) needs clang and its runtime.
pkgs+=(clang libclang-rt-14-dev)
# The folder-cycle check (Layout.NoFolderCycles, tools/folder_cycles.py) and tools/ scripts.
pkgs+=(python3)
# The Slurm job-array test (Slurm.JobArrayRendersOneFrame, tests/slurm/) starts its own cluster.
pkgs+=(slurm-wlm munge)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  echo "installing: ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
