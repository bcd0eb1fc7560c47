#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/: clang, AddressSanitizer + UndefinedBehaviorSanitizer) in
# ./build-fuzz and runs each for SECONDS seconds (default 60) on a copy of its seed corpus
# (fuzz/corpus/<reader>/, kept small in the repository; what a run adds stays in build-fuzz/).
# Any crash, sanitizer report, leak, exception other than relume::Error, allocation above 512 MB
# or input slower than 10 s fails the script; the input is kept in build-fuzz/findings/.
#   scripts/fuzz.sh [SECONDS]      build and run every target
#   scripts/fuzz.sh --make-seeds   rewrite the binary seeds (containers, .npy) in fuzz/corpus/
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=60
make_seeds=0
case "${1:-}" in
  --make-seeds) make_seeds=1 ;;
  "") ;;
  *) seconds="$1" ;;
esac

source scripts/compiler_cache.sh
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DRELUME_FUZZ=ON -DRELUME_BUILD_TESTS=OFF -DRELUME_BUILD_PYTHON=OFF "${compiler_cache[@]}" >/dev/null
cmake --build build-fuzz --target relume_fuzz_targets -j "$(nproc)"

if [ "$make_seeds" -eq 1 ]; then
  build-fuzz/fuzz/make_container_seeds fuzz/corpus
  exit 0
fi

# target:corpus folder
targets=(
  fuzz_container:container
  fuzz_container_repaired:container
  fuzz_section_coding:section_coding
  fuzz_container_strips:container
  fuzz_npz_export:container
  fuzz_npy:npy
  fuzz_light_files:light_files
  fuzz_field_folder:field_folder
  fuzz_environment_layout:environment_layout
  fuzz_weight_planes:weight_planes
)
mkdir -p build-fuzz/findings
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# Runs one target ("name:reader") on a fresh copy of its reader's seeds and prints the outcome;
# fails on a finding.
fuzz_target() {
  local target="${1%%:*}" corpus="build-fuzz/corpus/${1%%:*}"
  rm -rf "$corpus"
  mkdir -p "$corpus"
  cp "fuzz/corpus/${1#*:}"/* "$corpus"/
  if ! build-fuzz/fuzz/"$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -malloc_limit_mb=512 -max_len=16384 -print_final_stats=1 \
      -artifact_prefix="build-fuzz/findings/$target-" "$corpus" 2>"build-fuzz/$target.log"; then
    tail -n 40 "build-fuzz/$target.log"
    echo "fuzz.sh: $target FAILED (input in build-fuzz/findings/, log build-fuzz/$target.log)"
    return 1
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build-fuzz/$target.log" |
    tr '\n' ' ' | sed "s/^/fuzz.sh: $target: /"
  echo
}

# One target per core at a time (each fuzzer runs on one thread).
echo "fuzz.sh: ${#targets[@]} targets for ${seconds} s each, $(nproc) at a time"
failed=0
running=()
for entry in "${targets[@]}"; do
  fuzz_target "$entry" &
  running+=($!)
  if [ "${#running[@]}" -ge "$(nproc)" ]; then
    wait "${running[0]}" || failed=1
    running=("${running[@]:1}")
  fi
done
for pid in "${running[@]}"; do
  wait "$pid" || failed=1
done
exit "$failed"
