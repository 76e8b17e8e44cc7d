# Included by ctest after the discovered GoogleTest cases (tests/CMakeLists.txt): the fast tests
# the sanitizer build does not run (`ctest -LE "slow|sanitize_skip"`, scripts/test.sh
# --sanitize). The Release build runs them all.
#
# The rule (docs/reliability.md, "Which tests run under the sanitizers"): the sanitizers look for
# memory errors and undefined behaviour along a code path, and one run of a path finds what a
# second run of it finds. A fast test is left out of the sanitizer build only when all three hold:
#   1. it costs over 10 s under the sanitizers (measured, docs/reliability.md);
#   2. what it asserts is the numbers a long estimation converges to (an accuracy, an iteration
#      count, an agreement between two solves), which the Release build checks;
#   3. a cheaper test that the sanitizer build runs takes the same path through the library
#      and the tool with the same options; it is named beside the entry.
# Tests whose point is a path of their own (a command's files, a report, a reader, the detector,
# bad input) stay, whatever they cost.
set(SPLINECAL_SANITIZE_SKIP_TESTS
  # A 15 s rolling-shutter calibration on the coupled SE(3) spline. The same options and model
  # run in Calibrate.EstimatedIntrinsicsFromAPerturbedStartWithinThreeStd (10 s, rolling
  # shutter, SE(3), intrinsics estimated on top) and the same test's /split case runs the other
  # trajectory model.
  "Models/CalibrateOfModel.RollingShutterRoundTrip/se3  # GetParam() = se3"
  # Compares the iteration counts of two real-data calibrations (with and without
  # --rolling-shutter). The tool's --rolling-shutter path runs in every CalibrateCommand test
  # (simulated data), the same real window without it in
  # CalibrateCommandRealWindow.EvaluateOnTheSplinePredictsTheAccelerometer.
  "CalibrateCommandRealWindow.RollingShutterOnAGlobalShutterConvergesAsFast")
foreach(splinecal_skipped_test ${SPLINECAL_SANITIZE_SKIP_TESTS})
  # One label per test as ctest reads it; "fast" stays for `ctest -L fast`.
  set_tests_properties("${splinecal_skipped_test}" PROPERTIES LABELS "fast;sanitize_skip")
endforeach()
