# Run after a test program is built (tests/CMakeLists.txt,
# spook_discover_tests with SPOOK_TEST_BATCH_SIZE > 0): registers one CTest
# test per BATCH_SIZE consecutive test cases of the program, in doctest's
# file order (--first/--last, 1-based and inclusive), instead of one per
# case. A sanitized program takes ~0.14 s to start (ASan's shadow memory and
# LeakSanitizer's exit scan), which one test per case paid 975 times: a
# quarter of the sanitized stage's test time. A failing batch's output names
# its failing case.
#
# Inputs (-D): TEST_EXECUTABLE, TEST_PREFIX, BATCH_SIZE, WORKING_DIR, CTEST_FILE.

execute_process(
  COMMAND "${TEST_EXECUTABLE}" --list-test-cases
  OUTPUT_VARIABLE output
  RESULT_VARIABLE result
  WORKING_DIRECTORY "${WORKING_DIR}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "listing the test cases of '${TEST_EXECUTABLE}' failed (${result}):\n${output}")
endif()

string(REPLACE "\n" ";" lines "${output}")
set(names "")
foreach(line IN LISTS lines)
  if(line STREQUAL "" OR line MATCHES "^=+$" OR line MATCHES "^\\[doctest\\] ")
    continue()
  endif()
  list(APPEND names "${line}")
endforeach()
list(LENGTH names count)

set(script "")
set(first 1)
while(first LESS_EQUAL count)
  math(EXPR last "${first} + ${BATCH_SIZE} - 1")
  if(last GREATER count)
    set(last ${count})
  endif()
  math(EXPR index "${first} - 1")
  list(GET names ${index} head)
  string(REPLACE "]==]" "" head "${head}")
  set(name "${TEST_PREFIX}cases ${first}-${last} of ${count} from '${head}'")
  string(APPEND script
    "add_test([==[${name}]==] [==[${TEST_EXECUTABLE}]==] --first=${first} --last=${last})\n"
    "set_tests_properties([==[${name}]==] PROPERTIES WORKING_DIRECTORY [==[${WORKING_DIR}]==])\n")
  math(EXPR first "${last} + 1")
endwhile()
file(WRITE "${CTEST_FILE}" "${script}")
