# Run by CTest before it runs the tests (rill_add_test_batches in RillTestBatches.cmake): lists
# the executable's cases, groups them into batches (a test suite, or a suite and a parameter),
# writes an add_test() per batch to RILL_BATCH_OUTPUT and includes it. The list is written again
# only when the executable is newer than it, so a CTest run that changes nothing lists nothing.
if(NOT EXISTS "${RILL_BATCH_EXECUTABLE}")
  # Not built (yet): like gtest_discover_tests, one test that fails and says so.
  add_test("${RILL_BATCH_EXECUTABLE}_NOT_BUILT" "${RILL_BATCH_EXECUTABLE}_NOT_BUILT")
  return()
endif()

if(NOT EXISTS "${RILL_BATCH_OUTPUT}" OR "${RILL_BATCH_EXECUTABLE}" IS_NEWER_THAN "${RILL_BATCH_OUTPUT}")
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

  set(script "# Written by RillTestBatchesScript.cmake from ${RILL_BATCH_EXECUTABLE}\n")
  foreach(batch IN LISTS batches)
    string(MAKE_C_IDENTIFIER "${batch}" id)
    list(LENGTH cases_${id} count)
    list(JOIN cases_${id} ":" filter)
    set(test "${batch}${RILL_BATCH_SUFFIX}")
    string(APPEND script
      "add_test([==[${test}]==] [==[${RILL_BATCH_EXECUTABLE}]==] [==[--gtest_filter=${filter}]==])\n"
      "set_tests_properties([==[${test}]==] PROPERTIES WORKING_DIRECTORY [==[${RILL_BATCH_WORKING_DIRECTORY}]==]"
      " SKIP_RETURN_CODE 77")
    foreach(p IN LISTS RILL_BATCH_PROPERTIES)
      string(APPEND script " [==[${p}]==]")
    endforeach()
    string(APPEND script ")\n")
  endforeach()
  file(WRITE "${RILL_BATCH_OUTPUT}" "${script}")
endif()
include("${RILL_BATCH_OUTPUT}")
