"""userbench: issue #18's figures as users meet them (run it through userbench.sh).

Every figure is the median, with min and max, of N fresh processes of the
program (`shockfilter COMMAND IN OUT OPTIONS --timings --threads T`): the
filter's `total` and its phases from --timings (reading and writing excluded),
and the process's peak resident set (getrusage of the child, ru_maxrss) per
sample (pixel, voxel or vertex). The re-Apply rows time the second update of a
pvpython pipeline after FlowTime alone changed; the G'MIC row compares the time
to 90 % of the steady state (see userbench_gmic.py). Markdown on stdout,
progress on stderr.
"""
import argparse
import json
import os
import platform
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import userbench_gmic  # noqa: E402
from userbench_inputs import HERE, Inputs, log  # noqa: E402

PHASES = {"image": ["flow", "advection"], "surface": ["setup", "flow", "advection"],
          "sharpen": ["preprocessing", "flow", "advection", "fitting"]}


class Row:
    """A program row; `limit` (seconds): the total every run must stay below,
    counted in the table (runs at or above it)."""
    def __init__(self, name, work, command, make_input, options, goal, unit="pixel", limit=None):
        self.name, self.work, self.command, self.make_input = name, work, command, make_input
        self.options, self.goal, self.unit, self.limit = options, goal, unit, limit


ROWS = [
    Row("photo", "1368×1824 RGB photo, t = 1024, fixed flow", "image",
        Inputs.photo_1368x1824, ["--time", "1024", "--flow", "fixed"], "< 0.25 s in every run",
        limit=0.25),
    Row("colours", "416K-vertex RGB mesh colours (armadillo 2×), t = 4096", "surface",
        Inputs.armadillo_colours, ["--time", "4096"], "< 0.40 s", "vertex"),
    Row("sharpen", "640K-vertex scan sharpened (dragon 3×), t = 2048", "sharpen",
        lambda i: i.dragon(3), ["--time", "2048"], "< 1.2 s", "vertex"),
    Row("volume", "256³ float volume, t = 64", "image", lambda i: i.volume(256),
        ["--time", "64"], "< 1.5 s, ≤ 32 bytes/voxel", "voxel"),
    Row("photo8000", "8000×8000 RGB photo, t = 1024", "image", Inputs.photo_8000x8000,
        ["--time", "1024"], "≤ 30 bytes/pixel"),
    Row("sharpen4x", "2.56M-vertex scan sharpened (dragon 4×), t = 2048", "sharpen",
        lambda i: i.dragon(4), ["--time", "2048"], "scaling", "vertex"),
    Row("volume512", "512³ float volume, t = 64", "image", lambda i: i.volume(512),
        ["--time", "64", "--max-samples", "200000000"], "time, peak", "voxel"),
    Row("small-image", "64×48 RGB photo window, t = 64", "image", Inputs.photo_64x48,
        ["--time", "64"], "2 threads not slower than 1"),
    Row("small-mesh", "482-vertex sphere colours, t = 64", "surface", Inputs.small_mesh,
        ["--time", "64"], "2 threads not slower than 1", "vertex"),
]
REAPPLY = {"reapply-colours": ("colours", Inputs.armadillo_colours, 4096, 2048),
           "reapply-sharpen": ("sharpen", lambda i: i.dragon(3), 2048, 1024)}
ALL = [r.name for r in ROWS] + list(REAPPLY) + ["gmic"]


def run_process(command, env=None):
    """Runs `command` to its end: (wall seconds, stdout, peak resident bytes)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.perf_counter()
        process = subprocess.Popen(command, stdout=out, stderr=err, env=env)
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - start
        process.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        if process.returncode != 0:
            sys.exit("userbench: exit code %d from %s\n%s" % (
                process.returncode, shlex.join(command), err.read().decode(errors="replace")))
        return wall, out.read().decode(), usage.ru_maxrss * 1024


def spread(values, digits=3):
    """'median (min–max)' of a list of numbers."""
    if not values:
        return "-"
    form = "%%.%df" % digits
    median = form % statistics.median(values)
    if len(values) == 1:
        return median
    return "%s (%s–%s)" % (median, form % min(values), form % max(values))


def measure_row(row, args, inputs, workdir):
    """Table lines and the command of one program row, for each thread count."""
    source = row.make_input(inputs)
    output = os.path.join(workdir, "out" + os.path.splitext(source)[1])
    template = [args.program, row.command, source, output] + row.options + ["--timings"]
    lines = []
    for threads in args.threads:
        command = template + ["--threads", str(threads)]
        totals, peaks, bytes_, phases = [], [], [], {p: [] for p in PHASES[row.command]}
        for run in range(args.runs):
            _, stdout, peak = run_process(command)
            timings = json.loads(stdout.strip().splitlines()[-1])
            samples = timings.get("samples", timings.get("points"))
            totals.append(timings["total"])
            peaks.append(peak / samples)
            bytes_.append(peak)
            for p in phases:
                phases[p].append(timings[p])
            log("%s threads=%d run %d: total %.4f s, peak %.0f bytes/%s" % (
                row.name, threads, run + 1, timings["total"], peak / samples, row.unit))
            os.remove(output)
        phase_text = ", ".join("%s %.3f" % (p, statistics.median(v)) for p, v in phases.items())
        total_text = spread(totals)
        if row.limit is not None:
            total_text += "; %d of %d runs ≥ %g s (slowest %.4f)" % (
                sum(t >= row.limit for t in totals), len(totals), row.limit, max(totals))
        lines.append("| %s | %d | %s | %s | %s per %s (%.0f MiB) | %s |" % (
            row.work, threads, total_text, phase_text, spread(peaks, 0), row.unit,
            statistics.median(bytes_) / 2**20, row.goal))
    shown = template[:3] + ["OUT" + os.path.splitext(source)[1]] + template[4:]
    return lines, shlex.join(shown + ["--threads", "T"])


def measure_reapply(name, args, inputs):
    kind, make_input, first_t, second_t = REAPPLY[name]
    source = make_input(inputs)
    script = os.path.join(HERE, "reapply.py")
    template = [args.pvpython, script, "--plugin", args.plugin, "--filter", kind, "--input", source,
                "--time", str(first_t), "--second-time", str(second_t)]
    lines = []
    for threads in args.threads:
        firsts, seconds = [], []
        for run in range(args.runs):
            _, stdout, _ = run_process(template + ["--threads", str(threads)])
            result = json.loads(stdout.strip().splitlines()[-1])
            firsts.append(result["first"])
            seconds.append(result["second"])
            log("%s threads=%d run %d: first %.3f s, second %.3f s" % (
                name, threads, run + 1, result["first"], result["second"]))
        lines.append("| re-Apply in pvpython, %s: FlowTime %g → %g | %d | %s | first Apply %s | - | "
                     "second < first |" % (kind, first_t, second_t, threads, spread(seconds),
                                           spread(firsts)))
    return lines, shlex.join(template + ["--threads", "T"])


def source_commit(program):
    """The commit of the source tree of the build that holds `program`."""
    build = os.path.dirname(os.path.dirname(os.path.abspath(program)))
    source = None
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as cache:
            for line in cache:
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    source = line.split("=", 1)[1].strip()
    except OSError:
        return "unknown (no CMakeCache.txt next to the program)"
    described = subprocess.run(["git", "-C", source, "describe", "--always", "--dirty"],
                               stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    return "%s (%s)" % (described.stdout.strip() or "unknown", source)


def machine():
    model = "unknown CPU"
    with open("/proc/cpuinfo") as info:
        for line in info:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    with open("/proc/meminfo") as info:
        memory = int(info.readline().split()[1]) / 1024 / 1024
    return "%s, %d hardware threads, %.1f GiB RAM, %s; load average %s" % (
        model, os.cpu_count(), memory, platform.platform(),
        " ".join("%.2f" % x for x in os.getloadavg()))


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="userbench.sh", description=__doc__.split("\n\n")[0],
        epilog="rows: " + ", ".join(ALL) + ". Inputs are written once into --cache; "
        "they need the scans of Benchmarks/get_meshes.sh and the photo of Benchmarks/get_photo.sh "
        "(fetched when missing), and meshbench and shockbench in --tools (the build's bin/).")
    parser.add_argument("--build", default="build", help="build folder (default: build)")
    parser.add_argument("--program", help="the shockfilter program (default: BUILD/bin/shockfilter)")
    parser.add_argument("--tools", help="folder of meshbench, shockbench (default: BUILD/bin)")
    parser.add_argument("--plugin", help="ShockFilters.so for the re-Apply rows "
                        "(default: under BUILD/lib)")
    parser.add_argument("--pvpython", default="pvpython")
    parser.add_argument("--rows", default="photo,colours,sharpen,volume,photo8000,sharpen4x,"
                        "small-image,small-mesh,reapply-colours,reapply-sharpen,gmic",
                        help="comma-separated rows, or 'all' (default: all but volume512)")
    parser.add_argument("--runs", type=int, default=5, help="fresh processes per figure (default 5)")
    parser.add_argument("--threads", default="1,2", help="thread counts (default 1,2)")
    parser.add_argument("--cache", default=os.path.join(
        os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "shockfilters", "userbench"),
        help="folder of the inputs (default ~/.cache/shockfilters/userbench)")
    parser.add_argument("--photo", help="the photo (default: Benchmarks/get_photo.sh)")
    parser.add_argument("--mesh-dir", help="the scans (default: meshbench's)")
    parser.add_argument("--no-install", action="store_true",
                        help="gmic row: do not run scripts/install-deps.sh --benchmarks")
    userbench_gmic.add_arguments(parser)
    args = parser.parse_args(argv)
    args.rows = ALL[:] if args.rows == "all" else [r for r in args.rows.split(",") if r]
    unknown = [r for r in args.rows if r not in ALL]
    if unknown:
        parser.error("unknown rows %s (rows: %s)" % (", ".join(unknown), ", ".join(ALL)))
    args.threads = [int(t) for t in args.threads.split(",")]
    args.program = os.path.abspath(args.program or os.path.join(args.build, "bin", "shockfilter"))
    args.tools = os.path.abspath(args.tools or os.path.join(args.build, "bin"))
    if not args.plugin:
        plugins = [os.path.join(d, f) for d, _, files in os.walk(os.path.join(args.build, "lib"))
                   for f in files if f == "ShockFilters.so"]
        args.plugin = os.path.abspath(plugins[0]) if plugins else "ShockFilters.so"
    if not os.access(args.program, os.X_OK):
        parser.error("no program %s (give --build or --program)" % args.program)
    return args


def main(argv):
    args = parse_arguments(argv)
    inputs = Inputs(args.cache, args.tools, args.photo, args.mesh_dir)
    header = ["| work | threads | total (s): median (min–max) | phases (s, median) | "
              "peak (bytes per sample): median (min–max) | goal |", "|---|---:|---|---|---|---|"]
    lines, commands, extra = [], [], []
    with tempfile.TemporaryDirectory(prefix="userbench.") as workdir:
        for name in args.rows:
            log("[%s]" % name)
            if name in REAPPLY:
                row_lines, command = measure_reapply(name, args, inputs)
            elif name == "gmic":
                row_lines, command, extra = userbench_gmic.compare(args, inputs, workdir, run_process)
            else:
                row_lines, command = measure_row(next(r for r in ROWS if r.name == name),
                                                 args, inputs, workdir)
            lines += row_lines
            commands.append(command)
    print("## userbench (issue #18), %s\n" % time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()))
    print("- machine: %s" % machine())
    print("- program: `%s`, commit %s" % (args.program, source_commit(args.program)))
    print("- each figure: median (min–max) of %d fresh processes; total and phases from "
          "`--timings` (the filter only, no reading or writing); peak = the process's "
          "ru_maxrss over the input's samples\n" % args.runs)
    print("\n".join(header + lines))
    print("\nCommands (T = threads; inputs in %s):\n" % args.cache)
    print("\n".join("    " + c for c in commands))
    if extra:
        print("\n" + "\n".join(extra))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
