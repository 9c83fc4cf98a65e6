#!/bin/sh
# Reproduces the paper's evidence on this machine, into OUTDIR (default
# ./paper-evidence): Figure 2 and Figure 9 (advection vs the Osher-Rudin PDE on
# a real photograph), Table 1 (image, fixed/composed/naive flows), Tables 2
# and 3 (mesh colours and geometry sharpening on real scans) and the 1- vs
# 2-thread scaling of each. Not part of the CTest suite: it takes about 45
# minutes on 2 cores. Figures (PNG) and Markdown tables go to OUTDIR;
# OUTDIR/EVIDENCE.md gathers the tables with the machine, commit and commands.
#
#   Benchmarks/reproduce_paper.sh [OUTDIR]
#
# Steps: install what is missing (scripts/install-deps.sh), build the
# benchmarks (Release) in $SHOCK_BENCH_BUILD (default ./build-bench), fetch the
# photo and the meshes (Benchmarks/get_photo.sh, get_meshes.sh: Debian
# packages, unpacked, not installed), wait for a quiet machine, run, plot.
# Environment: SHOCK_BENCH_THREADS (default 2), SHOCK_PDE_KMAX_ONE_THREAD
# (default 8: the 1-thread PDE curve stops at t = 2^8, its full run alone
# would take about twice the 2-thread one).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/paper-evidence}
build=${SHOCK_BENCH_BUILD:-$root/build-bench}
threads=${SHOCK_BENCH_THREADS:-2}
pde_kmax_one=${SHOCK_PDE_KMAX_ONE_THREAD:-8}
mkdir -p "$out"
out=$(cd "$out" && pwd)

bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -DBUILD_TESTING=OFF -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --parallel 2 --target paperbench shockbench meshbench >/dev/null
photo=$("$root/Benchmarks/get_photo.sh")
"$root/Benchmarks/get_meshes.sh" >&2

# Wait (up to 15 minutes) for a 1-minute load average below 0.5.
waited=0
while awk -v l="$(cut -d' ' -f1 /proc/loadavg)" 'BEGIN { exit !(l >= 0.5) }' && [ $waited -lt 900 ]; do
  echo "reproduce_paper: waiting for a quiet machine (load $(cut -d' ' -f1 /proc/loadavg))" >&2
  sleep 30
  waited=$((waited + 30))
done

run() { # run NAME COMMAND...: Markdown to $out/NAME.md, progress to $out/NAME.log
  name=$1
  shift
  echo "reproduce_paper: $name: $*" >&2
  echo "\`$*\`" | sed "s|$build/bin/||; s|$root/||g; s|$HOME|~|g" > "$out/$name.cmd"
  start=$(date +%s)
  "$@" > "$out/$name.md" 2> "$out/$name.log"
  echo "reproduce_paper: $name done in $(( $(date +%s) - start )) s" >&2
}

bin=$build/bin
run figure9 "$bin/paperbench" "$photo" "$out" --threads "$threads"
run figure9_one_thread "$bin/paperbench" "$photo" "$out" --threads 1 --pde-kmax "$pde_kmax_one" --no-images
run table1 "$bin/shockbench" table1 threads
run table2 "$bin/meshbench" colors --threads "$threads"
run table3 "$bin/meshbench" sharpen --threads "$threads"
run table3_one_thread "$bin/meshbench" sharpen --threads 1 --times 2048 --smoothing 1
/usr/bin/python3 "$root/Benchmarks/paper_plots.py" "$out" >&2

{
  echo "# Evidence for Prada and Kazhdan (2015), reproduced"
  echo
  echo "- commit: $(git -C "$root" log -1 --format='%h %cd' --date=short 2>/dev/null || echo unknown)"
  echo "- machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, $(free -g | awk '/Mem:/ {print $2}') GiB; $(. /etc/os-release && echo "$PRETTY_NAME")"
  echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "- photo: $(basename "$photo") (Aitzol Berasategi, CC-BY-4.0, Debian lomiri-wallpapers-16.04)"
  echo
  for name in figure9 figure9_one_thread table1 table2 table3 table3_one_thread; do
    echo "## $name"
    echo
    echo "Command: $(cat "$out/$name.cmd")"
    echo
    sed 's/^#/##/' "$out/$name.md" # one level below this section
    echo
  done
  echo "## Figure 9: seconds to reach a fraction of each method's steady state (2 threads)"
  echo
  cat "$out/figure9_summary.md"
  echo
  echo "## Thread scaling of Figure 9 (seconds to reach t)"
  echo
  cat "$out/figure9_scaling.md"
} > "$out/EVIDENCE.md"
echo "reproduce_paper: wrote $out/EVIDENCE.md, figure2.png, figure9.png" >&2
