# Runs one golden-output case. See cinepath_golden_test() in CinepathHelpers.cmake.
# Inputs: CINEPATH (binary), CASE_DIR (tests/golden/<cmd>/<case>), OUT_DIR (fresh output folder).
file(REMOVE_RECURSE ${OUT_DIR})
file(MAKE_DIRECTORY ${OUT_DIR})

file(STRINGS ${CASE_DIR}/args raw_args ENCODING UTF-8)
set(args "")
foreach(a IN LISTS raw_args)
  string(REPLACE "@OUT@" "${OUT_DIR}" a "${a}")
  string(REPLACE "@IN@" "${CASE_DIR}" a "${a}")
  string(REPLACE "@SRC@" "${CMAKE_CURRENT_LIST_DIR}/.." a "${a}")
  list(APPEND args "${a}")
endforeach()

set(expected_rc 0)
if(EXISTS ${CASE_DIR}/exit_code)
  file(READ ${CASE_DIR}/exit_code expected_rc)
  string(STRIP "${expected_rc}" expected_rc)
endif()

# Optional `workdir` file: the working directory (tokens as in args; default the output folder). With
# @SRC@ there, a case gives its inputs relative to the repository root, as a user would type them, and
# messages and outputs that name those paths do not depend on where the tree is checked out.
set(workdir ${OUT_DIR})
if(EXISTS ${CASE_DIR}/workdir)
  file(STRINGS ${CASE_DIR}/workdir workdir LIMIT_COUNT 1)
  string(REPLACE "@OUT@" "${OUT_DIR}" workdir "${workdir}")
  string(REPLACE "@IN@" "${CASE_DIR}" workdir "${workdir}")
  string(REPLACE "@SRC@" "${CMAKE_CURRENT_LIST_DIR}/.." workdir "${workdir}")
endif()

execute_process(COMMAND ${CINEPATH} ${args}
  WORKING_DIRECTORY ${workdir}
  RESULT_VARIABLE rc
  OUTPUT_FILE ${OUT_DIR}/.stdout
  ERROR_FILE ${OUT_DIR}/.stderr)

set(update "$ENV{CINEPATH_UPDATE_GOLDEN}")
set(failures "")

if(NOT "${rc}" STREQUAL "${expected_rc}")
  file(READ ${OUT_DIR}/.stderr err)
  list(APPEND failures "exit code ${rc}, expected ${expected_rc}; stderr:\n${err}")
endif()

# stdout and stderr are compared like any expected file.
set(pairs "stdout;.stdout" "stderr;.stderr")
file(GLOB_RECURSE expected_files RELATIVE ${CASE_DIR}/expected ${CASE_DIR}/expected/*)
foreach(f IN LISTS expected_files)
  if(NOT f STREQUAL "stdout" AND NOT f STREQUAL "stderr")
    list(APPEND pairs "${f}" "${f}")
  endif()
endforeach()

list(LENGTH pairs n)
math(EXPR last "${n} - 1")
foreach(i RANGE 0 ${last} 2)
  math(EXPR j "${i} + 1")
  list(GET pairs ${i} exp_name)
  list(GET pairs ${j} out_name)
  set(exp ${CASE_DIR}/expected/${exp_name})
  set(out ${OUT_DIR}/${out_name})
  if(update)
    if(exp_name STREQUAL "stderr" OR exp_name STREQUAL "stdout")
      file(SIZE ${out} sz)
      if(sz GREATER 0 OR EXISTS ${exp})
        configure_file(${out} ${exp} COPYONLY)
      endif()
    elseif(EXISTS ${out})
      configure_file(${out} ${exp} COPYONLY)
    endif()
    continue()
  endif()
  if(NOT EXISTS ${exp})
    # A missing expected stderr means "stderr must be empty"; a missing stdout is not checked.
    if(exp_name STREQUAL "stderr")
      file(SIZE ${out} sz)
      if(sz GREATER 0)
        file(READ ${out} err)
        list(APPEND failures "unexpected stderr:\n${err}")
      endif()
    endif()
    continue()
  endif()
  if(NOT EXISTS ${out})
    list(APPEND failures "missing output ${out_name}")
    continue()
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${exp} ${out} RESULT_VARIABLE differ)
  if(differ)
    execute_process(COMMAND diff -u ${exp} ${out} OUTPUT_VARIABLE d)
    list(APPEND failures "${exp_name} differs from the golden file (actual output left in ${out}):\n${d}")
  endif()
endforeach()

if(failures)
  string(JOIN "\n" msg ${failures})
  message(FATAL_ERROR "golden case ${CASE_DIR} failed:\n${msg}")
endif()
