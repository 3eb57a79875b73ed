# `echosim exam` end to end on lavapipe (issue 31's tests), each exam scripted by `echosim case plan`
# on the simulated tissue and scored from the simulation's truth:
#   - the healthy anatomy, three-point: the correct exam collapses every station (lumen at the
#     deepest press <= 20 % of its rest, on the coarse volume) and flags nothing; one exam per classic error is flagged
#     for exactly that error (and the light press also for the false "not compressible" it leads to);
#   - two runs of the same exam write byte-identical report.json files;
#   - the shipped isolated femoral clot (extended): not collapsed at exactly the stations over the
#     clot (FV 16..24 cm), collapsed elsewhere, and its conclusion names them;
#   - the same clot under a two-point exam: both stations compress, and the report says the exam does
#     not exclude a clot between them;
#   - every exam is stored in the trainee records.
# Volumes are the coarse ones (--coarse), made once into this test's own cache.
set(ENV{XDG_CACHE_HOME} ${WORK}/cache)
set(ENV{XDG_DATA_HOME} ${WORK}/data)
file(REMOVE_RECURSE ${WORK}/runs)
file(MAKE_DIRECTORY ${WORK}/runs)

function(run_checked what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} exited ${rc}:\n${out}${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

# plans the case's exam in `style` and plays it into runs/NAME; report.json's text in `report`
function(exam name scenario style)
  set(script ${WORK}/runs/${name}.csv)
  run_checked("echosim case plan ${name}" ${ECHOSIM} case plan --scenario ${scenario} --style ${style} --out ${script})
  run_checked("echosim exam ${name}" ${ECHOSIM} exam --scenario ${scenario} --trajectory ${script} --out ${WORK}/runs/${name}
              --coarse --frames-per-s 0 --trainee "test ${style}" --records ${WORK}/records.sqlite)
  file(READ ${WORK}/runs/${name}/report.json text)
  set(report "${text}" PARENT_SCOPE)
  message(STATUS "${name}: ${last_output}")
endfunction()

include(${CMAKE_CURRENT_LIST_DIR}/report_errors.cmake)

# every station's collapse: those in `open_names` must stay open (ratio > 0.5), the others collapse
# (<= 0.2: the coarse volume's 0.6 mm labels blur a closed 8 mm vein's seam over a voxel or two;
# most stations close to 0.01..0.05, a few near a branch or the clot's tip to about 0.11)
function(check_collapse name json open_names)
  string(JSON n LENGTH "${json}" stations)
  math(EXPR last "${n} - 1")
  foreach(i RANGE ${last})
    string(JSON station GET "${json}" stations ${i} name)
    string(JSON ratio GET "${json}" stations ${i} collapse_ratio)
    list(FIND open_names "${station}" open)
    if(open GREATER -1)
      if(ratio LESS_EQUAL 0.5)
        message(FATAL_ERROR "${name}: ${station} is over the clot but collapsed to ${ratio}")
      endif()
    elseif(ratio GREATER 0.2)
      message(FATAL_ERROR "${name}: ${station} is a normal vein but only collapsed to ${ratio}")
    endif()
  endforeach()
endfunction()

set(three ${CASES_TEST}/healthy-three-point.json)

exam(correct ${three} correct)
report_errors("${report}" kind kinds)
if(NOT kinds STREQUAL "")
  message(FATAL_ERROR "the correct exam flagged: ${kinds}")
endif()
check_collapse(correct "${report}" "")
string(JSON passed GET "${report}" passed)
if(NOT passed)
  message(FATAL_ERROR "the correct exam did not pass:\n${report}")
endif()

exam(correct-again ${three} correct)
file(READ ${WORK}/runs/correct/report.json first)
if(NOT first STREQUAL report)
  message(FATAL_ERROR "two runs of the same exam wrote different report.json files (runs/correct, runs/correct-again)")
endif()

foreach(pair "skip=skipped-station" "light-press=too-little-pressure;wrong-call" "oblique=oblique-plane" "artery=wrong-vessel"
             "excessive=excessive-force")
  string(REPLACE "=" ";" parts "${pair}")
  list(GET parts 0 style)
  list(SUBLIST parts 1 -1 expected)
  exam(${style} ${three} ${style})
  report_errors("${report}" kind kinds)
  list(SORT kinds)
  list(SORT expected)
  if(NOT kinds STREQUAL expected)
    message(FATAL_ERROR "the ${style} exam flagged '${kinds}', expected exactly '${expected}':\n${report}")
  endif()
endforeach()

exam(fv-isolated ${CASES}/fv-isolated-acute.json correct)
check_collapse(fv-isolated "${report}" "FV 16 cm;FV 18 cm;FV 20 cm;FV 22 cm;FV 24 cm")
string(JSON conclusion GET "${report}" conclusion)
if(NOT conclusion MATCHES "FV 16 cm" OR NOT conclusion MATCHES "thrombosis")
  message(FATAL_ERROR "fv-isolated: the conclusion does not name the clot: ${conclusion}")
endif()

exam(two-point ${CASES_TEST}/fv-isolated-two-point.json correct)
check_collapse(two-point "${report}" "")
string(JSON conclusion GET "${report}" conclusion)
string(JSON dvt GET "${report}" dvt_present)
if(NOT conclusion MATCHES "not excluded" OR NOT dvt)
  message(FATAL_ERROR "two-point over an isolated FV clot: '${conclusion}' (dvt_present ${dvt}): should say the clot is not excluded")
endif()

run_checked("echosim records" ${ECHOSIM} records --records ${WORK}/records.sqlite)
string(REGEX MATCHALL "test [a-z-]+" trainees "${last_output}")
list(LENGTH trainees stored)
if(stored LESS 10)
  message(FATAL_ERROR "echosim records lists ${stored} of the 10 exams:\n${last_output}")
endif()
