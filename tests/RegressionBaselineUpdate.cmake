# shadelab_add_regression_test's update mode, checked: a baseline of another scene differs; with
# SHADELAB_UPDATE_BASELINES=1 it is replaced whole (no partial file left) and said so; then the
# same test passes. Run by CTest with SHADELAB, RUNNER, MESH, SCENE, OTHER_SCENE and WORK.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(baseline "${WORK}/baseline.vtp")
execute_process(COMMAND "${SHADELAB}" shade "${MESH}" --scene "${OTHER_SCENE}" --output "${baseline}"
  OUTPUT_QUIET RESULT_VARIABLE made)
if(NOT made EQUAL 0)
  message(FATAL_ERROR "could not make the first baseline")
endif()
# expected_text: a regular expression; expected_literal: text that must appear as it is.
function(run_test update expected_code expected_text expected_literal)
  set(ENV{SHADELAB_UPDATE_BASELINES} "${update}")
  execute_process(COMMAND "${CMAKE_COMMAND}" "-DSHADELAB=${SHADELAB}" "-DMESH=${MESH}" "-DSCENE=${SCENE}"
    "-DBASELINE=${baseline}" "-DARRAYS=default" "-DCOMPARE_ARGS=" "-DSHADE_ARGS=" "-DOUTPUT=${WORK}/result.vtp"
    "-DJUNIT=${WORK}/result.xml" -P "${RUNNER}"
    RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${out}${err}" "${expected_literal}" literal_at)
  if(NOT code EQUAL expected_code OR NOT "${out}${err}" MATCHES "${expected_text}" OR literal_at EQUAL -1)
    message(FATAL_ERROR "update=${update}: exit code ${code} (expected ${expected_code}), output:\n${out}${err}\n"
      "expected it to match: ${expected_text}")
  endif()
endfunction()
run_test(0 1 "FAIL: [0-9]+ of [0-9]+ arrays differ.*SHADELAB_UPDATE_BASELINES=1" "")
run_test(1 0 "shadelab: baseline updated: " "baseline updated: ${baseline}")
if(EXISTS "${WORK}/result.xml")
  message(FATAL_ERROR "the JUnit report of the comparison before the update was left behind")
endif()
file(GLOB partial "${WORK}/.*partial*")
if(partial)
  message(FATAL_ERROR "a partial baseline was left behind: ${partial}")
endif()
run_test(0 0 "PASS: [0-9]+ arrays agree" "")
message(STATUS "the baseline was updated and then agreed")
