#!/usr/bin/env bash
# Builds relume and its test suite with AddressSanitizer + UndefinedBehaviorSanitizer (GCC,
# -DRELUME_SANITIZE=ON) in ./build-sanitize and runs the tests under them: any memory error, leak
# or undefined behaviour fails its test.
#   scripts/test_sanitizers.sh [ctest arguments]   the whole suite (e.g. -R 'Container|LightFile')
#   scripts/test_sanitizers.sh --ci                the bounded set CI runs (scripts/test.sh): the
#                                                  relume binary and the test programs of the code
#                                                  that reads files and relights (list below)
# Left out: the Python tests (an instrumented module needs an instrumented interpreter) and
# install.consumer_program (the installed library does not carry the sanitizer link flags to a
# consumer). Leaks inside the OpenCL driver stack (PoCL, the ICD loader, LLVM) are suppressed:
# scripts/sanitizer_suppressions.txt says which and why.
set -euo pipefail
cd "$(dirname "$0")/.."

# The CI set: every reader of untrusted bytes (containers, light files, folders and their strips,
# .npy, .lp, encodings), the model's arithmetic, the relighting kernels' host code, the L1
# solvers, streamed compression (with its compressed field on disk and the container written
# strip by strip), and the command-line tests of early failures and interruption.
ci_tests=(
  container_test hostile_container_test field_io_test field_strips_test hostile_light_file_test
  light_file_test npy_test input_encoding_test quantization_test reconstruct_field_test
  compressed_field_rows_test haar_transform_test per_light_error_test npz_export_test
  atomic_file_test parallel_test progress_test l1_regression_test leading_subspace_test
  opencl_relighter_test environment_map_test streamed_compression_test early_failure_test
  container_strips_test compressed_strip_file_test disk_file_test
)

scripts/install_deps.sh
source scripts/compiler_cache.sh
# -O1 -g: compiles faster than -O2 on CI's 2 cores and runs the instrumented tests fast enough;
# without -DNDEBUG, so Eigen's bounds assertions check every block and index as well.
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRELUME_SANITIZE=ON \
  -DRELUME_BUILD_PYTHON=OFF -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" "${compiler_cache[@]}"
export RELUME_QUIET=1
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=0"
export LSAN_OPTIONS="suppressions=$PWD/scripts/sanitizer_suppressions.txt:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Death tests re-run the test program instead of forking a threaded one: a forked child of a
# process with threads can hang in the sanitizer runtime's locks at exit.
export GTEST_DEATH_TEST_STYLE=threadsafe

if [ "${1:-}" = "--ci" ]; then
  cmake --build build-sanitize -j "$(nproc)" --target relume "${ci_tests[@]}"
  failed=()
  for test in "${ci_tests[@]}"; do
    echo "test_sanitizers: $test"
    build-sanitize/tests/"$test" --gtest_brief=1 || failed+=("$test")
  done
  if [ ${#failed[@]} -gt 0 ]; then
    echo "test_sanitizers: FAILED under ASan + UBSan: ${failed[*]}" >&2
    exit 1
  fi
  echo "test_sanitizers: ${#ci_tests[@]} test programs clean under ASan + UBSan"
  exit 0
fi
cmake --build build-sanitize -j "$(nproc)"
ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" -E '^install\.' "$@"
