"""Two commands timed in turn, as whole fresh processes: A B A B ...

  /usr/bin/python3 Benchmarks/alternate.py [-n RUNS] [--warmup N] -a 'COMMAND A' -b 'COMMAND B'

Each command is split as a shell splits words and run without a shell; its
output is discarded. After the warm-up runs (not counted), A and B run in turn
RUNS times each; the user and wall seconds and peak resident memory of each run
come from the kernel's accounting of the finished process (wait4). Printed: the
median (min-max) of each figure for A and B, and the ratio A/B pair by pair
(a noisy machine moves both runs of a pair alike), so that "after / before"
holds within one run. Benchmarks/RESULTS.md quotes these rows.
"""
import argparse
import os
import shlex
import statistics
import subprocess
import time


def timed(command):
    start = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    process.returncode = os.waitstatus_to_exitcode(status)
    return dict(user=usage.ru_utime, wall=wall, peak_mib=usage.ru_maxrss / 1024.0, code=process.returncode)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("-n", type=int, default=5, help="counted runs of each command")
    parser.add_argument("--warmup", type=int, default=1, help="uncounted runs of each command first")
    parser.add_argument("-a", required=True, help="command A (the 'after', or the one measured)")
    parser.add_argument("-b", required=True, help="command B (the 'before', or the reference)")
    args = parser.parse_args()
    a, b = shlex.split(args.a), shlex.split(args.b)
    for _ in range(args.warmup):
        timed(a)
        timed(b)
    runs = [(timed(a), timed(b)) for _ in range(args.n)]
    codes = sorted({r["code"] for pair in runs for r in pair})
    span = lambda xs: "%.3f (%.3f-%.3f)" % (statistics.median(xs), min(xs), max(xs))
    for figure in ("user", "wall", "peak_mib"):
        print("A %-8s %s" % (figure, span([pair[0][figure] for pair in runs])))
        print("B %-8s %s" % (figure, span([pair[1][figure] for pair in runs])))
    for figure in ("user", "wall"):
        ratios = [pair[0][figure] / pair[1][figure] for pair in runs if pair[1][figure] > 0.0]
        print("A/B %-6s %s" % (figure, span(ratios) if ratios else "- (B took no measurable time)"))
    print("exit codes:", codes)


if __name__ == "__main__":
    main()
