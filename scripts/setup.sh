#!/usr/bin/env bash
# Installs the Debian 12 packages cdem needs (skipping those already installed), then configures
# and builds cdem in ./build (Release). Run as root on a fresh machine, or with sudo.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config git
  libcgal-dev libgmp-dev libmpfr-dev libeigen3-dev libboost-dev
  libbox2d-dev libhdf5-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  libcairo2-dev libgtest-dev libgmock-dev libbenchmark-dev libpagmo-dev
  libopenmpi-dev openmpi-bin
  python3 python3-h5py python3-numpy python3-matplotlib
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all Debian packages present"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
echo "setup: built build/bin/cdem"
