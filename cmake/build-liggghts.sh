#!/usr/bin/env bash
# Build the pinned LIGGGHTS-PUBLIC 3.8.0 (MPI, GCC 12), once, into a cache directory keyed by
# version, our patch set and the compilers. Prints on stdout:
#   LIGGGHTS_SOURCE_DIR=<patched source tree>   LIGGGHTS_EXECUTABLE=<liggghts>
# Not yet called by ./tbags setup (issue 22): run it by hand, bash cmake/build-liggghts.sh.
# Usage: build-liggghts.sh [--fetch-only]   (env: TBAGS_CACHE, TBAGS_JOBS, LIGGGHTS_SOURCE_DIR to
# build a user's tree instead of the pinned one, LIGGGHTS_TARBALL: the tarball at hand)
#
# LIGGGHTS has no plugin loader and its CMake build generates its style headers inside src/
# (Make.sh style), so it builds in a copy of the source tree in the cache. The pinned tarball
# needs three changes to build with GCC 12 and without VTK (Debian's own patch set is missing
# from the archive; ours is in cmake/liggghts-patches/, one change per file):
#   01  utils.h int_to_string: a cast of an rvalue stream, which GCC 12 rejects
#   02  finish.cpp: a pointer ordered against 0, which GCC 12 rejects
#   and dump_mesh_vtk.{cpp,h} left out (they include VTK's headers unguarded; VTK is not used)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cache=${TBAGS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tbags}
jobs=${TBAGS_JOBS:-$(nproc)}
fetch_only=0
[ "${1:-}" = "--fetch-only" ] && fetch_only=1
mkdir -p "$cache"

if [ -n "${LIGGGHTS_SOURCE_DIR:-}" ]; then
  upstream=$(cd "$LIGGGHTS_SOURCE_DIR" && pwd)
  [ -f "$upstream/src/lammps.cpp" ] || { echo "build-liggghts: LIGGGHTS_SOURCE_DIR=$upstream has no src/lammps.cpp" >&2; exit 1; }
  version=user
else
  upstream=$("$here/fetch-liggghts.sh" "$cache/src")
  version=3.8.0
fi
[ "$fetch_only" = 1 ] && exit 0
patches=$(cat "$here"/liggghts-patches/*.patch | sha256sum | cut -c1-10)
key=$(printf '%s|%s|%s|%s' "$upstream" "$patches" "$(c++ --version | head -1)" \
      "$(mpicxx --showme:version 2>/dev/null || true)" | sha256sum | cut -c1-10)
build="$cache/liggghts-$version-$key"
exe="$build/build/liggghts"
if [ ! -x "$exe" ] || [ ! -f "$build/.tbags-complete" ]; then
  echo "build-liggghts: building LIGGGHTS $version into $build (about 6 min on 2 cores) ..." >&2
  export CCACHE_DIR=${CCACHE_DIR:-$cache/ccache}
  log="$build.log"
  rm -rf "$build"
  mkdir -p "$build"
  cp -r "$upstream/src" "$build/src"
  for p in "$here"/liggghts-patches/*.patch; do
    patch -s -p1 -d "$build" < "$p" || { echo "build-liggghts: $p does not apply to $upstream" >&2; exit 1; }
  done
  rm -f "$build/src/dump_mesh_vtk.cpp" "$build/src/dump_mesh_vtk.h"
  if ! { cmake -S "$build/src" -B "$build/build" -D CMAKE_BUILD_TYPE=Release \
           -D CMAKE_DISABLE_FIND_PACKAGE_VTK=ON -D CMAKE_CXX_COMPILER_LAUNCHER=ccache \
           -D CMAKE_C_COMPILER_LAUNCHER=ccache &&
         cmake --build "$build/build" --target liggghts_bin -j "$jobs"; } >"$log" 2>&1; then
    tail -30 "$log" >&2
    echo "build-liggghts: LIGGGHTS build failed; full log in $log" >&2
    exit 1
  fi
  touch "$build/.tbags-complete"
fi
echo "LIGGGHTS_SOURCE_DIR=$build/src"
echo "LIGGGHTS_EXECUTABLE=$exe"
