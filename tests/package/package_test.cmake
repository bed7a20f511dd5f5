# The package test: installs a build of ontogen into a fresh prefix, builds this folder's
# project against it as another project would (find_package through CMAKE_PREFIX_PATH),
# runs it and compares what it prints with expected_output.txt. ctest runs it
# (tests/CMakeLists.txt, test `package`) as
#
#   cmake -DONTOGEN_BINARY_DIR=BUILD -DWORK_DIR=DIR [-DCONFIG=Release] [-DGENERATOR=G]
#         [-DCXX_COMPILER=C++] [-DSANITIZE=address,undefined] -P package_test.cmake
#
# WORK_DIR is emptied first; the prefix is WORK_DIR/prefix, the example's build WORK_DIR/build.
cmake_minimum_required(VERSION 3.25)

foreach(variable IN ITEMS ONTOGEN_BINARY_DIR WORK_DIR)
  if(NOT ${variable})
    message(FATAL_ERROR "package test: give -D${variable}=...")
  endif()
endforeach()
set(example "${CMAKE_CURRENT_LIST_DIR}")
set(prefix "${WORK_DIR}/prefix")
set(build "${WORK_DIR}/build")
file(REMOVE_RECURSE "${WORK_DIR}")

# Runs a command; on failure stops with everything it printed.
function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "package test: ${step} failed (${result}):\n${output}")
  endif()
endfunction()

set(config_args "")
if(CONFIG)
  set(config_args --config "${CONFIG}")
endif()
run("cmake --install" "${CMAKE_COMMAND}" --install "${ONTOGEN_BINARY_DIR}" --prefix "${prefix}" ${config_args})
foreach(file IN ITEMS bin/ontogen include/ontogen/core/world.h include/ontogen/lang/compiler.h)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "package test: the install has no ${file}")
  endif()
endforeach()
run("installed ontogen help" "${prefix}/bin/ontogen" help)
# The public headers alone, each including only public ones (public_headers_test.cmake).
run("checking the installed headers" "${CMAKE_COMMAND}" "-DINCLUDE_DIR=${prefix}/include/ontogen"
  "-DSOURCE_DIR=${example}/../.." -P "${example}/public_headers_test.cmake")

# The example is built like the libraries it links: same compiler, same sanitizers.
set(configure_args -S "${example}" -B "${build}" "-DCMAKE_PREFIX_PATH=${prefix}"
  -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON)
if(GENERATOR)
  list(APPEND configure_args -G "${GENERATOR}")
endif()
if(CONFIG)
  list(APPEND configure_args "-DCMAKE_BUILD_TYPE=${CONFIG}")
endif()
if(CXX_COMPILER)
  list(APPEND configure_args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()
if(SANITIZE)
  list(APPEND configure_args "-DCMAKE_CXX_FLAGS=-fsanitize=${SANITIZE} -fno-omit-frame-pointer"
    "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=${SANITIZE}")
endif()
run("configuring tests/package" "${CMAKE_COMMAND}" ${configure_args})

# The package must come from the fresh prefix, not from another ontogen on the machine.
file(STRINGS "${build}/CMakeCache.txt" found REGEX "^ontogen_DIR:")
string(REGEX REPLACE "^ontogen_DIR:[A-Z]+=" "" found "${found}")
file(REAL_PATH "${found}" found)
file(REAL_PATH "${prefix}" real_prefix)
string(FIND "${found}/" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "package test: ontogen was found in ${found}, not in ${prefix}")
endif()

run("building tests/package" "${CMAKE_COMMAND}" --build "${build}" ${config_args})

set(program "${build}/thue_morse")
if(NOT EXISTS "${program}" AND CONFIG)
  set(program "${build}/${CONFIG}/thue_morse")  # multi-configuration generators
endif()
execute_process(COMMAND "${program}" RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "package test: thue_morse failed (${result}):\n${output}${errors}")
endif()
file(READ "${example}/expected_output.txt" expected)
if(NOT output STREQUAL expected)
  message(FATAL_ERROR "package test: thue_morse printed\n${output}\ninstead of\n${expected}")
endif()
message(STATUS "package test: installed into ${prefix}, tests/package built against it and printed the expected word")
