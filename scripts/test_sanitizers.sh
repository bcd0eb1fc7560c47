#!/usr/bin/env bash
# Builds relume and its whole test suite with AddressSanitizer + UndefinedBehaviorSanitizer
# (GCC, -DRELUME_SANITIZE=ON) in ./build-sanitize and runs the suite under them: any memory error,
# leak or undefined behaviour fails its test. Extra arguments go to ctest (for example
# `-R 'Container|LightFile'` for a subset). Left out: the Python tests (an instrumented module
# needs an instrumented interpreter) and install.consumer_program (the installed library does not
# carry the sanitizer link flags to a consumer). Leaks inside the OpenCL driver stack (PoCL, the
# ICD loader, LLVM) are suppressed: scripts/sanitizer_suppressions.txt says which and why.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRELUME_SANITIZE=ON \
  -DRELUME_BUILD_PYTHON=OFF
cmake --build build-sanitize -j "$(nproc)"
export RELUME_QUIET=1
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=0"
export LSAN_OPTIONS="suppressions=$PWD/scripts/sanitizer_suppressions.txt:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" -E '^install\.' "$@"
