# Runs one test program, saves its stdout to OUTPUT and, if REFERENCE exists,
# compares the two with numdiff (tolerances below).
execute_process(COMMAND ${COMMAND} OUTPUT_FILE ${OUTPUT} ERROR_VARIABLE err
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  file(READ ${OUTPUT} out)
  message(FATAL_ERROR "test program failed (exit ${rc}):\n${out}\n${err}")
endif()
if(EXISTS ${REFERENCE})
  # 6 significant digits are printed by the tests; 1e-4 relative absorbs round-off.
  set(args -q -a 1e-9 -r 1e-4 -s " \\t\\n,=:()[]|")
  execute_process(COMMAND ${NUMDIFF} ${args} ${REFERENCE} ${OUTPUT}
    RESULT_VARIABLE rc OUTPUT_VARIABLE diff)
  if(NOT rc EQUAL 0)
    execute_process(COMMAND ${NUMDIFF} ${args} -V ${REFERENCE} ${OUTPUT} OUTPUT_VARIABLE diff)
    message(FATAL_ERROR "output differs from ${REFERENCE}:\n${diff}")
  endif()
endif()
