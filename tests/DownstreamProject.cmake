# The guide's downstream project (docs/guide/regression-tests.md: a CMakeLists.txt that finds ShadeLab's package), built against
# this build installed into a folder of its own, and its tests run. Run by CTest with BUILD,
# SOURCE (the folder of the extracted CMakeLists.txt), EXAMPLE (README.md's readme_example.cxx), DATA, WORK,
# GENERATOR, COMPILER and FLAGS (the sanitizers of the sanitizer build).
file(REMOVE_RECURSE "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/ScriptStep.cmake")
step("installing ShadeLab" "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${WORK}/prefix")
file(COPY "${SOURCE}/CMakeLists.txt" "${EXAMPLE}" DESTINATION "${WORK}/source")
step("configuring the downstream project" "${CMAKE_COMMAND}" -S "${WORK}/source" -B "${WORK}/build" -G "${GENERATOR}"
  "-DCMAKE_PREFIX_PATH=${WORK}/prefix" "-DDATA=${DATA}" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_COMPILER=${COMPILER}"
  "-DCMAKE_CXX_FLAGS=${FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}")
step("building the downstream project" "${CMAKE_COMMAND}" --build "${WORK}/build")
step("testing the downstream project" "${CMAKE_CTEST_COMMAND}" --test-dir "${WORK}/build" --output-on-failure)
if(NOT step_output MATCHES "100% tests passed, 0 tests failed out of 2")
  message(FATAL_ERROR "the downstream project's tests did not all pass:\n${step_output}")
endif()
message(STATUS "the downstream project built and its 2 tests passed")
