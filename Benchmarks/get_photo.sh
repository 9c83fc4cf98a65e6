#!/bin/sh
# Fetches the real photograph of paperbench (not committed): Aitzol
# Berasategi's "Picos de Europa" (3264 x 2448 JPEG, CC-BY-4.0), shipped by
# Debian's lomiri-wallpapers-16.04 package. The package is downloaded with
# `apt-get download` and unpacked with `dpkg -x` into the photo directory,
# without installing it (no root needed); only the photo is kept.
#
#   Benchmarks/get_photo.sh [DIR]
#
# DIR defaults to $SHOCK_PHOTO_DIR, else ${XDG_CACHE_HOME:-~/.cache}/shockfilters/photos.
# Prints the photo's path on stdout. Idempotent: does nothing when it is there.
set -eu
dir=${1:-${SHOCK_PHOTO_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/shockfilters/photos}}
photo=picosdeeuropa_by_Aitzol_Berasategi.jpg
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
if [ ! -s "$dir/$photo" ]; then
  mkdir -p "$dir/deb"
  if ! ls "$dir"/deb/lomiri-wallpapers-16.04_*.deb >/dev/null 2>&1; then
    (cd "$dir/deb" && apt-get download lomiri-wallpapers-16.04) >&2
  fi
  deb=$(ls "$dir"/deb/lomiri-wallpapers-16.04_*.deb | tail -n 1)
  work=$(mktemp -d "$dir/unpack.XXXXXX")
  trap 'rm -rf "$work"' EXIT
  dpkg -x "$deb" "$work"
  found=$(find "$work" -name "$photo" | head -n 1)
  if [ -z "$found" ]; then
    echo "get_photo.sh: no $photo in $deb" >&2
    exit 1
  fi
  mv "$found" "$dir/$photo"
  echo "extracted $photo into $dir (from $(basename "$deb"))" >&2
fi
echo "$dir/$photo"
