# Installs the exported targets and moteConfig.cmake (+ version file), so that an outside project
# writes find_package(mote REQUIRED) and target_link_libraries(app PRIVATE mote::mote), or links
# one layer (mote::logs, mote::engine, ...; docs/architecture.md).
include(CMakePackageConfigHelpers)
set(MOTE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/mote)

# The files of every installed target, for the check that runs before the install rules
# (MoteInstallCheck.cmake, registered at the top of the top-level CMakeLists.txt).
get_property(_mote_installed GLOBAL PROPERTY MOTE_INSTALLED_TARGETS)
set(_mote_files "")
foreach(_target IN LISTS _mote_installed)
  string(APPEND _mote_files "$<TARGET_FILE:${_target}>\n")
endforeach()
file(GENERATE OUTPUT ${PROJECT_BINARY_DIR}/mote_install_files.txt CONTENT "${_mote_files}")

install(EXPORT moteTargets NAMESPACE mote:: DESTINATION ${MOTE_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/moteConfig.cmake.in
  ${PROJECT_BINARY_DIR}/moteConfig.cmake INSTALL_DESTINATION ${MOTE_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/moteConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/moteConfig.cmake ${PROJECT_BINARY_DIR}/moteConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FindLZ4.cmake
        DESTINATION ${MOTE_CMAKE_DIR})
