# A malformed pose is refused with exit code 2 and a message naming the field; no file is written.
file(REMOVE ${OUT})
execute_process(COMMAND ${ECHOSIM} render --out ${OUT} --pose 1,2,nan,1,0,0,0 --gpu cpu
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "expected exit code 2, got ${rc}:\n${out}${err}")
endif()
if(NOT err MATCHES "--pose: pose field z is not a finite number")
  message(FATAL_ERROR "message does not name the field:\n${err}")
endif()
if(EXISTS ${OUT})
  message(FATAL_ERROR "a file was written for a refused pose")
endif()
