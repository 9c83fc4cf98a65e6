#!/bin/sh
# The scan set of sharpen_eval.py (not committed): the ten CAD parts of
# get_cad_meshes.sh as a scanner samples them. A CAD tessellation follows the
# part's faces with long thin triangles; a scan samples the surface evenly.
# Each part is remeshed isotropically by scan_cad.cxx (CGAL's isotropic
# remeshing: every point on the original surface, the creases of more than
# FEATURE_ANGLE degrees kept as edges) to about POINTS points.
#
#   Benchmarks/get_scan_meshes.sh [DIR]
#
# DIR defaults to $SHOCK_SCAN_DIR, else ${XDG_CACHE_HOME:-~/.cache}/shockfilters/scan,
# which is also where sharpen_eval.py looks; the CAD parts are fetched into
# the directory of get_cad_meshes.sh. CGAL's headers come from Debian's
# libcgal-dev, downloaded with `apt-get download` and unpacked into DIR/cgal
# without installing it (no root needed); scan_cad is compiled with c++ into
# DIR. Needs apt-get with current package lists, dpkg, a C++17 compiler and
# Boost's headers (libboost-dev; ParaView's dependencies bring them).
# Idempotent: does nothing when the ten files are there. About a minute.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
dir=${1:-${SHOCK_SCAN_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/shockfilters/scan}}
cad=${SHOCK_CAD_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/shockfilters/cad}
models="fandisk anchor_dense rotor_small couplingdown pinion spool oblong joint part dragknob"
POINTS=${POINTS:-20000}
FEATURE_ANGLE=${FEATURE_ANGLE:-30}

missing=
for model in $models; do
  [ -s "$dir/$model.off" ] || missing="$missing $model"
done
if [ -z "$missing" ]; then
  echo "the scan meshes are in $dir"
  exit 0
fi

"$here/get_cad_meshes.sh" "$cad"
mkdir -p "$dir/deb"
dir=$(cd "$dir" && pwd)
if [ ! -x "$dir/scan_cad" ]; then
  if ! ls "$dir"/deb/libcgal-dev_*.deb >/dev/null 2>&1; then
    (cd "$dir/deb" && apt-get download libcgal-dev)
  fi
  deb=$(ls "$dir"/deb/libcgal-dev_*.deb | tail -n 1)
  rm -rf "$dir/cgal"
  dpkg -x "$deb" "$dir/cgal"
  # CGAL_DISABLE_GMP: exact arithmetic from Boost.Multiprecision, so that
  # GMP's and MPFR's development packages are not needed.
  ${CXX:-c++} -std=c++17 -O2 -DNDEBUG -DCGAL_DISABLE_GMP -I "$dir/cgal/usr/include" \
    "$here/scan_cad.cxx" -o "$dir/scan_cad.tmp"
  mv "$dir/scan_cad.tmp" "$dir/scan_cad"
fi
for model in $missing; do
  printf '%s: ' "$dir/$model.off"
  "$dir/scan_cad" "$cad/$model.off" "$dir/$model.off.tmp" "$POINTS" "$FEATURE_ANGLE"
  mv "$dir/$model.off.tmp" "$dir/$model.off"
done
