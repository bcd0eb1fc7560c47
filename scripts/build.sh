#!/usr/bin/env bash
# Configures and builds relume (Release) in ./build. Safe to rerun: CMake and Ninja rebuild only
# what changed, and ccache (when installed: scripts/install_deps.sh adds it) serves objects
# compiled before, also in a fresh clone on the same machine.
#   scripts/build.sh              everything: the library, `relume`, the tests, the Python module
#   scripts/build.sh relume ...   only these targets (the main job builds just the command)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/compiler_cache.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${compiler_cache[@]}"
targets=()
for target in "$@"; do targets+=(--target "$target"); done
cmake --build build -j "$(nproc)" "${targets[@]}"
