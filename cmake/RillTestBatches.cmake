# rill_add_test_batches(): registers a GoogleTest executable's cases with CTest in batches, one
# CTest test per test suite (and per parameter, for a parameterized suite), instead of one
# process per case as gtest_discover_tests() does.
#
# Why: most of a small case's time on a fresh machine is the process, not the check. PoCL
# loads its kernel library (about 0.7 s) in every process that builds a program from source,
# so twelve of the backend suite's OpenCL cases took 9.2 s of CPU one process each and 3.4 s
# in one (docs/testing.md, "Batches"). A batch still reports every case: GoogleTest prints
# each failing case's name, CTest prints a failing batch's output (--output-on-failure), and
# scripts/test-times counts the cases that ran from the batches' output.
#
#   rill_add_test_batches(<target>
#     [FILTER <gtest filter>]   the cases to take (default: all), as --gtest_filter reads it
#     [SUFFIX <text>]           appended to every batch's name ("-long")
#     [PROPERTIES <name> <value> ...])  set on every batch (LABELS, ENVIRONMENT, TIMEOUT, ...)
#
# A batch is named <suite>/<parameter><suffix> ("Backends/OperationsTest/opencl",
# "Backends/Render/opencl-long") or <suite><suffix> for a suite without parameters, and runs
# `<target> --gtest_filter=<its cases>`. As with gtest_discover_tests(DISCOVERY_MODE PRE_TEST),
# the cases are listed when CTest starts, from the executable it is about to run, so a new case
# needs no CMake run; the list is kept until the executable changes. One case alone:
# `<target> --gtest_filter=<name>`. Property values are single words (no ';' lists).
include_guard(GLOBAL)

set(_rill_test_batches_script "${CMAKE_CURRENT_LIST_DIR}/RillTestBatchesScript.cmake")

function(rill_add_test_batches target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "FILTER;SUFFIX" "PROPERTIES")
  if(NOT arg_FILTER)
    set(arg_FILTER "*")
  endif()
  string(MD5 key_hash "${target}|${arg_SUFFIX}|${arg_FILTER}")
  string(SUBSTRING "${key_hash}" 0 8 key_hash)
  set(base "${CMAKE_CURRENT_BINARY_DIR}/${target}_batches_${key_hash}")
  # The properties, written as CMake source for the script to pass to set_tests_properties.
  set(properties "")
  foreach(p IN LISTS arg_PROPERTIES)
    if(p MATCHES ";")
      # Each value is passed on as one word; a list value would come apart on the way.
      message(FATAL_ERROR "rill_add_test_batches(${target}): the property value '${p}' is a "
                          "list; set it with set_tests_properties on the batches instead")
    endif()
    string(APPEND properties " [==[${p}]==]")
  endforeach()
  file(GENERATE OUTPUT "${base}_include.cmake" CONTENT
"set(RILL_BATCH_EXECUTABLE [==[$<TARGET_FILE:${target}>]==])
set(RILL_BATCH_FILTER [==[${arg_FILTER}]==])
set(RILL_BATCH_SUFFIX [==[${arg_SUFFIX}]==])
set(RILL_BATCH_WORKING_DIRECTORY [==[${CMAKE_CURRENT_BINARY_DIR}]==])
set(RILL_BATCH_PROPERTIES ${properties})
set(RILL_BATCH_OUTPUT [==[${base}_tests.cmake]==])
include([==[${_rill_test_batches_script}]==])
")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${base}_include.cmake")
endfunction()
