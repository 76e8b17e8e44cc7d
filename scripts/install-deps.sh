#!/usr/bin/env bash
# Installs splinecal's build dependencies from Debian's packages, and nothing when all are there.
set -euo pipefail

packages=(build-essential cmake ninja-build
          ccache  # compiled objects shared between build folders and clones (CMakeLists.txt)
          libceres-dev libeigen3-dev libgoogle-glog-dev libgflags-dev
          libgtest-dev libgmock-dev libbenchmark-dev libyaml-cpp-dev
          libsuitesparse-dev  # Ceres' sparse Cholesky and Schur solvers (SuiteSparse)
          # scripts/allan_speed_bench.py: the numpy reference of the Allan speed target
          python3-numpy
          # the Python module (python/, docs/python.md) and its tests: pybind11, the interpreter's
          # headers, pytest, and PyYAML to read the command line's result.yaml in the tests
          pybind11-dev python3-dev python3-pytest python3-yaml
          # the image front end (splinecal detect, docs/detect.md): OpenCV (with the contrib
          # modules: ArUco is benchmarked against libapriltag), libapriltag, libjpeg, libpng, zlib
          libopencv-dev libopencv-contrib-dev libapriltag-dev libjpeg-dev libpng-dev zlib1g-dev
          libbz2-dev liblz4-dev libzstd-dev libsqlite3-dev)  # ROS bags (docs/bags.md)
if [[ "${1:-}" == "--fuzz" ]]; then packages+=(clang libclang-rt-14-dev); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  exit 0
fi

sudo=()
if [[ $(id -u) -ne 0 ]]; then sudo=(sudo); fi
echo "install-deps: installing ${missing[*]}" >&2
"${sudo[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends \
  "${missing[@]}" >/dev/null
