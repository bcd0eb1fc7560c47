# The install test: installs the build into a fresh prefix, builds the consumer program
# (tests/install/consumer) against it with find_package(relume), writes a small field with the
# installed `relume synth` and runs the consumer on it. Any failing step fails the test.
# Run as: cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P install_test.cmake
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "install test: ${what} failed (${status})")
  endif()
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run("install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")
foreach(installed bin/relume include/relume/relume.hpp lib/librelume.a
                  lib/cmake/relume/relumeConfig.cmake)
  if(NOT EXISTS "${prefix}/${installed}")
    message(FATAL_ERROR "install test: ${prefix}/${installed} was not installed")
  endif()
endforeach()
file(GLOB_RECURSE internal_headers "${prefix}/include/*/compress/*.hpp" "${prefix}/include/core/*")
if(internal_headers)
  message(FATAL_ERROR "install test: internal headers were installed: ${internal_headers}")
endif()

run("configure the consumer" "${CMAKE_COMMAND}" -S "${SOURCE_DIR}/tests/install/consumer"
    -B "${WORK_DIR}/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
run("build the consumer" "${CMAKE_COMMAND}" --build "${WORK_DIR}/consumer")
run("relume synth" "${prefix}/bin/relume" synth -q -o "${WORK_DIR}/scene" --size 48x40
    --lights 60 --samples 1)
run("the consumer" "${WORK_DIR}/consumer/relume_consumer" "${WORK_DIR}/scene" "${WORK_DIR}")
