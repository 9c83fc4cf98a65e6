#!/usr/bin/env bash
# The main job on built-in data: installs what is missing, builds, then runs
# `shockfilter demo`, which writes its images to demo-output/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
"$root/build/bin/shockfilter" demo "$root/demo-output"
echo "Results in $root/demo-output (before_after.png, volume_before_after.png, ...)"
