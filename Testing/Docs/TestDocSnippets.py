"""Run every code block of a Markdown file exactly as written.

Usage: python3 TestDocSnippets.py --source SRC --build BUILD --work DIR
           [--pvpython P] [--python PY] [--pythonpath DIR] FILE.md

Each fenced block tagged python, sh/bash or cpp is extracted from FILE.md (not
copied anywhere) and run in a fresh folder under DIR that looks like the
repository as a user has it after building: every top-level entry of SRC is
linked in, `build` is the build folder, and the fixture files a user would
bring are there (photo.png, ct.vti with the point array "density", scan.ply
with colours, script.py, a pvbatch script). The build's bin/ is first on PATH
and PYTHONPATH holds the build's Python package shockfilters.

- python: with pvpython when it uses paraview.simple (under `xvfb-run -a`
  when it shows or renders), else with PY;
- sh/bash: `bash -e`; Open MPI may run as root and oversubscribe (environment);
- cpp: a complete program, compiled against the build tree with
  find_package(ShockFilters) and VTK, then run.

A block passes when it exits with 0 and prints no VTK error or warning
("ERR|", "WARN|") and no
Python traceback. A block that needs a missing tool (xvfb-run, mpirun,
pvpython) is skipped and says so; a block preceded by the line
`<!-- snippet: not run: REASON -->` is skipped with that reason (for commands
that run this test suite itself or take most of an hour). Blocks without a
language (file trees, output) are not code and are not run.

Exit code 0, 1 when a block failed, 77 (CTest: skipped) when every block was
skipped.
"""
import argparse
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

FENCE = re.compile(r"^(?P<indent> *)```(?P<lang>[\w+-]*)[^\n]*\n(?P<body>.*?)^(?P=indent)```[ \t]*$",
                   re.M | re.S)
NOT_RUN = re.compile(r"<!--\s*snippet:\s*not run:\s*(?P<why>.*?)\s*-->\s*$")
LANGUAGES = {"python": "python", "py": "python", "sh": "sh", "bash": "sh", "shell": "sh",
             "cpp": "cpp", "c++": "cpp", "cxx": "cpp"}
RENDERS = re.compile(r"\b(Show|Render|SaveScreenshot|CreateView|GetActiveViewOrCreate)\s*\(")
FAILURE = re.compile(r"ERR\||WARN\||Traceback \(most recent call last\)")
TIMEOUT = 900
FIXTURE_SCRIPT = pathlib.Path(__file__).resolve().parent.parent / "Python" / "MakeUserFixtures.py"


CPP_PROJECT = """cmake_minimum_required(VERSION 3.16)
project(Snippet LANGUAGES C CXX)
set(CMAKE_CXX_STANDARD 17)
find_package(ShockFilters REQUIRED)
find_package(VTK REQUIRED COMPONENTS CommonCore CommonDataModel CommonExecutionModel
  FiltersCore FiltersSources ImagingCore ImagingSources IOImage IOLegacy IOPLY IOXML
  PATHS "${ParaView_DIR}/vtk" NO_DEFAULT_PATH)
add_executable(snippet snippet.cxx)
target_link_libraries(snippet PRIVATE VTK::FiltersShock ${VTK_LIBRARIES})
vtk_module_autoinit(TARGETS snippet MODULES VTK::FiltersShock ${VTK_LIBRARIES})
"""


def blocks(path):
    """(line, language, code, reason not to run or None) of each code block."""
    text = path.read_text()
    for match in FENCE.finditer(text):
        language = LANGUAGES.get(match.group("lang").lower())
        if language is None:
            continue
        indent = len(match.group("indent"))
        code = "".join(l[indent:] if l[:indent].strip() == "" else l
                       for l in match.group("body").splitlines(True))
        before = text[:match.start()].rstrip("\n").rsplit("\n", 1)[-1]
        not_run = NOT_RUN.search(before)
        yield (text[:match.start()].count("\n") + 1, language, code,
               not_run.group("why") if not_run else None)


def sandbox(args, index):
    folder = pathlib.Path(args.work) / str(index)
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    for entry in pathlib.Path(args.source).iterdir():
        if not entry.name.startswith(".") and entry.name != "build":
            (folder / entry.name).symlink_to(entry)
    (folder / "build").symlink_to(pathlib.Path(args.build).resolve())
    for fixture in (pathlib.Path(args.work) / "fixtures").iterdir():
        shutil.copy(fixture, folder / fixture.name)
    return folder


def environment(args):
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(pathlib.Path(args.build) / "bin"), env.get("PATH", "")])
    if args.pythonpath:
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [args.pythonpath, env.get("PYTHONPATH")]))
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    return env


def command(args, language, code, folder):
    """The command running one block, or (None, reason to skip)."""
    if language == "python":
        (folder / "snippet.py").write_text(code)
        if "paraview" not in code:
            return [args.python or sys.executable, "snippet.py"], None
        if not args.pvpython:
            return None, "pvpython not found"
        if RENDERS.search(code):
            if not shutil.which("xvfb-run"):
                return None, "renders, and xvfb-run is not installed"
            # -noreset: pvpython opens a test window first; a reset would drop the next.
            return ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24 -noreset", args.pvpython, "snippet.py"], None
        return [args.pvpython, "--force-offscreen-rendering", "snippet.py"], None
    if language == "sh":
        for tool in ("xvfb-run", "mpirun", "pvpython", "pvbatch"):
            if re.search(r"(^|[\s;&|(])%s\b" % tool, code) and not shutil.which(tool):
                return None, tool + " is not installed"
        (folder / "snippet.sh").write_text(code)
        return ["bash", "-e", "snippet.sh"], None
    (folder / "snippet.cxx").write_text(code)
    (folder / "CMakeLists.txt").unlink()  # the repository's, linked in
    (folder / "CMakeLists.txt").write_text(CPP_PROJECT)
    return ["sh", "-e", "-c",
            'cmake -S . -B cpp-build -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=$0" '
            '-DCMAKE_CXX_COMPILER_LAUNCHER="$(command -v ccache || true)" >/dev/null '
            "&& cmake --build cpp-build >/dev/null && ./cpp-build/snippet",
            str(pathlib.Path(args.build).resolve())], None


def main():
    parser = argparse.ArgumentParser()
    for option in ("--source", "--build", "--work"):
        parser.add_argument(option, required=True)
    parser.add_argument("--pvpython")
    parser.add_argument("--python")
    parser.add_argument("--pythonpath")
    parser.add_argument("markdown")
    args = parser.parse_args()
    markdown = pathlib.Path(args.markdown)
    shutil.rmtree(args.work, ignore_errors=True)
    fixtures = pathlib.Path(args.work) / "fixtures"
    fixtures.mkdir(parents=True)
    subprocess.run([args.python or sys.executable, str(FIXTURE_SCRIPT)], cwd=fixtures, check=True)

    counts = {"PASS": 0, "FAIL": 0, "SKIP": 0}
    for index, (line, language, code, not_run) in enumerate(blocks(markdown)):
        where = "%s:%d %s" % (markdown.name, line, language)
        if not_run:
            counts["SKIP"] += 1
            print("SKIP %s: not run: %s" % (where, not_run))
            continue
        folder = sandbox(args, index)
        cmd, skip = command(args, language, code, folder)
        if cmd is None:
            counts["SKIP"] += 1
            print("SKIP %s: %s" % (where, skip))
            continue
        start = time.time()
        try:
            run = subprocess.run(cmd, cwd=folder, env=environment(args), stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, text=True, timeout=TIMEOUT)
            output, code_ok = run.stdout, run.returncode == 0
        except subprocess.TimeoutExpired as expired:
            output, code_ok = (expired.stdout or "") + "\n(timed out)", False
        ok = code_ok and not FAILURE.search(output)
        counts["PASS" if ok else "FAIL"] += 1
        print("%s %s (%.1f s, in %s)" % ("PASS" if ok else "FAIL", where, time.time() - start, folder))
        if not ok:
            print("---- code\n%s---- output\n%s----" % (code, output[-6000:]))
    print("%(PASS)d passed, %(FAIL)d failed, %(SKIP)d skipped" % counts)
    if counts["FAIL"]:
        return 1
    return 77 if counts["SKIP"] and not counts["PASS"] else 0


if __name__ == "__main__":
    sys.exit(main())
