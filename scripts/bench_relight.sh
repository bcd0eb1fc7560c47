#!/usr/bin/env bash
# The relighting figures of docs/relighting.md: runs `relume bench` (default shape: 640x640 RGB,
# 253 lights, 128 clusters, 4 terms, 12 residual entries per function) RUNS times on one OpenCL
# device and prints one markdown table row per run plus the median of the runs: read and copy
# ceilings, residual SpMV and relight GB/s with their share of the device's peak, frames/s of a
# single frame and of a batch of 16, the batch's speed-up, and where the single and batched
# relights sit against their binding roof (memory or the relighter's work ceiling). Then one run per residual cap in
# $CAPS (default "0 3 6 12"): the speed side of the dynamic residual's trade.
# Usage: scripts/bench_relight.sh [RELUME_BINARY] [RUNS] [more bench options...]
#   RELUME_BINARY defaults to build/apps/relume, RUNS to 5; the device is RELUME_DEVICE or the
#   default one (a GPU, else PoCL). JSON records go to $BENCH_DIR (default /tmp/relume-bench-relight).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
relume="${1:-$root/build/apps/relume}"
runs="${2:-5}"
shift $(( $# > 2 ? 2 : $# ))
out="${BENCH_DIR:-/tmp/relume-bench-relight}"
[ -x "$relume" ] || { echo "bench_relight.sh: no relume binary at $relume" >&2; exit 1; }
mkdir -p "$out"

device_option=()
[ -n "${RELUME_DEVICE:-}" ] && device_option=(--device "$RELUME_DEVICE")
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(date -u +%Y-%m-%d)"
echo "command: relume bench --repeats 15 --no-reference --assign-rows 0 ${device_option[*]} $*"
for run in $(seq 1 "$runs"); do
  load="$(cut -d' ' -f1 /proc/loadavg)"
  RELUME_QUIET=1 "$relume" bench --repeats 15 --no-reference --assign-rows 0 \
    "${device_option[@]}" "$@" --json "$out/run$run.json" > /dev/null
  echo "$load" > "$out/run$run.load"
done

/usr/bin/python3 - "$out" "$runs" <<'PY'
import json, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
rows = []
for run in range(1, runs + 1):
    records = json.load(open(f"{out}/run{run}.json"))["records"]
    by_kernel = {r["kernel"]: r for r in records if r["platform"] != "reference"}
    single, batched = by_kernel["relight"], by_kernel["relight_batched"]
    rows.append({
        "run": str(run),
        "load": float(open(f"{out}/run{run}.load").read()),
        "read": by_kernel["read"]["gbps"], "copy": by_kernel["copy"]["gbps"],
        "spmv": by_kernel["spmv"]["gbps"], "spmv_peak": by_kernel["spmv"]["ratio_to_peak"],
        "relight": single["gbps"], "relight_peak": single["ratio_to_peak"],
        "fps": single["frames_per_second"], "fps_wall": single["wall_frames_per_second"],
        "batched_fps": batched["frames_per_second"],
        "batched_fps_wall": batched["wall_frames_per_second"],
        "speedup": batched["frames_per_second"] / single["frames_per_second"],
        "bound": single["ratio_to_binding_ceiling"], "bound_by": single["binding_ceiling"],
        "batched_bound": batched["ratio_to_binding_ceiling"],
        "batched_bound_by": batched["binding_ceiling"],
    })
    device = f'{single["platform"]} / {single["device"]}'
print(f"device: {device}")
print("| run | load | read GB/s | copy GB/s | spmv GB/s (of peak) | relight GB/s (of peak) "
      "| relight frames/s (whole call) | batched frames/s (whole call) | batched / single "
      "| relight of binding roof | batched of binding roof |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
roofs = ("run", "bound_by", "batched_bound_by")
median = {k: statistics.median(r[k] for r in rows) for k in rows[0] if k not in roofs}
median["run"] = "median"
for k in roofs[1:]:  # the roof that binds in most runs
    median[k] = max({r[k] for r in rows}, key=[r[k] for r in rows].count)
for r in rows + [median]:
    print(f'| {r["run"]} | {r["load"]:.2f} | {r["read"]:.1f} | {r["copy"]:.1f} '
          f'| {r["spmv"]:.1f} ({100 * r["spmv_peak"]:.0f}%) '
          f'| {r["relight"]:.1f} ({100 * r["relight_peak"]:.0f}%) '
          f'| {r["fps"]:.0f} ({r["fps_wall"]:.0f}) '
          f'| {r["batched_fps"]:.0f} ({r["batched_fps_wall"]:.0f}) | {r["speedup"]:.1f}x '
          f'| {100 * r["bound"]:.0f}% ({r["bound_by"]}) '
          f'| {100 * r["batched_bound"]:.0f}% ({r["batched_bound_by"]}) |')
PY

caps="${CAPS:-0 3 6 12}"
echo
echo "residual caps: relume bench --repeats 15 --no-reference --assign-rows 0 --cap N ${device_option[*]} $*"
for cap in $caps; do
  RELUME_QUIET=1 "$relume" bench --repeats 15 --no-reference --assign-rows 0 --cap "$cap" \
    "${device_option[@]}" "$@" --json "$out/cap$cap.json" > /dev/null
done
/usr/bin/python3 - "$out" $caps <<'PY'
import json, sys
out, caps = sys.argv[1], sys.argv[2:]
print("| cap | relight MB/frame | relight of peak | relight frames/s | batched frames/s | layout |")
print("|---|---|---|---|---|---|")
for cap in caps:
    records = json.load(open(f"{out}/cap{cap}.json"))["records"]
    by_kernel = {r["kernel"]: r for r in records if r["platform"] != "reference"}
    single, batched = by_kernel["relight"], by_kernel["relight_batched"]
    layout = single["layout"]
    print(f'| {cap} | {single["bytes"] / 1e6:.1f} | {100 * single["ratio_to_peak"]:.0f}% '
          f'| {single["frames_per_second"]:.0f} | {batched["frames_per_second"]:.0f} '
          f'| slices of {layout["slice_rows"]}, work-groups of {layout["work_group_rows"]}, '
          f'head {layout["head_entries"]} |')
PY
