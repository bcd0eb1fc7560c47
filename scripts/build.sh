#!/usr/bin/env bash
# Configures and builds relume (Release) in ./build. Safe to rerun: CMake and Ninja rebuild only
# what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
