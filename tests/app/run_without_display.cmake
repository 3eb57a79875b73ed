# With no display at all, `echosim run` says so, points to the headless command, and fails.
execute_process(COMMAND ${ECHOSIM} run RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "echosim run succeeded without a display:\n${out}${err}")
endif()
if(NOT err MATCHES "no display" OR NOT err MATCHES "echosim render")
  message(FATAL_ERROR "message lacks the reason or the hint:\n${err}")
endif()
