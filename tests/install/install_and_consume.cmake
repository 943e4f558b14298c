# Run by the install.find_package test (cmake -P). Installs the build in RILL_BUILD_DIR to
# WORK_DIR/prefix, builds CONSUMER_SOURCE_DIR (with the example from README) against it in
# WORK_DIR/build and runs both programs. RAYTRACER=ON: the ray tracer was built, so its
# headers must be installed and the rill::raytracer consumer is built and run too.
cmake_minimum_required(VERSION 3.25)

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(build ${WORK_DIR}/build)

function(step what)
  message(STATUS "install test: ${what}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install test: '${what}' failed (${rc})")
  endif()
endfunction()

step("cmake --install" ${CMAKE_COMMAND} --install ${RILL_BUILD_DIR} --prefix ${prefix})
if(NOT EXISTS ${prefix}/include/rill/rill.h)
  message(FATAL_ERROR "install test: ${prefix}/include/rill/rill.h was not installed")
endif()
if(RAYTRACER AND NOT EXISTS ${prefix}/include/rill/rt/Tracer.h)
  message(FATAL_ERROR "install test: ${prefix}/include/rill/rt/Tracer.h was not installed")
endif()

set(configure ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${build} -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DRILL_README=${README}
    -DRILL_CONSUMER_RAYTRACER=${RAYTRACER})
if(CONSUMER_FLAGS)
  list(APPEND configure "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}"
       "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}")
endif()
step("configure the consumer" ${configure})
step("build the consumer" ${CMAKE_COMMAND} --build ${build})
step("run the consumer" ${build}/rill-consumer)
step("run the README example" ${build}/rill-readme-example)
if(RAYTRACER)
  step("run the ray tracer consumer" ${build}/rill-consumer-raytracer)
endif()
