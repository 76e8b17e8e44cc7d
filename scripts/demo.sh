#!/usr/bin/env bash
# The whole splinecal pipeline on bundled data: installs what is missing, builds (Release) and
# runs each command, printing a short summary of each. Results go to demo-out/.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
echo "== building (Release) =="
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target splinecal_tool 2>&1 | grep -E "error|warning: unused" || true
splinecal=build/splinecal
out=demo-out
rm -rf "$out"
mkdir -p "$out"

echo
echo "== 1. the spline: evaluate the bundled control poses (data/vio_course_spline.csv) =="
$splinecal evaluate --spline data/vio_course_spline.csv --samples 5 --out "$out/evaluate"
