# The public headers test: the installed API is at most kMaxHeaders headers, and each of
# them includes only standard or third-party headers and other installed ones, so a
# program built against the install finds every header it is given. ctest runs it over
# the list in the source tree (test `public_headers`); the `package` test runs it over
# the install tree:
#
#   cmake -DSOURCE_DIR=REPO -P public_headers_test.cmake        (cmake/ontogen_public_headers.cmake)
#   cmake -DINCLUDE_DIR=PREFIX/include/ontogen [-DSOURCE_DIR=REPO] -P public_headers_test.cmake
#
# The second checks every file installed there; with SOURCE_DIR also that they are the
# list, no more and no fewer.
cmake_minimum_required(VERSION 3.25)

# The bound the API is held to: what a user of the package needs (compile, grow, read,
# interpret, run, sweep) fits in it; a header past it is an internal one leaking out.
set(max_headers 60)
# ontogen's own folders: a quoted include of one of these is ontogen's header.
set(ontogen_folders "pools|model|lang|core|interpreters|batch|studio|apps|python")

set(failures "")
if(SOURCE_DIR)
  include("${SOURCE_DIR}/cmake/ontogen_public_headers.cmake")
endif()
if(INCLUDE_DIR)
  set(root "${INCLUDE_DIR}")
  file(GLOB_RECURSE headers LIST_DIRECTORIES false RELATIVE "${root}" "${root}/*")
  set(where "${INCLUDE_DIR}")
  if(SOURCE_DIR)
    foreach(header IN LISTS headers)
      if(NOT header IN_LIST ONTOGEN_PUBLIC_HEADERS)
        string(APPEND failures "  ${header} is installed but not a public header\n")
      endif()
    endforeach()
    foreach(header IN LISTS ONTOGEN_PUBLIC_HEADERS)
      if(NOT header IN_LIST headers)
        string(APPEND failures "  ${header} is a public header but not installed\n")
      endif()
    endforeach()
  endif()
elseif(SOURCE_DIR)
  set(root "${SOURCE_DIR}")
  set(headers ${ONTOGEN_PUBLIC_HEADERS})
  set(where "cmake/ontogen_public_headers.cmake")
else()
  message(FATAL_ERROR "public headers test: give -DSOURCE_DIR=... or -DINCLUDE_DIR=...")
endif()

list(LENGTH headers count)
if(count EQUAL 0)
  string(APPEND failures "  no headers in ${where}\n")
endif()
if(count GREATER max_headers)
  string(APPEND failures "  ${count} public headers, more than ${max_headers}\n")
endif()
foreach(header IN LISTS headers)
  if(NOT header MATCHES "\\.h$")
    string(APPEND failures "  ${header} is not a header\n")
    continue()
  endif()
  if(NOT EXISTS "${root}/${header}")
    string(APPEND failures "  ${header} is listed but not in ${root}\n")
    continue()
  endif()
  file(STRINGS "${root}/${header}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]")
  foreach(line IN LISTS lines)
    if(line MATCHES "#[ \t]*include[ \t]*\"([^\"]+)\"")
      set(included "${CMAKE_MATCH_1}")
    elseif(line MATCHES "#[ \t]*include[ \t]*<((${ontogen_folders})/[^>]+)>")
      set(included "${CMAKE_MATCH_1}")
    else()
      continue()  # a standard or third-party header
    endif()
    if(NOT included IN_LIST headers)
      string(APPEND failures "  ${header} includes ${included}, which is not public\n")
    endif()
  endforeach()
endforeach()

if(failures)
  message(FATAL_ERROR "public headers test (${where}):\n${failures}")
endif()
message(STATUS "public headers test: ${count} headers in ${where}, each including only public ones")
