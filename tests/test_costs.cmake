# Each test's measured seconds as its ctest COST, from the table tests/test_costs.txt (written by
# scripts/test_costs.py; docs/reliability.md, "The cold and warm figures": how to regenerate).
# Included by ctest after the discovered GoogleTest cases (tests/CMakeLists.txt), so that
# `ctest -j2` in a fresh build folder (no CTestCostData yet) starts the longest first. The
# figures only order the tests: ctest ignores names it does not have, and a test not in the table
# (shorter than 1 s, or new) still runs, with cost 0. The sanitizer build has its own figures
# (the rows "sanitize"), chosen by SPLINECAL_TESTS_SANITIZED (set by the generated
# test_build_kind.cmake read just before this file); the others take the rows "release".
# SPLINECAL_COSTED_TESTS lists the tests with a row: sanitize_batches.cmake runs the others in
# batches.
if(SPLINECAL_TESTS_SANITIZED)
  set(splinecal_cost_build sanitize)
else()
  set(splinecal_cost_build release)
endif()
file(STRINGS "${CMAKE_CURRENT_LIST_DIR}/test_costs.txt" splinecal_cost_rows
  REGEX "^${splinecal_cost_build} ")
foreach(row IN LISTS splinecal_cost_rows)
  if(row MATCHES "^${splinecal_cost_build} ([0-9.]+) (.+)$")
    set_tests_properties("${CMAKE_MATCH_2}" PROPERTIES COST ${CMAKE_MATCH_1})
    list(APPEND SPLINECAL_COSTED_TESTS "${CMAKE_MATCH_2}")
  endif()
endforeach()
