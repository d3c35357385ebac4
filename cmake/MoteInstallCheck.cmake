# Run by `cmake --install` before any file is copied (the install(CODE) at the top of the
# top-level CMakeLists.txt), or as `cmake -DMOTE_INSTALL_FILES=LIST -P MoteInstallCheck.cmake`:
# fails, naming the build folder to build, when a file of an installed target is missing.
# MOTE_INSTALL_FILES: a text file with one built file per line (MoteInstall.cmake writes it).
file(STRINGS "${MOTE_INSTALL_FILES}" _mote_files)
set(_mote_missing "")
foreach(_file IN LISTS _mote_files)
  if(NOT EXISTS "${_file}")
    cmake_path(GET _file FILENAME _name)
    list(APPEND _mote_missing "${_name}")
  endif()
endforeach()
if(_mote_missing)
  cmake_path(GET MOTE_INSTALL_FILES PARENT_PATH _mote_build)
  list(JOIN _mote_missing ", " _mote_missing)
  message(FATAL_ERROR "mote: cannot install, not built yet: ${_mote_missing}. Build everything "
                      "first: cmake --build ${_mote_build} -j (a build of one target, such as "
                      "the tool alone, leaves the other libraries out)")
endif()
