#!/usr/bin/env bash
# Builds Manifold natively from its public source, for bench/boolean_compare.sh's
# native peer (issue #36). A benchmark peer only: nothing of it enters the repo
# or CI. Its source is not a Debian or npm package; give the path of a git
# directory of github.com/elalish/manifold (a clone, or a mirror).
#   bench/peers/build_manifold.sh GIT_DIR [TAG] [PREFIX]
# TAG: v3.5.2 by default (npm's manifold-3d is 3.5.x). PREFIX: where it is
# installed, /tmp/manifold-prefix by default; then configure polyvol's bench
# with -DPOLYVOL_MANIFOLD_PEER=ON -Dmanifold_DIR=PREFIX/lib/cmake/manifold.
# Needs only Debian's cmake, g++ and libtbb-dev (its parallel backend);
# CrossSection (Clipper2, not in Debian 12) and every download are off.
set -euo pipefail
GIT_DIR=$1
TAG=${2:-v3.5.2}
PREFIX=${3:-/tmp/manifold-prefix}
SRC=/tmp/manifold-src-$TAG
BUILD=/tmp/manifold-build-$TAG
mkdir -p "$SRC"
# Only what the library's build reads (the samples' models may be absent from a mirror).
git --git-dir="$GIT_DIR" archive "$TAG" CMakeLists.txt cmake include src bindings LICENSE | tar -x -C "$SRC"
cmake -S "$SRC" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DMANIFOLD_PAR=ON -DMANIFOLD_CROSS_SECTION=OFF \
  -DMANIFOLD_CBIND=OFF -DMANIFOLD_PYBIND=OFF -DMANIFOLD_JSBIND=OFF -DMANIFOLD_TEST=OFF \
  -DMANIFOLD_DOWNLOADS=OFF -DBUILD_SHARED_LIBS=OFF -DCMAKE_INSTALL_PREFIX="$PREFIX" >/dev/null
cmake --build "$BUILD" -j2
cmake --install "$BUILD" >/dev/null
echo "installed: $PREFIX/lib/cmake/manifold"
