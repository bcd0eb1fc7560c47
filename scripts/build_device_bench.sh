#!/usr/bin/env bash
# Builds the device-only `relume` (only `bench` and `devices`, no image I/O; see
# cmake/device_bench.cmake) in ./build-device and puts what a GPU machine with nothing installed
# needs into ./device-bench (ignored by git): the binary and the OpenCL ICD loader it finds next to
# itself (RUNPATH $ORIGIN). Checks that the binary starts in an empty environment, lists what it
# still takes from the system, and prints the size of what the device tool would carry: the
# tracked and untracked-not-ignored files plus device-bench/ (the limit is 64 MiB).
# Run it (the device tool's `run` with carry ["device-bench"]): scripts/device_bench.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-device -G Ninja -DCMAKE_BUILD_TYPE=Release -DRELUME_DEVICE_BENCH_ONLY=ON
cmake --build build-device -j "$(nproc)"

rm -rf device-bench
mkdir device-bench
cp build-device/relume device-bench/relume
strip device-bench/relume
# The ICD loader the binary was linked against (ocl-icd's libOpenCL.so.1), under its soname.
loader="$(ldd build-device/relume | awk '$1 == "libOpenCL.so.1" { print $3 }')"
[ -n "$loader" ] || { echo "build_device_bench.sh: relume does not load libOpenCL.so.1" >&2; exit 1; }
cp "$(readlink -f "$loader")" device-bench/libOpenCL.so.1

echo "== device-bench/relume in an empty environment:"
env -i device-bench/relume --version
echo "== what it still takes from the system (everything else is in device-bench/):"
env -i ldd device-bench/relume
newest_glibc="$(objdump -T device-bench/relume device-bench/libOpenCL.so.1 |
  grep -o 'GLIBC_[0-9.]*' | sort -t. -k2,2n -k3,3n | tail -1)"
echo "newest glibc symbol version needed: $newest_glibc"

echo "== what the device tool would carry:"
du -sh device-bench
tree_bytes="$( { git ls-files -z; git ls-files -z --others --exclude-standard; } |
  du -cb --files0-from=- 2>/dev/null | tail -1 | cut -f1)"
bench_bytes="$(du -sb device-bench | cut -f1)"
echo "working tree $((tree_bytes / 1024)) KiB + device-bench $((bench_bytes / 1024)) KiB =" \
  "$(((tree_bytes + bench_bytes) / 1024)) KiB of 65536 KiB"
