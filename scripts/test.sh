#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds, runs every CTest test
# (GoogleTest kernel and filter tests, pvpython plugin tests).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
# One test at a time: each test already uses every core through OpenMP.
ctest --test-dir "$root/build" --output-on-failure --timeout 900
