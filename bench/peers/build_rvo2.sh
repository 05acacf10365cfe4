#!/usr/bin/env bash
# Builds RVO2 (github.com/snape/RVO2, crowd avoidance) from its public source, with OpenMP, and
# our timing driver (bench/peers/rvo2_driver.cpp) against it, in a scratch directory outside the
# repository (bench/peers/README.md).
#
#   bench/peers/build_rvo2.sh [SOURCE [REF]]
#
# SOURCE is a git URL or a local clone (work tree or bare) of RVO2 (default: its public
# repository, https://github.com/snape/RVO2.git), REF a revision in it (default: HEAD). Output:
# $PEERS_DIR/rvo2/rvo2_driver (PEERS_DIR defaults to /tmp/floornav-peers). Dependencies from
# Debian: git, g++ (OpenMP is GCC's libgomp).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/peer_source.sh"
peers=${PEERS_DIR:-/tmp/floornav-peers}
dir=$peers/rvo2
rm -rf "$dir/build" "$dir/install"
peer_source "${1:-https://github.com/snape/RVO2.git}" "${2:-HEAD}" "$dir"
# RVO2's own CMake wants CMake >= 3.26 (Debian 12 has 3.25), so its five sources are compiled
# here with the flags of its Release build (-O3 -DNDEBUG) and OpenMP for its doStep loop, without
# its hardening flags (stack protector, _FORTIFY_SOURCE), so that it runs as fast as it can.
mkdir -p "$dir/build" "$dir/install/include/RVO"
cp "$dir"/src/src/*.h "$dir/install/include/RVO/"
objs=()
for f in "$dir"/src/src/*.cc; do
  o="$dir/build/$(basename "$f" .cc).o"
  g++ -O3 -DNDEBUG -fopenmp -fPIC -c "$f" -o "$o"
  objs+=("$o")
done
ar rcs "$dir/build/libRVO.a" "${objs[@]}"
g++ -O3 -DNDEBUG -fopenmp -I"$dir/install/include" "$here/rvo2_driver.cpp" "$dir/build/libRVO.a" \
  -o "$dir/rvo2_driver"
echo "RVO2 $(cat "$dir/commit") and rvo2_driver built in $dir"
