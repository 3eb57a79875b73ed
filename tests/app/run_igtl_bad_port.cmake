# `echosim run --igtl PORT` refuses a port that is not one (bad input: exit 2), naming what it was
# given, before it looks for a display or makes anything.
foreach(port abc 0 65536 -1 18944.5)
  execute_process(COMMAND ${ECHOSIM} run --igtl=${port} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "echosim run --igtl=${port} exited ${rc}, not 2:\n${out}${err}")
  endif()
  if(NOT err MATCHES "--igtl ${port}: a port number in 1..65535")
    message(FATAL_ERROR "echosim run --igtl=${port}: the message does not name the port:\n${err}")
  endif()
endforeach()
