#!/usr/bin/env bash
# Fetch one pinned upstream tarball of a Debian source package into DEST, verify its sha256 and
# unpack it. The deb-src entry is derived from this machine's own apt sources: no host name is
# written anywhere in the repository. A tarball already at hand can be given instead (TARBALL_ENV).
# Usage: fetch-debian-source.sh NAME PACKAGE=VERSION SUITE TARBALL SHA256 TOPDIR MARKER DEST TARBALL_ENV
#   NAME       what the messages call it (fetch-NAME: ...)
#   TOPDIR     the tarball's top directory; MARKER a file inside it that shows it unpacked
# Prints the unpacked source dir on stdout.
set -euo pipefail
name=$1 pkgver=$2 suite=$3 tarball=$4 sha=$5 top=$6 marker=$7 dest=$8 envvar=$9
srcdir="$dest/$top"
mkdir -p "$dest"
if [ -f "$srcdir/$marker" ]; then echo "$srcdir"; exit 0; fi

given=${!envvar:-}
if [ -n "$given" ]; then cp "$given" "$dest/$tarball"; fi
if [ ! -f "$dest/$tarball" ]; then
  # The first Debian archive URI of this machine's apt sources (deb822 or one-line format).
  uri=$( (cat /etc/apt/sources.list.d/*.sources 2>/dev/null | awk '/^URIs:/{print $2}';
          cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null |
          awk '$1=="deb"{for(i=2;i<=NF;i++) if($i ~ /^[a-z]+:\/\//){print $i; break}}') |
        grep -v -- '-security' | grep -m1 '/debian/\?$' || true)
  if [ -z "$uri" ]; then
    echo "fetch-$name: no Debian archive found in /etc/apt/sources*; set $envvar=/path/to/$tarball" >&2
    exit 1
  fi
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  mkdir -p "$work/lists/partial" "$work/cache/archives/partial" "$work/etc/preferences.d" "$work/etc/sources.list.d"
  printf 'deb-src %s %s main\n' "$uri" "$suite" > "$work/etc/sources.list"
  aptopt=(-o Dir::Etc::sourcelist="$work/etc/sources.list" -o Dir::Etc::sourceparts="$work/etc/sources.list.d"
          -o Dir::State::Lists="$work/lists" -o Dir::Cache="$work/cache"
          -o Dir::Etc::preferencesparts="$work/etc/preferences.d" -o APT::Sandbox::User=root)
  echo "fetch-$name: downloading the ${pkgver%%=*} source package ($suite) ..." >&2
  apt-get "${aptopt[@]}" -qq update >&2 || { echo "fetch-$name: apt-get update of the $suite deb-src entry failed" >&2; exit 1; }
  # apt may exit non-zero and print "404 Not Found" for a part of the source package missing from
  # the archive (the .dsc, a Debian patch tarball) while the upstream tarball arrives: its output
  # goes to a log and the sha256 below decides
  log="$dest/fetch-$name.apt.log"
  (cd "$work" && apt-get "${aptopt[@]}" -qq source --download-only "$pkgver" >"$log" 2>&1) || true
  [ -f "$work/$tarball" ] || { cat "$log" >&2; echo "fetch-$name: $tarball did not arrive (apt's output above, in $log); set $envvar=/path/to/it" >&2; exit 1; }
  mv "$work/$tarball" "$dest/$tarball"
  fetched=1
fi
got=$(sha256sum "$dest/$tarball" | cut -d' ' -f1)
if [ "$got" != "$sha" ]; then
  rm -f "$dest/$tarball"
  echo "fetch-$name: sha256 mismatch for $tarball (got $got, want $sha); refusing to build. Delete the cache and retry" >&2
  exit 1
fi
if [ -n "${fetched:-}" ]; then
  echo "fetch-$name: $tarball fetched and verified (sha256 ${sha:0:12}...; apt's messages, which may report a missing part of the source package, are in $dest/fetch-$name.apt.log)" >&2
fi
tar -C "$dest" -xJf "$dest/$tarball"
[ -f "$srcdir/$marker" ] || { echo "fetch-$name: $tarball did not unpack to $srcdir" >&2; exit 1; }
echo "$srcdir"
