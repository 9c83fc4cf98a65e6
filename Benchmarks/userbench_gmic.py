"""userbench's G'MIC row: time to 90 % of the steady state, ours against G'MIC.

The measure is the one of Figure 9 (Benchmarks/paperbench.cxx,
paper_plots.time_to_fraction): for a method whose output after "time" s is
I_s, the fraction of the steady state reached is |I_s - I_0| / |I_inf - I_0|
(L2 over all samples and channels), with I_inf the output at a very large s;
the time to 90 % is interpolated linearly between the two samples around 0.9,
starting from (0 s, 0).
- ours: `shockfilter image` at t = 2^k, k = 0..--ours-kmax (I_inf: the last),
  the time of each t the median `total` of --timings over --runs processes;
- G'MIC: `gmic ... sharpen 10,0.1,0.8,1.1` (its shock-filter sharpening)
  iterated n = 2^k times, k = 0..log2(--gmic-iterations) (I_inf: the last),
  its outputs rounded to 0..255 as ours are; its time for n iterations is n
  times the cost of one, measured as (wall(m iterations) - wall(0 iterations))
  / m over --runs processes each (m = --gmic-cost-iterations), so that for both
  the time excludes reading, writing and process start-up.
Both on the same 1368 x 1824 photo window, in the same run, at each --threads
(OMP_NUM_THREADS for G'MIC, which uses OpenMP).
"""
import json
import os
import shutil
import statistics
import subprocess

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

from userbench_inputs import HERE, log

SHARPEN = "sharpen 10,0.1,0.8,1.1"


def add_arguments(parser):
    parser.add_argument("--ours-kmax", type=int, default=16,
                        help="gmic row: ours at t = 2^0..2^K, I_inf at 2^K (default 16)")
    parser.add_argument("--gmic-iterations", type=int, default=256,
                        help="gmic row: G'MIC iterated 1, 2, 4, ... up to this (a power of "
                        "two; I_inf; default 256)")
    parser.add_argument("--gmic-cost-iterations", type=int, default=16,
                        help="gmic row: iterations of the per-iteration cost runs (default 16)")


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).astype(np.float64).ravel()


def read_pfm(path):
    """A G'MIC PFM file (header 'PF', width height, scale; big endian when scale > 0)."""
    with open(path, "rb") as stream:
        data = stream.read()
    words = data.split(maxsplit=4)
    width, height, scale = int(words[1]), int(words[2]), float(words[3])
    count = 3 * width * height
    values = np.frombuffer(data[len(data) - 4 * count:], dtype=">f4" if scale > 0 else "<f4")
    return np.rint(np.clip(values.astype(np.float64), 0.0, 255.0))


def fractions(outputs, initial):
    """|I_s - I_0| / |I_inf - I_0| for each output, I_inf the last."""
    total = np.linalg.norm(outputs[-1] - initial)
    return [float(np.linalg.norm(o - initial) / total) if total > 0 else 1.0 for o in outputs]


def time_to_fraction(points, fraction=0.9):
    """Seconds at which (seconds, ratio) points, in order of t, first reach `fraction`."""
    previous = (0.0, 0.0)
    for seconds, ratio in points:
        if ratio >= fraction:
            s0, r0 = previous
            return s0 + (seconds - s0) * (fraction - r0) / (ratio - r0) if ratio > r0 else seconds
        previous = (seconds, ratio)
    return None


def ensure_gmic(args):
    if shutil.which("gmic") is None and not args.no_install:
        log("installing gmic: bash scripts/install-deps.sh --benchmarks")
        subprocess.run(["bash", os.path.join(HERE, "..", "scripts", "install-deps.sh"),
                        "--benchmarks"], check=True)
    if shutil.which("gmic") is None:
        raise SystemExit("userbench: gmic row needs G'MIC (bash scripts/install-deps.sh --benchmarks)")


def ours(args, photo, workdir, run_process):
    """Per thread count, the (median total, ratio) points of t = 2^k; and the command."""
    times = [2.0 ** k for k in range(args.ours_kmax + 1)]
    outputs, curves = [], {}
    for threads in args.threads:
        medians = []
        for t in times:
            out = os.path.join(workdir, "ours-%g.png" % t)
            command = [args.program, "image", photo, out, "--time", "%g" % t, "--flow", "fixed",
                       "--timings", "--threads", str(threads)]
            totals = [json.loads(run_process(command)[1].strip().splitlines()[-1])["total"]
                      for _ in range(args.runs)]
            medians.append(statistics.median(totals))
            if len(outputs) < len(times):
                outputs.append(read_png(out))
            os.remove(out)
        curves[threads] = medians
        log("ours threads=%d: %s" % (threads, " ".join("%.3f" % s for s in medians)))
    ratios = fractions(outputs, read_png(photo))
    command = "%s image PHOTO OUT --time t --flow fixed --timings --threads T" % args.program
    return {n: list(zip(s, ratios)) for n, s in curves.items()}, times, ratios, command


def gmic_ratios(args, photo, workdir, run_process):
    """G'MIC's fraction of its steady state after 1, 2, 4, ... iterations (one process)."""
    counts = [1]
    while counts[-1] < args.gmic_iterations:
        counts.append(2 * counts[-1])
    pattern = os.path.join(workdir, "gmic_{$>+1}.pfm")
    command = ["gmic", "-v", "-1", photo, "o", os.path.join(workdir, "gmic_0.pfm"),
               "repeat", str(counts[-1])] + SHARPEN.split() + [
        "if", "isin($>+1,%s)" % ",".join(map(str, counts)), "o", pattern, "fi", "done"]
    run_process(command)
    initial = read_pfm(os.path.join(workdir, "gmic_0.pfm"))
    outputs = [read_pfm(os.path.join(workdir, "gmic_%d.pfm" % n)) for n in counts]
    for n in [0] + counts:
        os.remove(os.path.join(workdir, "gmic_%d.pfm" % n))
    return counts, fractions(outputs, initial)


def gmic_cost(args, photo, workdir, threads, run_process):
    """Median seconds of one G'MIC iteration (start-up, reading and writing excluded)."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out = os.path.join(workdir, "gmic_cost.pfm")
    m = args.gmic_cost_iterations
    plain = ["gmic", "-v", "-1", photo, "o", out]
    iterated = ["gmic", "-v", "-1", photo, "repeat", str(m)] + SHARPEN.split() + ["done", "o", out]
    empty = statistics.median(run_process(plain, env)[0] for _ in range(args.runs))
    full = statistics.median(run_process(iterated, env)[0] for _ in range(args.runs))
    return max(full - empty, 0.0) / m


def compare(args, inputs, workdir, run_process):
    ensure_gmic(args)
    photo = inputs.photo_1368x1824()
    curves, times, ratios, our_command = ours(args, photo, workdir, run_process)
    counts, gmic_fractions = gmic_ratios(args, photo, workdir, run_process)
    lines = []
    for threads in args.threads:
        ours_90 = time_to_fraction(curves[threads])
        cost = gmic_cost(args, photo, workdir, threads, run_process)
        gmic_90 = time_to_fraction([(n * cost, r) for n, r in zip(counts, gmic_fractions)])
        factor = "%.0f×" % (gmic_90 / ours_90) if ours_90 and gmic_90 else "-"
        lines.append("| time to 90 %% of the steady state, 1368×1824 RGB photo: ours vs G'MIC "
                     "`%s` | %d | ours %s s | G'MIC %s s (%.3f s per iteration); G'MIC / ours = %s | - "
                     "| ≥ 50× |" % (SHARPEN, threads, "%.3f" % ours_90 if ours_90 else "never",
                                    "%.2f" % gmic_90 if gmic_90 else "never", cost, factor))
    extra = ["Fractions of the steady state (|I - I_0| / |I_inf - I_0|), G'MIC row:", "",
             "| ours t | " + " | ".join("%g" % t for t in times) + " |",
             "|---|" + "---:|" * len(times),
             "| fraction | " + " | ".join("%.3f" % r for r in ratios) + " |", "",
             "| G'MIC iterations | " + " | ".join(map(str, counts)) + " |",
             "|---|" + "---:|" * len(counts),
             "| fraction | " + " | ".join("%.3f" % r for r in gmic_fractions) + " |"]
    command = "%s; gmic -v -1 PHOTO repeat n %s done o OUT.pfm (OMP_NUM_THREADS=T)" % (
        our_command, SHARPEN)
    return lines, command, extra
