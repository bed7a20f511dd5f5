# Install rules and the exported CMake package (docs/EMBEDDING.md).
#
# Every library of ontogen goes into one export set, ontogenTargets, under the namespace
# ontogen::, so another project's find_package(ontogen CONFIG REQUIRED) gives the same
# names as the build tree's aliases (ontogen_core is ontogen::core). A folder's
# CMakeLists.txt adds its library with one call next to add_library:
#
#   add_library(ontogen_music ...)
#   add_library(ontogen::music ALIAS ontogen_music)
#   target_include_directories(ontogen_music PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>)
#   ontogen_install_library(ontogen_music)
#
# Only the public headers are installed (cmake/ontogen_public_headers.cmake, an explicit
# list), each at its path in the repository; every other header is private to its library.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# Installed headers are included as in the repository, "core/world.h", from here.
set(ONTOGEN_INSTALL_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}/ontogen")
set(ONTOGEN_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/ontogen")

# Makes `target` (named ontogen_<name>) installable as ontogen::<name>: its export name,
# the include directory and C++ standard its installed headers need, and (with
# ONTOGEN_INSTALL) its install rule in the export set.
function(ontogen_install_library target)
  string(REGEX REPLACE "^ontogen_" "" name "${target}")
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(${target} INTERFACE $<INSTALL_INTERFACE:${ONTOGEN_INSTALL_INCLUDEDIR}>)
  # The headers are C++20; say so in the interface, not only in this project's settings.
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_compile_features(${target} INTERFACE cxx_std_20)
  else()
    target_compile_features(${target} PUBLIC cxx_std_20)
  endif()
  set_property(GLOBAL APPEND PROPERTY ONTOGEN_INSTALLED_LIBRARIES ${name})
  if(ONTOGEN_INSTALL)
    install(TARGETS ${target} EXPORT ontogenTargets
      ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
      LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
      RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endfunction()

include("${CMAKE_CURRENT_LIST_DIR}/ontogen_public_headers.cmake")

# Installs the public headers into include/ontogen/<their folder in the repository>/.
function(ontogen_install_public_headers)
  foreach(header IN LISTS ONTOGEN_PUBLIC_HEADERS)
    get_filename_component(folder "${header}" DIRECTORY)
    install(FILES "${PROJECT_SOURCE_DIR}/${header}" DESTINATION "${ONTOGEN_INSTALL_INCLUDEDIR}/${folder}")
  endforeach()
endfunction()

# The export set and the package files; called once, after every library is added.
function(ontogen_install_package)
  if(NOT ONTOGEN_INSTALL)
    return()
  endif()
  ontogen_install_public_headers()
  get_property(ONTOGEN_PACKAGE_COMPONENTS GLOBAL PROPERTY ONTOGEN_INSTALLED_LIBRARIES)
  set(ONTOGEN_PACKAGE_LIVE_MIDI OFF)
  if(TARGET ontogen_live_midi)
    set(ONTOGEN_PACKAGE_LIVE_MIDI ON)
  endif()
  install(EXPORT ontogenTargets
    NAMESPACE ontogen::
    FILE ontogenTargets.cmake
    DESTINATION "${ONTOGEN_INSTALL_CMAKEDIR}")
  configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/ontogenConfig.cmake.in"
    "${PROJECT_BINARY_DIR}/ontogenConfig.cmake"
    INSTALL_DESTINATION "${ONTOGEN_INSTALL_CMAKEDIR}")
  # 0.x: a new minor version may break the interface.
  write_basic_package_version_file("${PROJECT_BINARY_DIR}/ontogenConfigVersion.cmake"
    VERSION ${PROJECT_VERSION}
    COMPATIBILITY SameMinorVersion)
  install(FILES
    "${PROJECT_BINARY_DIR}/ontogenConfig.cmake"
    "${PROJECT_BINARY_DIR}/ontogenConfigVersion.cmake"
    DESTINATION "${ONTOGEN_INSTALL_CMAKEDIR}")
endfunction()
