# Install rules and the CMake package for spook (header-only).
#
# Installed layout (paths relative to CMAKE_INSTALL_PREFIX):
#   include/spook/...                    the headers, as in the source tree
#   include/spook/single/spook.hpp       the generated single header
#                                        (#include <spook/single/spook.hpp>)
#   lib/libspook_compiled.a              spook compiled once (top-level builds)
#   share/cmake/spook/spookConfig.cmake  find_package(spook CONFIG) → spook::spook,
#                                        spook::spook_compiled
#   share/cmake/spook/spookConfigVersion.cmake
#   share/cmake/spook/spookTargets.cmake
#
# Included from the top-level CMakeLists.txt after GNUInstallDirs and after
# the `spook` and `spook_compiled` targets exist. Also active when spook is added with
# add_subdirectory(), so that a parent project that installs and exports its
# own targets linking spook::spook finds spook in an export set; set
# SPOOK_INSTALL=OFF to drop spook's install rules there.

option(SPOOK_INSTALL "Generate spook's install rules and CMake package" ON)
if(NOT SPOOK_INSTALL)
  return()
endif()

include(CMakePackageConfigHelpers)

# find_package searches <prefix>/share/cmake/<name>/ as well as lib/cmake.
set(SPOOK_INSTALL_CMAKEDIR "${CMAKE_INSTALL_DATADIR}/cmake/spook"
    CACHE STRING "Where spookConfig.cmake is installed, relative to the prefix")

install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/spook"
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}"
        FILES_MATCHING PATTERN "*.hpp")

set(_spook_single_header "${PROJECT_SOURCE_DIR}/single_include/spook/spook.hpp")
if(EXISTS "${_spook_single_header}")
  install(FILES "${_spook_single_header}" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/spook/single")
else()
  message(WARNING "${_spook_single_header} is missing (run python3 tools/amalgamate.py); "
                  "it will not be installed")
endif()
unset(_spook_single_header)

install(TARGETS spook EXPORT spookTargets)
# The compiled-once library is installed where spook is the top-level project
# (it is then built by default); a parent project that add_subdirectory()s
# spook builds it only if it links it, so it is not in the export set there.
if(PROJECT_IS_TOP_LEVEL)
  install(TARGETS spook_compiled EXPORT spookTargets ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}")
endif()
install(EXPORT spookTargets
        NAMESPACE spook::
        DESTINATION "${SPOOK_INSTALL_CMAKEDIR}")

configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/spookConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/spookConfig.cmake"
  INSTALL_DESTINATION "${SPOOK_INSTALL_CMAKEDIR}")
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/spookConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}"
  COMPATIBILITY SameMajorVersion)
install(FILES "${PROJECT_BINARY_DIR}/spookConfig.cmake"
              "${PROJECT_BINARY_DIR}/spookConfigVersion.cmake"
        DESTINATION "${SPOOK_INSTALL_CMAKEDIR}")
