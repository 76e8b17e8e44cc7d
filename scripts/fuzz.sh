#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and runs each for a bounded time.
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET ...]     default 60 s, every target
# Seed corpora: tests/fuzz/corpus/<target>/ plus the bundled data/. New crashing inputs are left
# in build-fuzz/findings/<target>/; copy them into tests/fuzz/regressions/ once fixed.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true

scripts/install-deps.sh --fuzz
scripts/configure.sh . build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DSPLINECAL_FUZZ=ON -DSPLINECAL_BUILD_TESTS=OFF
targets=("$@")
if ((${#targets[@]} == 0)); then
  for f in tests/fuzz/*_fuzz.cc; do targets+=("$(basename "$f" .cc)"); done
fi
cmake --build build-fuzz -j "$(nproc)" --target "${targets[@]}"

export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
printf '%-26s %12s %10s %s\n' target executions seconds result
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t
  findings=build-fuzz/findings/$t
  mkdir -p "$corpus" "$findings"
  [[ -d tests/fuzz/corpus/$t ]] && cp -n tests/fuzz/corpus/$t/* "$corpus"/ 2>/dev/null || true
  [[ -d tests/fuzz/regressions ]] && cp -n tests/fuzz/regressions/* "$corpus"/ 2>/dev/null || true
  log=build-fuzz/$t.log
  set +e
  build-fuzz/tests/fuzz/$t "$corpus" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
    -rss_limit_mb=4096 -artifact_prefix="$findings/" -print_final_stats=1 >"$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -m1 'stat::number_of_executed_units' "$log" | awk '{print $2}')
  result=ok
  ((rc != 0)) && result="FOUND (see $log, $findings)"
  printf '%-26s %12s %10s %s\n' "$t" "${execs:-?}" "$seconds" "$result"
done
