#!/usr/bin/env bash
# Builds the Google Benchmark programs (Release, -march=native like the issues' reference
# figures) and runs them; results go to build-bench/results/<bench>.txt and the console.
#   scripts/bench.sh [BENCH ...]      default: every bench/*_bench.cc
# docs/performance.md quotes these files, with the machine and the date.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DSPLINECAL_NATIVE=ON \
  -DSPLINECAL_BUILD_TESTS=OFF >/dev/null
benches=("$@")
if ((${#benches[@]} == 0)); then
  for f in bench/*_bench.cc; do benches+=("$(basename "$f" .cc)"); done
fi
cmake --build build-bench -j "$(nproc)" --target "${benches[@]}"
mkdir -p build-bench/results
{
  echo "date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
  echo "cores: $(nproc), memory: $(free -g | awk '/Mem:/{print $2}') GiB"
  echo "compiler: $(c++ --version | head -1), flags: -O3 -march=native (Release + SPLINECAL_NATIVE)"
} | tee build-bench/results/machine.txt
for b in "${benches[@]}"; do
  build-bench/bench/$b --benchmark_min_time=0.5 2>&1 | tee build-bench/results/$b.txt
done
