#!/usr/bin/env bash
# Installs what is missing (Debian packages), builds floornav in ./build, runs the factory demo.
# Usage: scripts/quickstart.sh [extra cmake options]
set -euo pipefail
cd "$(dirname "$0")/.."

apt_install() {  # Debian packages, as root or with sudo
  local sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "$@"
}

packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libyaml-cpp-dev libcli11-dev
  nlohmann-json3-dev libfmt-dev libtinyxml2-dev libpng-dev libzstd-dev libdeflate-dev libgtest-dev libgmock-dev
  libbenchmark-dev libssl-dev libompl-dev python3
  pybind11-dev python3-dev python3-numpy python3-pytest python3-hypothesis python3-matplotlib python3-pil
  python3-venv python3-setuptools)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "Installing: ${missing[*]}"
  apt_install "${missing[@]}"
fi

# The test suite's own tools, so that the README's test command skips nothing: Debian's chromium
# (the replay in a real browser), Node.js and npm (Debian's only when the commands are missing:
# a vendor nodejs bundles its own npm), and the npm packages pinned by the lock files of
# tests/browser (puppeteer-core) and tests/mcap (the reference MCAP and ROS 2 readers), Dask and
# PyTorch.
# FLOORNAV_NO_TEST_TOOLS=1 leaves them out (the tests that need them are then skipped).
if [ "${FLOORNAV_NO_TEST_TOOLS:-0}" != 1 ]; then
  tools=()
  command -v chromium >/dev/null || tools+=(chromium)
  command -v node >/dev/null || tools+=(nodejs)
  command -v npm >/dev/null || tools+=(npm)
  # Dask's scheduler, for the test of docs/PYTHON.md's sharding pattern.
  dpkg-query -W -f='${Status}' python3-distributed 2>/dev/null | grep -q "install ok installed" ||
    tools+=(python3-distributed)
  # PyTorch, for the smoke test of examples/python/05_train_ppo.py (a few PPO iterations).
  dpkg-query -W -f='${Status}' python3-torch 2>/dev/null | grep -q "install ok installed" ||
    tools+=(python3-torch)
  if ((${#tools[@]})); then
    echo "Installing the test tools: ${tools[*]}"
    apt_install "${tools[@]}"
  fi
  for d in tests/browser tests/mcap; do
    [ -d "$d/node_modules" ] || (cd "$d" && npm ci --no-audit --no-fund --silent)
  done
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build
./build/floornav demo
if [ -d build/python/floornav ]; then
  echo "Python: PYTHONPATH=$PWD/build/python /usr/bin/python3 -c 'import floornav'"
fi
