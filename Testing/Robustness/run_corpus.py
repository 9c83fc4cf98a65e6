#!/usr/bin/env python3
"""Runs shockfilter on every file of a corpus made by make_corpus.py.

    run_corpus.py CORPUSDIR SHOCKFILTER WORKDIR

Each file is copied to WORKDIR and filtered in place (OUTPUT = INPUT), so
that a refusal which damaged the file would show. Every run must end within
its time limit with exit code 0 or 2 (no signal: no crash, no abort); a
refusal (2) prints exactly one line "shockfilter: ..." on stderr and leaves
the file byte for byte as it was, and no temporary file behind. The kinds
marked "refuse" must be refused, "ok" accepted; "scaled" meshes (a unit mesh
times 1e-300 .. 1e300) must give the unit mesh's result times the scale, or be
refused; a large image under a memory limit (RLIMIT_AS, not under
AddressSanitizer) must be refused as out of memory. Then writes are made to fail (a file size limit, as a full disk
would: RLIMIT_FSIZE) for every output format: the existing target must stay.
Prints the counts; exit status 1 if anything went wrong.
"""
import concurrent.futures
import json
import os
import resource
import shutil
import subprocess
import sys

CORPUS, PROGRAM, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
TIMEOUT = 120
ARGS = {"image": ["--time", "16"], "surface": ["--time", "64"], "sharpen": ["--time", "256"]}
ENV = dict(os.environ, OMP_NUM_THREADS="1")


def run(command, file_limit=None, memory_limit=None):
    def limit():
        if file_limit is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (file_limit, file_limit))
        if memory_limit is not None:
            resource.setrlimit(resource.RLIMIT_AS, (memory_limit, memory_limit))
    try:
        done = subprocess.run(command, capture_output=True, text=True, errors="replace", timeout=TIMEOUT,
                              env=ENV, preexec_fn=limit)
        return done.returncode, done.stdout, done.stderr
    except subprocess.TimeoutExpired:
        return "hang", "", ""


def read(path):
    with open(path, "rb") as f:
        return f.read()


def leftovers(directory):
    return [name for name in os.listdir(directory) if ".partial-" in name]


def check_refusal(label, code, err, before, path, problems):
    """The checks every exit code 2 must pass; counts are kept by the caller."""
    lines = err.splitlines()
    if len(lines) != 1 or not lines[0].startswith("shockfilter: "):
        problems.append("%s: a refusal must print one line, got %r" % (label, err))
    if os.path.exists(path) and read(path) != before or not os.path.exists(path):
        problems.append("%s: LOST INPUT: the refused file changed or vanished" % label)
        return True
    return False


def off_points(path):
    words = [line.split("#")[0].split() for line in read(path).decode().splitlines()]
    words = [w for w in words if w]
    count = int(words[1][0]) if len(words[0]) == 1 else int(words[0][1])
    first = 2 if len(words[0]) == 1 else 1
    return [[float(v) for v in w] for w in words[first:first + count]]


def check_scaled(kind, directory, problems):
    """A mesh times `scale` must give the unit mesh's result times `scale`, or a refusal."""
    label, scale = kind["name"], kind["scale"]
    source, unit = os.path.join(CORPUS, kind["name"]), os.path.join(CORPUS, kind["unit"])
    out, unit_out = os.path.join(directory, "scaled.off"), os.path.join(directory, "unit.off")
    extra = ARGS[kind["command"]]
    code, _, err = run([PROGRAM, kind["command"], source, out] + extra)
    if code == 2:
        return "refused", err
    if code != 0:
        problems.append("%s: exit %s: %s" % (label, code, err))
        return "crash" if code != "hang" else "hang", err
    run([PROGRAM, kind["command"], unit, unit_out] + extra)
    ours, reference, start = off_points(out), off_points(unit_out), off_points(unit)
    # Coordinates scale; colours (the surface command's result) stay.
    worst = max(max(abs(a / scale - b) for a, b in zip(p[:3], q[:3])) for p, q in zip(ours, reference))
    worst = max([worst] + [abs(a - b) / 255.0 for p, q in zip(ours, reference) for a, b in zip(p[3:], q[3:])])
    moved = max(abs(a - b) for p, q in zip(reference, start) for a, b in zip(p[:3], q[:3]))
    changed = max([0.0] + [abs(a - b) for p, q in zip(reference, start) for a, b in zip(p[3:], q[3:])])
    if worst > 1e-6 or (moved if kind["command"] == "sharpen" else changed) < 1e-3:
        problems.append("%s: the result is not the unit result scaled (difference %g, unit moved %g)" % (label, worst, moved))
    return "ok", err


SANITIZED = b"__asan_init" in read(PROGRAM)  # AddressSanitizer reserves terabytes of address space


def check_memory(kind, problems):
    """Too little memory for the filter: one line that names what it needs, the input untouched."""
    if SANITIZED:
        return "skipped", problems
    source = os.path.join(CORPUS, kind["name"])
    code, _, err = run([PROGRAM, "image", source, source, "--time", "16"], memory_limit=200 * 2**20)
    if code != 2 or "out of memory" not in err:
        problems.append("%s: expected an out-of-memory refusal, got exit %s: %s" % (kind["name"], code, err))
        return "crash" if code not in (0, 2, "hang") else str(code), problems
    check_refusal(kind["name"], code, err, read(source), source, problems)
    return "refused", problems


def one(kind):
    """Runs one kind; returns (outcome, problems)."""
    problems = []
    if kind["expect"] == "memory":
        return check_memory(kind, problems)
    directory = os.path.join(WORK, kind["name"] + ".d")
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    if kind["expect"] == "scaled":
        outcome, err = check_scaled(kind, directory, problems)
        if outcome == "refused":
            check_refusal(kind["name"], 2, err, b"", os.path.join(CORPUS, kind["name"]), problems)
        return outcome, problems
    path = os.path.join(directory, kind["name"])
    shutil.copyfile(os.path.join(CORPUS, kind["name"]), path)
    before = read(path)
    code, _, err = run([PROGRAM, kind["command"], path, path] + ARGS[kind["command"]])
    outcome = {0: "ok", 2: "refused", "hang": "hang"}.get(code, "crash")
    if outcome in ("crash", "hang"):
        problems.append("%s: %s (exit %s): %s" % (kind["name"], outcome.upper(), code, err.strip()[-300:]))
    if code == 2 and check_refusal(kind["name"], code, err, before, path, problems):
        outcome = "lost"
    if leftovers(directory):
        problems.append("%s: temporary files left: %s" % (kind["name"], leftovers(directory)))
    expected = {"refuse": "refused", "ok": "ok"}.get(kind["expect"])
    if expected and outcome in ("ok", "refused") and outcome != expected:
        problems.append("%s: expected %s, got %s: %s" % (kind["name"], expected, outcome, err.strip()))
    return outcome, problems


# A write that fails (the file size limit stands for a full disk) must leave the target as it was.
FULL_DISK = [("png_valid.png", "image", ".png"), ("png_valid.png", "image", ".jpg"), ("png_valid.png", "image", ".tif"),
             ("png_valid.png", "image", ".bmp"), ("png_valid.png", "image", ".ppm"), ("png_valid.png", "image", ".vti"),
             ("png_valid.png", "image", ".vtk"), ("coff_valid.off", "surface", ".off"), ("coff_valid.off", "surface", ".ply"),
             ("coff_valid.off", "surface", ".vtp"), ("coff_valid.off", "surface", ".vtk"), ("off_valid.off", "sharpen", ".obj"),
             ("off_valid.off", "sharpen", ".stl")]


def full_disk(case):
    source, command, extension = case
    label = "full disk %s -> %s" % (source, extension)
    problems = []
    directory = os.path.join(WORK, "full-disk" + extension + command)
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    target = os.path.join(directory, "target" + extension)
    before = b"the existing file, which must survive\n"
    with open(target, "wb") as f:
        f.write(before)
    code, _, err = run([PROGRAM, command, os.path.join(CORPUS, source), target] + ARGS[command], file_limit=64)
    outcome = {2: "refused"}.get(code, "crash" if code not in (0, "hang") else str(code))
    if code != 2:
        problems.append("%s: expected a refusal, got exit %s: %s" % (label, code, err))
    elif check_refusal(label, code, err, before, target, problems):
        outcome = "lost"
    if leftovers(directory):
        problems.append("%s: temporary files left: %s" % (label, leftovers(directory)))
    return outcome, problems


def main():
    with open(os.path.join(CORPUS, "corpus.json")) as f:
        kinds = json.load(f)
    os.makedirs(WORK, exist_ok=True)
    counts, problems = {}, []
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(one, kinds)) + list(pool.map(full_disk, FULL_DISK))
    for outcome, found in results:
        counts[outcome] = counts.get(outcome, 0) + 1
        problems += found
    for problem in problems:
        print("FAIL:", problem)
    print("corpus: %d kinds of file, %d failed writes; outcomes: %s" % (
        len(kinds), len(FULL_DISK), ", ".join("%s %d" % kv for kv in sorted(counts.items()))))
    print("crashes %d, hangs %d, lost inputs %d, problems %d" % (
        counts.get("crash", 0), counts.get("hang", 0), counts.get("lost", 0), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
