#!/usr/bin/env bash
# The whole test suite, in stages (SHOCK_TEST_STAGES, default "main sanitize fuzz"):
#  main      installs what is missing, builds build/, runs every CTest test
#            (GoogleTest kernel, filter and IO tests, the command line, the corpus
#            of damaged files, pvpython plugin, GUI and MPI tests);
#  sanitize  builds the project a second time with -fsanitize=address,undefined
#            (build-asan/, VTK module, program and tests, no plugin) and runs the
#            kernel, filter, IO, command-line and corpus tests under it;
#  fuzz      builds the libFuzzer targets with clang (build-fuzz/) and runs each
#            from Testing/Fuzz/seeds/<format> for a fixed number of runs from a
#            fixed seed (the same search on every machine; SHOCK_FUZZ_RUNS,
#            SHOCK_FUZZ_SEED (0 = random) and SHOCK_FUZZ_SECONDS change it);
#            an input that crashes one is left in build-fuzz/crashes/ (add it to
#            the seeds as crash-<what> once fixed: it stays as a regression test).
# e.g. `SHOCK_TEST_STAGES=main bash scripts/test.sh` runs the first stage only.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
stages="${SHOCK_TEST_STAGES:-main sanitize fuzz}"
jobs="$(nproc)"
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
# ParaView's VTK: the sanitizer and fuzz builds use it without the plugin.
vtk_dir="$(dirname "$(find /usr/lib -path '*paraview-*/vtk/vtk-config.cmake' -print -quit 2>/dev/null)")"
sanitizers="-fsanitize=address,undefined -fno-omit-frame-pointer"
# Leak checks off: VTK 9.2's own writers leak on a failed write (vtkJPEGWriter's
# file name buffers), which the tests make happen on purpose.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}"

stage() { echo "== test.sh: $1 ($(date -u +%H:%M:%S))"; }

if [[ " $stages " == *" main "* ]]; then
  stage "main: build and the whole CTest suite"
  bash "$root/scripts/build.sh"
  # One test at a time: each test already uses every core through OpenMP.
  ctest --test-dir "$root/build" --output-on-failure --timeout 900
else
  bash "$root/scripts/install-deps.sh"
fi

if [[ " $stages " == *" sanitize "* ]]; then
  stage "sanitize: build-asan with $sanitizers"
  cmake -S "$root" -B "$root/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" \
    -DSHOCK_ENABLE_PARAVIEW=OFF -DVTK_DIR="$vtk_dir" -DSHOCK_ENABLE_AVX2=ON \
    -DCMAKE_CXX_FLAGS="$sanitizers -fno-sanitize-recover=all" -DCMAKE_C_FLAGS="$sanitizers" \
    -DCMAKE_EXE_LINKER_FLAGS="$sanitizers" -DCMAKE_SHARED_LINKER_FLAGS="$sanitizers"
  cmake --build "$root/build-asan" --parallel "$jobs"
  # As many tests at a time as cores (results do not depend on the thread count): 7 min measured.
  ctest --test-dir "$root/build-asan" --output-on-failure --timeout 1800 --parallel "$jobs" -L 'kernels|filters|io|cli|robustness'
fi

if [[ " $stages " == *" fuzz "* ]]; then
  # A bounded search with fixed parameters: seed 1, a number of runs per target
  # (SHOCK_FUZZ_RUNS overrides it; 0 replays the seeds only; -1 searches until
  # the time limit SHOCK_FUZZ_SECONDS, otherwise only a safety net), the seeds
  # in name order (-seed_inputs: a directory's order depends on the file
  # system), a scratch file name of fixed length, no comparison tracing
  # (-use_cmp=0: it feeds pointer values into the mutations), no address
  # randomisation (setarch -R where allowed), the same environment and
  # arguments (env -i, relative paths). The first thousands of inputs are then
  # the same on every run; later ones can differ, because VTK's uninstrumented
  # readers take address-dependent paths on damaged files (docs/files.md).
  stage "fuzz: libFuzzer targets, seed ${SHOCK_FUZZ_SEED:-1}, ${SHOCK_FUZZ_RUNS:-100000 to 300000} runs each, at most ${SHOCK_FUZZ_SECONDS:-600} s each"
  fuzz="$root/build-fuzz"
  cmake -S "$root" -B "$fuzz" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSHOCK_FUZZ=ON -DBUILD_TESTING=OFF \
    -DSHOCK_ENABLE_PARAVIEW=OFF -DVTK_DIR="$vtk_dir" \
    -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer" \
    -DCMAKE_EXE_LINKER_FLAGS="$sanitizers" -DCMAKE_SHARED_LINKER_FLAGS="$sanitizers"
  # Runs per target: 1 to 3 minutes each on a shared 2-core machine (2.4 million, about 25 minutes in all).
  declare -A fuzz_runs=([png]=200000 [jpg]=200000 [tif]=300000 [bmp]=300000 [ppm]=300000 [vtk]=100000
    [vti]=100000 [off]=300000 [ply]=300000 [stl]=100000 [obj]=100000 [vtp]=100000)
  formats=(png jpg tif bmp ppm vtk vti off ply stl obj vtp)
  export LC_ALL=C
  cmake --build "$fuzz" --parallel "$jobs" --target "${formats[@]/#/fuzz_}"
  mkdir -p "$fuzz/crashes"
  fixed=("$(command -v setarch)" "$(uname -m)" -R)
  "${fixed[@]}" true 2>/dev/null || { fixed=(); echo "fuzz: setarch -R is not allowed here: addresses are random"; }
  for format in "${formats[@]}"; do
    # New inputs go to a scratch corpus; the committed seeds are only read.
    rm -rf "$fuzz/corpus/$format" && mkdir -p "$fuzz/corpus/$format"
    seeds=("$root/Testing/Fuzz/seeds/$format"/*) # in C collation (LC_ALL above)
    (IFS=,; echo "${seeds[*]}") > "$fuzz/seeds-$format.txt"
    runs="${SHOCK_FUZZ_RUNS:-${fuzz_runs[$format]}}"
    echo "fuzz_$format: from ${#seeds[@]} seeds, $runs runs"
    (cd "$fuzz" && env -i ASAN_OPTIONS="$ASAN_OPTIONS" UBSAN_OPTIONS="$UBSAN_OPTIONS" TMPDIR=/tmp LC_ALL=C \
      "${fixed[@]}" "./bin/fuzz_$format" -seed="${SHOCK_FUZZ_SEED:-1}" -runs="$runs" -use_cmp=0 \
      -max_total_time="${SHOCK_FUZZ_SECONDS:-600}" -timeout=30 -rss_limit_mb=2048 -print_final_stats=1 \
      -seed_inputs="@seeds-$format.txt" -artifact_prefix="crashes/$format-" \
      "corpus/$format" 2>"$fuzz/fuzz_$format.log") ||
      { tail -50 "$fuzz/fuzz_$format.log"; echo "fuzz_$format failed: see $fuzz/crashes" >&2; exit 1; }
    grep -E '^stat::number_of_executed_units|^stat::new_units_added|^stat::peak_rss_mb' "$fuzz/fuzz_$format.log" | tr '\n' ' '; echo
  done
fi
stage "done"
