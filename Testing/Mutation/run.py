#!/usr/bin/python3
"""Mutation testing of the shock-filter kernels (see docs/testing.md).

Each mutant in mutants.py is (file, exact original snippet, replacement): a
small semantic bug of one of the paper's steps. For every mutant the script
copies the source tree (the working tree, tracked files only) into
WORK/src once, applies the mutant there, rebuilds with ccache into WORK/build,
runs the kernel test programs and, if they all pass, the kernel, filter,
command-line, io, robustness and mpi tests through CTest (labels: every label
whose tests run the mutated code), with a time limit per mutant, and
restores the file. A mutant is

  killed    a test failed (or the run exceeded the time limit),
  survived  every test passed,
  stale     its snippet is not in the file exactly once (the code moved on),
  invalid   the mutated code does not compile.

The kill rate is killed / (killed + survived). Usage:

  /usr/bin/python3 Testing/Mutation/run.py [--work DIR] [--only ID,...]
         [--labels REGEX] [--timeout SECONDS] [--jobs N] [--list]
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

os.environ.setdefault("CCACHE_BASEDIR", os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from mutants import MUTANTS  # noqa: E402

# Stage 1: the kernel test programs, run directly (one process each: seconds).
KERNEL_TARGETS = ["TestShockKernels", "TestShockFit"]
# The step-by-step tests, which take a second or two: run first.
STEP_TESTS = "GridSteps.*:GridFlows.*:MeshSteps.*:FitOperators.*"
# Stage 2, for a mutant that survives stage 1: everything the filter and
# command-line tests run, through CTest.
# ("all": the io and robustness tests' programs, the plugin and the Python
# package that the mpi tests load.)
ALL_TARGETS = ["all"]


def run(command, cwd, timeout=None, log=None):
    """Run a command; returns (exit code or None on timeout, seconds)."""
    start = time.time()
    try:
        result = subprocess.run(command, cwd=cwd, stdout=log or subprocess.DEVNULL,
                                stderr=subprocess.STDOUT, timeout=timeout)
        return result.returncode, time.time() - start
    except subprocess.TimeoutExpired:
        return None, time.time() - start


def copy_tree(work):
    """Copy the tracked files of the working tree (as they are now) into WORK/src."""
    src = os.path.join(work, "src")
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True,
                           stdout=subprocess.PIPE).stdout.decode().split("\0")
    for name in filter(None, files):
        target = os.path.join(src, name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        source = os.path.join(ROOT, name)
        if os.path.isfile(source):
            if not os.path.exists(target) or open(source, "rb").read() != open(target, "rb").read():
                shutil.copyfile(source, target)  # a new mtime: make rebuilds
    # Files an earlier copy left that are no longer tracked (moved or removed):
    # a stale header of the same name on another include folder would be built.
    tracked = set(filter(None, files))
    for folder, subfolders, names in os.walk(src):
        if folder == src:
            subfolders[:] = [d for d in subfolders if d != "build"]  # the build tree lives in src/build
        for name in names:
            path = os.path.join(folder, name)
            if os.path.relpath(path, src) not in tracked:
                os.remove(path)
    return src


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--work", default=os.path.join(ROOT, "build-mutation"))
    parser.add_argument("--only", default="", help="comma-separated mutant ids")
    parser.add_argument("--labels", default="kernels|filters|cli|io|robustness|mpi")
    parser.add_argument("--timeout", type=float, default=900.0, help="seconds per mutant's tests")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--list", action="store_true", help="list the mutants and exit")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 when a mutant's snippet is not in its file exactly once (stale)")
    parser.add_argument("--skip-baseline", action="store_true",
                        help="do not first check that the unmutated tree passes its tests")
    parser.add_argument("--kernel-baseline", action="store_true",
                        help="check only the kernel test programs on the unmutated tree")
    args = parser.parse_args()

    mutants = MUTANTS
    if args.only:
        wanted = set(args.only.split(","))
        mutants = [m for m in MUTANTS if m["id"] in wanted]
    if args.list:
        for m in mutants:
            print(f"{m['id']:28s} {m['file']}: {m['bug']}")
        return 0
    if args.check:
        stale = []
        for m in mutants:
            path = os.path.join(ROOT, m["file"])
            text = open(path).read() if os.path.exists(path) else ""
            if text.count(m["original"]) != 1:
                stale.append(m["id"])
                print("stale: %s (%s: the snippet occurs %d times)" % (m["id"], m["file"], text.count(m["original"])))
        print("%d mutants, %d stale" % (len(mutants), len(stale)))
        return 1 if stale else 0

    work = os.path.abspath(args.work)
    os.makedirs(work, exist_ok=True)
    src = copy_tree(work)
    # An interrupted run may have built a mutant: rebuild every mutated file.
    for name in {m["file"] for m in MUTANTS}:
        if os.path.exists(os.path.join(src, name)):
            os.utime(os.path.join(src, name))
    # The build inside the copy, as build/ inside the worktree: the same relative
    # paths, so that ccache (with CCACHE_BASEDIR) reuses the worktree's objects.
    build = os.path.join(src, "build")
    # ccache when installed (Debian's ccache); without it every mutant rebuilds what it touches.
    launcher = shutil.which("ccache") or ""
    env_launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=" + launcher, "-DCMAKE_C_COMPILER_LAUNCHER=" + launcher]
    code, _ = run(["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release"] + env_launcher,
                  cwd=work)
    def build_command(targets):
        return ["cmake", "--build", build, "-j", str(args.jobs), "--target"] + targets

    def kernel_tests(log, deadline, fail_fast=True):
        """Stage 1: the kernel test programs, the fast step tests first; 0 when all pass."""
        runs = [(program, ["--gtest_filter=" + STEP_TESTS]) for program in KERNEL_TARGETS]
        runs += [(program, []) for program in KERNEL_TARGETS]
        for program, extra in runs:
            left = deadline - time.time()
            if left <= 0:
                return None
            command = [os.path.join(build, "bin", program), "--gtest_brief=1"] + extra
            code, _ = run(command + (["--gtest_fail_fast"] if fail_fast else []), cwd=work,
                          timeout=left, log=log)
            if code != 0:
                return code
        return 0

    test_command = ["ctest", "--test-dir", build, "-L", args.labels, "-j", str(args.jobs),
                    "--stop-on-failure", "--timeout", "300"]
    code, seconds = run(build_command(ALL_TARGETS), cwd=work)
    if code != 0:
        print("mutate: the unmutated tree does not build", file=sys.stderr)
        return 2
    if args.kernel_baseline:
        start = time.time()
        if kernel_tests(None, start + args.timeout, fail_fast=False) != 0:
            print("mutate: the unmutated tree fails its kernel tests", file=sys.stderr)
            return 2
        print(f"baseline: kernel tests pass in {time.time() - start:.0f} s", flush=True)
    elif not args.skip_baseline:
        code, seconds = run(test_command, cwd=work, timeout=args.timeout)
        if code != 0:
            print("mutate: the unmutated tree fails its tests", file=sys.stderr)
            return 2
        print(f"baseline: tests pass in {seconds:.0f} s", flush=True)

    results = {"killed": [], "survived": [], "stale": [], "invalid": []}
    logs = os.path.join(work, "logs")
    os.makedirs(logs, exist_ok=True)
    for m in mutants:
        path = os.path.join(src, m["file"])
        original = open(path).read() if os.path.exists(path) else ""
        if original.count(m["original"]) != 1:
            results["stale"].append(m["id"])
            print(f"{m['id']:36s} stale (snippet found {original.count(m['original'])} times)",
                  flush=True)
            continue
        start = time.time()
        stage = "kernels"
        try:
            with open(path, "w") as f:
                f.write(original.replace(m["original"], m["replacement"]))
            with open(os.path.join(logs, m["id"] + ".log"), "w") as log:
                code, _ = run(build_command(KERNEL_TARGETS), cwd=work, log=log)
                if code != 0:
                    outcome = "invalid"
                else:
                    code = kernel_tests(log, start + args.timeout)
                    if code == 0:
                        stage = "all"
                        code, _ = run(build_command(ALL_TARGETS), cwd=work, log=log)
                        if code == 0:
                            left = max(1.0, start + args.timeout - time.time())
                            code, _ = run(test_command, cwd=work, timeout=left, log=log)
                        else:
                            code = "build"
                    outcome = ("invalid" if code == "build" else
                               "survived" if code == 0 else "killed")
        finally:
            with open(path, "w") as f:
                f.write(original)
        results[outcome].append(m["id"])
        print(f"{m['id']:36s} {outcome:8s} ({stage} tests, {time.time() - start:4.0f} s)",
              flush=True)
    # Leave the build matching the unmutated sources.
    run(build_command(ALL_TARGETS), cwd=work)

    decided = len(results["killed"]) + len(results["survived"])
    rate = 100.0 * len(results["killed"]) / decided if decided else 0.0
    print(f"\nmutants: {len(mutants)}; killed {len(results['killed'])}, survived "
          f"{len(results['survived'])}, stale {len(results['stale'])}, invalid "
          f"{len(results['invalid'])}; kill rate {rate:.1f} %")
    for outcome in ("survived", "stale", "invalid"):
        if results[outcome]:
            print(f"{outcome}: {', '.join(results[outcome])}")
    return 0 if not results["survived"] else 1


if __name__ == "__main__":
    sys.exit(main())
