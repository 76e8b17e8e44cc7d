# Included by ctest after the discovered GoogleTest cases, test_costs.cmake and
# sanitize_skip.cmake (tests/CMakeLists.txt): in the sanitizer build, the short tests run many to
# a process.
#
# Why: every sanitized process pays a fixed start and exit (the sanitizer runtime maps its shadow
# memory, the dynamic loader binds Ceres, OpenCV and the rest, LeakSanitizer scans the heap at
# exit), and ctest starts one process per GoogleTest case. Most sanitized tests are short (docs/
# reliability.md, "Short tests in batches": the measured start and the time it saves), so their
# sum was mostly that fixed cost.
#
# What: every test of the sanitizer build that has no row in tests/test_costs.txt (measured under
# 1 s) and is not left out by sanitize_skip.cmake or disabled joins a batch: one ctest test that
# runs up to kBatchSize of them, in discovery order, through one process of the same executable
# (--gtest_filter with their names). The tests with a row keep a process each, so that ctest -j
# still starts the longest first and balances the two cores.
#
# Each batched test keeps its own ctest entry, labelled "in_batch" (scripts/test.sh --sanitize
# runs `ctest -LE "slow|sanitize_skip|in_batch"`), so that `ctest -R <name>` still runs it alone
# and scripts/test.sh --skip-sanitized still finds every test of the Release build by name.
# A batch passes when its process exits 0 having run every test it names
# (testing/run_batch.cmake).
if(NOT SPLINECAL_TESTS_SANITIZED)
  return()
endif()
cmake_policy(SET CMP0057 NEW)  # if(... IN_LIST ...): ctest reads this file with no policies set

set(splinecal_batch_size 40)

# Starts a new batch of `executable`'s tests and adds the finished one, if any.
macro(splinecal_flush_batch)
  list(LENGTH splinecal_batch_names splinecal_batch_count)
  if(splinecal_batch_count GREATER 0)
    math(EXPR splinecal_batch_index "${splinecal_batch_index} + 1")
    set(splinecal_batch_test "${splinecal_executable_name}.batch${splinecal_batch_index}")
    list(JOIN splinecal_batch_filters ":" splinecal_filter)
    add_test("${splinecal_batch_test}" "${SPLINECAL_CMAKE_COMMAND}"
      "-DEXECUTABLE=${splinecal_executable_path}" "-DFILTER=${splinecal_filter}"
      "-DEXPECTED=${splinecal_batch_count}" -P "${SPLINECAL_RUN_BATCH_SCRIPT}")
    set_tests_properties("${splinecal_batch_test}" PROPERTIES
      LABELS "fast;batch" WORKING_DIRECTORY "${SPLINECAL_TEST_WORKING_DIRECTORY}")
    foreach(splinecal_name IN LISTS splinecal_batch_names)
      set_tests_properties("${splinecal_name}" PROPERTIES LABELS "fast;in_batch")
    endforeach()
  endif()
  set(splinecal_batch_names "")
  set(splinecal_batch_filters "")
endmacro()

foreach(splinecal_executable_name IN LISTS SPLINECAL_TEST_EXECUTABLES)
  set(splinecal_executable_path "${SPLINECAL_TEST_EXECUTABLE_${splinecal_executable_name}}")
  set(splinecal_batch_index 0)
  set(splinecal_batch_names "")
  set(splinecal_batch_filters "")
  # Each case's ctest name and its GoogleTest name, from the file gtest_discover_tests wrote
  # (GoogleTest.cmake: <target>[1]_tests.cmake, one add_test line a case). The two differ for
  # value-parameterised cases, named after the value in ctest ("Suite.Case/4-byte object <02-00
  # 00-00>") and by index in GoogleTest ("Suite.Case/2").
  set(splinecal_discovered
    "${SPLINECAL_TEST_WORKING_DIRECTORY}/${splinecal_executable_name}[1]_tests.cmake")
  if(NOT EXISTS "${splinecal_discovered}")
    message(FATAL_ERROR "sanitize_batches.cmake: ${splinecal_discovered} is missing")
  endif()
  file(STRINGS "${splinecal_discovered}" splinecal_lines REGEX "^add_test\\(")
  foreach(splinecal_line IN LISTS splinecal_lines)
    if(NOT splinecal_line MATCHES
       "^add_test\\(\\[=\\[(.+)\\]=\\] .* \\[==\\[--gtest_filter=(.+)\\]==\\] ")
      message(FATAL_ERROR "sanitize_batches.cmake: cannot read ${splinecal_discovered}: ${splinecal_line}")
    endif()
    set(splinecal_name "${CMAKE_MATCH_1}")
    set(splinecal_filter_name "${CMAKE_MATCH_2}")
    if(splinecal_name IN_LIST SPLINECAL_SANITIZE_SKIP_TESTS OR
       splinecal_name IN_LIST SPLINECAL_COSTED_TESTS OR splinecal_name MATCHES "DISABLED_")
      continue()
    endif()
    list(APPEND splinecal_batch_names "${splinecal_name}")
    list(APPEND splinecal_batch_filters "${splinecal_filter_name}")
    list(LENGTH splinecal_batch_names splinecal_batch_count)
    if(splinecal_batch_count EQUAL splinecal_batch_size)
      splinecal_flush_batch()
    endif()
  endforeach()
  splinecal_flush_batch()
endforeach()
