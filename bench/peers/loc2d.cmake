# Included by bench/peers/CMakeLists.txt.
# The peer driver of bench/compare-loc2d: iris_lama's Loc2D (a scan matcher) run over the same
# logs with mote's readers and mote's ATE code. Built only when MOTE_LOC2D_SOURCE names a checkout
# of https://github.com/iris-ua/iris_lama: no peer source is committed and nothing is downloaded.
set(_lama "${MOTE_LOC2D_SOURCE}")
if(NOT EXISTS "${_lama}/include/lama/loc2d.h" OR NOT EXISTS "${_lama}/src/loc2d.cpp")
  message(FATAL_ERROR "MOTE_LOC2D_SOURCE=${_lama} is not an iris_lama source folder (no "
                      "include/lama/loc2d.h or src/loc2d.cpp): clone "
                      "https://github.com/iris-ua/iris_lama and point MOTE_LOC2D_SOURCE at it")
endif()

# The part of iris_lama's library that Loc2D uses (its src/CMakeLists.txt builds more: SLAM,
# the pose graph). The sparse-dense maps can compress their patches, which Loc2D never asks
# for, but buffer_compressor.cpp must link: its headers come from iris_lama's vendor folder,
# the code from the system's liblz4 and libzstd that mote's readers link already.
add_library(mote_peer_lama STATIC
  ${_lama}/src/loc2d.cpp
  ${_lama}/src/match_surface_2d.cpp
  ${_lama}/src/pose2d.cpp
  ${_lama}/src/pose3d.cpp
  ${_lama}/src/random.cpp
  ${_lama}/src/print.cpp
  ${_lama}/src/buffer_compressor.cpp
  ${_lama}/src/nlls/gauss_newton.cpp
  ${_lama}/src/nlls/levenberg_marquardt.cpp
  ${_lama}/src/nlls/robust_cost.cpp
  ${_lama}/src/nlls/solver.cpp
  ${_lama}/src/sdm/container.cpp
  ${_lama}/src/sdm/map.cpp
  ${_lama}/src/sdm/dynamic_distance_map.cpp
  ${_lama}/src/sdm/simple_occupancy_map.cpp)
# As iris_lama builds itself (C++14), and its warnings are not ours to fix.
set_target_properties(mote_peer_lama PROPERTIES CXX_STANDARD 14 CXX_EXTENSIONS OFF)
target_compile_options(mote_peer_lama PRIVATE -w)
target_include_directories(mote_peer_lama SYSTEM PUBLIC ${_lama}/include)
target_include_directories(mote_peer_lama PRIVATE ${_lama}/vendor/lz4 ${_lama}/vendor/zstd)
target_link_libraries(mote_peer_lama PUBLIC Eigen3::Eigen Threads::Threads
                                     PRIVATE LZ4::LZ4 zstd::libzstd_shared)

add_executable(loc2d_replay loc2d_replay.cpp)
mote_target_options(loc2d_replay)
target_link_libraries(loc2d_replay PRIVATE mote_peer_lama mote::logs mote::maps mote::replay)
