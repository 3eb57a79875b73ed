# The build's check that the frame loop exists once (STYLE.md 15), a supplement to the runner's
# tests (tests/runner/runner_test.cpp: each configuration counted step by step through an observer):
# in engine/app no source moves a session's clock (Session::advance) or presents a frame itself
# (WindowPresenter::draw, OffscreenPresenter::render) but headless.cpp, the one frame of
# `echosim render`; and the commands that run the simulator (run, soak, haptics-demo) make a
# runner::Runner.
# Run: cmake -DAPP=engine/app -P one_loop.cmake
cmake_policy(SET CMP0007 NEW)
file(GLOB sources ${APP}/*.cpp ${APP}/*.hpp)
set(failures "")
foreach(f ${sources})
  get_filename_component(name ${f} NAME)
  file(STRINGS ${f} lines)
  set(n 0)
  foreach(line IN LISTS lines)
    math(EXPR n "${n} + 1")
    if(line MATCHES "^[ \t]*//")
      continue()
    endif()
    if(line MATCHES "\\.advance\\(|->advance\\(")
      list(APPEND failures "${name}:${n}: moves the session's clock outside the runner: ${line}")
    endif()
    if(line MATCHES "\\.draw\\(|presenter\\.render\\(" AND NOT name STREQUAL "headless.cpp")
      list(APPEND failures "${name}:${n}: presents a frame outside the runner: ${line}")
    endif()
  endforeach()
endforeach()
foreach(name cmd_run.cpp soak.cpp haptics_demo.cpp)
  file(READ ${APP}/${name} text)
  if(NOT text MATCHES "runner::Runner runner\\(")
    list(APPEND failures "${name}: makes no runner::Runner")
  endif()
endforeach()
if(failures)
  list(JOIN failures "\n  " shown)
  message(FATAL_ERROR "one runner: the frame loop is not the runner's alone:\n  ${shown}")
endif()
message(STATUS "one runner: engine/app steps no session and presents no frame of its own")
