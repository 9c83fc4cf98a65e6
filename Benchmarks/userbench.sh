#!/bin/sh
# userbench: the figures of issue #18 as users meet them, each the median (with
# min and max) of N fresh processes of the program `shockfilter ... --timings`
# at 1 and 2 threads, with the process's peak memory; prints a Markdown table
# (machine, commit, exact commands) for Benchmarks/RESULTS.md.
#
#   bash Benchmarks/userbench.sh [--build DIR] [--rows a,b,...] [--runs N] ...
#   bash Benchmarks/userbench.sh --help        the options and the rows
#
# The work is done by userbench.py, run with an interpreter that has numpy and
# ParaView's vtkmodules (/usr/bin/python3, else pvpython; the python3 first on
# PATH may lack numpy).
here=$(cd "$(dirname "$0")" && pwd)
for python in /usr/bin/python3 pvpython; do
  if command -v "$python" >/dev/null 2>&1 &&
     "$python" -c "import numpy, vtkmodules" >/dev/null 2>&1; then
    exec "$python" "$here/userbench.py" "$@"
  fi
done
echo "userbench.sh: needs /usr/bin/python3 or pvpython with numpy and vtkmodules" \
  "(bash scripts/install-deps.sh)" >&2
exit 2
