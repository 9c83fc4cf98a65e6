#!/usr/bin/env python3
"""Evidence of the gradient domain (docs/gradient-domain.md): value advection
(the paper) against Domain Gradients on eight blurred natural photographs.

    /usr/bin/python3 Benchmarks/gradient_domain.py [--build build] [--out DIR]
        [--photos DIR] [--times 64,256,...] [--runs 3]

(pvpython works too: it needs numpy and PIL, and the build's Python package
`shockfilters`, found under --build.) Every photo (Benchmarks/get_natural_photos.sh
fetches them) is scaled to [0, 1], blurred with a Gaussian of sigma = 1.5, 2.5
and 4 pixels (separable, mirrored borders) and given mild Gaussian noise
(standard deviation 2/255, a fixed seed per photo and sigma). Each method runs
through vtkImageShockAdvectionFilter, defaults otherwise, at every flow time of
--times; for each one the script reports, against the sharp original:

- MAE: the mean absolute error (in 1/255 units);
- sharpness: the mean gradient length of the result over the original's
  strongest 5 % of pixel differences, divided by the original's there (1 = as
  sharp as the original; the blurred input is far below);
- overshoot: how far the result leaves [0, 1] (the noisy input itself leaves
  it by about 0.03).

Tables (Markdown, to stdout and OUT/gradient_domain.md): per photo and sigma,
the blurred input and each method at its best t (lowest MAE) and at the fixed
t = 1024; a summary over all photos; the screening sweep of Domain Gradients
at its best t; time and peak memory of `shockfilter image` on the largest
photo in fresh processes (median of --runs). A picture grid (blurred | values
| gradients | original, each method at its best t) goes to
OUT/gradient_domain_grid.jpg.
"""
import argparse
import datetime
import glob
import os
import platform
import statistics
import subprocess
import sys
import time

import numpy as np
from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PHOTOS = ["astronaut.png", "camera.png", "chelsea.png", "coffee.png", "coins.png", "moon.png",
          "motorcycle_left.png", "rocket.jpg"]
SIGMAS = [1.5, 2.5, 4.0]
NOISE = 2.0 / 255.0
FIXED_T = 1024.0
SCREENINGS = [0.001, 0.01, 0.1, 1.0]


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(ROOT, "build", "gradient-domain"))
    parser.add_argument("--photos", default=None, help="folder of the photos (default: fetch them)")
    parser.add_argument("--times", default="64,256,1024,4096,16384,65536")
    parser.add_argument("--timing-photo", default=None,
                        help="photo of the time and memory rows (default: Benchmarks/get_photo.sh's, "
                             "3264 x 2448; else the largest of the eight)")
    parser.add_argument("--runs", type=int, default=3, help="fresh processes per timing (median)")
    return parser.parse_args()


ARGS = arguments()
sys.path.insert(0, glob.glob(os.path.join(ARGS.build, "lib", "python3*", "site-packages"))[0])
from shockfilters import vtkImageShockAdvectionFilter  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402


def gaussian_blur(image, sigma):
    """Separable Gaussian (radius 4 sigma), mirrored borders, per channel."""
    radius = int(np.ceil(4 * sigma))
    x = np.arange(-radius, radius + 1, dtype=float)
    kernel = np.exp(-0.5 * (x / sigma) ** 2)
    kernel /= kernel.sum()
    out = image
    for axis in (0, 1):
        padded = np.pad(out, [(radius, radius) if a == axis else (0, 0) for a in range(out.ndim)],
                        mode="symmetric")
        acc = np.zeros_like(out)
        for k, w in enumerate(kernel):
            acc += w * np.take(padded, range(k, k + out.shape[axis]), axis=axis)
        out = acc
    return out


def shock(image, t, domain, screening=0.01):
    """vtkImageShockAdvectionFilter on an H x W x C float image (point data); seconds too."""
    h, w, c = image.shape
    data = vtkImageData()
    data.SetDimensions(w, h, 1)
    array = numpy_to_vtk(image.reshape(-1, c).astype(np.float64), deep=1)
    array.SetName("photo")
    data.GetPointData().SetScalars(array)
    f = vtkImageShockAdvectionFilter()
    f.SetInputData(data)
    f.SetFlowTime(t)
    f.SetDomain(domain)
    f.SetGradientScreening(screening)
    start = time.perf_counter()
    f.Update()
    seconds = time.perf_counter() - start
    out = vtk_to_numpy(f.GetOutput().GetPointData().GetArray("photo")).reshape(h, w, c).copy()
    return out, seconds


def differences(image):
    dx = np.zeros(image.shape[:2])
    dy = np.zeros(image.shape[:2])
    dx[:, :-1] = (np.diff(image, axis=1) ** 2).sum(axis=2)
    dy[:-1, :] = (np.diff(image, axis=0) ** 2).sum(axis=2)
    return np.sqrt(dx + dy)


class Scorer:
    def __init__(self, sharp):
        self.sharp = sharp
        g = differences(sharp)
        self.edges = g > np.quantile(g, 0.95)
        self.reference = g[self.edges].mean()

    def __call__(self, result):
        return {"mae": 255.0 * float(np.abs(result - self.sharp).mean()),
                "sharpness": float(differences(result)[self.edges].mean() / self.reference),
                "excess": float(max(0.0, -result.min(), result.max() - 1.0))}


def load(path):
    image = Image.open(path)
    image = image.convert("L" if image.mode in ("L", "I", "I;16") else "RGB")
    array = np.asarray(image, dtype=np.float64) / 255.0
    return array[:, :, None] if array.ndim == 2 else array


def machine():
    model = "unknown"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    return "%s, %d cores, %s, commit %s, %s" % (model, os.cpu_count(), platform.platform(), commit,
                                                 datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC"))


def timed_process(command):
    """(wall seconds of the filter from --timings, peak RSS in MB) of one fresh process."""
    run = subprocess.run(["/usr/bin/time", "-f", "%M"] + command, capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError("%s failed: %s" % (" ".join(command), run.stderr))
    total = float(run.stdout.split('"total":')[1].split(",")[0])
    rss = float(run.stderr.strip().splitlines()[-1]) / 1024.0
    return total, rss


def main():
    times = [float(t) for t in ARGS.times.split(",")]
    photos_dir = ARGS.photos or subprocess.run([os.path.join(HERE, "get_natural_photos.sh")],
                                               capture_output=True, text=True, check=True).stdout.strip()
    os.makedirs(ARGS.out, exist_ok=True)
    lines = ["# Gradient domain against value advection", "",
             "Machine: %s." % machine(),
             "Command: `/usr/bin/python3 Benchmarks/gradient_domain.py --times %s --runs %d`." % (
                 ARGS.times, ARGS.runs), ""]
    rows = []
    grid_cases = {}
    for name in PHOTOS:
        sharp = load(os.path.join(photos_dir, name))
        score = Scorer(sharp)
        for sigma in SIGMAS:
            rng = np.random.default_rng([ord(ch) for ch in name] + [int(10 * sigma)])
            blurred = gaussian_blur(sharp, sigma) + rng.normal(0.0, NOISE, sharp.shape)
            row = {"photo": name.split(".")[0], "sigma": sigma, "blurred": score(blurred)}
            for domain, label in ((0, "values"), (1, "gradients")):
                results = {}
                for t in times:
                    out, _ = shock(blurred, t, domain)
                    results[t] = (score(out), out)
                best = min(times, key=lambda t: results[t][0]["mae"])
                row[label] = {"best_t": best, "best": results[best][0],
                              "fixed": results[FIXED_T][0] if FIXED_T in results else shock_score(
                                  score, blurred, FIXED_T, domain)}
                if sigma == 2.5 and name in ("chelsea.png", "astronaut.png"):
                    grid_cases.setdefault(name, {"blurred": blurred, "sharp": sharp})[label] = results[best][1]
            # The screening sweep of the gradient domain, at its best t.
            t = row["gradients"]["best_t"]
            row["sweep"] = {lam: score(shock(blurred, t, 1, lam)[0]) for lam in SCREENINGS}
            rows.append(row)
            print("%s sigma %.1f: blurred %.2f, values %.2f (t=%g), gradients %.2f (t=%g)" % (
                name, sigma, row["blurred"]["mae"], row["values"]["best"]["mae"], row["values"]["best_t"],
                row["gradients"]["best"]["mae"], row["gradients"]["best_t"]), file=sys.stderr, flush=True)

    lines += ["## Per photo and blur", "",
              "MAE in 1/255, sharpness 1 = the original's; best = the flow time (of %s) with the lowest MAE; "
              "fixed = t = %g. Gradient screening 0.01 (the default)." % (ARGS.times, FIXED_T), "",
              "| photo | sigma | blurred MAE / sharp | values best t | MAE / sharp | gradients best t | MAE / sharp "
              "| values t=%g MAE / sharp | gradients t=%g MAE / sharp | overshoot values / gradients |" % (FIXED_T, FIXED_T),
              "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        v, g = r["values"], r["gradients"]
        lines.append("| %s | %.1f | %.2f / %.2f | %g | %.2f / %.2f | %g | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | %.3f / %.3f |" % (
            r["photo"], r["sigma"], r["blurred"]["mae"], r["blurred"]["sharpness"], v["best_t"], v["best"]["mae"],
            v["best"]["sharpness"], g["best_t"], g["best"]["mae"], g["best"]["sharpness"], v["fixed"]["mae"],
            v["fixed"]["sharpness"], g["fixed"]["mae"], g["fixed"]["sharpness"], v["best"]["excess"],
            g["best"]["excess"]))

    def ratio(key, which):
        return [r["gradients"][which][key] / r["values"][which][key] for r in rows]

    wins = sum(1 for r in rows if r["gradients"]["best"]["mae"] < r["values"]["best"]["mae"])
    lines += ["", "## Summary over %d photo-blur cases" % len(rows), "",
              "| measure | gradients / values, median | min | max |", "|---|---|---|---|"]
    for key, which, label in (("mae", "best", "MAE at each one's best t"), ("sharpness", "best", "sharpness at best t"),
                              ("mae", "fixed", "MAE at t = %g" % FIXED_T),
                              ("sharpness", "fixed", "sharpness at t = %g" % FIXED_T)):
        values = ratio(key, which)
        lines.append("| %s | %.3f | %.3f | %.3f |" % (label, statistics.median(values), min(values), max(values)))
    lines += ["", "Domain Gradients has the lower best MAE in %d of %d cases." % (wins, len(rows)), ""]
    lines += ["## Gradient screening sweep (MAE at the gradients' best t, median over the cases, "
              "relative to value advection's best)", "", "| screening | MAE ratio median | min | max |",
              "|---|---|---|---|"]
    for lam in SCREENINGS:
        values = [r["sweep"][lam]["mae"] / r["values"]["best"]["mae"] for r in rows]
        lines.append("| %g | %.3f | %.3f | %.3f |" % (lam, statistics.median(values), min(values), max(values)))

    # Time and memory: the program in fresh processes, on a large photo as 8-bit PNG.
    source = ARGS.timing_photo
    if not source:
        fetched = subprocess.run([os.path.join(HERE, "get_photo.sh")], capture_output=True, text=True)
        source = fetched.stdout.strip() if fetched.returncode == 0 else None
    if not source:
        source = os.path.join(photos_dir, max(PHOTOS, key=lambda n: np.prod(Image.open(os.path.join(photos_dir, n)).size)))
    largest = os.path.basename(source)
    png = os.path.join(ARGS.out, "timing_input.png")
    Image.open(source).convert("RGB").save(png)
    program = os.path.join(ARGS.build, "bin", "shockfilter")
    lines += ["", "## Time and memory", "",
              "`shockfilter image %s out.png --time T [--domain gradients] --timings` (8-bit RGB, %s), "
              "fresh processes, median of %d; peak RSS of the whole process (`/usr/bin/time -f %%M`)." % (
                  os.path.splitext(largest)[0] + ".png", "x".join(str(s) for s in Image.open(source).size), ARGS.runs),
              "", "| t | values s | gradients s | ratio | values MB | gradients MB |", "|---|---|---|---|---|---|"]
    for t in (256.0, FIXED_T, 4096.0):
        measured = {}
        for domain in ("values", "gradients"):
            runs = [timed_process([program, "image", png, os.path.join(ARGS.out, "timing_out.png"), "--time", "%g" % t,
                                   "--domain", domain, "--timings"]) for _ in range(ARGS.runs)]
            measured[domain] = (statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs))
        lines.append("| %g | %.3f | %.3f | %.2f | %.0f | %.0f |" % (
            t, measured["values"][0], measured["gradients"][0], measured["gradients"][0] / measured["values"][0],
            measured["values"][1], measured["gradients"][1]))

    # The picture grid.
    tiles = []
    for name, case in grid_cases.items():
        h, w = case["sharp"].shape[:2]
        crop = (slice(h // 4, h // 4 + min(200, h // 2)), slice(w // 4, w // 4 + min(200, w // 2)))
        row = [np.clip(case[k][crop], 0, 1) for k in ("blurred", "values", "gradients", "sharp")]
        row = [np.repeat(r, 3, axis=2) if r.shape[2] == 1 else r for r in row]
        tiles.append(np.concatenate(row, axis=1))
    if tiles:
        width = max(t.shape[1] for t in tiles)
        tiles = [np.pad(t, ((0, 4), (0, width - t.shape[1]), (0, 0)), constant_values=1.0) for t in tiles]
        grid = os.path.join(ARGS.out, "gradient_domain_grid.jpg")
        Image.fromarray((np.concatenate(tiles, axis=0) * 255).astype(np.uint8)).save(grid, quality=92)
        lines += ["", "Picture grid (blurred | values | gradients | original, sigma 2.5, each at its best t): `%s`." % grid]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(ARGS.out, "gradient_domain.md"), "w") as f:
        f.write(text)
    print(text)


def shock_score(score, blurred, t, domain):
    return score(shock(blurred, t, domain)[0])


if __name__ == "__main__":
    main()
