# Install rules: `cmake --install build --prefix P` puts the `relume` command in P/bin, the
# library in P/lib, the public headers in P/include/relume and the CMake package in
# P/lib/cmake/relume, so that a consumer can say find_package(relume) and link relume::relume.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(package_dir "${CMAKE_INSTALL_LIBDIR}/cmake/relume")
install(TARGETS relume RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
install(TARGETS relume_library EXPORT relumeTargets ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}")
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/relume" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
install(EXPORT relumeTargets NAMESPACE relume:: DESTINATION "${package_dir}")

configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/relumeConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/relumeConfig.cmake" INSTALL_DESTINATION "${package_dir}")
# Before 1.0 a minor version may change the API.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/relumeConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/relumeConfig.cmake"
              "${PROJECT_BINARY_DIR}/relumeConfigVersion.cmake"
              "${PROJECT_SOURCE_DIR}/cmake/FindGLPK.cmake"
              "${PROJECT_SOURCE_DIR}/cmake/FindZstd.cmake"
              "${PROJECT_SOURCE_DIR}/cmake/FindOpenJP2.cmake"
        DESTINATION "${package_dir}")
