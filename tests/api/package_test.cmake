# CTest host_example_package (docs/api.md, "The CMake package"): installs this build tree into a
# scratch prefix, configures and builds samples/host_example as a project of its own against it
# (find_package(Firmament), target Firmament::firmament), and runs it with --check.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DSCRATCH=... -DCXX_COMPILER=... -DBUILD_TYPE=... -P package_test.cmake
foreach(variable BUILD_DIR SOURCE_DIR SCRATCH CXX_COMPILER BUILD_TYPE)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "package_test.cmake: -D${variable}=... is needed")
  endif()
endforeach()
file(REMOVE_RECURSE ${SCRATCH})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message(STATUS "${output}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${SCRATCH}/prefix)
foreach(file include/firmament/sky.h include/firmament/embed.h include/firmament/atmosphere_lookup.glsl
             lib/libfirmament.a lib/cmake/Firmament/FirmamentConfig.cmake)
  if(NOT EXISTS ${SCRATCH}/prefix/${file})
    message(FATAL_ERROR "the install lacks ${file}")
  endif()
endforeach()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/samples/host_example -B ${SCRATCH}/build -G Ninja
    -DCMAKE_PREFIX_PATH=${SCRATCH}/prefix -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
run(${CMAKE_COMMAND} --build ${SCRATCH}/build)
run(${SCRATCH}/build/host_example --check --out ${SCRATCH}/host_example.exr)
