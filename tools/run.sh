#!/usr/bin/env bash
# Set up a Debian 12 machine (as root), build pcl_phaser, and run one job.
#   tools/run.sh demo   install deps, build pcl_phaser_align, run it on its embedded default
#   tools/run.sh test   install deps (gnuplot too), build everything (bench/ too), run the whole
#                       test suite
#   tools/run.sh benchmark [ARGS]   also installs gnuplot, then runs pcl_phaser_bench ARGS
#                       (default: compare, all methods on the shared scans; see
#                       doc/benchmarks.md)
# Idempotent: packages already installed are skipped, the build directory is reused.
set -euo pipefail
job=${1:-demo}
shift || true
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${PCL_PHASER_BUILD_DIR:-$here/build}

# pcl-tools: pcl_viewer, which the demo's last line suggests for its overlay.
packages=(g++ make cmake pkg-config libpcl-dev libeigen3-dev libfftw3-dev libboost-dev
          libgtest-dev nlohmann-json3-dev xvfb xauth pcl-tools)
# gnuplot-nox: the benchmark's plots, and pcl_phaser_optimize --png (its tests).
if [[ $job == benchmark || $job == test ]]; then packages+=(gnuplot-nox); fi
# The batch tool's tests run it sharded under GNU parallel and a single-node Slurm;
# libceres-dev builds pcl_phaser_optimize (the pose graph) and its tests.
if [[ $job == test ]]; then packages+=(parallel slurm-wlm munge libceres-dev); fi
# The Python module (built when pybind11 is found) and its pytest suite (label python).
if [[ $job == test ]]; then
  packages+=(python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest
             python3-distributed)
fi
# Open3D: the peer the benchmark's Python scripts (bench/*_open3d.py) compare against.
if [[ $job == benchmark ]]; then packages+=(python3-open3d); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "Installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The demo builds what `cmake --install` installs (the libraries, the tools and, when
# pybind11 is present, the Python module) but no tests; test and benchmark build
# everything, the bench/ programs and their tests included, and the Python module
# (PCL_PHASER_BUILD_PYTHON=ON: a missing pybind11 is an error, not a silent skip).
case "$job" in
  demo) options=(-DPCL_PHASER_BUILD_TESTS=OFF -DPCL_PHASER_BUILD_BENCH=OFF
                 -DPCL_PHASER_BUILD_PYTHON=AUTO) ;;
  test|benchmark) options=(-DPCL_PHASER_BUILD_TESTS=ON -DPCL_PHASER_BUILD_BENCH=ON)
    if [[ $job == test ]]; then options+=(-DPCL_PHASER_BUILD_PYTHON=ON); fi ;;
  *) echo "usage: $0 demo|test|benchmark [ARGS]" >&2; exit 2 ;;
esac
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release "${options[@]}"
cmake --build "$build" -j"$(nproc)"

case "$job" in
  demo)
    # The embedded default: a simulated 64-beam LiDAR pair a few meters and >100 degrees
    # apart, registered globally and refined with ICP; prints the errors and writes an
    # overlay for pcl_viewer into the current directory.
    "$build/tools/pcl_phaser_align" --demo ;;
  test)
    cd "$build" && ctest --output-on-failure -j"$(nproc)" ;;
  benchmark)
    # Reads ../shared/data (or --data DIR); plots go to ./benchmark_plots.
    if (($#)); then "$build/bench/pcl_phaser_bench" "$@"
    else "$build/bench/pcl_phaser_bench" compare --methods all --icp --pairs --plots benchmark_plots; fi ;;
esac
