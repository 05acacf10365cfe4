#!/usr/bin/env bash
# Builds Stage (github.com/rtv/Stage, the robot simulator) from its public source into a
# scratch directory outside the repository, for the peer comparison (bench/peers/README.md).
#
#   bench/peers/build_stage.sh [SOURCE [REF]]
#
# SOURCE is a git URL or a local clone (work tree or bare) of Stage (default: its public
# repository, https://github.com/rtv/Stage.git), REF a revision in it (default: HEAD). Output:
# $PEERS_DIR/stage/install (PEERS_DIR defaults to /tmp/floornav-peers), with bin/stage,
# lib/libstage and the wander controller, and $PEERS_DIR/stage/stage_driver (stage_driver.cpp,
# our timing loop). Build dependencies, all from Debian:
#   apt-get install git cmake g++ libfltk1.3-dev fluid libltdl-dev libpng-dev libjpeg-dev libgl-dev libglu1-mesa-dev
# (fluid: Debian 12's FLTK CMake config names /usr/bin/fluid, and CMake stops without it.)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/peer_source.sh"
peers=${PEERS_DIR:-/tmp/floornav-peers}
dir=$peers/stage
rm -rf "$dir/build"
peer_source "${1:-https://github.com/rtv/Stage.git}" "${2:-HEAD}" "$dir"
# Stage's CMakeLists predate CMake 3: the minimum-version policy shim lets CMake 3.25+ build
# it unchanged. Release is Stage's own -O2 -DNDEBUG; no Player plugin.
cmake -S "$dir/src" -B "$dir/build" -DCMAKE_BUILD_TYPE=release \
  -DCMAKE_POLICY_VERSION_MINIMUM=3.5 -DBUILD_PLAYER_PLUGIN=OFF -DCPACK_CFG=OFF \
  -DCMAKE_INSTALL_PREFIX="$dir/install" >"$dir/cmake.log"
nice cmake --build "$dir/build" -j "${JOBS:-2}" >"$dir/build.log"
cmake --install "$dir/build" >"$dir/install.log"
# Our timing driver (bench/peers/stage_driver.cpp), linked against the libstage just built.
g++ -O2 -DNDEBUG -I"$dir/install/include" "$here/stage_driver.cpp" -o "$dir/stage_driver" \
  -L"$dir/install/lib" -Wl,-rpath,"$dir/install/lib" -lstage
echo "Stage $(cat "$dir/commit") installed in $dir/install; driver $dir/stage_driver"
