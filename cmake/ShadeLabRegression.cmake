# shadelab_add_regression_test: one CTest test that shades a mesh under a scene and compares the
# result with a baseline file by `shadelab compare` (docs/guide/regression-tests.md).
#
#   shadelab_add_regression_test(NAME name MESH mesh SCENE scene.json BASELINE baseline.vtp
#     [ARRAYS list] [ATOL rule...] [RTOL rule...] [ULPS rule...] [EXCLUDE pattern...]
#     [STANDARD_ERRORS k [SIGNIFICANCE alpha]] [NEAREST distance] [SHADE_ARGS arg...])
#
# ARRAYS is shade's --arrays (default "default"); ATOL, RTOL and ULPS are compare's rules
# ("1e-6", "total:1e-6", "1e-3*range") and EXCLUDE its arrays left out ("*_std_error"), which
# cannot hold ';' or '|' (CMake's lists, and the separator the rules travel to the test with).
# STANDARD_ERRORS and SIGNIFICANCE are compare's statistical mode for Monte Carlo arrays.
# Relative paths are from the calling folder. The test writes name.vtp and name.xml (JUnit) in
# the build folder. With the environment variable SHADELAB_UPDATE_BASELINES=1 it writes the result
# over the baseline instead (through a temporary file, renamed when complete) and says so:
#   SHADELAB_UPDATE_BASELINES=1 ctest -R name
# SHADELAB_EXECUTABLE is the shadelab command (default: this build's shadelab target).
set(_shadelab_regression_script "${CMAKE_CURRENT_LIST_DIR}/ShadeLabRegressionRun.cmake")

function(shadelab_add_regression_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "NAME;MESH;SCENE;BASELINE;ARRAYS;STANDARD_ERRORS;SIGNIFICANCE;NEAREST"
    "ATOL;RTOL;ULPS;EXCLUDE;SHADE_ARGS")
  foreach(required NAME MESH SCENE BASELINE)
    if(NOT arg_${required})
      message(FATAL_ERROR "shadelab_add_regression_test: ${required} is required")
    endif()
  endforeach()
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "shadelab_add_regression_test(${arg_NAME}): unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(DEFINED arg_SIGNIFICANCE AND NOT DEFINED arg_STANDARD_ERRORS)
    message(FATAL_ERROR "shadelab_add_regression_test(${arg_NAME}): SIGNIFICANCE is the statistical mode's: give "
      "STANDARD_ERRORS k with it (3 is usual)")
  endif()
  if(NOT arg_ARRAYS)
    set(arg_ARRAYS "default")
  endif()
  # Paths relative to the folder of the CMakeLists.txt that calls this, as add_test's are.
  foreach(path MESH SCENE BASELINE)
    get_filename_component(arg_${path} "${arg_${path}}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  endforeach()
  set(compare_args "")
  foreach(kind ATOL RTOL ULPS EXCLUDE)
    string(TOLOWER "${kind}" option)
    foreach(rule IN LISTS arg_${kind})
      list(APPEND compare_args "--${option}" "${rule}")
    endforeach()
  endforeach()
  foreach(kind STANDARD_ERRORS SIGNIFICANCE NEAREST)
    if(DEFINED arg_${kind}) # NEAREST 0 too
      string(TOLOWER "${kind}" option)
      string(REPLACE "_" "-" option "${option}")
      list(APPEND compare_args "--${option}" "${arg_${kind}}")
    endif()
  endforeach()
  if(SHADELAB_EXECUTABLE)
    set(executable "${SHADELAB_EXECUTABLE}")
  else()
    set(executable "$<TARGET_FILE:shadelab>")
  endif()
  # Lists go to the script joined by '|', which neither CMake nor a shell splits.
  string(REPLACE ";" "|" compare_text "${compare_args}")
  string(REPLACE ";" "|" shade_text "${arg_SHADE_ARGS}")
  add_test(NAME ${arg_NAME}
    COMMAND "${CMAKE_COMMAND}"
      "-DSHADELAB=${executable}" "-DMESH=${arg_MESH}" "-DSCENE=${arg_SCENE}" "-DBASELINE=${arg_BASELINE}"
      "-DARRAYS=${arg_ARRAYS}" "-DCOMPARE_ARGS=${compare_text}" "-DSHADE_ARGS=${shade_text}"
      "-DOUTPUT=${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}.vtp" "-DJUNIT=${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}.xml"
      -P "${_shadelab_regression_script}")
endfunction()
