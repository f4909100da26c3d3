# step(WHAT COMMAND...): runs a command of a test script, and fails the script, naming WHAT and
# showing what the command printed, unless it succeeds; its standard output is then in
# step_output.
function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${what} failed (exit code ${code}):\n${out}${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()
