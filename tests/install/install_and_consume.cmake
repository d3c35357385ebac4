# cmake -P script run by the install_and_consume test: installs mote, builds examples/consumer
# against it with no -march or -m<isa> flag anywhere (design.md section 3, Portability), and runs
# it with the dispatched kernels and again with MOTE_ISA=generic. Then builds
# examples/consumer_logs, which links mote::logs and nothing else of mote, and reads the ROS 2
# recording in DATA_DIR with it (357 scans).
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${what}: ok\n${out}")
endfunction()

# Fails when text holds an instruction-set flag (-march=..., -mavx2, -mfma, ...).
function(expect_no_isa_flags what text)
  string(REGEX MATCH "-march=[^ \"]*|-m(avx|fma|sse|bmi)[^ \"]*" flag "${text}")
  if(flag)
    message(FATAL_ERROR "${what} carries ${flag}: the installed package must be portable")
  endif()
  message(STATUS "${what}: no -march or -m<isa> flag")
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})

set(flags "")
if(SANITIZE)
  set(flags "-fsanitize=${SANITIZE}")
endif()

run_step("install" ${CMAKE_COMMAND} --install ${MOTE_BINARY_DIR} --prefix ${prefix})
# The Python package, when built, is installed under the prefix too.
if(EXISTS ${MOTE_BINARY_DIR}/python/mote/__init__.py)
  file(GLOB_RECURSE python_package ${prefix}/__init__.py)
  list(FILTER python_package INCLUDE REGEX "/mote/__init__.py$")
  if(NOT python_package)
    message(FATAL_ERROR "cmake --install --prefix ${prefix} put no mote/__init__.py under it")
  endif()
  message(STATUS "Python package: ${python_package}")
endif()
file(GLOB_RECURSE exported ${prefix}/*/moteTargets*.cmake)
foreach(file IN LISTS exported)
  file(READ ${file} text)
  expect_no_isa_flags("${file}" "${text}")
endforeach()
run_step("configure consumer" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${WORK_DIR}/build
         -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
         -DCMAKE_CXX_FLAGS=${flags} -DCMAKE_EXE_LINKER_FLAGS=${flags}
         -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
file(READ ${WORK_DIR}/build/compile_commands.json commands)
expect_no_isa_flags("consumer compile command" "${commands}")
run_step("build consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run_step("run consumer" ${WORK_DIR}/build/consumer)
run_step("run consumer, MOTE_ISA=generic" ${CMAKE_COMMAND} -E env MOTE_ISA=generic
         ${WORK_DIR}/build/consumer)

# A reader of recorded data links mote::logs alone: no filter, ray casting or map library.
run_step("configure logs consumer" ${CMAKE_COMMAND} -S ${CONSUMER_LOGS_SOURCE_DIR}
         -B ${WORK_DIR}/build-logs -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
         -DCMAKE_CXX_FLAGS=${flags} -DCMAKE_EXE_LINKER_FLAGS=${flags})
run_step("build logs consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/build-logs)
# The link line: Makefiles keep it in link.txt, Ninja in build.ninja (CMAKE_GENERATOR, as CI sets).
set(link_file ${WORK_DIR}/build-logs/CMakeFiles/consumer_logs.dir/link.txt)
if(NOT EXISTS ${link_file})
  set(link_file ${WORK_DIR}/build-logs/build.ninja)
endif()
file(READ ${link_file} link_line)
string(REGEX MATCH "libmote_(maps|raycast|engine|calibrate|sim|replay)[.]" other "${link_line}")
if(other)
  message(FATAL_ERROR "the logs consumer links ${other}: mote::logs must stand alone\n${link_line}")
endif()
set(recording ${DATA_DIR}/ros2/mac_take2)
if(EXISTS ${recording}/metadata.yaml)
  run_step("run logs consumer on ${recording}" ${WORK_DIR}/build-logs/consumer_logs ${recording}
           357)
else()
  message(STATUS "logs consumer built; ${recording} is absent (see ../shared/data/README), "
                 "so it reads nothing")
endif()
