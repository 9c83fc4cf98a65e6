#!/usr/bin/env bash
# The one install list of this project: Debian 12 packages needed to build the
# VTK module, the ParaView plugin, the tests and the benchmarks, and to run the
# GUI/MPI tests. Idempotent: installs only what is missing. Needs root (or sudo).
#   bash scripts/install-deps.sh               what the build, the tests and CI need
#   bash scripts/install-deps.sh --benchmarks  also what only Benchmarks/userbench.sh needs
set -euo pipefail

PACKAGES=(
  # toolchain and test frameworks
  cmake g++ make libgtest-dev libbenchmark-dev
  # the fuzz stage of scripts/test.sh: clang with libFuzzer (compiler-rt) and its OpenMP
  clang libclang-rt-14-dev libomp-dev
  # ParaView 5.11 SDK (carries VTK 9.2) and what its CMake config probes
  paraview paraview-dev python3-paraview
  python3-dev   # headers for the Python wrapping (package shockfilters)
  libeigen3-dev qtbase5-dev qttools5-dev libqt5svg5-dev libqt5opengl5-dev
  qtxmlpatterns5-dev-tools libqt5x11extras5-dev qtmultimedia5-dev
  libhdf5-mpi-dev libutfcpp-dev libnetcdf-dev libexpat1-dev
  libdouble-conversion-dev liblz4-dev libjpeg-dev libpng-dev libtiff-dev
  libxml2-dev zlib1g-dev libfreetype-dev libgl2ps-dev libglew-dev
  libtheora-dev libogg-dev mpi-default-dev libjsoncpp-dev liblzma-dev
  libgl-dev libx11-dev libavcodec-dev libavformat-dev libavutil-dev
  libswscale-dev libgdal-dev libproj-dev
  # plots of the paper evidence (Benchmarks/reproduce_paper.sh)
  python3-numpy python3-matplotlib python3-pil
  # the photograph of the Figure 3 test (Testing/Cxx/TestFigure3.cxx)
  python-matplotlib-data
  # headless display for rendering tests and screenshots; MPI launcher
  xvfb xauth mpi-default-bin
)
# Only for the benchmarks (not CI): G'MIC, the shock-filter sharpening that
# Benchmarks/userbench.sh compares against (row "gmic").
BENCHMARK_PACKAGES=(gmic)
if [ "${1:-}" = "--benchmarks" ]; then
  PACKAGES+=("${BENCHMARK_PACKAGES[@]}")
elif [ $# -gt 0 ]; then
  echo "usage: bash scripts/install-deps.sh [--benchmarks]" >&2
  exit 2
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${#missing[@]} missing package(s): ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
