# Every C++ file of the repository is as clang-format-14 would write it (.clang-format at the
# top). Run by CTest with CLANG_FORMAT (the program) and SOURCE (the repository).
file(GLOB_RECURSE sources LIST_DIRECTORIES false RELATIVE "${SOURCE}"
  "${SOURCE}/filters/*.h" "${SOURCE}/filters/*.cxx" "${SOURCE}/filters/*.cpp"
  "${SOURCE}/apps/*.h" "${SOURCE}/apps/*.cxx" "${SOURCE}/bench/*.h" "${SOURCE}/bench/*.cxx"
  "${SOURCE}/tests/*.h" "${SOURCE}/tests/*.cxx" "${SOURCE}/tests/*.cpp" "${SOURCE}/paraview/*.h"
  "${SOURCE}/paraview/*.cxx")
list(LENGTH sources count)
if(count LESS 100)
  message(FATAL_ERROR "found only ${count} C++ files under ${SOURCE}: is SOURCE the repository?")
endif()
# clang-format names each file it would change as "<file>:<line>:<column>: error: ...".
execute_process(COMMAND "${CLANG_FORMAT}" --dry-run -Werror ${sources} WORKING_DIRECTORY "${SOURCE}"
  RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE complaints)
if(NOT code EQUAL 0)
  string(REGEX MATCHALL "[^\n:]+:[0-9]+:[0-9]+: error" places "${complaints}")
  list(TRANSFORM places REPLACE ":[0-9]+:[0-9]+: error$" "")
  list(REMOVE_DUPLICATES places)
  list(JOIN places " " files)
  message(FATAL_ERROR "not as clang-format-14 writes them: ${files}\n"
    "Run from the repository: clang-format-14 -i ${files}")
endif()
message(STATUS "all ${count} C++ files are formatted")
