# cinepath_add_library(NAME <area> SRCS ... LINK_LIBS ...)
#   Declares the area library cinepath_<area>; headers are included as "<area>/<file>.h".
function(cinepath_add_library)
  cmake_parse_arguments(ARG "" "NAME" "SRCS;LINK_LIBS;PRIVATE_LIBS" ${ARGN})
  set(target cinepath_${ARG_NAME})
  add_library(${target} STATIC ${ARG_SRCS})
  target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${target} PUBLIC ${ARG_LINK_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  target_compile_options(${target} PRIVATE -Wall -Wextra)
endfunction()

# cinepath_add_test(NAME <name> SRCS ... LINK_LIBS ...)
#   One GoogleTest executable, registered with CTest test by test.
include(GoogleTest)
function(cinepath_add_test)
  cmake_parse_arguments(ARG "" "NAME" "SRCS;LINK_LIBS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SRCS})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_LINK_LIBS} GTest::gtest_main)
  target_compile_definitions(${ARG_NAME} PRIVATE
    CINEPATH_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data"
    CINEPATH_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  gtest_discover_tests(${ARG_NAME} DISCOVERY_TIMEOUT 60)
endfunction()

# cinepath_golden_test(CMD <cmd> CASE <case>)
#   Runs the real binary on tests/golden/<cmd>/<case>/: reads `args` (one argument per line; the token
#   @OUT@ stands for the case's output folder in the build tree, @IN@ for the case folder), expects the
#   exit code in `exit_code` (default 0), compares stdout with `expected/stdout` when present, stderr with
#   `expected/stderr` (empty when absent), and every other file under expected/ with the file of the same
#   name in the output folder, byte for byte. CINEPATH_UPDATE_GOLDEN=1 rewrites expected/.
function(cinepath_golden_test)
  cmake_parse_arguments(ARG "" "CMD;CASE" "" ${ARGN})
  set(case_dir ${PROJECT_SOURCE_DIR}/tests/golden/${ARG_CMD}/${ARG_CASE})
  set(out_dir ${CMAKE_BINARY_DIR}/golden/${ARG_CMD}/${ARG_CASE})
  add_test(NAME golden.${ARG_CMD}.${ARG_CASE}
    COMMAND ${CMAKE_COMMAND}
      -DCINEPATH=$<TARGET_FILE:cinepath>
      -DCASE_DIR=${case_dir}
      -DOUT_DIR=${out_dir}
      -P ${PROJECT_SOURCE_DIR}/cmake/RunGoldenTest.cmake)
endfunction()

# Registers every case folder under tests/golden/<cmd>/.
function(cinepath_golden_tests_for CMD)
  file(GLOB cases LIST_DIRECTORIES true RELATIVE ${PROJECT_SOURCE_DIR}/tests/golden/${CMD}
       ${PROJECT_SOURCE_DIR}/tests/golden/${CMD}/*)
  foreach(c ${cases})
    if(IS_DIRECTORY ${PROJECT_SOURCE_DIR}/tests/golden/${CMD}/${c})
      cinepath_golden_test(CMD ${CMD} CASE ${c})
    endif()
  endforeach()
endfunction()
