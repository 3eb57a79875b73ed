# One field of every error an exam's report.json flags, in their order, as a list: `kind`,
# `station`, ... (the exam tests' scripts include this: exam_cli.cmake, shipped_exams_cli.cmake).
function(report_errors json field out)
  string(JSON n LENGTH "${json}" errors)
  set(values "")
  if(n GREATER 0)
    math(EXPR last "${n} - 1")
    foreach(i RANGE ${last})
      string(JSON v GET "${json}" errors ${i} ${field})
      list(APPEND values ${v})
    endforeach()
  endif()
  set(${out} "${values}" PARENT_SCOPE)
endfunction()
