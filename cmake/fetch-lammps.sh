#!/usr/bin/env bash
# Fetch the pinned LAMMPS source (Debian source package lammps 20250204+dfsg.1-2, trixie) into
# DEST and verify its sha256 (fetch-debian-source.sh; LAMMPS_TARBALL: a copy at hand instead).
# Usage: fetch-lammps.sh DEST_DIR      (prints the unpacked source dir on stdout)
set -euo pipefail
dest=${1:?usage: fetch-lammps.sh DEST_DIR}
exec bash "$(dirname "$0")/fetch-debian-source.sh" lammps "lammps=20250204+dfsg.1-2" trixie \
  lammps_20250204+dfsg.1.orig.tar.xz 3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7 \
  lammps-4Feb2025 src/version.h "$dest" LAMMPS_TARBALL
