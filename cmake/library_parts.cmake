# What every build of the relume library shares (lib/CMakeLists.txt, and cmake/device_bench.cmake
# for the device-only build): the OpenCL kernels embedded as strings, the version with the git
# commit it was built from, and the OpenCL C++ bindings' settings.
set(relume_opencl_cpp_definitions CL_HPP_TARGET_OPENCL_VERSION=120
    CL_HPP_MINIMUM_OPENCL_VERSION=120 CL_HPP_ENABLE_EXCEPTIONS)

# Adds the embedded kernels and the git commit header to `target`, a library made of lib/ sources
# in the calling directory.
function(relume_add_library_parts target)
  set(generated "${CMAKE_CURRENT_BINARY_DIR}/generated")
  file(GLOB kernel_files CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/kernels/*.cl")
  set(embedded "${generated}/kernel_sources.cpp")
  add_custom_command(
    OUTPUT "${embedded}"
    COMMAND ${CMAKE_COMMAND} -DDIR=${PROJECT_SOURCE_DIR}/kernels -DPATTERN=*.cl
            -DHEADER=opencl/kernel_sources.hpp -DFUNCTION=kernel_sources -DOUTPUT=${embedded}
            -P ${PROJECT_SOURCE_DIR}/cmake/embed_folder.cmake
    DEPENDS ${kernel_files} ${PROJECT_SOURCE_DIR}/cmake/embed_folder.cmake
    COMMENT "Embedding OpenCL kernels")
  target_sources(${target} PRIVATE "${embedded}")
  # Runs at every build; rewrites the header only when the commit changed.
  add_custom_target(relume_git_commit
    COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
            -DOUTPUT=${generated}/relume_git_commit.hpp -P ${PROJECT_SOURCE_DIR}/cmake/git_commit.cmake
    BYPRODUCTS "${generated}/relume_git_commit.hpp"
    COMMENT "Recording the git commit")
  add_dependencies(${target} relume_git_commit)
  target_include_directories(${target} PRIVATE "${generated}")
  set_source_files_properties("${PROJECT_SOURCE_DIR}/lib/core/version.cpp" PROPERTIES
    COMPILE_DEFINITIONS "RELUME_VERSION=\"${PROJECT_VERSION}\"")
  target_compile_definitions(${target} PRIVATE ${relume_opencl_cpp_definitions})
endfunction()
