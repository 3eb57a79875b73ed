# The build's check that the frame loop exists once (STYLE.md 15), a supplement to the runner's
# tests (tests/runner/runner_test.cpp: each configuration counted step by step through an observer):
#   - no source of engine/app presents a frame itself (WindowPresenter::draw,
#     OffscreenPresenter::render) but headless.cpp, the one frame of `echosim render`;
#   - the sources of the runner's configurations (`run`, `soak`, `haptics-demo`, `exam`) move no
#     session's clock (Session::advance) and each makes a runner::Runner: their steps are its.
# (A command that is no running simulator may still use the session's own helpers: `case plan`
# settles presses with Session::press_to_force.)
# Run: cmake -DAPP=engine/app -P one_loop.cmake
cmake_policy(SET CMP0007 NEW)
file(GLOB sources ${APP}/*.cpp ${APP}/*.hpp)
set(configurations cmd_run.cpp soak.cpp haptics_demo.cpp exam_run.cpp)
set(failures "")
foreach(f ${sources})
  get_filename_component(name ${f} NAME)
  list(FIND configurations ${name} configuration)
  file(STRINGS ${f} lines)
  set(n 0)
  foreach(line IN LISTS lines)
    math(EXPR n "${n} + 1")
    if(line MATCHES "^[ \t]*//")
      continue()
    endif()
    if(configuration GREATER -1 AND line MATCHES "\\.advance\\(|->advance\\(")
      list(APPEND failures "${name}:${n}: a configuration of the runner moves the session's clock itself")
    endif()
    if(line MATCHES "\\.draw\\(|presenter\\.render\\(" AND NOT name STREQUAL "headless.cpp")
      list(APPEND failures "${name}:${n}: presents a frame outside the runner")
    endif()
  endforeach()
endforeach()
foreach(name ${configurations})
  if(NOT EXISTS ${APP}/${name})
    if(name STREQUAL "exam_run.cpp")
      continue()  # `echosim exam`, where it is built
    endif()
    list(APPEND failures "${name}: missing")
    continue()
  endif()
  file(READ ${APP}/${name} text)
  if(NOT text MATCHES "runner::Runner runner\\(")
    list(APPEND failures "${name}: makes no runner::Runner")
  endif()
endforeach()
if(failures)
  list(JOIN failures "\n  " shown)
  message(FATAL_ERROR "one runner: the frame loop is not the runner's alone:\n  ${shown}")
endif()
message(STATUS "one runner: the configurations in engine/app step through the runner; no frame is presented outside it")
