#!/usr/bin/env python3
"""Plots of the paper's Figure 2 and Figure 9 from paperbench's output.

    python3 Benchmarks/paper_plots.py OUTDIR

Reads OUTDIR/figure9_threads*.csv (paperbench) and, when present,
OUTDIR/input.png, pde.png and advection.png; writes OUTDIR/figure9.png
(convergence to the steady state against compute time, one curve per method
and thread count), OUTDIR/figure9_scaling.md (seconds per t and thread count) and OUTDIR/figure2.png (the photo with three zoom-ins of the
input, the PDE's and the advection's steady states). Needs numpy, matplotlib
and PIL (Debian: python3-numpy python3-matplotlib python3-pil).
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

# Zoom-in windows (x, y, width, height) in the 2848 x 2136 window of the photo,
# top-left origin: the rock face against the cloud, snow on rock, a stone on grass.
ZOOMS = [(1120, 560, 320, 240), (2130, 420, 320, 240), (1300, 1340, 320, 240)]


def read_curves(outdir):
    curves = {}
    for path in sorted(glob.glob(os.path.join(outdir, "figure9_threads*.csv"))):
        with open(path) as f:
            for row in csv.DictReader(f):
                key = (row["method"], int(row["threads"]))
                curves.setdefault(key, []).append(
                    (float(row["t"]), float(row["seconds"]), float(row["ratio"])))
    return curves


def reference_ratios(curves):
    """Per method, the ratio at each t from its longest curve. The kernels give
    bit-identical results for any thread count, so a shorter curve (the 1-thread
    PDE run stops early) is placed at the ratios of the longest one; its own
    I_inf would be an earlier state."""
    longest = {}
    for (method, _), points in curves.items():
        if method not in longest or max(p[0] for p in points) > max(p[0] for p in longest[method]):
            longest[method] = points
    return {method: {t: ratio for t, _, ratio in points} for method, points in longest.items()}


def scaling_table(curves):
    """Markdown: seconds per t for each thread count, and the speed-up."""
    threads = sorted({n for _, n in curves})
    lines = ["| method | t | " + " | ".join("%d thread%s (s)" % (n, "s" if n > 1 else "") for n in threads)
             + " | speed-up |", "|---|---:|" + "---:|" * (len(threads) + 1)]
    for method in sorted({m for m, _ in curves}):
        seconds = {n: {t: s for t, s, _ in curves.get((method, n), [])} for n in threads}
        for t in sorted(set.intersection(*(set(seconds[n]) for n in threads))):
            row = [seconds[n][t] for n in threads]
            lines.append("| %s | %g | %s | %.2f |" % (method, t, " | ".join("%.3f" % s for s in row),
                                                      row[0] / row[-1]))
    return "\n".join(lines) + "\n"


def time_to_fraction(points, fraction):
    """Seconds at which the curve (t, seconds, ratio) first reaches `fraction`,
    interpolated linearly between the two samples around it; None if never."""
    previous = (0.0, 0.0)
    for _, seconds, ratio in sorted(points):
        if ratio >= fraction:
            s0, r0 = previous
            return s0 + (seconds - s0) * (fraction - r0) / (ratio - r0) if ratio > r0 else seconds
        previous = (seconds, ratio)
    return None


def summary_table(curves, threads):
    """Markdown: seconds for each method to reach given fractions of its own steady state."""
    lines = ["| fraction of the steady state | advection (s) | PDE (s) | PDE / advection |",
             "|---:|---:|---:|---:|"]
    for fraction in (0.25, 0.5, 0.8, 0.9, 0.99):
        a = time_to_fraction(curves.get(("advection", threads), []), fraction)
        p = time_to_fraction(curves.get(("pde", threads), []), fraction)
        if a is not None and p is not None:
            lines.append("| %g %% | %.2f | %.1f | %.0fx |" % (100 * fraction, a, p, p / a))
    return "\n".join(lines) + "\n"


def plot_figure9(outdir, curves):
    ratios = reference_ratios(curves)
    fig, ax = plt.subplots(figsize=(7.5, 4.6), dpi=120)
    colours = {"advection": "tab:blue", "pde": "tab:red"}
    names = {"advection": "advection (fixed flow)", "pde": "PDE (Osher-Rudin, upwind/minmod)"}
    for (method, threads), points in sorted(curves.items()):
        t, seconds, _ = (np.array(v) for v in zip(*points))
        ratio = np.array([ratios[method][ti] for ti in t])
        style = "-" if threads > 1 else "--"
        ax.plot(seconds, ratio, style, marker="o", markersize=3.5, color=colours.get(method, "k"),
                label="%s, %d thread%s" % (names.get(method, method), threads, "s" if threads > 1 else ""))
        for ti, si, ri in zip(t, seconds, ratio):
            if threads > 1 and ti in (2, 64, 2048):
                ax.annotate("t=%g" % ti, (si, ri), textcoords="offset points", xytext=(4, -10),
                            fontsize=7, color=colours.get(method, "k"))
    ax.axhline(0.99, color="grey", linewidth=0.8, linestyle=":")
    ax.text(0.0, 0.99, " 99 %", va="bottom", fontsize=7, color="grey", transform=ax.get_yaxis_transform())
    ax.set_xscale("log")
    ax.set_xlabel("compute time (s)")
    ax.set_ylabel(r"$\|I_t - I_0\| \,/\, \|I_\infty - I_0\|$")
    ax.set_title("Steady-state convergence, t = 2^k (Figure 9)", fontsize=10)
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize=7.5, loc="lower right")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "figure9.png"))
    plt.close(fig)


def plot_figure2(outdir, steady_time):
    paths = [os.path.join(outdir, name) for name in ("input.png", "pde.png", "advection.png")]
    if not all(os.path.exists(p) for p in paths):
        return False
    images = [np.asarray(Image.open(p).convert("RGB")) for p in paths]
    height, width = images[0].shape[:2]
    fig = plt.figure(figsize=(10, 12.5), dpi=110)
    grid = fig.add_gridspec(1 + len(ZOOMS), 3, height_ratios=[2.3] + [1] * len(ZOOMS),
                            wspace=0.03, hspace=0.08)
    overview = fig.add_subplot(grid[0, :])
    overview.imshow(images[0])
    for k, (x, y, w, h) in enumerate(ZOOMS):
        overview.add_patch(plt.Rectangle((x, y), w, h, fill=False, edgecolor="yellow", linewidth=1.2))
        overview.text(x, y - 30, str(k + 1), color="yellow", fontsize=10)
    overview.set_axis_off()
    overview.set_title("input, %d x %d; zoom-ins below (native pixels)" % (width, height), fontsize=10)
    titles = ["(a) input", "(b) PDE, t = %g" % steady_time, "(c) advection, t = %g" % steady_time]
    for k, (x, y, w, h) in enumerate(ZOOMS):
        for j, image in enumerate(images):
            ax = fig.add_subplot(grid[k + 1, j])
            ax.imshow(image[y:y + h, x:x + w], interpolation="nearest")
            ax.set_xticks([])
            ax.set_yticks([])
            if k == 0:
                ax.set_title(titles[j], fontsize=10)
            if j == 0:
                ax.set_ylabel(str(k + 1), rotation=0, labelpad=8, fontsize=10)
    fig.savefig(os.path.join(outdir, "figure2.png"), bbox_inches="tight")
    plt.close(fig)
    return True


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: paper_plots.py OUTDIR")
    outdir = sys.argv[1]
    curves = read_curves(outdir)
    if not curves:
        sys.exit("paper_plots.py: no figure9_threads*.csv in %s" % outdir)
    plot_figure9(outdir, curves)
    most = max(n for _, n in curves)
    with open(os.path.join(outdir, "figure9_summary.md"), "w") as f:
        f.write(summary_table(curves, most))
    if len({n for _, n in curves}) > 1:
        with open(os.path.join(outdir, "figure9_scaling.md"), "w") as f:
            f.write(scaling_table(curves))
    steady_time = max(t for points in curves.values() for t, _, _ in points)
    wrote = ["figure9.png"] + (["figure2.png"] if plot_figure2(outdir, steady_time) else [])
    print("wrote %s in %s" % (", ".join(wrote), outdir))


if __name__ == "__main__":
    main()
