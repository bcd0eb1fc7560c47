# The device-only build (-DRELUME_DEVICE_BENCH_ONLY=ON, made by scripts/build_device_bench.sh):
# the `relume` command with only `bench` and `devices`, to carry to a GPU machine that has nothing
# installed. It holds the stages those two commands use (core, model, opencl, relight and the
# assignment pieces of compress) and no image I/O, container, GLPK or OpenImageIO; libstdc++ and
# libgcc are linked in, and the OpenCL ICD loader is looked for next to the binary first
# (RUNPATH $ORIGIN), where scripts/build_device_bench.sh copies it. `bench --container` says that
# this build cannot read containers (apps/commands/bench/device_only/).
include("${PROJECT_SOURCE_DIR}/cmake/library_parts.cmake")

set(lib "${PROJECT_SOURCE_DIR}/lib")
file(GLOB device_library_sources CONFIGURE_DEPENDS "${lib}/core/*.cpp" "${lib}/model/*.cpp"
     "${lib}/opencl/*.cpp" "${lib}/relight/*.cpp")
foreach(name cluster_assignment cluster_basis cluster_function_fit cluster_model
             opencl_assignment random_assignment_problem)
  list(APPEND device_library_sources "${lib}/compress/${name}.cpp")
endforeach()
add_library(relume_device_library STATIC ${device_library_sources})
relume_add_library_parts(relume_device_library)
target_include_directories(relume_device_library PUBLIC "${PROJECT_SOURCE_DIR}/include" "${lib}")
target_compile_definitions(relume_device_library PUBLIC ${relume_opencl_cpp_definitions})
target_link_libraries(relume_device_library PUBLIC Eigen3::Eigen OpenCL::OpenCL
                      nlohmann_json::nlohmann_json Threads::Threads)

set(apps "${PROJECT_SOURCE_DIR}/apps")
add_executable(relume
  "${apps}/main.cpp" "${apps}/command_registry.cpp" "${apps}/command_suggestion.cpp"
  "${apps}/commands/inspect/devices_command.cpp"
  "${apps}/commands/bench/bench_command.cpp"
  "${apps}/commands/bench/bench_runs.cpp" "${apps}/commands/bench/bench_records.cpp"
  "${apps}/commands/bench/bench_report.cpp"
  "${apps}/commands/bench/device_only/container_sweep_unavailable.cpp")
target_include_directories(relume PRIVATE "${apps}")
target_link_libraries(relume PRIVATE relume_device_library CLI11::CLI11)
target_link_options(relume PRIVATE -static-libstdc++ -static-libgcc)
set_target_properties(relume PROPERTIES BUILD_RPATH "\$ORIGIN")
