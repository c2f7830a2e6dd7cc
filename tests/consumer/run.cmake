# Installs the built linkbox into a scratch prefix, then configures, builds and runs the
# consumer project against it, as another CMake project would use linkbox. The consumer is
# compiled with the build's own flags (a sanitizer build's library needs its runtime).
set(prefix ${BUILD_DIR}/consumer-install)
set(work ${BUILD_DIR}/consumer-build)
file(REMOVE_RECURSE ${prefix} ${work})
foreach(step
    "${CMAKE_COMMAND};--install;${BUILD_DIR};--prefix;${prefix}"
    "${CMAKE_COMMAND};-S;${SOURCE_DIR}/tests/consumer;-B;${work};-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release;-DCMAKE_CXX_FLAGS=${CXX_FLAGS};-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}"
    "${CMAKE_COMMAND};--build;${work}"
    "${work}/consumer;${SOURCE_DIR}/cases/polynomial/circle-line.toml"
    "${prefix}/bin/linkbox;--version")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${step}")
  endif()
endforeach()
