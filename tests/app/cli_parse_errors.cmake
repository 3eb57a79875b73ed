# Every command-line error exits 2 (bad input), as documented, whatever CLI11 calls it: a value out
# of range, NaN or an infinity (which CLI11's own ranges let through), a value that is not a number, an unknown option, a missing required one; --help exits 0.
foreach(args "render;--width;99999;--out;x.png" "slice;--press-mm;deep;--out;x.png" "reconstruct;--sweep;a.mha"
        "render;--out;x.png;--no-such-option" "reconstruct;--sweep;a.mha;--out;v.nrrd;--compound;median"
        "render;--out;x.png;--press-mm;nan" "render;--out;x.png;--width;8192;--height;8192" "render;--out;x.png;--width;16384;--height;16384" "slice;--out;x.png;--pixel-mm;0.005" "slice;--out;x.png;--force;inf" "reconstruct;--sweep;a.mha;--out;v.nrrd;--voxel-mm;nan"
        "soak;--seconds;0" "soak;--seconds;5" "soak;--seconds;nan" "soak;--seconds;inf" "soak;--deadlines;lenient")
  execute_process(COMMAND ${ECHOSIM} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "echosim ${args}: expected exit code 2, got ${rc}:\n${out}${err}")
  endif()
endforeach()
execute_process(COMMAND ${ECHOSIM} render --help RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "--width")
  message(FATAL_ERROR "echosim render --help: exit ${rc}:\n${out}${err}")
endif()

# `echosim --version` says the project's version; a bare `echosim` prints its help (every command)
execute_process(COMMAND ${ECHOSIM} --version RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^echosim [0-9]+\\.[0-9]+\\.[0-9]+")
  message(FATAL_ERROR "echosim --version: exit ${rc}:\n${out}${err}")
endif()
execute_process(COMMAND ${ECHOSIM} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
foreach(command run exam case records soak render phantom)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "\n  ${command} ")
    message(FATAL_ERROR "a bare echosim: exit ${rc}, its help does not list ${command}:\n${out}${err}")
  endif()
endforeach()

# an output that is not a regular file is refused before any work, and stays what it was
file(MAKE_DIRECTORY ${WORK})
foreach(args "render;--gpu;cpu;--out;${WORK}" "reconstruct;--sweep;a.mha;--out;${WORK}/v.txt" "soak;--seconds;10;--json;${WORK}")
  execute_process(COMMAND ${ECHOSIM} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "echosim ${args}: expected exit code 2, got ${rc}:\n${out}${err}")
  endif()
endforeach()
if(NOT IS_DIRECTORY ${WORK})
  message(FATAL_ERROR "the folder named as --out was replaced")
endif()
