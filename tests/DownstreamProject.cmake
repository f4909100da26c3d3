# The guide's downstream project (docs/guide/regression-tests.md: a CMakeLists.txt that finds ShadeLab's package), built against
# this build installed into a folder of its own, and its tests run; then every installed header compiled alone, in a
# project of its own that finds the package the same way. Run by CTest with BUILD,
# SOURCE (the folder of the extracted CMakeLists.txt), EXAMPLE (README.md's readme_example.cxx), DATA, WORK,
# GENERATOR, COMPILER, LAUNCHER (the build's compiler launcher, if any: .ci/compiler-cache) and FLAGS (the sanitizers
# of the sanitizer build).
file(REMOVE_RECURSE "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/ScriptStep.cmake")
step("installing ShadeLab" "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${WORK}/prefix")
file(COPY "${SOURCE}/CMakeLists.txt" "${EXAMPLE}" DESTINATION "${WORK}/source")
step("configuring the downstream project" "${CMAKE_COMMAND}" -S "${WORK}/source" -B "${WORK}/build" -G "${GENERATOR}"
  "-DCMAKE_PREFIX_PATH=${WORK}/prefix" "-DDATA=${DATA}" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_COMPILER=${COMPILER}"
  "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}" "-DCMAKE_CXX_FLAGS=${FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}")
step("building the downstream project" "${CMAKE_COMMAND}" --build "${WORK}/build")
step("testing the downstream project" "${CMAKE_CTEST_COMMAND}" --test-dir "${WORK}/build" --output-on-failure)
if(NOT step_output MATCHES "100% tests passed, 0 tests failed out of 2")
  message(FATAL_ERROR "the downstream project's tests did not all pass:\n${step_output}")
endif()

# One source file per installed header, which includes it twice (alone, then again: include guards).
file(GLOB headers RELATIVE "${WORK}/prefix/include/shadelab" "${WORK}/prefix/include/shadelab/*.h")
list(LENGTH headers header_count)
if(header_count LESS 80)
  message(FATAL_ERROR "only ${header_count} headers installed in ${WORK}/prefix/include/shadelab")
endif()
set(header_sources "")
foreach(header IN LISTS headers)
  string(MAKE_C_IDENTIFIER "${header}" name)
  file(WRITE "${WORK}/headers/${name}.cxx" "#include \"${header}\"\n#include \"${header}\"\n")
  list(APPEND header_sources "${name}.cxx")
endforeach()
file(WRITE "${WORK}/headers/CMakeLists.txt" "cmake_minimum_required(VERSION 3.20)
project(InstalledHeaders CXX)
find_package(ShadeLab 0.1 REQUIRED)
add_library(installed_headers OBJECT ${header_sources})
target_link_libraries(installed_headers PRIVATE ShadeLab::Filters ShadeLab::shadelab_core)
")
step("configuring the project of the installed headers" "${CMAKE_COMMAND}" -S "${WORK}/headers" -B "${WORK}/headers-build"
  -G "${GENERATOR}" "-DCMAKE_PREFIX_PATH=${WORK}/prefix" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_COMPILER=${COMPILER}"
  "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}" "-DCMAKE_CXX_FLAGS=${FLAGS}")
step("compiling each installed header alone" "${CMAKE_COMMAND}" --build "${WORK}/headers-build")
message(STATUS "the downstream project built and its 2 tests passed; each of the ${header_count} installed headers compiled alone")
