# Run by CTest before it runs the tests (rill_add_test_batches in RillTestBatches.cmake): lists
# the executable's cases, groups them into batches (a test suite, or a suite and a parameter),
# writes them to RILL_BATCH_OUTPUT and registers an add_test() for each. The list is written again
# only when the executable (or this script) is newer than it, so a CTest run that changes
# nothing lists nothing.
if(NOT EXISTS "${RILL_BATCH_EXECUTABLE}")
  # Not built (yet): like gtest_discover_tests, one test that fails and says so.
  add_test("${RILL_BATCH_EXECUTABLE}_NOT_BUILT" "${RILL_BATCH_EXECUTABLE}_NOT_BUILT")
  return()
endif()
cmake_policy(PUSH)
cmake_policy(VERSION 3.25)  # CTest reads this with no policies set: IN_LIST needs CMP0057

# A function, for a scope of its own: CTest reads every batch script of a directory in one
# scope, and one call's variables (cases_<batch>) must not leak into the next.
function(rill_write_test_batches)
  execute_process(
    COMMAND "${RILL_BATCH_EXECUTABLE}" --gtest_list_tests "--gtest_filter=${RILL_BATCH_FILTER}"
    WORKING_DIRECTORY "${RILL_BATCH_WORKING_DIRECTORY}"
    OUTPUT_VARIABLE listing
    RESULT_VARIABLE status
    TIMEOUT 60)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${RILL_BATCH_EXECUTABLE} --gtest_list_tests failed (${status}):\n${listing}")
  endif()

  # --gtest_list_tests prints a suite as "Suite." and its cases below it, indented, each maybe
  # followed by "  # GetParam() = ...". A case "Name/param" of a parameterized suite joins the
  # batch "Suite/param"; a case without '/' joins "Suite".
  string(REPLACE ";" "\\;" listing "${listing}")
  string(REPLACE "\n" ";" lines "${listing}")
  set(suite "")
  set(batches "")
  foreach(line IN LISTS lines)
    # A typed suite's line ends in a comment, "Suite/0.  # TypeParam = int": drop it.
    string(REGEX REPLACE "  #.*$" "" line "${line}")
    if(line MATCHES "^([^ #][^ ]*)\\.$")
      set(suite "${CMAKE_MATCH_1}")
    elseif(suite AND line MATCHES "^  ([^ ]+)")
      set(name "${CMAKE_MATCH_1}")
      if(name MATCHES "^DISABLED_" OR suite MATCHES "(^|/)DISABLED_")
        continue()  # as gtest_discover_tests: a disabled case is not run
      endif()
      set(batch "${suite}")
      if(name MATCHES "/([^/]+)$")
        string(APPEND batch "/${CMAKE_MATCH_1}")
      endif()
      string(MAKE_C_IDENTIFIER "${batch}" id)
      if(NOT DEFINED cases_${id})
        list(APPEND batches "${batch}")
      endif()
      list(APPEND cases_${id} "${suite}.${name}")
    endif()
  endforeach()

  # The batches, as CMake source: a name, the filter and the count of its cases each.
  set(script "# Written by RillTestBatchesScript.cmake from ${RILL_BATCH_EXECUTABLE}\n")
  foreach(batch IN LISTS batches)
    string(MAKE_C_IDENTIFIER "${batch}" id)
    list(JOIN cases_${id} ":" filter)
    string(APPEND script "list(APPEND rill_batches [==[${batch}${RILL_BATCH_SUFFIX}]==])\n"
                         "set([==[rill_batch_filter_${batch}${RILL_BATCH_SUFFIX}]==] [==[${filter}]==])\n")
  endforeach()
  # Written whole, then renamed: a second CTest run in the same build reads the old list or the
  # new one, never half of one.
  string(RANDOM LENGTH 8 tag)
  file(WRITE "${RILL_BATCH_OUTPUT}.${tag}" "${script}")
  file(RENAME "${RILL_BATCH_OUTPUT}.${tag}" "${RILL_BATCH_OUTPUT}")
endfunction()

if(NOT EXISTS "${RILL_BATCH_OUTPUT}" OR "${RILL_BATCH_EXECUTABLE}" IS_NEWER_THAN "${RILL_BATCH_OUTPUT}"
   OR "${CMAKE_CURRENT_LIST_FILE}" IS_NEWER_THAN "${RILL_BATCH_OUTPUT}")
  rill_write_test_batches()
endif()

set(rill_batches "")
include("${RILL_BATCH_OUTPUT}")
# Two batches of one name would leave one of them silently unregistered (CTest keeps the
# first): a second call for the same suites needs a SUFFIX of its own. Such a name gets a test
# that fails and says so.
get_property(taken GLOBAL PROPERTY RILL_TEST_BATCH_NAMES)
foreach(test IN LISTS rill_batches)
  if(test IN_LIST taken)
    add_test("${test}_DUPLICATE_BATCH_NAME" "${test}_DUPLICATE_BATCH_NAME_give_rill_add_test_batches_a_SUFFIX")
    continue()
  endif()
  list(APPEND taken "${test}")
  add_test("${test}" "${RILL_BATCH_EXECUTABLE}" "--gtest_filter=${rill_batch_filter_${test}}")
  set_tests_properties("${test}" PROPERTIES WORKING_DIRECTORY "${RILL_BATCH_WORKING_DIRECTORY}"
                       SKIP_RETURN_CODE 77 ${RILL_BATCH_PROPERTIES})
endforeach()
set_property(GLOBAL PROPERTY RILL_TEST_BATCH_NAMES "${taken}")
cmake_policy(POP)
