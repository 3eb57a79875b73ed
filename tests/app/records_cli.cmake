# `echosim records` on a temporary database: exams stored from report.json files (`records add`),
# listed with the learning curve and its plot, as JSON, exported as xAPI twice to the same bytes,
# the default database under XDG_DATA_HOME, and the refusals (a missing database, a file that is
# not one, a report missing a field) naming the file.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(db ${WORK}/records.sqlite)

function(run expect_rc)
  execute_process(COMMAND ${ECHOSIM} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL ${expect_rc})
    message(FATAL_ERROR "echosim ${ARGN}: exit ${rc}, expected ${expect_rc}:\n${out}${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(write_report path trainee score passed sfj_correct)
  file(WRITE ${path} "{
  \"format\": \"echosim-exam-report\", \"version\": 1,
  \"trainee\": \"${trainee}\", \"case_id\": \"healthy\", \"case_title\": \"Healthy veins\", \"protocol\": \"three-point\",
  \"started_utc\": \"\", \"score\": ${score}, \"pass_mark\": 0.8, \"passed\": ${passed},
  \"conclusion\": \"DVT excluded\", \"dvt_present\": false, \"adequate_force_N\": 9.0, \"excessive_force_N\": 30.0,
  \"stations\": [
    {\"name\": \"CFV\", \"segment\": \"cfv\", \"s_cm\": 1.0, \"status\": \"covered\", \"reached\": true, \"reached_at_s\": 2.0,
     \"offset_mm\": 1.0, \"angle_deg\": 2.0, \"peak_force_N\": 12.0, \"deepest_press_at_s\": 4.0, \"lumen_rest_mm2\": 90.0,
     \"lumen_pressed_mm2\": 1.0, \"collapse_ratio\": 0.011, \"artery_area_ratio\": 0.95, \"thrombosed\": false,
     \"call\": \"compressible\", \"call_correct\": true, \"image_png\": \"\"},
    {\"name\": \"SFJ\", \"segment\": \"cfv\", \"s_cm\": 2.5, \"status\": \"covered\", \"reached\": true, \"reached_at_s\": 6.0,
     \"offset_mm\": 1.0, \"angle_deg\": 2.0, \"peak_force_N\": 12.0, \"deepest_press_at_s\": 8.0, \"lumen_rest_mm2\": 90.0,
     \"lumen_pressed_mm2\": 1.0, \"collapse_ratio\": 0.011, \"artery_area_ratio\": 0.95, \"thrombosed\": false,
     \"call\": \"compressible\", \"call_correct\": ${sfj_correct}, \"image_png\": \"\"}
  ],
  \"errors\": [],
  \"motion\": {\"duration_s\": 20.5, \"path_mm\": 150.0, \"mean_angle_deg\": 3.0, \"max_angle_deg\": 8.0},
  \"osaus\": {\"systematic_examination\": 4, \"interpretation\": 4, \"decision\": 4}
}
")
endfunction()

# nothing there yet: a named database that is missing is a mistyped path
run(2 records --records ${db})
if(NOT err MATCHES "no records database")
  message(FATAL_ERROR "a missing --records was not named:\n${err}")
endif()

write_report(${WORK}/a1.json "Ada" 0.5 false false)
write_report(${WORK}/a2.json "Ada" 1.0 true true)
run(0 records add ${WORK}/a1.json --records ${db})
if(NOT out MATCHES "Stored session 1 \\(Ada, healthy\\)")
  message(FATAL_ERROR "records add said:\n${out}")
endif()
run(0 records add ${WORK}/a2.json --records ${db})
run(0 records add ${WORK}/a2.json --records ${db} --trainee Bob)

run(0 records --records ${db} --trainee Ada --plot ${WORK}/curve.png)
foreach(expected "Trainee Ada: 2 sessions" "CUSUM per station type" "cfv +2 +0 +-0.29 +undecided" "sfj +2 +1 +0.71 +undecided")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "records --trainee Ada lacks '${expected}':\n${out}")
  endif()
endforeach()
if(out MATCHES "Bob")
  message(FATAL_ERROR "records --trainee Ada listed Bob:\n${out}")
endif()
if(NOT EXISTS ${WORK}/curve.png)
  message(FATAL_ERROR "--plot wrote no PNG")
endif()

run(0 records --records ${db} --json)
string(JSON sessions LENGTH "${out}" sessions)
string(JSON curves LENGTH "${out}" learning_curves)
string(JSON s LENGTH "${out}" learning_curves 0 station_types)
if(NOT sessions EQUAL 3 OR NOT curves EQUAL 2 OR NOT s EQUAL 2)
  message(FATAL_ERROR "records --json: ${sessions} sessions, ${curves} curves, ${s} station types:\n${out}")
endif()

# the xAPI statements: one per exam and one per station, the same bytes when exported again
run(0 records export --xapi ${WORK}/x1.json --records ${db})
run(0 records export --records ${db} --xapi ${WORK}/x2.json)
file(READ ${WORK}/x1.json x1)
file(READ ${WORK}/x2.json x2)
string(JSON n LENGTH "${x1}")
if(NOT n EQUAL 9 OR NOT x1 STREQUAL x2)
  message(FATAL_ERROR "xAPI export: ${n} statements (expected 9), or two exports differ")
endif()
string(JSON verb GET "${x1}" 0 verb id)
if(NOT verb STREQUAL "http://adlnet.gov/expapi/verbs/failed")
  message(FATAL_ERROR "the first exam's verb is ${verb}")
endif()
run(0 records export --xapi ${WORK}/bob.json --records ${db} --trainee Bob)
file(READ ${WORK}/bob.json bob)
string(JSON n LENGTH "${bob}")
if(NOT n EQUAL 3)
  message(FATAL_ERROR "Bob's export holds ${n} statements, expected 3")
endif()

# the default database: under XDG_DATA_HOME, made with its folder
execute_process(COMMAND ${CMAKE_COMMAND} -E env XDG_DATA_HOME=${WORK}/xdg ${ECHOSIM} records add ${WORK}/a1.json RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/xdg/echosim/records.sqlite)
  message(FATAL_ERROR "records add into the default database (${rc}):\n${out}${err}")
endif()

# refusals naming the file
file(WRITE ${WORK}/not_a_db.sqlite "just some text, long enough to be read as a header of something that is not SQLite at all ...")
run(1 records --records ${WORK}/not_a_db.sqlite)
if(NOT err MATCHES "not_a_db.sqlite: not an SQLite database")
  message(FATAL_ERROR "a file that is not a database was not named:\n${err}")
endif()
file(READ ${WORK}/a1.json good)
string(REPLACE "\"case_id\": \"healthy\"," "" broken "${good}")
file(WRITE ${WORK}/broken.json "${broken}")
run(2 records add ${WORK}/broken.json --records ${db})
if(NOT err MATCHES "broken.json: field '/case_id': missing")
  message(FATAL_ERROR "a report without case_id was not refused by name:\n${err}")
endif()
