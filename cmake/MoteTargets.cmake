# Helpers that give every mote target the same shape: C++20, warnings, optional -march=native,
# public headers in <folder>/include, exported as mote::<name>.

set(MOTE_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wconversion)

# Warnings, -Werror and -march=native for a target of mote's own (never PUBLIC).
function(mote_target_options target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE ${MOTE_WARNINGS})
  if(MOTE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(MOTE_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
    # GCC 12 with AVX-512 warns inside its own intrinsics when Eigen's small fixed-size
    # matrices (and mote's gathers) reach them: -Wmaybe-uninitialized on _mm512_undefined_ps
    # (GCC bug 105593) and -Warray-bounds on 64-byte loads of 16-byte matrices that Eigen masks
    # (GCC bug 106247). Both are false positives and fatal with MOTE_WERROR.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized -Wno-array-bounds)
    endif()
  endif()
endfunction()

# TSan needs clang: only clang can leave TBB's header templates uninstrumented (see
# cmake/tsan-ignorelist.txt for why that is needed with the system libtbb).
function(mote_configure_thread_sanitizer)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "MOTE_SANITIZE=thread needs clang (CXX=clang++): GCC cannot skip "
                        "instrumenting TBB's headers, and the system libtbb is not instrumented")
  endif()
  add_compile_options(-fsanitize-ignorelist=${PROJECT_SOURCE_DIR}/cmake/tsan-ignorelist.txt)
endfunction()

# Sanitizers must instrument every translation unit and the final link, so they are the one
# setting applied directory-wide.
macro(mote_apply_sanitizers)
  if(MOTE_SANITIZE)
    string(REPLACE ";" "," _mote_san "${MOTE_SANITIZE}")
    # GCC's -fsanitize=undefined leaves out float-cast-overflow (clang's includes it): add it, so
    # a NaN or out-of-range float converted to an integer is caught with either compiler.
    if("undefined" IN_LIST MOTE_SANITIZE)
      string(APPEND _mote_san ",float-cast-overflow")
    endif()
    add_compile_options(-fsanitize=${_mote_san} -fno-omit-frame-pointer -fno-sanitize-recover=all)
    add_link_options(-fsanitize=${_mote_san})
    if("thread" IN_LIST MOTE_SANITIZE)
      mote_configure_thread_sanitizer()
    endif()
  endif()
  if(MOTE_BUILD_FUZZERS)
    mote_check_fuzzing_toolchain()
    # The fuzzers run under AddressSanitizer + UndefinedBehaviorSanitizer: the whole build is
    # compiled with them unless MOTE_SANITIZE already is (the tests then run beside the fuzzers
    # in one build). tests/fuzz adds the coverage that guides libFuzzer to the code it reads with.
    if(NOT MOTE_SANITIZE)
      add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer
                          -fno-sanitize-recover=all)
      add_link_options(-fsanitize=address,undefined)
    endif()
  endif()
endmacro()

# MOTE_BUILD_FUZZERS needs clang with libFuzzer (Debian: clang, libclang-rt-14-dev).
function(mote_check_fuzzing_toolchain)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "MOTE_BUILD_FUZZERS=ON needs clang (libFuzzer), not "
                        "${CMAKE_CXX_COMPILER_ID}: configure a new build folder with "
                        "-DCMAKE_CXX_COMPILER=clang++ (or run `make fuzz`)")
  endif()
  if(MOTE_SANITIZE AND NOT ("address" IN_LIST MOTE_SANITIZE AND "undefined" IN_LIST MOTE_SANITIZE))
    message(FATAL_ERROR "MOTE_BUILD_FUZZERS=ON runs the fuzzers under address and undefined, not "
                        "MOTE_SANITIZE=${MOTE_SANITIZE}: leave MOTE_SANITIZE empty or set "
                        "\"address;undefined\"")
  endif()
  include(CheckCXXSourceCompiles)
  set(CMAKE_REQUIRED_FLAGS -fsanitize=fuzzer,address,undefined)
  set(CMAKE_REQUIRED_LINK_OPTIONS -fsanitize=fuzzer,address,undefined)
  check_cxx_source_compiles([[
    #include <cstddef>
    #include <cstdint>
    extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }
  ]] MOTE_HAVE_LIBFUZZER)
  if(NOT MOTE_HAVE_LIBFUZZER)
    message(FATAL_ERROR "MOTE_BUILD_FUZZERS=ON: ${CMAKE_CXX_COMPILER} cannot link "
                        "-fsanitize=fuzzer; install libFuzzer (Debian: libclang-rt-14-dev)")
  endif()
endfunction()

# The standard library headers a library's files parse (2-3 s of each file's compile time, more
# than most files' own code), precompiled once per library: each library's own header, because
# their flags differ (the engine's math flags, the fuzz build's coverage on the readers) and a
# header precompiled with other flags is refused (-Winvalid-pch, fatal with -Werror).
set(MOTE_LIBRARY_PCH <algorithm> <array> <cmath> <cstdint> <filesystem> <functional> <limits>
                     <map> <memory> <numbers> <optional> <span> <sstream> <string> <string_view>
                     <vector>)

# mote_add_library(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...] [PRECOMPILED ...])
# Creates mote_<name> with alias mote::<name>, headers in ${CMAKE_CURRENT_SOURCE_DIR}/include.
# PRECOMPILED: third-party headers most of its files include (Eigen, TBB), added to the
# precompiled standard ones.
function(mote_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS;PRECOMPILED" ${ARGN})
  add_library(mote_${name} ${ARG_SOURCES})
  add_library(mote::${name} ALIAS mote_${name})
  set_target_properties(mote_${name} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME mote_${name}
                                                POSITION_INDEPENDENT_CODE ON)
  target_include_directories(mote_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(mote_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  mote_target_options(mote_${name})
  target_precompile_headers(mote_${name} PRIVATE ${MOTE_LIBRARY_PCH} ${ARG_PRECOMPILED})
  install(TARGETS mote_${name} EXPORT moteTargets)
  set_property(GLOBAL APPEND PROPERTY MOTE_INSTALLED_TARGETS mote_${name})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# The headers every test file parses (GoogleTest, Eigen's core, the standard library's usual
# ones: ~2 s of each test file's compile time), precompiled once by mote_test_pch and reused by
# every test executable (g++ and clang check that the flags agree; the few macros a test
# executable defines itself are not used by these headers).
set(MOTE_TEST_PCH <gtest/gtest.h> <Eigen/Core> <algorithm> <cmath> <cstdint> <filesystem>
                  <fstream> <random> <span> <string> <vector>)
function(mote_test_precompiled_headers name)
  if(NOT TARGET mote_test_pch)
    file(WRITE ${PROJECT_BINARY_DIR}/mote_test_pch.cpp "// compiles the tests' header\n")
    add_library(mote_test_pch STATIC ${PROJECT_BINARY_DIR}/mote_test_pch.cpp)
    target_link_libraries(mote_test_pch PRIVATE mote_test_support GTest::gtest)
    mote_target_options(mote_test_pch)
    target_precompile_headers(mote_test_pch PRIVATE ${MOTE_TEST_PCH})
  endif()
  target_precompile_headers(${name} REUSE_FROM mote_test_pch)
endfunction()

# mote_add_test(<name> SOURCES ... [LIBS ...]): a GoogleTest executable registered with ctest.
# Its tests that match MOTE_LONG_TESTS (a GoogleTest filter; tests/long_tests.txt) carry the
# ctest label `long`.
function(mote_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} mote_test_support GTest::gtest_main)
  mote_target_options(${name})
  mote_test_precompiled_headers(${name})
  set(environment "MOTE_DATA_DIR=${MOTE_DATA_DIR}")
  if(NOT MOTE_LONG_TESTS)
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ENVIRONMENT "${environment}")
    return()
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 TEST_FILTER "-${MOTE_LONG_TESTS}"
                       PROPERTIES ENVIRONMENT "${environment}")
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 TEST_FILTER "${MOTE_LONG_TESTS}"
                       PROPERTIES ENVIRONMENT "${environment}" LABELS long)
endfunction()

# mote_add_bench(<name> SOURCES ... [LIBS ...]): a Google Benchmark executable.
function(mote_add_bench name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} mote_bench_support benchmark::benchmark)
  mote_target_options(${name})
endfunction()
