# The test shadelab_add_regression_test adds (ShadeLabRegression.cmake): shade, then compare
# with the baseline, or, with SHADELAB_UPDATE_BASELINES=1, write the result over it.
string(REPLACE "|" ";" compare_args "${COMPARE_ARGS}")
string(REPLACE "|" ";" shade_args "${SHADE_ARGS}")
execute_process(COMMAND "${SHADELAB}" shade "${MESH}" --scene "${SCENE}" --arrays "${ARRAYS}" ${shade_args}
  --output "${OUTPUT}" RESULT_VARIABLE shaded)
if(NOT shaded EQUAL 0)
  message(FATAL_ERROR "shadelab shade failed (exit code ${shaded}): nothing to compare")
endif()
if("$ENV{SHADELAB_UPDATE_BASELINES}" STREQUAL "1")
  # Complete before it replaces the baseline: a copy beside it, then a rename.
  get_filename_component(folder "${BASELINE}" DIRECTORY)
  get_filename_component(name "${BASELINE}" NAME)
  set(partial "${folder}/.${name}.partial")
  execute_process(COMMAND "${CMAKE_COMMAND}" -E copy "${OUTPUT}" "${partial}" RESULT_VARIABLE copied)
  if(NOT copied EQUAL 0)
    file(REMOVE "${partial}")
    message(FATAL_ERROR "could not write ${partial}: the baseline ${BASELINE} is unchanged")
  endif()
  file(RENAME "${partial}" "${BASELINE}")
  file(REMOVE "${JUNIT}") # a report of an earlier comparison would no longer be true
  message(STATUS "shadelab: baseline updated: ${BASELINE} (from ${OUTPUT})")
  return()
endif()
execute_process(COMMAND "${SHADELAB}" compare "${BASELINE}" "${OUTPUT}" ${compare_args} --junit "${JUNIT}"
  RESULT_VARIABLE compared)
if(compared EQUAL 1)
  message(FATAL_ERROR "the result ${OUTPUT} differs from the baseline ${BASELINE} (see above). If the change is "
    "deliberate, update the baseline: SHADELAB_UPDATE_BASELINES=1 ctest -R <this test>")
elseif(NOT compared EQUAL 0)
  message(FATAL_ERROR "shadelab compare could not compare ${OUTPUT} with ${BASELINE} (exit code ${compared})")
endif()
