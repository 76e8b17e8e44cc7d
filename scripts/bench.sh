#!/usr/bin/env bash
# Builds the Google Benchmark programs (Release, -march=native, the build docs/performance.md's
# reference figures were measured with) and runs them; results go to build-bench/results/<bench>.txt
# and the console.
#   scripts/bench.sh [BENCH ...]                 default: every bench/*_bench.cc
#   scripts/bench.sh --against REV [--rounds N] [--filter REGEX] BENCH ...
#       side by side with commit REV, in one run: REV's benchmarks are built in a worktree
#       (build-bench-against/), and each round runs REV's program, then this tree's, so both
#       see the same machine state; scripts/bench_compare.py prints the median of each
#       benchmark over the rounds and the ratio (this tree / REV). Results in
#       build-bench/results/against-REV/.
# docs/performance.md quotes these files, with the machine and the date.
set -euo pipefail
cd "$(dirname "$0")/.."
against=""
rounds=5
filter="."
benches=()
while (($#)); do
  case "$1" in
    --against) against="$2"; shift 2 ;;
    --rounds) rounds="$2"; shift 2 ;;
    --filter) filter="$2"; shift 2 ;;
    *) benches+=("$1"); shift ;;
  esac
done
scripts/install-deps.sh
configure() {  # source dir, build dir
  scripts/configure.sh "$1" "$2" -DCMAKE_BUILD_TYPE=Release -DSPLINECAL_NATIVE=ON \
    -DSPLINECAL_BUILD_TESTS=OFF -DSPLINECAL_BUILD_BENCH=ON
}
if ((${#benches[@]} == 0)); then
  for f in bench/*_bench.cc; do benches+=("$(basename "$f" .cc)"); done
fi
configure . build-bench
cmake --build build-bench -j "$(nproc)" --target "${benches[@]}"
mkdir -p build-bench/results
{
  echo "date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
  echo "cores: $(nproc), memory: $(free -g | awk '/Mem:/{print $2}') GiB"
  echo "compiler: $(c++ --version | head -1), flags: -O3 -march=native (Release + SPLINECAL_NATIVE)"
  echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
} | tee build-bench/results/machine.txt

if [[ -z "$against" ]]; then
  for b in "${benches[@]}"; do
    build-bench/bench/$b --benchmark_min_time=0.5 --benchmark_filter="$filter" 2>&1 |
      tee build-bench/results/$b.txt
  done
  exit 0
fi

# Side by side with REV.
rev=$(git rev-parse --short "$against")
worktree=build-bench-against/src-$rev
if [[ ! -d "$worktree" ]]; then
  git worktree add --detach "$worktree" "$rev" >/dev/null
fi
configure "$worktree" build-bench-against/build-$rev
cmake --build build-bench-against/build-$rev -j "$(nproc)" --target "${benches[@]}"
out=build-bench/results/against-$rev
rm -rf "$out"
mkdir -p "$out"
cp build-bench/results/machine.txt "$out/"
for b in "${benches[@]}"; do
  for ((r = 1; r <= rounds; ++r)); do
    for side in before after; do
      if [[ $side == before ]]; then bin=build-bench-against/build-$rev/bench/$b; else bin=build-bench/bench/$b; fi
      echo "== $b round $r: $side" >&2
      "$bin" --benchmark_min_time=0.5 --benchmark_filter="$filter" \
        --benchmark_out="$out/$b.$side.$r.json" --benchmark_out_format=json >/dev/null
    done
  done
done
python3 scripts/bench_compare.py "$out" "$rev" | tee "$out/summary.txt"
