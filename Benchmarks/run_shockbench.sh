#!/bin/sh
# Build shockbench (Release) in its own build tree, wait for a quiet machine,
# run it and keep the markdown tables (stdout) and the progress log (stderr).
#
#   Benchmarks/run_shockbench.sh [BUILD_DIR] [OUTPUT_PREFIX] [shockbench arguments...]
#
# Defaults: BUILD_DIR=/tmp/build-bench, OUTPUT_PREFIX=/tmp/shockbench, arguments "all".
# Waits (up to SHOCKBENCH_WAIT_MINUTES, default 15) for a 1-minute load average
# below SHOCKBENCH_MAX_LOAD (default 0.5) before running.
set -eu
src=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-/tmp/build-bench}
out=${2:-/tmp/shockbench}
[ $# -ge 2 ] && shift 2 || shift $#
[ $# -eq 0 ] && set -- all
max_load=${SHOCKBENCH_MAX_LOAD:-0.5}
wait_minutes=${SHOCKBENCH_WAIT_MINUTES:-15}

cmake -S "$src" -B "$build" -DBUILD_TESTING=OFF -DCMAKE_BUILD_TYPE=Release >/dev/null
make -C "$build" -j2 shockbench >/dev/null

waited=0
while :; do
  load=$(cut -d' ' -f1 /proc/loadavg)
  if awk -v l="$load" -v m="$max_load" 'BEGIN { exit !(l < m) }'; then
    break
  fi
  if [ "$waited" -ge $((wait_minutes * 60)) ]; then
    echo "load $load still >= $max_load after $wait_minutes min: running anyway" >&2
    break
  fi
  echo "load $load >= $max_load: waiting" >&2
  sleep 30
  waited=$((waited + 30))
done

{
  echo "- source: $src, commit $(git -C "$src" log -1 --format=%h 2>/dev/null || echo unknown)"
  changes=$(git -C "$src" status --short Filters 2>/dev/null || true)
  echo "- uncommitted changes under Filters/ at start: ${changes:-none}" | tr '\n' ' '
  echo
  echo "- uptime at start: $(uptime)"
} >"$out.md"
"$build/bin/shockbench" "$@" >>"$out.md" 2>"$out.log"
{
  changes=$(git -C "$src" status --short Filters 2>/dev/null || true)
  echo "- uncommitted changes under Filters/ at end: ${changes:-none}" | tr '\n' ' '
  echo
  echo "- uptime at end: $(uptime)"
} >>"$out.md"
echo "tables in $out.md, progress in $out.log" >&2
