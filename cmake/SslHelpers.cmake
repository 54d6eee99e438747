# The one helper for declaring targets. Every target gets an `ssl::<name>` alias, our warning set and
# C++20 through the `ssl_project_options` interface target; include paths are the source root and the
# binary root, so headers are included as "libs/geometry/angle.h" and generated ones as "idl/vision.h".
#
#   ssl_cc_library(NAME n [SRCS ...] [HDRS ...] [DEPS ...] [PRIVATE_DEPS ...] [TESTONLY])
#   ssl_cc_binary(NAME n SRCS ... [DEPS ...])        -> build/bin/n
#   ssl_cc_test(NAME n SRCS ... [DEPS ...] [LABELS ...] [TIMEOUT s])   -> GoogleTest, registered with ctest
#   ssl_cc_benchmark(NAME n SRCS ... [DEPS ...])      -> Google Benchmark, run by ./ssl bench
#   ssl_cc_fuzzer(NAME n SRCS ... [DEPS ...])         -> libFuzzer target when SSL_FUZZ is on; `fuzzers`
#                                                        builds them all (tests/fuzz/run runs them)

add_library(ssl_project_options INTERFACE)
target_compile_features(ssl_project_options INTERFACE cxx_std_20)
target_include_directories(ssl_project_options INTERFACE ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})

add_library(ssl_warnings INTERFACE)
target_compile_options(ssl_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
  # Designated initialisers of option structs rely on member defaults; GCC 12 warns about them anyway.
  -Wno-missing-field-initializers)
if(SSL_WARNINGS_AS_ERRORS)
  target_compile_options(ssl_warnings INTERFACE -Werror)
endif()

if(SSL_SANITIZE)
  target_compile_options(ssl_project_options INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer)
  target_link_options(ssl_project_options INTERFACE -fsanitize=address,undefined)
endif()

if(SSL_FUZZ)
  # Instrument every library for coverage-guided fuzzing; the fuzz targets add the libFuzzer driver.
  # Undefined behaviour aborts (UBSan only prints and goes on by default) so the fuzzer reports it.
  target_compile_options(ssl_project_options INTERFACE -fsanitize=fuzzer-no-link,address,undefined
    -fno-sanitize-recover=undefined)
  target_link_options(ssl_project_options INTERFACE -fsanitize=address,undefined)
  add_custom_target(fuzzers)
endif()

set(CMAKE_CXX_EXTENSIONS OFF)

function(_ssl_common_setup target)
  target_link_libraries(${target} PRIVATE ssl_warnings)
endfunction()

function(ssl_cc_library)
  cmake_parse_arguments(ARG "TESTONLY" "NAME" "SRCS;HDRS;DEPS;PRIVATE_DEPS" ${ARGN})
  if(ARG_TESTONLY AND NOT SSL_BUILD_TESTS)
    return()
  endif()
  if(ARG_SRCS)
    add_library(ssl_${ARG_NAME} STATIC ${ARG_SRCS} ${ARG_HDRS})
    target_link_libraries(ssl_${ARG_NAME} PUBLIC ssl_project_options ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
    _ssl_common_setup(ssl_${ARG_NAME})
  else()
    add_library(ssl_${ARG_NAME} INTERFACE ${ARG_HDRS})
    target_link_libraries(ssl_${ARG_NAME} INTERFACE ssl_project_options ${ARG_DEPS})
  endif()
  add_library(ssl::${ARG_NAME} ALIAS ssl_${ARG_NAME})
endfunction()

function(ssl_cc_binary)
  cmake_parse_arguments(ARG "" "NAME" "SRCS;DEPS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SRCS})
  target_link_libraries(${ARG_NAME} PRIVATE ssl_project_options ${ARG_DEPS})
  _ssl_common_setup(${ARG_NAME})
endfunction()

# RUN_SERIAL: each of the test's cases runs with no other test beside it (ctest -j): for tests that measure
# time budgets across many processes.
function(ssl_cc_test)
  cmake_parse_arguments(ARG "RUN_SERIAL" "NAME;TIMEOUT" "SRCS;DEPS;LABELS" ${ARGN})
  if(NOT SSL_BUILD_TESTS)
    return()
  endif()
  add_executable(${ARG_NAME} ${ARG_SRCS})
  target_link_libraries(${ARG_NAME} PRIVATE ssl_project_options ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  set_target_properties(${ARG_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  _ssl_common_setup(${ARG_NAME})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 120)
  endif()
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  set(serial FALSE)
  if(ARG_RUN_SERIAL)
    set(serial TRUE)
  endif()
  gtest_discover_tests(${ARG_NAME}
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT} RUN_SERIAL ${serial}
    DISCOVERY_TIMEOUT 60)
endfunction()

function(ssl_cc_benchmark)
  cmake_parse_arguments(ARG "" "NAME" "SRCS;DEPS" ${ARGN})
  if(NOT SSL_BUILD_BENCHMARKS)
    return()
  endif()
  add_executable(${ARG_NAME} ${ARG_SRCS})
  target_link_libraries(${ARG_NAME} PRIVATE ssl_project_options ${ARG_DEPS} benchmark::benchmark)
  set_target_properties(${ARG_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
  _ssl_common_setup(${ARG_NAME})
endfunction()

function(ssl_cc_fuzzer)
  cmake_parse_arguments(ARG "" "NAME" "SRCS;DEPS" ${ARGN})
  if(NOT SSL_FUZZ)
    return()
  endif()
  add_executable(${ARG_NAME} ${ARG_SRCS})
  target_link_libraries(${ARG_NAME} PRIVATE ssl_project_options ${ARG_DEPS})
  target_compile_options(${ARG_NAME} PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_options(${ARG_NAME} PRIVATE -fsanitize=fuzzer,address,undefined)
  set_target_properties(${ARG_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
  _ssl_common_setup(${ARG_NAME})
  add_dependencies(fuzzers ${ARG_NAME})
endfunction()
