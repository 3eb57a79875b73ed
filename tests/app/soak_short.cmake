# `echosim soak` for a few seconds on lavapipe: it runs every part (frames, physics steps, haptic
# ticks), writes its JSON report with every field, and memory and validation hold. Deadlines are
# reported, not judged (--deadlines report): a test on a loaded machine, maybe without real-time
# priority, must not fail on timing; scripts/test's soak stage judges them.
file(REMOVE ${JSON})
execute_process(COMMAND ${ECHOSIM} soak --seconds 8 --gpu cpu --width 320 --height 180 --deadlines report --json ${JSON}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "echosim soak failed (${rc}):\n${out}${err}")
endif()
if(NOT out MATCHES "resident memory .* MiB after the warm-up" OR NOT out MATCHES "passed")
  message(FATAL_ERROR "echosim soak did not summarise:\n${out}")
endif()
file(READ ${JSON} j)
foreach(field seconds frames physics_steps haptic_ticks rss_start_mib rss_end_mib rss_max_mib validation_messages
              haptic_period_p99_ms haptic_period_max_ms haptic_missed_deadlines warmup_s)
  string(JSON v ERROR_VARIABLE e GET "${j}" ${field})
  if(e)
    message(FATAL_ERROR "soak JSON: no ${field}: ${e}\n${j}")
  endif()
  set(${field} ${v})
endforeach()
string(JSON pass GET "${j}" pass)
string(JSON bounds LENGTH "${j}" bounds)
# sane values: about 8 s, frames and steps made, 1 kHz ticks within a wide margin, memory in MiB
if(seconds LESS 8 OR seconds GREATER 30)
  message(FATAL_ERROR "soak JSON: seconds ${seconds}")
endif()
if(frames LESS 8 OR physics_steps LESS 100 OR haptic_ticks LESS 1000 OR NOT validation_messages EQUAL 0 OR NOT pass)
  message(FATAL_ERROR "soak JSON: frames ${frames}, physics steps ${physics_steps}, haptic ticks ${haptic_ticks}, validation ${validation_messages}, pass ${pass}")
endif()
if(rss_start_mib LESS 10 OR rss_max_mib LESS rss_end_mib OR rss_max_mib LESS rss_start_mib OR NOT bounds EQUAL 5)
  message(FATAL_ERROR "soak JSON: rss start ${rss_start_mib}, end ${rss_end_mib}, max ${rss_max_mib}; ${bounds} bounds")
endif()
