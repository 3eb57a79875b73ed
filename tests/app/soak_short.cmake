# `echosim soak` for 12 s on lavapipe: it runs every part (frames, physics steps, haptic ticks),
# writes its JSON report with every field and sane values, and validation stays silent. It judges
# no timing (--deadlines report) and does not require the memory bounds (exit 1 is accepted when the
# report says memory is what failed): 12 s in the middle of a parallel ctest, maybe without
# real-time priority, is no measure of either; the 2-minute soak after the tests (scripts/test)
# judges memory, validation and the p99, alone on the machine.
file(REMOVE ${JSON})
execute_process(COMMAND ${ECHOSIM} soak --seconds 12 --gpu cpu --width 320 --height 180 --deadlines report --json ${JSON}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 AND NOT rc EQUAL 1)
  message(FATAL_ERROR "echosim soak failed (${rc}):\n${out}${err}")
endif()
if(NOT out MATCHES "resident memory .* MiB after the warm-up" OR NOT out MATCHES "haptic period error p50")
  message(FATAL_ERROR "echosim soak did not summarise:\n${out}")
endif()
file(READ ${JSON} j)
foreach(field seconds frames physics_steps haptic_ticks rss_start_mib rss_end_mib rss_max_mib validation_messages
              haptic_period_p99_ms haptic_period_max_ms haptic_missed_deadlines haptic_cpus_awake warmup_s pass
              host_steal_s steal_free_s haptic_period_p99_steal_free_ms)
  string(JSON v ERROR_VARIABLE e GET "${j}" ${field})
  if(e)
    message(FATAL_ERROR "soak JSON: no ${field}: ${e}\n${j}")
  endif()
  set(${field} ${v})
endforeach()
string(JSON bounds LENGTH "${j}" bounds)
string(JSON samples LENGTH "${j}" samples)
# sane values: about 12 s, frames, steps and ticks made (how many is timing, which a test does not
# judge: under AddressSanitizer the physics makes 570 steps in 12 s), memory in MiB
if(seconds LESS 12 OR seconds GREATER 60 OR NOT warmup_s GREATER 7)
  message(FATAL_ERROR "soak JSON: seconds ${seconds}, warm-up ${warmup_s}")
endif()
if(frames LESS 1 OR physics_steps LESS 1 OR haptic_ticks LESS 1 OR NOT validation_messages EQUAL 0)
  message(FATAL_ERROR "soak JSON: frames ${frames}, physics steps ${physics_steps}, haptic ticks ${haptic_ticks}, validation ${validation_messages}")
endif()
if(rss_start_mib LESS 10 OR rss_max_mib LESS rss_end_mib OR rss_max_mib LESS rss_start_mib OR NOT bounds EQUAL 6 OR samples LESS 12)
  message(FATAL_ERROR "soak JSON: rss start ${rss_start_mib}, end ${rss_end_mib}, max ${rss_max_mib}; ${bounds} bounds, ${samples} samples")
endif()
# the seconds free of host steal are some of the run's; the steal read on Linux (-1: unreadable)
if(steal_free_s LESS 0 OR steal_free_s GREATER seconds OR host_steal_s LESS 0)
  message(FATAL_ERROR "soak JSON: ${steal_free_s} s free of host steal of ${seconds} s; host steal ${host_steal_s} s")
endif()
# exit 1 only for the memory bounds (validation is 0, deadlines are reported only)
if(rc EQUAL 1 AND pass)
  message(FATAL_ERROR "echosim soak exit 1 but its report passes:\n${out}${err}")
endif()
message(STATUS "soak: ${frames} frames, rss ${rss_start_mib} -> ${rss_end_mib} MiB (max ${rss_max_mib}), pass ${pass}")
