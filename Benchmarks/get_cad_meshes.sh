#!/bin/sh
# Fetches the CAD parts of sharpen_eval.py (not committed): Debian's
# libcgal-demo package ships CGAL's data.tar.gz, whose data/meshes/ holds
# mechanical parts with sharp creases. Ten closed ones are kept: fandisk,
# anchor_dense, dragknob, rotor_small, couplingdown, pinion, spool, oblong,
# joint and part (.off). The package is downloaded with `apt-get download`
# and unpacked with `dpkg -x` into the mesh directory, without installing it
# (no root needed); sharpen_eval.py subdivides the coarse ones itself.
#
#   Benchmarks/get_cad_meshes.sh [DIR]
#
# DIR defaults to $SHOCK_CAD_DIR, else ${XDG_CACHE_HOME:-~/.cache}/shockfilters/cad,
# which is also where sharpen_eval.py looks. Idempotent: does nothing when the
# ten files are there; the downloaded .deb is kept in DIR/deb for later runs.
# Needs apt-get with current package lists (`apt-get update`), dpkg and tar.
set -eu
dir=${1:-${SHOCK_CAD_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/shockfilters/cad}}
SHOCK_MESH_FILES="fandisk.off anchor_dense.off dragknob.off rotor_small.off couplingdown.off pinion.off spool.off oblong.off joint.off part.off" \
  exec "$(dirname "$0")/get_meshes.sh" "$dir"
