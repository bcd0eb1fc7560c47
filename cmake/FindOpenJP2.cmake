# Finds OpenJPEG's libopenjp2 (Debian libopenjp2-7-dev) and defines the imported target
# OpenJP2::OpenJP2. Debian's own OpenJPEG CMake package is not used: its path carries the
# library's minor version. Installed with relume's CMake package, whose static library links it.
find_path(OPENJP2_INCLUDE_DIR openjpeg.h PATH_SUFFIXES openjpeg-2.5 openjpeg-2.4 openjpeg-2.3)
find_library(OPENJP2_LIBRARY openjp2)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenJP2 REQUIRED_VARS OPENJP2_LIBRARY OPENJP2_INCLUDE_DIR)
if(OpenJP2_FOUND AND NOT TARGET OpenJP2::OpenJP2)
  add_library(OpenJP2::OpenJP2 UNKNOWN IMPORTED)
  set_target_properties(OpenJP2::OpenJP2 PROPERTIES IMPORTED_LOCATION "${OPENJP2_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${OPENJP2_INCLUDE_DIR}")
endif()
mark_as_advanced(OPENJP2_INCLUDE_DIR OPENJP2_LIBRARY)
