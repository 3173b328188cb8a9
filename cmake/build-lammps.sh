#!/usr/bin/env bash
# Build the pinned LAMMPS (4 Feb 2025) with the packages the toolkit needs, once, into a cache
# directory keyed by version and options. Prints two lines on stdout:
#   LAMMPS_SOURCE_DIR=<source tree>   LAMMPS_EXECUTABLE=<lmp>
# Usage: build-lammps.sh [--asan | --fetch-only]      (env: TBAGS_CACHE, LAMMPS_SOURCE_DIR to build a user's tree)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cache=${TBAGS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tbags}
jobs=${TBAGS_JOBS:-$(nproc)}
san=""
[ "${1:-}" = "--asan" ] && san="-fsanitize=address,undefined -fno-omit-frame-pointer"
fetch_only=0
[ "${1:-}" = "--fetch-only" ] && fetch_only=1    # download and verify the source, build nothing

# Only what the decks, tests and benchmark use (OPENMP's 232 files, EXTRA-FIX and RIGID are not:
# 7.2 instead of 9 min on 2 cores, before the precompiled header).
packages="GRANULAR MOLECULE BPM PLUGIN"
# the precompiled-header include, by content in the cache: the build key (and the cached build)
# does not depend on where the repository is cloned
mkdir -p "$cache"
pch="$cache/lammps-pch-$(sha256sum <"$here/lammps-pch.cmake" | cut -c1-10).cmake"
[ -f "$pch" ] || cp "$here/lammps-pch.cmake" "$pch"
opts=(-D BUILD_SHARED_LIBS=on -D BUILD_MPI=on -D BUILD_OMP=off -D LAMMPS_EXCEPTIONS=on
      -D CMAKE_BUILD_TYPE=Release -D CMAKE_CXX_COMPILER_LAUNCHER=ccache -D CMAKE_C_COMPILER_LAUNCHER=ccache
      -D "CMAKE_PROJECT_INCLUDE=$pch")   # precompiled header: a third less compiling
for p in $packages; do opts+=(-D PKG_$p=on); done
# No VTK package: the ParaView files come from the dumps (postprocess/tbagspost/vtkout.py), and
# LAMMPS's VTK needs libvtk9-dev and Qt5's dev packages, a minute of the fresh machine's install
# before the build can start.
[ -n "$san" ] && opts+=(-D "CMAKE_CXX_FLAGS=$san" -D "CMAKE_EXE_LINKER_FLAGS=$san" -D "CMAKE_SHARED_LINKER_FLAGS=$san")

if [ -n "${LAMMPS_SOURCE_DIR:-}" ]; then
  src=$(cd "$LAMMPS_SOURCE_DIR" && pwd)
  version=$(sed -n 's/#define LAMMPS_VERSION "\(.*\)"/\1/p' "$src/src/version.h" | tr -d ' ')
else
  src=$("$here/fetch-lammps.sh" "$cache/src")
  version=4Feb2025
fi
[ "$fetch_only" = 1 ] && exit 0
key=$(printf '%s|%s|%s|%s' "$src" "${opts[*]}" "$(c++ --version | head -1)" "$(mpicxx --showme:version 2>/dev/null || true)" | sha256sum | cut -c1-10)
build="$cache/lammps-$version-${san:+asan-}$key"
lmp="$build/lmp"
# one build of a tree at a time (a configure and ./tbags setup may ask together): wait for it
exec 9>"$build.lock"
flock 9
if [ ! -x "$lmp" ] || [ ! -f "$build/.tbags-complete" ]; then
  echo "build-lammps: building LAMMPS $version with $packages into $build (about 7 min on 2 cores) ..." >&2
  export CCACHE_DIR=${CCACHE_DIR:-$cache/ccache}
  export CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
  log="$build.log"
  mkdir -p "$build"
  if ! { cmake -S "$src/cmake" -B "$build" "${opts[@]}" && cmake --build "$build" -j "$jobs"; } >"$log" 2>&1; then
    tail -30 "$log" >&2
    echo "build-lammps: LAMMPS build failed; full log in $log" >&2
    exit 1
  fi
  touch "$build/.tbags-complete"
fi
echo "LAMMPS_SOURCE_DIR=$src"
echo "LAMMPS_EXECUTABLE=$lmp"
