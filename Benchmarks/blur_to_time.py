"""Which flow time sharpens which blur: the table of README.md ("Choosing t").

  /usr/bin/python3 Benchmarks/blur_to_time.py [build/lib/python3.11/site-packages]

A 2D test picture (a straight step, a disc of radius 20 and a thin bar, values
0..1, 128 x 128 samples) is blurred with a Gaussian of sigma = 0.5 ... 6
samples, then filtered with vtkImageShockAdvectionFilter (defaults except
FlowTime) at t = 4, 8, ..., 2^20. For each blur the table gives the smallest t
at which the straight edge is sharp again (its 10-90 % rise within 2.5
samples: the shock itself spans 2)
and, at that t, the mean absolute error to the unblurred picture (in % of the
range) and that of the blurred input. Beyond it the flow keeps flattening:
fine features (the bar) merge or vanish, the posterised look.
"""
import sys

import numpy as np

sys.path.insert(0, sys.argv[1] if len(sys.argv) > 1 else "build/lib/python3.11/site-packages")
from shockfilters import vtkImageShockAdvectionFilter  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

N = 128


def picture():
    y, x = np.mgrid[0:N, 0:N].astype(float)
    sharp = (x >= 64.0).astype(float)                       # the straight step (rows 0..39)
    disc = np.hypot(x - 40.0, y - 88.0) <= 20.0
    bar = (np.abs(x - 96.0) <= 1.0) & (y >= 70.0)
    sharp[y >= 48] = 0.0
    sharp[disc | bar] = 1.0
    return sharp


def gaussian(values, sigma):
    if sigma <= 0:
        return values.copy()
    radius = int(np.ceil(4 * sigma))
    k = np.exp(-0.5 * (np.arange(-radius, radius + 1) / sigma) ** 2)
    k /= k.sum()
    padded = np.pad(values, radius, mode="edge")
    rows = np.apply_along_axis(lambda r: np.convolve(r, k, mode="valid"), 1, padded)
    return np.apply_along_axis(lambda c: np.convolve(c, k, mode="valid"), 0, rows)


def shock(values, t):
    image = vtkImageData()
    image.SetDimensions(N, N, 1)
    array = numpy_to_vtk(values.ravel(), deep=1)
    array.SetName("I")
    image.GetPointData().SetScalars(array)
    f = vtkImageShockAdvectionFilter()
    f.SetInputData(image)
    f.SetFlowTime(t)
    f.Update()
    return vtk_to_numpy(f.GetOutput().GetPointData().GetArray("I")).reshape(N, N)


def rise(values):
    """10-90 % width of the straight edge, in samples (rows 8..31, linear interpolation)."""
    widths = []
    for row in values[8:32]:
        low, high = row[:48].mean(), row[80:].mean()
        if high - low < 0.5:
            return float("inf")
        r = (row - low) / (high - low)
        crossings = []
        for level in (0.1, 0.9):
            i = int(np.argmax(r[40:90] >= level)) + 40
            crossings.append(i - 1 + (level - r[i - 1]) / max(r[i] - r[i - 1], 1e-12))
        widths.append(crossings[1] - crossings[0])
    return float(np.median(widths))


def main():
    sharp = picture()
    print("| input blur sigma (samples) | edge rise blurred (samples) | smallest t that re-sharpens "
          "(rise <= 2.5) | error blurred / after (% of range) |")
    print("|---|---|---|---|")
    for sigma in (0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0):
        blurred = gaussian(sharp, sigma)
        found = None
        for k in range(2, 21):
            t = float(2 ** k)
            out = shock(blurred, t)
            if rise(out) <= 2.5:
                found = (t, out)
                break
        before = 100 * np.abs(blurred - sharp).mean()
        if found:
            t, out = found
            print("| %.1f | %.1f | %g | %.2f / %.2f |" % (sigma, rise(blurred), t, before,
                                                         100 * np.abs(out - sharp).mean()), flush=True)
        else:
            print("| %.1f | %.1f | > 2^20 | %.2f / - |" % (sigma, rise(blurred), before), flush=True)


if __name__ == "__main__":
    main()
