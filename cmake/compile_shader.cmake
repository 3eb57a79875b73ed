# Run by cmake -P for one shader: glslangValidator to a C header, warnings treated as errors.
set(args --target-env vulkan1.2 --vn ${VARNAME} --depfile ${DEPFILE} -o ${OUTPUT})
foreach(dir IN LISTS INCLUDE_DIRS)
  list(APPEND args "-I${dir}")
endforeach()
execute_process(
  COMMAND ${GLSLANG} ${args} ${SOURCE}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REPLACE "${SOURCE}\n" "" quiet "${out}${err}")  # glslang echoes the file name on success
if(NOT rc EQUAL 0 OR quiet MATCHES "WARNING|ERROR")
  file(REMOVE ${OUTPUT})
  message(FATAL_ERROR "glslang failed on ${SOURCE} (warnings are errors):\n${out}${err}")
endif()
