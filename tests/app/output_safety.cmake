# What the writing commands do with the paths they are given (README "Output files"): outputs that
# name the same file as each other or as an input are refused before any work (exit 2, naming both
# options) and nothing is written; a file the command did not write is never deleted; a name too
# long once a suffix is added is refused before the work, one that fits is written; what a killed
# run left is removed by the next write there; a link planted where the temporary once was
# (OUT.partial) is neither followed nor removed.
#   cmake -DECHOSIM=... -DWORK=... -P output_safety.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/sub)

function(run_echosim expect_rc)
  execute_process(COMMAND ${ECHOSIM} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL expect_rc)
    message(FATAL_ERROR "echosim ${ARGN}: expected exit code ${expect_rc}, got ${rc}:\n${out}${err}")
  endif()
  set(err "${err}" PARENT_SCOPE)
  set(out "${out}" PARENT_SCOPE)
endfunction()

function(expect_in text)
  foreach(word ${ARGN})
    string(FIND "${text}" "${word}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "no '${word}' in:\n${text}")
    endif()
  endforeach()
endfunction()

# inputs: a sweep with its labels' sweep, one without, a volume
run_echosim(0 phantom --out ${WORK}/s.mha --frames 8 --pixel-mm 0.5)
file(COPY_FILE ${WORK}/s.mha ${WORK}/bare.mha)
run_echosim(0 reconstruct --sweep ${WORK}/s.mha --out ${WORK}/v.nrrd --voxel-mm 1)
file(SHA256 ${WORK}/s.mha sweep_sum)
file(SHA256 ${WORK}/v.nrrd volume_sum)

# outputs that collide with each other
run_echosim(2 phantom --out ${WORK}/p.mha --frames 8 --pixel-mm 0.5 --labels ${WORK}/sub/../p.mha)
expect_in("${err}" "--out" "--labels" "same file")
if(EXISTS ${WORK}/p.mha)
  message(FATAL_ERROR "phantom wrote ${WORK}/p.mha although its outputs collide")
endif()
run_echosim(2 phantom --out ${WORK}/p.mha --frames 8 --pixel-mm 0.5 --labels ${WORK}/p.labels.mha)
expect_in("${err}" "--out's label sweep" "--labels")

# an output that is an input, spelt another way
run_echosim(2 reconstruct --sweep ${WORK}/s.mha --out ${WORK}/sub/../s.mha)
expect_in("${err}" "--out" "--sweep" "same file")
run_echosim(2 reconstruct --sweep ${WORK}/s.mha --out ${WORK}/./s.labels.mha --voxel-mm 1)
expect_in("${err}" "--sweep's labels")
run_echosim(2 slice --cpu --volume ${WORK}/v.nrrd --out ${WORK}/sub/../v.nrrd)
expect_in("${err}" "--out" "--volume" "same file")
file(SHA256 ${WORK}/s.mha sum)
if(NOT sum STREQUAL sweep_sum)
  message(FATAL_ERROR "reconstruct replaced its own input ${WORK}/s.mha")
endif()
file(SHA256 ${WORK}/v.nrrd sum)
if(NOT sum STREQUAL volume_sum)
  message(FATAL_ERROR "slice replaced its own input ${WORK}/v.nrrd")
endif()

# a sweep without labels: the labels file already beside the output is not this command's to delete
file(WRITE ${WORK}/w.labels.nrrd "someone's labels")
run_echosim(0 reconstruct --sweep ${WORK}/bare.mha --out ${WORK}/w.nrrd --voxel-mm 1)
expect_in("${err}" "w.labels.nrrd" "left as it was")
file(READ ${WORK}/w.labels.nrrd kept)
if(NOT kept STREQUAL "someone's labels")
  message(FATAL_ERROR "reconstruct deleted or replaced ${WORK}/w.labels.nrrd, a file it did not write")
endif()

# names: 250 bytes is legal, but the labels' name (.labels.nrrd added) is not: refused before the
# work; a name of the longest length the folder allows is written
string(REPEAT "a" 245 stem)
run_echosim(2 reconstruct --sweep ${WORK}/s.mha --out ${WORK}/${stem}.nrrd --voxel-mm 1)
expect_in("${err}" "--out's labels" "file name of 257 bytes")
if(EXISTS ${WORK}/${stem}.nrrd)
  message(FATAL_ERROR "reconstruct wrote a volume whose labels it could not write")
endif()
string(REPEAT "m" 251 stem)
run_echosim(0 measure --out ${WORK}/${stem}.csv)
if(NOT EXISTS ${WORK}/${stem}.csv)
  message(FATAL_ERROR "measure did not write ${WORK}/${stem}.csv (a 255-byte name)")
endif()

# what runs killed while writing left (PID 2147483647: above any pid_max, so gone) is removed by the
# next write there
file(MAKE_DIRECTORY ${WORK}/killed/.echosim-writing-2147483647-abc123)
file(WRITE ${WORK}/killed/.echosim-writing-2147483647-abc123/k.mha "half a sweep")
file(WRITE ${WORK}/killed/m.csv.echosim-partial-2147483647-abc123 "half a campaign")
run_echosim(0 measure --out ${WORK}/killed/m.csv)
run_echosim(0 phantom --out ${WORK}/killed/k.mha --frames 8 --pixel-mm 0.5)
file(GLOB left ${WORK}/killed/*.echosim-partial-* ${WORK}/killed/.echosim-writing-*)
if(left)
  message(FATAL_ERROR "what killed runs left was not removed: ${left}")
endif()

# a link planted under the name the temporary once had
file(WRITE ${WORK}/victim.txt "not yours")
file(CREATE_LINK ${WORK}/victim.txt ${WORK}/m.csv.partial SYMBOLIC)
run_echosim(0 measure --out ${WORK}/m.csv)
file(READ ${WORK}/victim.txt victim)
if(NOT victim STREQUAL "not yours" OR NOT IS_SYMLINK ${WORK}/m.csv.partial OR IS_SYMLINK ${WORK}/m.csv)
  message(FATAL_ERROR "measure wrote through the link ${WORK}/m.csv.partial, or replaced it")
endif()
file(GLOB left ${WORK}/*.echosim-partial-* ${WORK}/.echosim-writing-*)
if(left)
  message(FATAL_ERROR "temporaries left behind: ${left}")
endif()
file(REMOVE_RECURSE ${WORK})
