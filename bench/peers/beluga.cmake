# Included by bench/peers/CMakeLists.txt. The drivers of bench/compare-beluga: beluga_driver
# (Beluga's particle filter) and beluga_mote (mote's Localizer), both on the scenario of
# beluga_scenario.cpp. Built only when MOTE_BELUGA_SOURCE names a checkout of
# https://github.com/Ekumen-OS/beluga and MOTE_SOPHUS_SOURCE one of
# https://github.com/strasdat/Sophus: Beluga is header-only, so nothing of it is compiled but the
# driver. Beluga also needs range-v3 (Debian: librange-v3-dev) and TBB (its parallel policies).
set(_beluga "${MOTE_BELUGA_SOURCE}")
set(_sophus "${MOTE_SOPHUS_SOURCE}")
if(NOT EXISTS "${_beluga}/beluga/include/beluga/sensor/likelihood_field_model.hpp")
  message(FATAL_ERROR "MOTE_BELUGA_SOURCE=${_beluga} is not a Beluga source folder (no "
                      "beluga/include/beluga/sensor/likelihood_field_model.hpp): clone "
                      "https://github.com/Ekumen-OS/beluga and point MOTE_BELUGA_SOURCE at it")
endif()
if(NOT EXISTS "${_sophus}/sophus/se2.hpp")
  message(FATAL_ERROR "MOTE_SOPHUS_SOURCE=${_sophus} is not a Sophus source folder (no "
                      "sophus/se2.hpp): clone https://github.com/strasdat/Sophus and point "
                      "MOTE_SOPHUS_SOURCE at it (Beluga needs it)")
endif()
find_package(range-v3 QUIET)
if(NOT range-v3_FOUND)
  message(FATAL_ERROR "Beluga needs range-v3, which CMake did not find (Debian: "
                      "apt-get install librange-v3-dev)")
endif()

# The scenario both drivers run, built with mote (mote's map loader and simulator). C++20 for
# itself only (mote_target_options would make it PUBLIC and so the Beluga driver's): its header
# is C++17.
add_library(mote_peer_beluga_scenario STATIC beluga_scenario.cpp)
target_compile_features(mote_peer_beluga_scenario PRIVATE cxx_std_20)
target_compile_options(mote_peer_beluga_scenario PRIVATE ${MOTE_WARNINGS})
if(MOTE_WERROR)
  target_compile_options(mote_peer_beluga_scenario PRIVATE -Werror)
endif()
target_include_directories(mote_peer_beluga_scenario PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(mote_peer_beluga_scenario PRIVATE mote::maps mote::sim)

# Beluga as it builds itself (C++17, EIGEN_NO_DEBUG, Sophus without fmt), -O3 and no -march
# whatever the build type: the figures BENCHMARKS.md quotes compare against a generic build.
# Its headers are SYSTEM: their warnings are not ours to fix.
add_executable(beluga_driver beluga_driver.cpp)
set_target_properties(beluga_driver PROPERTIES CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON
                                               CXX_EXTENSIONS OFF)
target_compile_options(beluga_driver PRIVATE -O3)
target_compile_definitions(beluga_driver PRIVATE EIGEN_NO_DEBUG SOPHUS_USE_BASIC_LOGGING)
target_include_directories(beluga_driver SYSTEM PRIVATE ${_beluga}/beluga/include ${_sophus})
target_link_libraries(beluga_driver PRIVATE mote_peer_beluga_scenario Eigen3::Eigen
                                            range-v3::range-v3 TBB::tbb Threads::Threads)

# mote's counterpart: the Localizer as mote's default (portable) build compiles it.
add_executable(beluga_mote beluga_mote.cpp)
mote_target_options(beluga_mote)
target_link_libraries(beluga_mote PRIVATE mote_peer_beluga_scenario mote::engine mote::maps)
