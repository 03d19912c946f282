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
  python3 python3-h5py python3-numpy python3-matplotlib python3-scipy python3-meshio
  pybind11-dev python3-dev python3-pytest
)
sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all Debian packages present"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
echo "setup: built build/bin/cdem"

# The Python module (docs/python.md): build/python/cdem, built for the Debian interpreter, is
# copied into the site directory of /usr/bin/python3 and of the `python3` first on PATH when that
# is another interpreter of the same ABI (pyenv, say), so that `import cdem` works in a fresh
# shell with no PYTHONPATH.
suffix=$(ls build/python/cdem/_cdem*.so | sed 's/.*_cdem//')
installed=""
for py in /usr/bin/python3 "$(command -v python3 || true)"; do
  [ -x "$py" ] || continue
  site=$("$py" -c "import sysconfig; print(sysconfig.get_path('platlib'))")
  case " $installed " in *" $site "*) continue ;; esac
  [ "$("$py" -c "import sysconfig; print(sysconfig.get_config_var('EXT_SUFFIX'))")" = "$suffix" ] ||
    { echo "setup: $py is not the ABI of build/python (${suffix}); cdem not installed for it"; continue; }
  $sudo mkdir -p "$site"
  $sudo rm -rf "$site/cdem.tmp$$"
  $sudo cp -a build/python/cdem "$site/cdem.tmp$$"
  $sudo rm -rf "$site/cdem"
  $sudo mv "$site/cdem.tmp$$" "$site/cdem"
  installed="$installed $site"
  echo "setup: installed the Python module cdem in $site"
done
