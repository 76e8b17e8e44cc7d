#!/usr/bin/env bash
# Writes the large recordings bench/bag_bench.cc reads (about 110 MB each, six files) into DIR,
# with the writers of scripts/make_bag_fixtures.sh (and Debian's lz4 command line). Then:
#   SPLINECAL_BENCH_BAGS=DIR build-bench/bench/bag_bench
#   scripts/make_bench_bags.sh DIR
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
out=$(mkdir -p "$1" && cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$repo/scripts/fixtures/package.json" "$repo/scripts/fixtures/make_bench_bags.mjs" \
  "$repo/scripts/fixtures/ros2_definitions.mjs" "$work/"
(cd "$work" && npm install --no-audit --no-fund --silent >/dev/null)
node "$work/make_bench_bags.mjs" "$repo" "$out"
/usr/bin/python3 "$repo/scripts/fixtures/make_bench_bags.py" "$out"
rm -f "$out/frames.raw" "$out/frames.json"
ls -l "$out"
