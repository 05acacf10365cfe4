#!/usr/bin/env bash
# Builds Stage (github.com/rtv/Stage, the robot simulator) from its public source into a
# scratch directory outside the repository, for the peer comparison (bench/peers/README.md).
#
#   bench/peers/build_stage.sh [STAGE_GIT_DIR]
#
# STAGE_GIT_DIR is a clone or bare mirror of rtv/Stage (default: the mirror the session's
# `fetch github:rtv/Stage` made, /work/.mirror/rtv+Stage/repo). Output: $PEERS_DIR/stage/install
# (PEERS_DIR defaults to /tmp/floornav-peers), with bin/stage, lib/libstage and the wander
# controller, and $PEERS_DIR/stage/stage_driver (stage_driver.cpp, our timing loop). Build dependencies, all from Debian:
#   apt-get install cmake g++ libfltk1.3-dev fluid libltdl-dev libpng-dev libjpeg-dev libgl-dev libglu1-mesa-dev
# (fluid: Debian 12's FLTK CMake config names /usr/bin/fluid, and CMake stops without it.)
set -euo pipefail
src_git=${1:-/work/.mirror/rtv+Stage/repo}
peers=${PEERS_DIR:-/tmp/floornav-peers}
dir=$peers/stage
mkdir -p "$dir"
rm -rf "$dir/src" "$dir/build"
mkdir -p "$dir/src"
git --git-dir="$src_git" archive HEAD | tar -x -C "$dir/src"
git --git-dir="$src_git" rev-parse HEAD >"$dir/commit"
# Stage's CMakeLists predate CMake 3: the minimum-version policy shim lets CMake 3.25+ build
# it unchanged. Release is Stage's own -O2 -DNDEBUG; no Player plugin.
cmake -S "$dir/src" -B "$dir/build" -DCMAKE_BUILD_TYPE=release \
  -DCMAKE_POLICY_VERSION_MINIMUM=3.5 -DBUILD_PLAYER_PLUGIN=OFF -DCPACK_CFG=OFF \
  -DCMAKE_INSTALL_PREFIX="$dir/install" >"$dir/cmake.log"
nice cmake --build "$dir/build" -j "${JOBS:-2}" >"$dir/build.log"
cmake --install "$dir/build" >"$dir/install.log"
# Our timing driver (bench/peers/stage_driver.cpp), linked against the libstage just built.
here=$(cd "$(dirname "$0")" && pwd)
g++ -O2 -DNDEBUG -I"$dir/install/include" "$here/stage_driver.cpp" -o "$dir/stage_driver" \
  -L"$dir/install/lib" -Wl,-rpath,"$dir/install/lib" -lstage
echo "Stage $(cat "$dir/commit") installed in $dir/install; driver $dir/stage_driver"
