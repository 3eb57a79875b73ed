# `echosim soak --seconds 60` sent SIGTERM after 3 s stops in order (issue 34, signals): it ends
# promptly, not after its 60 s, prints its summary, writes its JSON report naming the signal, and
# exits 143 (128 + SIGTERM). coreutils' timeout sends the signal (and SIGKILL 30 s later, should
# the soak not stop); --preserve-status passes the soak's own exit status through. --foreground:
# without it timeout sends the TERM twice, to the soak and then to its whole process group, and a
# second TERM ends a soak at once by design (app/stop_signals.hpp); under load the soak took the
# first before the second came and was killed with nothing printed (a clean clone's scripts/test,
# 2026-11-28).
file(REMOVE ${JSON})
string(TIMESTAMP started "%s" UTC)
execute_process(COMMAND timeout --foreground --preserve-status -k 30 -s TERM 3
                        ${ECHOSIM} soak --seconds 60 --gpu cpu --width 320 --height 180 --deadlines report --json ${JSON}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(TIMESTAMP ended "%s" UTC)
math(EXPR took "${ended} - ${started}")
if(NOT rc EQUAL 143)
  message(FATAL_ERROR "echosim soak sent SIGTERM exited ${rc}, not 143, after ${took} s:\n${out}${err}")
endif()
# its set-up (a coarse volume, lavapipe, the validation layer) is seconds; a soak that ignored the
# signal would run its 60 s
if(took GREATER 45)
  message(FATAL_ERROR "echosim soak took ${took} s to stop after SIGTERM at 3 s:\n${out}${err}")
endif()
if(NOT out MATCHES "stopped by SIGTERM after" OR NOT out MATCHES "haptic period error p50" OR NOT out MATCHES "wrote ")
  message(FATAL_ERROR "echosim soak stopped without its summary:\n${out}${err}")
endif()
if(NOT EXISTS ${JSON})
  message(FATAL_ERROR "echosim soak stopped without writing ${JSON}:\n${out}${err}")
endif()
file(READ ${JSON} j)
string(JSON by GET "${j}" stopped_by_signal)
string(JSON seconds GET "${j}" seconds)
string(JSON requested GET "${j}" requested_seconds)
if(NOT by STREQUAL "SIGTERM" OR NOT seconds LESS 45 OR NOT requested EQUAL 60)
  message(FATAL_ERROR "soak JSON: stopped_by_signal ${by}, seconds ${seconds} of ${requested}\n${j}")
endif()
message(STATUS "soak stopped by SIGTERM in ${took} s (${seconds} s of session)")

# a log redirected to a file keeps every line printed before a kill (stdout is line-buffered): a
# kiosk killed by its watchdog, SIGKILL here, leaves what it said
set(log ${JSON}.log)
file(REMOVE ${log})
execute_process(COMMAND timeout -s KILL 2 ${ECHOSIM} soak --seconds 60 --gpu cpu --width 320 --height 180
                OUTPUT_FILE ${log} ERROR_VARIABLE err RESULT_VARIABLE rc)
file(READ ${log} logged)
if(NOT (rc EQUAL 137 OR rc STREQUAL "Subprocess killed") OR NOT logged MATCHES "making its volume")
  message(FATAL_ERROR "echosim soak killed after 2 s (exit ${rc}) left a log without its first line:\n${logged}${err}")
endif()
