#!/usr/bin/env bash
# Builds rpkCpp (Oscar Chavarro's C++ port of RenderPark, the peer of bench/rpkcpp/compare.sh)
# at a fixed commit, with Debian packages only:
#   apt-get install cmake g++ freeglut3-dev libglu1-mesa-dev
#   bash bench/rpkcpp/build.sh DIR [GIT_DIR]
# DIR receives the sources and DIR/build/rpk. GIT_DIR: a clone of
# https://github.com/OscarChavarro/rpkCpp that holds the commit below (default: cloned into
# DIR/git). Only CMakeLists.txt, src/ and etc/ are taken (the repository's doc/ is papers in
# PDF). One patch is applied, bench/rpkcpp/raw_radiance_vrml.patch: the Galerkin VRML export
# writes each element corner's radiance with 9 digits instead of its tone-mapped, clipped
# display colour with 3 (the solver is untouched). Nothing of rpkCpp is copied into relight.
# Running it again rebuilds what changed only.
set -euo pipefail
COMMIT=37e5ff4eede5fd7444916eb06f0379db137fefc9  # 2025-04-18, "Documentation: validating build ..."
dir=${1:?usage: build.sh DIR [GIT_DIR]}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
if [ ! -f "$dir/src/GALERKIN/GalerkinRadianceMethod.cpp" ]; then
  git_dir=${2:-}
  if [ -z "$git_dir" ]; then
    git clone --quiet --no-checkout https://github.com/OscarChavarro/rpkCpp "$dir/git"
    git_dir="$dir/git"
  fi
  git -C "$git_dir" archive "$COMMIT" CMakeLists.txt src etc LICENSE | tar -x -C "$dir"
fi
if ! grep -q "relight bench: full precision" "$dir/src/GALERKIN/GalerkinRadianceMethod.cpp"; then
  patch -d "$dir" -p1 < "$here/raw_radiance_vrml.patch"
fi
cmake -S "$dir" -B "$dir/build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$dir/build" -j"${JOBS:-2}"
echo "built $dir/build/rpk (rpkCpp $COMMIT, patched: $here/raw_radiance_vrml.patch)"
