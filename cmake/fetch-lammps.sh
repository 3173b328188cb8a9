#!/usr/bin/env bash
# Fetch the pinned LAMMPS source (Debian source package lammps 20250204+dfsg.1-2, trixie)
# into DEST and verify its sha256. The deb-src entry is derived from this machine's own apt
# sources: no host name is written anywhere in the repository.
# Usage: fetch-lammps.sh DEST_DIR      (prints the unpacked source dir on stdout)
set -euo pipefail
dest=${1:?usage: fetch-lammps.sh DEST_DIR}
tarball=lammps_20250204+dfsg.1.orig.tar.xz
sha=3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7
srcdir="$dest/lammps-4Feb2025"   # the tarball's top directory
mkdir -p "$dest"
if [ -f "$srcdir/src/version.h" ]; then echo "$srcdir"; exit 0; fi

if [ -n "${LAMMPS_TARBALL:-}" ]; then cp "$LAMMPS_TARBALL" "$dest/$tarball"; fi
if [ ! -f "$dest/$tarball" ]; then
  # The first Debian archive URI of this machine's apt sources (deb822 or one-line format).
  uri=$( (cat /etc/apt/sources.list.d/*.sources 2>/dev/null | awk '/^URIs:/{print $2}';
          cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null |
          awk '$1=="deb"{for(i=2;i<=NF;i++) if($i ~ /^[a-z]+:\/\//){print $i; break}}') |
        grep -v -- '-security' | grep -m1 '/debian/\?$' || true)
  if [ -z "$uri" ]; then
    echo "fetch-lammps: no Debian archive found in /etc/apt/sources*; set LAMMPS_TARBALL=/path/to/$tarball or -DLAMMPS_SOURCE_DIR=..." >&2
    exit 1
  fi
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  mkdir -p "$work/lists/partial" "$work/cache/archives/partial" "$work/etc/preferences.d" "$work/etc/sources.list.d"
  printf 'deb-src %s trixie main\n' "$uri" > "$work/etc/sources.list"
  aptopt=(-o Dir::Etc::sourcelist="$work/etc/sources.list" -o Dir::Etc::sourceparts="$work/etc/sources.list.d"
          -o Dir::State::Lists="$work/lists" -o Dir::Cache="$work/cache"
          -o Dir::Etc::preferencesparts="$work/etc/preferences.d" -o APT::Sandbox::User=root)
  echo "fetch-lammps: downloading the LAMMPS source package (trixie) ..." >&2
  apt-get "${aptopt[@]}" -qq update >&2 || { echo "fetch-lammps: apt-get update of the trixie deb-src entry failed" >&2; exit 1; }
  # apt exits non-zero and prints "404 Not Found" because the .dsc is missing from the archive while
  # the tarball arrives: expected, so apt's output goes to a log and the sha256 below decides
  log="$dest/fetch-lammps.apt.log"
  (cd "$work" && apt-get "${aptopt[@]}" -qq source --download-only "lammps=20250204+dfsg.1-2" >"$log" 2>&1) || true
  [ -f "$work/$tarball" ] || { cat "$log" >&2; echo "fetch-lammps: $tarball did not arrive (apt's output above, in $log); set LAMMPS_TARBALL=/path/to/it or use -DLAMMPS_SOURCE_DIR=" >&2; exit 1; }
  mv "$work/$tarball" "$dest/$tarball"
  fetched=1
fi
got=$(sha256sum "$dest/$tarball" | cut -d' ' -f1)
if [ "$got" != "$sha" ]; then
  rm -f "$dest/$tarball"
  echo "fetch-lammps: sha256 mismatch for $tarball (got $got, want $sha); refusing to build. Delete the cache and retry, or use -DLAMMPS_SOURCE_DIR=/your/lammps" >&2
  exit 1
fi
if [ -n "${fetched:-}" ]; then
  echo "fetch-lammps: $tarball fetched and verified (sha256 ${sha:0:12}...; the source package's .dsc is missing from the archive, as expected: apt's messages are in $dest/fetch-lammps.apt.log)" >&2
fi
tar -C "$dest" -xJf "$dest/$tarball"
[ -f "$srcdir/src/version.h" ] || { echo "fetch-lammps: $tarball did not unpack to $srcdir" >&2; exit 1; }
echo "$srcdir"
