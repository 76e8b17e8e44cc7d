# A committed generated file must equal what its generator writes now: runs
#   ${PYTHON} ${SCRIPT} > ${OUT}
# from ${SOURCE_DIR} and fails, naming both files, when ${OUT} differs from ${COMMITTED}.
# (ctest test Camera.ReferencePixelsMatchTheirScript, tests/CMakeLists.txt.)
execute_process(COMMAND ${PYTHON} ${SCRIPT}
  WORKING_DIRECTORY ${SOURCE_DIR}
  OUTPUT_FILE ${OUT}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${SCRIPT} failed (${status})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${COMMITTED}
  RESULT_VARIABLE differs)
if(differs)
  message(FATAL_ERROR "${COMMITTED} differs from what ${SCRIPT} writes now (${OUT}): "
                      "regenerate it (the script's docstring has the command) or fix the script")
endif()
message(STATUS "${COMMITTED} matches ${SCRIPT}")
