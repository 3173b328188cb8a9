#!/usr/bin/env bash
# Build the pinned LIGGGHTS-PUBLIC 3.8.0 (MPI, GCC 12) with our styles compiled in, once per
# version, patch set, our sources and compilers, into a cache directory. Prints on stdout:
#   LIGGGHTS_SOURCE_DIR=<patched source tree>   LIGGGHTS_EXECUTABLE=<liggghts>
#   LIGGGHTS_DEPENDS=<our files it is keyed on, ;-separated>
# Usage: build-liggghts.sh [--asan | --fetch-only]   (env: TBAGS_CACHE, TBAGS_JOBS,
# LIGGGHTS_SOURCE_DIR to build a user's tree instead of the pinned one, LIGGGHTS_TARBALL: the
# tarball at hand). --asan: with AddressSanitizer + UBSan (./tbags test --sanitize), its own tree.
#
# LIGGGHTS has no plugin loader and its CMake build generates its style headers inside src/
# (Make.sh style), so it builds in a copy of the source tree in the cache, with our files added:
#   src-liggghts/*          the LIGGGHTS adapters (contact model, ...) and the user whitelist of
#                           contact-model combinations that LIGGGHTS compiles optimised
#   src-plugin/law/*.h      the pure laws they call, as src/law/ (the same files LAMMPS uses)
#   src-plugin/yarn_table.* the yarn bond's table reader and bond_coeff parser (engine-neutral)
#   src-plugin/parse_words.h the word parsing both use
# Our laws are C++17, so LIGGGHTS builds with -std=c++17 (its own flags otherwise; all of its
# sources compile so). The pinned tarball gets five changes (Debian's own patch set is missing from
# the archive; ours is in cmake/liggghts-patches/):
#   01  utils.h int_to_string: a cast of an rvalue stream, which GCC 12 rejects
#   02  finish.cpp: a pointer ordered against 0, which GCC 12 rejects
#   03  error_special.h: the "tip of the day" added to one error in five pointed at a destroyed
#       string (it printed bytes of freed memory after the error message)
#   04  lattice.cpp: Domain's constructor makes a 'lattice none 1.0' before Force exists, and that
#       called a member of the unset Force pointer (the UBSan build stopped there at start-up)
#   and dump_mesh_vtk.{cpp,h} left out (they include VTK's headers unguarded; VTK is not used)
# A change of our sources makes a new directory; ccache (base dir = the tree) keeps that rebuild
# to the files that changed. The two newest trees are kept.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
cache=${TBAGS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tbags}
jobs=${TBAGS_JOBS:-$(nproc)}
fetch_only=0
san=""
[ "${1:-}" = "--fetch-only" ] && fetch_only=1
[ "${1:-}" = "--asan" ] && san="-fsanitize=address,undefined -fno-omit-frame-pointer"
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
flags="-O2 -funroll-loops -fstrict-aliasing -Wall -Wno-uninitialized -std=c++17 -Wno-literal-suffix -fPIC${san:+ $san}"
# the files of ours the build is keyed on (printed too: the configure re-runs when one changes)
inputs=("$root"/cmake/liggghts-patches/*.patch "$root"/src-liggghts/* "$root"/src-plugin/law/*.h
        "$root"/src-plugin/yarn_table.* "$root"/src-plugin/parse_words.h)
ours=$(cat "${inputs[@]}" | sha256sum | cut -c1-16)
key=$(printf '%s|%s|%s|%s|%s' "$upstream" "$ours" "$flags" "$(c++ --version | head -1)" \
      "$(mpicxx --showme:version 2>/dev/null || true)" | sha256sum | cut -c1-10)
build="$cache/liggghts-$version-${san:+asan-}$key"
exe="$build/build/liggghts"
# one build of a tree at a time (a configure and ./tbags setup may ask together): wait for it
exec 9>"$build.lock"
flock 9
if [ ! -x "$exe" ] || [ ! -f "$build/.tbags-complete" ]; then
  echo "build-liggghts: building LIGGGHTS $version with our styles into $build (6 min on 2 cores, less from ccache) ..." >&2
  export CCACHE_DIR=${CCACHE_DIR:-$cache/ccache} CCACHE_BASEDIR=$build
  log="$build.log"
  rm -rf "$build"
  mkdir -p "$build"
  cp -r "$upstream/src" "$build/src"
  for p in "$here"/liggghts-patches/*.patch; do
    patch -s -p1 -d "$build" < "$p" || { echo "build-liggghts: $p does not apply to $upstream" >&2; exit 1; }
  done
  rm -f "$build/src/dump_mesh_vtk.cpp" "$build/src/dump_mesh_vtk.h"
  cp "$root"/src-liggghts/* "$root"/src-plugin/yarn_table.* "$root"/src-plugin/parse_words.h "$build/src/"
  mkdir -p "$build/src/law"
  cp "$root"/src-plugin/law/*.h "$build/src/law/"
  if ! { cmake -S "$build/src" -B "$build/build" -D CMAKE_BUILD_TYPE=Release \
           -D "CMAKE_CXX_FLAGS=$flags" ${san:+-D "CMAKE_EXE_LINKER_FLAGS=$san"} \
           -D CMAKE_DISABLE_FIND_PACKAGE_VTK=ON -D CMAKE_CXX_COMPILER_LAUNCHER=ccache \
           -D CMAKE_C_COMPILER_LAUNCHER=ccache &&
         cmake --build "$build/build" --target liggghts_bin -j "$jobs"; } >"$log" 2>&1; then
    grep -E "error|Error" "$log" | head -20 >&2
    echo "build-liggghts: LIGGGHTS build failed; full log in $log" >&2
    exit 1
  fi
  touch "$build/.tbags-complete"
  # keep this tree and the one before it
  ls -1dt "$cache/liggghts-$version-${san:+asan-}"??????????/ 2>/dev/null | tail -n +3 | while read -r old; do
    rm -rf "$old" "${old%/}.log" "${old%/}.lock"
  done
fi
echo "LIGGGHTS_SOURCE_DIR=$build/src"
echo "LIGGGHTS_EXECUTABLE=$exe"
echo "LIGGGHTS_DEPENDS=$(IFS=';'; echo "${inputs[*]}")"
