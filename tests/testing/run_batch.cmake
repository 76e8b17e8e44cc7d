# Runs one batch of short GoogleTest cases in one process (tests/sanitize_batches.cmake):
#   cmake -DEXECUTABLE=... -DFILTER=Suite.A:Suite.B:... -DEXPECTED=N -P run_batch.cmake
# and fails unless the process exits 0 having run exactly N tests. The exit code carries a
# failed test, a sanitizer report (LeakSanitizer's comes after GoogleTest's summary) and a crash;
# the count, a name that matched no test.
execute_process(COMMAND ${EXECUTABLE} --gtest_filter=${FILTER}
  RESULT_VARIABLE status
  OUTPUT_VARIABLE output
  ERROR_VARIABLE output)
message(NOTICE "${output}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${EXECUTABLE}: exit status ${status} (a test above failed or the process did)")
endif()
if(NOT output MATCHES "\\[==========\\] ([0-9]+) tests? from [0-9]+ test suites? ran")
  message(FATAL_ERROR "${EXECUTABLE}: no GoogleTest summary in the output")
endif()
if(NOT CMAKE_MATCH_1 EQUAL EXPECTED)
  message(FATAL_ERROR "${EXECUTABLE}: ran ${CMAKE_MATCH_1} tests, the batch names ${EXPECTED}")
endif()
