# The layers are enforced by the build: a library that includes a layer it does not link fails to
# compile, naming the header. Builds the control (an allowed include) and each violation; and,
# since a quoted include is looked up beside the including file first, refuses any engine source
# that climbs out of its folder with "../" (which would reach a layer around the include roots).
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
  # GCC says "No such file or directory", Clang "file not found"
  if(NOT "${out}${err}" MATCHES "${header}[^\n]*(No such file or directory|file not found)")
    message(FATAL_ERROR "${target} failed, but not for ${header}:\n${out}${err}")
  endif()
endforeach()

file(GLOB_RECURSE sources ${ENGINE}/*.cpp ${ENGINE}/*.hpp ${ENGINE}/*.h)
foreach(source ${sources})
  file(STRINGS ${source} climbing REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<][^\">]*\\.\\./")
  if(climbing)
    message(FATAL_ERROR "${source} includes through '../', around the layers' include roots: ${climbing}")
  endif()
endforeach()
