# `echosim render --press-mm`: the tissue is simulated until it settles under the pressed probe, the
# force is reported, and the frame differs from the one at rest.
foreach(press 0 12)
  execute_process(COMMAND ${ECHOSIM} render --out ${WORK}_${press}.png --width 320 --height 200 --gpu cpu --validation
                          --press-mm ${press} --camera 1.3,0.35,380,probe
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "echosim render --press-mm ${press} failed (${rc}):\n${out}${err}")
  endif()
  string(REGEX MATCH "pushes back ([0-9.]+) N" m "${out}")
  set(force_${press} ${CMAKE_MATCH_1})
endforeach()
if(NOT force_0 EQUAL 0)
  message(FATAL_ERROR "a probe resting on the skin should feel no force, got ${force_0} N")
endif()
# the fitted model at 12 mm in: a few newtons (the pseudo-probe measured 5 to 10 N there)
if(force_12 LESS 3 OR force_12 GREATER 20)
  message(FATAL_ERROR "pressing 12 mm gave ${force_12} N, outside 3..20 N")
endif()
file(SHA256 ${WORK}_0.png a)
file(SHA256 ${WORK}_12.png b)
if(a STREQUAL b)
  message(FATAL_ERROR "the pressed frame is identical to the frame at rest")
endif()
