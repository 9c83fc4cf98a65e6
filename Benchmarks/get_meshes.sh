#!/bin/sh
# Fetches the real scanned meshes of meshbench (not committed): Debian's
# libcgal-demo package ships CGAL's data.tar.gz, whose data/meshes/ holds
# ChineseDragon-10kv.off (the paper's Chinese Dragon, decimated to 10K
# vertices), armadillo.off, bunny00.off, fandisk_large.off and
# refined_elephant.off. The package is downloaded with `apt-get download` and
# unpacked with `dpkg -x` into the mesh directory, without installing it
# (no root needed), and only those five files are kept.
#
#   Benchmarks/get_meshes.sh [DIR]
#
# DIR defaults to $SHOCK_MESH_DIR, else ${XDG_CACHE_HOME:-~/.cache}/shockfilters/meshes,
# which is also where meshbench looks. Idempotent: does nothing when the five
# files are there; the downloaded .deb is kept in DIR/deb for later runs.
# Needs apt-get with current package lists (`apt-get update`), dpkg and tar.
set -eu
dir=${1:-${SHOCK_MESH_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/shockfilters/meshes}}
# SHOCK_MESH_FILES names other files of CGAL's data/meshes (get_cad_meshes.sh does).
meshes=${SHOCK_MESH_FILES:-"ChineseDragon-10kv.off armadillo.off bunny00.off fandisk_large.off refined_elephant.off"}

missing=
for mesh in $meshes; do
  [ -s "$dir/$mesh" ] || missing="$missing $mesh"
done
if [ -z "$missing" ]; then
  echo "the meshes are in $dir"
  exit 0
fi

mkdir -p "$dir/deb"
dir=$(cd "$dir" && pwd)
if ! ls "$dir"/deb/libcgal-demo_*.deb >/dev/null 2>&1; then
  # apt-get download writes into the current directory.
  (cd "$dir/deb" && apt-get download libcgal-demo)
fi
deb=$(ls "$dir"/deb/libcgal-demo_*.deb | tail -n 1)

work=$(mktemp -d "$dir/unpack.XXXXXX")
trap 'rm -rf "$work"' EXIT
dpkg -x "$deb" "$work/root"
data=$(find "$work/root" -path '*/libcgal-dev/data.tar.gz' | head -n 1)
if [ -z "$data" ]; then
  echo "get_meshes.sh: no data.tar.gz in $deb" >&2
  exit 1
fi
members=
for mesh in $missing; do
  members="$members data/meshes/$mesh"
done
# shellcheck disable=SC2086 # one member per word
tar -xzf "$data" -C "$work" $members
for mesh in $missing; do
  mv "$work/data/meshes/$mesh" "$dir/$mesh"
done
echo "extracted$missing into $dir (from $(basename "$deb"))"
