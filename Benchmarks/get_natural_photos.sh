#!/bin/sh
# Fetches the eight natural photographs of the gradient-domain evidence
# (Benchmarks/gradient_domain.py; not committed): astronaut, camera, chelsea,
# coffee, coins, moon, motorcycle_left and rocket from scikit-image's data
# folder, shipped by Debian's python3-skimage package (BSD-licensed; the
# images' own licences are in its data/README.txt). The package is downloaded
# with `apt-get download` and unpacked with `dpkg -x` into the photo directory,
# without installing it; only the photos and the README are kept.
#
#   Benchmarks/get_natural_photos.sh [DIR]
#
# DIR defaults to $SHOCK_PHOTO_DIR/natural, else
# ${XDG_CACHE_HOME:-~/.cache}/shockfilters/photos/natural.
# Prints the directory on stdout. Idempotent: does nothing when they are there.
set -eu
base=${SHOCK_PHOTO_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/shockfilters/photos}
dir=${1:-$base/natural}
photos="astronaut.png camera.png chelsea.png coffee.png coins.png moon.png motorcycle_left.png rocket.jpg"
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
missing=0
for p in $photos; do
  [ -s "$dir/$p" ] || missing=1
done
if [ "$missing" = 1 ]; then
  mkdir -p "$dir/deb"
  if ! ls "$dir"/deb/python3-skimage_*.deb >/dev/null 2>&1; then
    (cd "$dir/deb" && apt-get download python3-skimage) >&2
  fi
  deb=$(ls "$dir"/deb/python3-skimage_*.deb | tail -n 1)
  work=$(mktemp -d "$dir/unpack.XXXXXX")
  trap 'rm -rf "$work"' EXIT
  dpkg -x "$deb" "$work"
  data=$(find "$work" -type d -path "*/skimage/data" | head -n 1)
  for p in $photos README.txt; do
    if [ ! -s "$data/$p" ]; then
      echo "get_natural_photos.sh: no $p in $deb" >&2
      exit 1
    fi
    cp "$data/$p" "$dir/$p"
  done
  echo "extracted the photos into $dir (from $(basename "$deb"))" >&2
fi
echo "$dir"
