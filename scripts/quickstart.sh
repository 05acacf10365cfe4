#!/usr/bin/env bash
# Installs what is missing (Debian packages), builds floornav in ./build, runs the factory demo.
# Usage: scripts/quickstart.sh [extra cmake options]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libyaml-cpp-dev libcli11-dev
  nlohmann-json3-dev libfmt-dev libtinyxml2-dev libpng-dev libgtest-dev libgmock-dev
  libbenchmark-dev libssl-dev libompl-dev python3
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-pil)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "Installing: ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build
./build/floornav demo
if [ -d build/python/floornav ]; then
  echo "Python: PYTHONPATH=$PWD/build/python /usr/bin/python3 -c 'import floornav'"
fi
