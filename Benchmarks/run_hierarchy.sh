#!/bin/sh
# The evidence of docs/hierarchy.md: does the coarse-to-fine tracing
# (HierarchyLevels) pay? Runs hierbench on its synthetic scene and on two
# photographs from Debian's lomiri-wallpapers-16.04 (fetched by get_photo.sh,
# not installed, not committed): Picos de Europa by Aitzol Berasategi
# (CC-BY-4.0) and Seeding by Clemens Engelhardt (CC0-1.0).
#
#   Benchmarks/run_hierarchy.sh [BUILD_DIR] [PICTURE_DIR]
#
# BUILD_DIR defaults to build (Release, with the hierbench target); pictures go
# to PICTURE_DIR (default hierarchy-pictures). Markdown tables on stdout. About
# 20 minutes. One thread: on a shared machine a team of OpenMP threads stalls
# at its barriers whenever another job holds a core (results do not depend on
# the thread count).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
pictures=${2:-hierarchy-pictures}
cmake --build "$build" --target hierbench >&2
picos=$(sh "$here/get_photo.sh")
dir=$(dirname "$picos")
for photo in seeding_by_Clements_Engelhardt.jpg; do
  if [ ! -s "$dir/$photo" ]; then
    work=$(mktemp -d "$dir/unpack.XXXXXX")
    dpkg -x "$(ls "$dir"/deb/lomiri-wallpapers-16.04_*.deb | tail -n 1)" "$work"
    mv "$(find "$work" -name "$photo" | head -n 1)" "$dir/$photo"
    rm -rf "$work"
  fi
done
mkdir -p "$pictures"
"$build/bin/hierbench" --threads 1 --pictures "$pictures" "$picos" \
  "$dir/seeding_by_Clements_Engelhardt.jpg"
"$build/bin/hierbench" --cost --threads 1 --photo-width 1368 "$picos"
