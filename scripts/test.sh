#!/usr/bin/env bash
# Installs what is missing, builds splinecal and runs the whole test suite with ctest (the
# benchmarks are not built here: scripts/bench.sh builds and runs them).
#   scripts/test.sh              Release build in build/, every test (slow Monte-Carlo included)
#   scripts/test.sh --sanitize   ASan + UBSan build in build-sanitize/: the library and the C++
#                                tests; slow and arithmetic tests, Python module and consumer
#                                test left out, and the fast tests labelled sanitize_skip
#                                (tests/sanitize_skip.cmake says which and why)
#   scripts/test.sh --fast       leaves out the tests labelled slow
#   scripts/test.sh --skip-sanitized
#                                after --sanitize: Release build, leaving out the fast C++ tests
#                                that --sanitize ran, then checks that the two together ran every
#                                test (.ci/run: every test once, the fast ones under the
#                                sanitizers, which check what Release checks and memory on top)
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
cmake_args=(-DCMAKE_BUILD_TYPE=Release)
ctest_args=()
for arg in "$@"; do
  case "$arg" in
    --sanitize)
      build_dir=build-sanitize
      # -O2 without debug info: Eigen needs the inlining of -O2 to run the tests at a usable
      # speed (at -O1 they ran 40 times slower than Release), and debug info only costs time.
      # The sanitizers check the library and the C++ tests that drive it. Left out: the Python
      # module (pybind11 bindings, the slowest units to compile; its tests run in the Release
      # build), the downstream-project test (it checks installation and packaging, which the
      # sanitizers do not see) and the tests labelled arithmetic (Jet and autodiff checks of
      # template math, tests/CMakeLists.txt: the costliest compiles, no memory to check).
      cmake_args=(-DCMAKE_BUILD_TYPE=Sanitize "-DCMAKE_CXX_FLAGS_SANITIZE=-O2 -g0"
                  -DSPLINECAL_SANITIZE=ON -DSPLINECAL_SLOW_TESTS=OFF -DSPLINECAL_PYTHON=OFF
                  -DSPLINECAL_CONSUMER_TEST=OFF -DSPLINECAL_ARITHMETIC_TESTS=OFF)
      # The short tests run in batches, many to a process (tests/sanitize_batches.cmake): each
      # keeps its own entry, labelled in_batch, for `ctest -R`.
      ctest_args+=(-LE "slow|sanitize_skip|in_batch")
      # ASan's allocator costs: each malloc and free records its call stack (30 frames by
      # default) and freed memory waits in a 256 MB quarantine before reuse, which faults in
      # fresh pages (system time). 10 frames still reach the caller in the library (a
      # use-after-free report names the access, the free and the allocation, each through
      # std::vector's internals to the function that called them), and 16 MB of quarantine
      # still catches a use shortly after the free, the common case. Measured
      # (docs/reliability.md, "CI time against its targets: the tests"): 3 to 24% less CPU per
      # sanitized test. Leak detection stays on (it runs once, at exit). UBSan's options only
      # shape its reports: its checks are chosen at compile time (CMakeLists.txt).
      export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:malloc_context_size=10:quarantine_size_mb=16
      export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
      ;;
    --fast) ctest_args+=(-LE slow) ;;
    --skip-sanitized)
      # What --sanitize does not run: the slow tests, the Jet and autodiff checks (not built
      # there), the tests tests/sanitize_skip.cmake leaves out, the Python module's tests and the
      # downstream-project test (neither built there). .ci/run checks that the two phases
      # together run every test.
      release_labels="slow|arithmetic|sanitize_skip|python|consumer"
      ctest_args+=(-L "$release_labels")
      if [[ ! -f build-sanitize/CTestTestfile.cmake ]]; then
        echo "scripts/test.sh --skip-sanitized: run scripts/test.sh --sanitize first" >&2
        exit 2
      fi
      ;;
    *) echo "usage: scripts/test.sh [--sanitize] [--fast] [--skip-sanitized]" >&2; exit 2 ;;
  esac
done

# Each phase's wall time, for docs/reliability.md's account of where CI's time goes.
phase_start=$SECONDS
phase_done() {
  echo "scripts/test.sh ($build_dir): $1 in $((SECONDS - phase_start)) s"
  phase_start=$SECONDS
}
scripts/install-deps.sh
phase_done "dependencies checked"
jobs=$(nproc)
scripts/configure.sh . "$build_dir" "${cmake_args[@]}"
phase_done "configured"
cmake --build "$build_dir" -j "$jobs"
phase_done "built"
ctest --test-dir "$build_dir" --output-on-failure -j "$jobs" "${ctest_args[@]}"
phase_done "tests run"

if [[ -n "${release_labels:-}" ]]; then
  # Every test of the Release build ran here or in the sanitizer build (a label that went
  # missing would otherwise drop tests silently). The sanitizer build's list holds its batched
  # tests by name (label in_batch; their batch ran them).
  list_tests() { ctest --test-dir "$1" -N "${@:2}" | sed -n 's/^ *Test *#[0-9]*: //p' | sort -u; }
  missing=$(comm -23 <(list_tests build) \
    <(sort -u <(list_tests build -L "$release_labels") \
              <(list_tests build-sanitize -LE "slow|sanitize_skip")))
  if [[ -n "$missing" ]]; then
    echo "run neither here nor by scripts/test.sh --sanitize:" >&2
    echo "$missing" >&2
    exit 1
  fi
  phase_done "coverage checked"
fi
