# The layers are enforced by the build: a library that includes a layer it does not link fails to
# compile, naming the header. Builds the control (an allowed include) and each violation.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD} --target layer_control RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the control, an allowed include, does not build:\n${out}${err}")
endif()
string(REPLACE "," ";" violations "${VIOLATIONS}")  # target:header,target:header
foreach(pair ${violations})
  string(REPLACE ":" ";" pair ${pair})
  list(GET pair 0 target)
  list(GET pair 1 header)
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD} --target ${target} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "${target} built: the layer reached ${header} it does not link")
  endif()
  if(NOT "${out}${err}" MATCHES "${header}: No such file or directory")
    message(FATAL_ERROR "${target} failed, but not for ${header}:\n${out}${err}")
  endif()
endforeach()
