#!/usr/bin/env bash
# Fetch the pinned LIGGGHTS-PUBLIC 3.8.0 source (Debian source package liggghts, bookworm; its
# Debian patch tarball is missing from the archive, so the project keeps its own patches in
# cmake/liggghts-patches/) into DEST and verify its sha256 (fetch-debian-source.sh;
# LIGGGHTS_TARBALL: a copy at hand instead).
# Usage: fetch-liggghts.sh DEST_DIR      (prints the unpacked source dir on stdout)
set -euo pipefail
dest=${1:?usage: fetch-liggghts.sh DEST_DIR}
exec bash "$(dirname "$0")/fetch-debian-source.sh" liggghts liggghts bookworm \
  liggghts_3.8.0+repack1.orig.tar.xz c18721d9a870c5170f03b91e4f1ffe13335c66ed1f0ff2c64ebd3be91c37867a \
  LIGGGHTS-PUBLIC-3.8.0 src/lammps.cpp "$dest" LIGGGHTS_TARBALL
