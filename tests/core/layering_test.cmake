# The layering test: the engine and the layers under it reach no layer above them.
# Dependencies point one way (docs/ARCHITECTURE.md): core -> model -> pools. core runs a
# compiled program and links no parser, so no source of pools/, model/ or core/ includes a
# header of a layer above it, and no library the ontogen_core target links (directly or
# through another) is one above it. ctest runs it (tests/core/CMakeLists.txt, test
# `layering`) as
#
#   cmake -DSOURCE_DIR=REPO -DCORE_LINKS=ontogen_model,ontogen_pools,... -P layering_test.cmake
#
# CORE_LINKS is every ontogen_* target ontogen_core reaches through its link libraries,
# gathered when the build is configured (tests/core/CMakeLists.txt).
cmake_minimum_required(VERSION 3.25)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "layering test: give -DSOURCE_DIR=...")
endif()

# Each layer and the folders it must not include from: every folder above it.
set(above_pools model lang core interpreters batch studio apps python)
set(above_model lang core interpreters batch studio apps python)
set(above_core lang interpreters batch studio apps python)

set(failures "")
foreach(layer IN ITEMS pools model core)
  file(GLOB_RECURSE sources LIST_DIRECTORIES false
    "${SOURCE_DIR}/${layer}/*.h" "${SOURCE_DIR}/${layer}/*.cpp")
  if(NOT sources)
    message(FATAL_ERROR "layering test: no sources in ${SOURCE_DIR}/${layer}")
  endif()
  string(JOIN "|" above ${above_${layer}})
  foreach(source IN LISTS sources)
    file(STRINGS "${source}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<](${above})/")
    foreach(line IN LISTS lines)
      file(RELATIVE_PATH name "${SOURCE_DIR}" "${source}")
      string(STRIP "${line}" line)
      string(APPEND failures "  ${name}: ${line} (${layer}/ is below it)\n")
    endforeach()
  endforeach()
endforeach()

# The libraries core links: none of a layer above it.
string(REPLACE "," ";" CORE_LINKS "${CORE_LINKS}")
if(NOT CORE_LINKS)
  message(FATAL_ERROR "layering test: give -DCORE_LINKS=... (ontogen_core's link libraries)")
endif()
if(NOT "ontogen_model" IN_LIST CORE_LINKS)
  string(APPEND failures "  ontogen_core does not link ontogen_model (links: ${CORE_LINKS})\n")
endif()
foreach(library IN LISTS CORE_LINKS)
  if(NOT library MATCHES "^ontogen_(pools|model)$")
    string(APPEND failures "  ontogen_core links ${library}, which is not below it\n")
  endif()
endforeach()

if(failures)
  message(FATAL_ERROR "layering test: core reaches above itself:\n${failures}")
endif()
message(STATUS "layering test: pools/, model/ and core/ include nothing above them; ontogen_core links ${CORE_LINKS}")
