#!/usr/bin/env bash
# Installs dependencies, builds, and runs the whole GoogleTest suite through ctest (PoCL executes
# the OpenCL kernels on the CPU). Real data is read from ../shared/data unless RELUME_DATA says
# otherwise; tests that need it say so when they skip. Before the suite, every fuzz target runs
# for a bounded time (RELUME_FUZZ_SECONDS, default 20 s each; scripts/fuzz.sh,
# docs/reliability.md). After the suite, the bounded AddressSanitizer + UndefinedBehaviorSanitizer
# run (scripts/test_sanitizers.sh --ci) builds the readers', the model's and the relighter's test
# programs instrumented and runs them; RELUME_SANITIZERS=0 leaves it out.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh
scripts/fuzz.sh "${RELUME_FUZZ_SECONDS:-20}"
export RELUME_QUIET=1
ctest --test-dir build --output-on-failure -j "$(nproc)"
[ "${RELUME_SANITIZERS:-1}" = 0 ] || scripts/test_sanitizers.sh --ci
