# No usable GPU: with no Vulkan driver at all, and with --gpu naming a device that is not there,
# `render` stops with a message that says so (and what it saw), exits 1, and writes nothing over
# the file already there. With no --gpu the best device is taken, lavapipe when there is no GPU
# (every other headless test runs that way).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/out.png "old result")
file(WRITE ${WORK}/none.json "{\"file_format_version\": \"1.0.0\", \"ICD\": {\"library_path\": \"/nonexistent/libvulkan_none.so\", \"api_version\": \"1.3.0\"}}")

function(expect_refused what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 1)
    message(FATAL_ERROR "${what}: exit ${rc}, expected 1:\n${out}${err}")
  endif()
  if(NOT err MATCHES "Vulkan")
    message(FATAL_ERROR "${what}: the message does not say what is missing:\n${err}")
  endif()
  file(READ ${WORK}/out.png kept)
  if(NOT kept STREQUAL "old result")
    message(FATAL_ERROR "${what}: the file already there was replaced")
  endif()
  message(STATUS "${what}: ${err}")
endfunction()

expect_refused("no Vulkan driver" ${CMAKE_COMMAND} -E env VK_ICD_FILENAMES=${WORK}/none.json VK_DRIVER_FILES=${WORK}/none.json
               ${ECHOSIM} render --out ${WORK}/out.png --width 64 --height 64)
expect_refused("--gpu naming no device here" ${ECHOSIM} render --out ${WORK}/out.png --width 64 --height 64 --gpu no-such-gpu-xyz)
execute_process(COMMAND ${CMAKE_COMMAND} -E env ECHOSIM_GPU=no-such-gpu-xyz ${ECHOSIM} render --out ${WORK}/out.png --width 64 --height 64
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "no-such-gpu-xyz")
  message(FATAL_ERROR "ECHOSIM_GPU naming no device here: exit ${rc}:\n${err}")
endif()
