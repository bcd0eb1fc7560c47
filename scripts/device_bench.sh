#!/usr/bin/env bash
# The GPU measurement of issue 16 in one call: `relume bench` on the default shape (640x640 RGB,
# 253 lights, 128 clusters, 4 terms, 12 residual entries per function) and on a 4x larger one
# (1280x1280), each with the read/copy ceilings, GEMV, residual SpMV, single-frame relight and
# batched relight at B = 1, 4, 16 and 64; on the default shape also the assignment kernel and the
# CPU reference paths (relight and assignment). Writes the JSON, the bench tables and the machine's
# description under $OUT and prints a short summary: the device and driver, GB/s and % of the
# measured copy bandwidth, frames/s, fits/s against the CPU path, and the issue's targets.
#
# Usage: scripts/device_bench.sh [--quick] [RELUME_BINARY]
#   RELUME_BINARY: default device-bench/relume (scripts/build_device_bench.sh) if it is there, else
#     build/apps/relume.
#   --quick: small shapes (32x32 and 64x64, 20 lights, 4 clusters, 2 terms, 4 entries), 3 rounds and
#     no GPU required: checks the script on PoCL in seconds (tests/apps/device_bench_script_test.cpp).
#   OUT: results folder (default /tmp/relume-device-bench).
#   RELUME_DEVICE: the device to bench, as `relume devices` names it. Unset: every device, and
#     without --quick at least one must be a GPU (when none is listed, the NVIDIA driver is looked
#     for and named to the ICD loader through OCL_ICD_VENDORS).
# On the GPU machine (the device tool, with carry ["device-bench"]): scripts/device_bench.sh
# Files under $OUT: default.json, large.json, bench.log, environment.txt, summary.txt.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
quick=0
if [ "${1:-}" = "--quick" ]; then
  quick=1
  shift
fi
relume="${1:-}"
if [ -z "$relume" ]; then
  relume="$root/build/apps/relume"
  [ -f "$root/device-bench/relume" ] && relume="$root/device-bench/relume"
fi
# A carried copy may have lost its executable bit.
[ -f "$relume" ] && [ ! -x "$relume" ] && chmod +x "$relume"
out="${OUT:-/tmp/relume-device-bench}"
mkdir -p "$out"
export RELUME_QUIET=1

# --- The machine: what the summary quotes and what a failed run needs to be understood.
environment="$out/environment.txt"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "host: $(uname -srm), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
  echo "glibc: $(getconf GNU_LIBC_VERSION 2>/dev/null || echo unknown) (device-bench/relume needs 2.36 or newer)"
  echo "relume: $relume"
  if command -v nvidia-smi > /dev/null; then
    echo "nvidia-smi: $(nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm,clocks.max.mem \
      --format=csv,noheader 2>&1 | head -1)"
  fi
  echo "OpenCL vendors (/etc/OpenCL/vendors):"
  for icd in /etc/OpenCL/vendors/*.icd; do [ -e "$icd" ] && echo "  $icd: $(cat "$icd")"; done
  echo "OCL_ICD_VENDORS: ${OCL_ICD_VENDORS:-unset}"
} > "$environment"

fail() {  # prints the machine's description, then the message
  echo "device_bench.sh: $*" >> "$environment"
  cat "$environment" >&2
  exit 1
}

if ! version="$("$relume" --version 2>&1)"; then
  fail "$relume does not start: $version
$(ldd "$relume" 2>&1)"
fi
echo "relume --version: $version" >> "$environment"

# The NVIDIA OpenCL driver, when no ICD file names it (or names it by a bare soname that the
# loader cannot find): an ICD folder of our own with its full path.
nvidia_opencl_library() {
  ldconfig -p 2>/dev/null | awk '/libnvidia-opencl\.so\.1/ { print $NF; exit }'
  find /usr/local/nvidia /usr/lib/x86_64-linux-gnu /usr/lib64 /usr/local/cuda/compat -maxdepth 2 \
    -name 'libnvidia-opencl.so.1' 2>/dev/null | head -1
}
devices="$("$relume" devices 2>&1)" || fail "relume devices failed: $devices"
# Without --quick or RELUME_DEVICE the run is for a GPU: find one or stop.
if [ "$quick" = 0 ] && [ -z "${RELUME_DEVICE:-}" ] && ! grep -qw gpu <<< "$devices"; then
  library="$(nvidia_opencl_library | head -1 || true)"
  [ -n "$library" ] || fail "no OpenCL GPU and no libnvidia-opencl.so.1 found:
$devices"
  mkdir -p /tmp/relume-icd
  echo "$library" > /tmp/relume-icd/nvidia.icd
  export OCL_ICD_VENDORS=/tmp/relume-icd
  # The driver's own dependencies (libcuda.so.1, ...) lie beside it.
  export LD_LIBRARY_PATH="$(dirname "$library")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  echo "no GPU through the installed ICD files; using OCL_ICD_VENDORS=/tmp/relume-icd -> $library" \
    "and LD_LIBRARY_PATH=$LD_LIBRARY_PATH" >> "$environment"
  devices="$("$relume" devices 2>&1)" || fail "relume devices failed: $devices"
  grep -qw gpu <<< "$devices" || fail "still no OpenCL GPU with $library:
$devices
the ICD loader's account (OCL_ICD_DEBUG=15):
$(OCL_ICD_DEBUG=15 "$relume" devices 2>&1 | tail -40)"
fi
printf 'relume devices:\n%s\n' "$devices" >> "$environment"

# --- The runs.
if [ "$quick" = 1 ]; then
  shape=(--width 32 --height 32 --lights 20 --clusters 4 --terms 2 --residual 4)
  large=(--width 64 --height 64 --lights 20 --clusters 4 --terms 2 --residual 4)
  # One slice height for both shapes, so that the second run reuses the first one's programs.
  rounds=(--repeats 3 --ceiling-mib 4 --slice 512)
  assignment=(--assign-rows 256)
else
  shape=()
  large=(--width 1280 --height 1280)
  # 1 GiB ceilings: well past the H200's 60 MB L2.
  rounds=(--repeats 15 --ceiling-mib 1024)
  assignment=(--assign-rows 65536)
fi
batches=(--frames 1,4,16,64 --max-batch 64)
device_option=()
[ -n "${RELUME_DEVICE:-}" ] && device_option=(--device "$RELUME_DEVICE")

log="$out/bench.log"
: > "$log"
run_bench() {  # NAME OPTIONS...
  local name="$1"
  shift
  local command=(bench "${device_option[@]}" "${rounds[@]}" "${batches[@]}" "$@"
                 --json "$out/$name.json")
  echo "== relume ${command[*]}" >> "$log"
  local start=$SECONDS
  "$relume" "${command[@]}" >> "$log" 2>&1 || fail "relume ${command[*]} failed:
$(tail -20 "$log")"
  echo "== $name: $((SECONDS - start)) s" >> "$log"
}
run_bench default "${shape[@]}" "${assignment[@]}"
run_bench large "${large[@]}" --assign-rows 0 --no-reference

# --- The summary.
if ! command -v python3 > /dev/null; then
  echo "device_bench.sh: no python3 for the summary; the results are in $out" >&2
  exit 0
fi
python3 - "$out" <<'PY' | tee "$out/summary.txt"
import json, sys

out = sys.argv[1]
for name in ("default", "large"):
    report = json.load(open(f"{out}/{name}.json"))
    field = report["field"]
    print(f'{name}: {field["width"]}x{field["height"]}x{field["channels"]}, {field["lights"]} lights, '
          f'{field["clusters"]} clusters, {field["terms"]} terms, '
          f'{field["residual_per_function"]} residual entries per function '
          f'({report["repeats"]} rounds, medians)')
    records = report["records"]
    reference_assign = [r for r in records if r["platform"] == "reference" and r["kernel"] == "assign"]
    for device in report["devices"]:
        mine = [r for r in records
                if r["platform"] == device["platform"] and r["device"] == device["device"]]
        kernel = {r["kernel"]: r for r in mine}
        copy = kernel["copy"]["gbps"]
        print(f'  {device["platform"]} / {device["device"]}: driver {device["driver_version"]}, '
              f'{device["version"]}, {device["compute_units"]} compute units, '
              f'{device["global_memory_bytes"] / 2**30:.1f} GiB')
        print(f'  read {kernel["read"]["gbps"]:.1f} GB/s, copy {copy:.1f} GB/s (read + write bytes)')
        print(f'  {"kernel":<18} {"MB/run":>9} {"GB/s":>9} {"of copy":>8} {"frames/s":>10} '
              f'{"whole call":>11}')
        relight = {}
        for r in mine:
            if r["kernel"] in ("read", "copy", "assign"):
                continue
            label = r["kernel"]
            if r["kernel"] == "relight_batched":
                label = f'batched B={r["frames"]}'
                relight[r["frames"]] = r
            elif r["kernel"] == "relight":
                label = "relight (1 frame)"
                relight["single"] = r
            fps = f'{r["frames_per_second"]:.0f}' if "frames_per_second" in r else "-"
            wall = f'{r["wall_frames_per_second"]:.0f}' if "wall_frames_per_second" in r else "-"
            print(f'  {label:<18} {r["bytes"] / 1e6:9.1f} {r["gbps"]:9.1f} '
                  f'{100 * r["gbps"] / copy:7.0f}% {fps:>10} {wall:>11}')
        if "assign" in kernel:
            a = kernel["assign"]
            line = (f'  assign: {a["fits_per_second"]:.4g} fits/s '
                    f'(whole call {a["wall_fits_per_second"]:.4g}) on {a["fits"]} fits')
            for r in reference_assign:
                line += (f'; CPU path ({r["device"]}) {r["fits_per_second"]:.4g} fits/s: '
                         f'{a["fits_per_second"] / r["fits_per_second"]:.1f}x')
            print(line)
        single, batch16 = relight["single"]["gbps"] / copy, relight[16]["gbps"] / copy
        print(f'  targets: single-frame relight {100 * single:.0f}% of copy (target 70%: '
              f'{"met" if single >= 0.70 else "missed"}), batched B=16 {100 * batch16:.0f}% '
              f'(target 85%: {"met" if batch16 >= 0.85 else "missed"})')
PY
