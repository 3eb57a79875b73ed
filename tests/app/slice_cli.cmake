# `echosim slice` as a user meets it: the default volume made on first use and cached in
# XDG_CACHE_HOME (the second run takes it from there), PNG and NRRD outputs (the NRRD placed in the
# volume's space: sizes W H 1, space directions, space origin), --force settling the tissue first,
# the CPU twin, and bad input refused by name with exit code 2. The default volume is the coarse
# one (--coarse, 0.6 mm: the same making and caching, its own cache folder; the 0.4 mm one takes
# 50 s here and four minutes under AddressSanitizer, where CI's time is short).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(ENV{XDG_CACHE_HOME} ${WORK}/cache)
function(run_ok what)
  execute_process(COMMAND ${ECHOSIM} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}${err}")
  endif()
  set(last_out "${out}${err}" PARENT_SCOPE)
endfunction()
# the scanner's deepest image (70 mm) with the probe pressed in all the way (25 mm): the case's
# volume holds all of it (its frames are 95 mm deep), no band beyond the recorded sweep
run_ok("first slice" slice --coarse --out ${WORK}/a.png --press-mm 25 --depth-mm 70 --gpu cpu --validation)
# the cache's folder is named by the case, the voxel and the recipe's version (app/volume_source.hpp)
file(GLOB cached ${WORK}/cache/echosim/volumes/healthy-0.6mm-v*/labels.nrrd)
if(NOT last_out MATCHES "made and cached in" OR NOT cached)
  message(FATAL_ERROR "the default volume was not made and cached:\n${last_out}")
endif()
if(last_out MATCHES "outside the volume" OR NOT last_out MATCHES "probe pressed 25.0 mm")
  message(FATAL_ERROR "the deepest image pressed in all the way was not all in the volume:\n${last_out}")
endif()
# its progress, read from a pipe as a log would: whole lines, a stage's at 0, 25, 50, 75 and 100 %
# only, with no carriage return or terminal code (a terminal gets one line rewritten in place)
string(ASCII 27 escape)
string(REGEX MATCHALL "it is cached\\): [a-z ]+ +[0-9]+ %\n" progress_lines "${last_out}")  # no ';': a CMake list's separator
list(LENGTH progress_lines progress_count)
if(last_out MATCHES "\r" OR last_out MATCHES "${escape}" OR progress_count LESS 3 OR progress_count GREATER 15
   OR NOT last_out MATCHES "filling holes 100 %\n")
  message(FATAL_ERROR "the progress was not whole lines (${progress_count} of them):\n${last_out}")
endif()
run_ok("second slice" slice --coarse --out ${WORK}/b.nrrd --force 12 --gpu cpu --validation)
if(NOT last_out MATCHES "cached in" OR last_out MATCHES "making")
  message(FATAL_ERROR "the cached volume was not taken:\n${last_out}")
endif()
if(NOT last_out MATCHES "tissue pushes back 1[12]\\.[0-9]+ N")
  message(FATAL_ERROR "--force 12 did not settle near 12 N:\n${last_out}")
endif()
file(STRINGS ${WORK}/b.nrrd header LIMIT_COUNT 14)
foreach(want "sizes: 400 500 1" "space directions:" "space origin:" "space: left-posterior-superior")
  string(FIND "${header}" "${want}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the image's NRRD lacks '${want}':\n${header}")
  endif()
endforeach()
run_ok("CPU slice" slice --coarse --out ${WORK}/c.png --press-mm 10 --cpu)
# bad input: named, exit 2, nothing written
execute_process(COMMAND ${ECHOSIM} slice --volume ${WORK}/missing.nrrd --out ${WORK}/never.png RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "missing.nrrd" OR EXISTS ${WORK}/never.png)
  message(FATAL_ERROR "a missing volume was not refused by name (${rc}):\n${err}")
endif()
execute_process(COMMAND ${ECHOSIM} slice --coarse --out ${WORK}/never.png --pose 0,0,nan,1,0,0,0 --cpu RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "--pose" OR EXISTS ${WORK}/never.png)
  message(FATAL_ERROR "a NaN pose was not refused by name (${rc}):\n${err}")
endif()
# issue 34: a user's own volume away from our leg (a 2-D MetaImage, one slice, 20 x 10 mm at the
# origin): without --pose the image is made on the volume's middle and says so, on the GPU and on
# the CPU twin (whose index of size - 2 on the one-voxel axis crashed); a plane that misses the
# volume writes nothing and says so (it wrote a black image with exit 0)
string(REPEAT "A" 200 voxels)
file(WRITE ${WORK}/one_slice.mha "ObjectType = Image\nNDims = 2\nBinaryData = True\nElementSpacing = 1 1\nOffset = 100 100\nDimSize = 20 10\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n${voxels}")
foreach(backend --cpu "--gpu;cpu;--validation")
  run_ok("slice of a 2-D volume (${backend})" slice --volume ${WORK}/one_slice.mha --out ${WORK}/one_slice.png ${backend})
  if(NOT last_out MATCHES "misses [^\n]*one_slice.mha: sliced on the volume's middle instead, --pose 109\\.500,99\\.500,0\\.000,"
     OR NOT last_out MATCHES "9[0-9] % of the image lies outside the volume")
    message(FATAL_ERROR "the default pose was not placed on the user's volume (${backend}):\n${last_out}")
  endif()
endforeach()
execute_process(COMMAND ${ECHOSIM} slice --volume ${WORK}/one_slice.mha --pose 0,0,0,1,0,0,0 --out ${WORK}/black.png --cpu
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "misses [^\n]*one_slice.mha[^\n]* entirely: nothing written" OR EXISTS ${WORK}/black.png)
  message(FATAL_ERROR "a plane missing the volume was not said (${rc}):\n${out}${err}")
endif()
# issue 33: the generative image, on the GPU (validation on) and the CPU twin, pressed; a volume of
# the user's without labels cannot be imaged so, and says why (exit 2, nothing written)
run_ok("generative slice (GPU)" slice --coarse --out ${WORK}/gen.png --press-mm 8 --imaging generative --gpu cpu --validation)
run_ok("generative slice (CPU twin)" slice --coarse --out ${WORK}/gen_cpu.png --press-mm 8 --imaging generative --cpu)
foreach(png gen.png gen_cpu.png)
  file(SIZE ${WORK}/${png} bytes)
  if(bytes LESS 20000)
    message(FATAL_ERROR "the generative image ${png} is ${bytes} bytes: not a speckled 400 x 500 image")
  endif()
endforeach()
execute_process(COMMAND ${ECHOSIM} slice --volume ${WORK}/one_slice.mha --imaging generative --out ${WORK}/never.png --cpu
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "--imaging generative: [^\n]*one_slice.mha[^\n]* no tissue labels" OR EXISTS ${WORK}/never.png)
  message(FATAL_ERROR "a generative image without labels was not refused by name (${rc}):\n${out}${err}")
endif()
