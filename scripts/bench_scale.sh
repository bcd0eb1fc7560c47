#!/usr/bin/env bash
# Scale benchmark (issue 12), in parts:
#  lights: a 320x320 synthetic field with 64, 253 and 1024 lights compressed with 64 clusters,
#    4 terms and 12 residual entries on 2 threads; seconds per phase (and of clustering's parts)
#    from each report, the time ratio against the data ratio, and seeding's share of the run.
#  fields: synthetic fields of 253 lights growing past a 3 GB memory budget (640x640: 1.2 GB as
#    float32, 1280x1280: 5 GB, 2560x2560: 20 GB; FIELD_SIDES overrides the list), compressed with
#    --memory-limit 3G, and the 640x640 one also streamed under 400M: seconds, peak memory,
#    scratch bytes, Eq. 16 error and seconds per stored function, in memory and streamed.
#  24mp: a 6000x4000, 60-light hemisphere field (17 GB as float32) within 4 GB, and the same
#    kind of field at 1500x1000 in memory for the cost per stored function.
#  mpi: the 640x640x253 field (MPI_FIELD_SIDE overrides the side) streamed (--memory-limit 400M,
#    which keeps its compressed field in memory; MPI_MEMORY_LIMIT=300M puts it on disk)
#    by 1, 2, 4 and 8 ranks of one thread (mpirun --oversubscribe: 4 and 8 share this machine's
#    cores), each rank's stored functions, time outside the exchanges and bytes sent, and a model
#    of the efficiency at 8 and 64 ranks. MPI_RUNS=N (default 1) runs 1 and 2 ranks N times each,
#    alternating, for the median speed-up (one run's time varies by 10% on a shared machine).
#   scripts/bench_scale.sh [BUILD_DIR] [OUT_DIR] [lights|fields|24mp|mpi ...]   (default: lights)
# Writes OUT_DIR/scale_<part>.csv; the synthetic fields are kept in OUT_DIR for reruns (the big
# ones take tens of GB of disk).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-/tmp/relume-scale}"
shift $(( $# > 2 ? 2 : $# ))
parts=("${@:-lights}")
relume="$build/apps/relume"
mkdir -p "$out"

# One compress under a memory limit: a CSV row from its report.
#   streamed_run NAME FIELD LIMIT CSV
streamed_run() {
  local name="$1" field="$2" limit="$3" csv="$4"
  local report="$out/report_$name.json"
  "$relume" -q --memory-limit "$limit" compress "$field" -o "$out/$name.relume" -y \
    --clusters 64 --terms 4 --residual 12 --threads 2 --scratch "$out/scratch" --report "$report"
  /usr/bin/python3 - "$report" "$name" "$limit" >>"$csv" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
f, plan = r["field"], r["plan"]
stream = r.get("streamed", {})
cells = [sys.argv[2], f["width"], f["height"], f["lights"], r["float32_input_bytes"], sys.argv[3],
         ("streamed (compressed field on disk)" if plan.get("compressed_on_disk") else "streamed")
         if plan["streamed"] else "in memory", plan.get("strip_rows", ""),
         plan.get("sample_rows", ""), stream.get("scratch_bytes", ""), r["seconds"],
         r["peak_memory_bytes"], f["stored_rows"], r["seconds"] / f["stored_rows"] * 1e6,
         r["error_masked"], r["bytes"]]
print(",".join(f"{v:.4g}" if isinstance(v, float) else str(v) for v in cells))
PY
}
streamed_header="name,width,height,lights,float32_bytes,memory_limit,plan,strip_rows,sample_rows,scratch_bytes,seconds,peak_memory_bytes,stored_rows,microseconds_per_stored_function,error_masked,bytes"

for part in "${parts[@]}"; do
case "$part" in
lights)

csv="$out/scale_lights.csv"
echo "lights,seconds,load,prepare,clustering,seeding,basis_fit,candidates,assignment,residual,error_measure,write,error_masked,peak_memory_bytes" >"$csv"
for lights in 64 253 1024; do
  field="$out/synth_320_$lights"
  [ -d "$field" ] || "$relume" -q synth -o "$field" --size 320x320 --lights "$lights"
  report="$out/report_$lights.json"
  "$relume" -q compress "$field" -o "$out/synth_320_$lights.relume" -y --clusters 64 --terms 4 \
    --residual 12 --threads 2 --report "$report"
  /usr/bin/python3 - "$report" "$lights" >>"$csv" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
p, c = r["phases_seconds"], r["clustering"]["seconds"]
cells = [sys.argv[2], r["seconds"], p["load"], p["prepare"], p["clustering"], c["seeding"],
         c["basis_fit"], c["candidates"], c["assignment"], p["residual"], p["error_measure"],
         p["write"], r["error_masked"], r["peak_memory_bytes"]]
print(",".join(f"{v:.4g}" if isinstance(v, float) else str(v) for v in cells))
PY
done
cat "$csv"
/usr/bin/python3 - "$csv" <<'PY'
import csv, sys
rows = {int(r["lights"]): r for r in csv.DictReader(open(sys.argv[1]))}
a, b = rows[64], rows[1024]
print(f"64 -> 1024 lights (16x the data): {float(b['seconds']) / float(a['seconds']):.1f}x the time;"
      f" seeding {float(b['seeding']) / float(b['seconds']):.0%} of the 1024-light run")
PY
;;
fields)
  sides="${FIELD_SIDES:-640 1280 2560}"
  csv="$out/scale_fields_${sides// /_}.csv"
  echo "$streamed_header" >"$csv"
  for side in $sides; do
    field="$out/synth_${side}_253"
    [ -d "$field" ] || "$relume" -q synth -o "$field" --size "${side}x${side}" --lights 253 \
      --samples 1
    streamed_run "fields_$side" "$field" 3G "$csv"
    [ "$side" = 640 ] && streamed_run "fields_640_streamed" "$field" 400M "$csv"
    if [ "$side" != 640 ]; then rm -rf "$field"; fi  # tens of GB: not kept
  done
  cat "$csv"
;;
24mp)
  csv="$out/scale_24mp.csv"
  echo "$streamed_header" >"$csv"
  # The same kind of field at 1.5 megapixels, in memory: the cost per stored function to compare.
  small="$out/synth_1500x1000_60"
  [ -d "$small" ] || "$relume" -q synth -o "$small" --size 1500x1000 --lights 60 --hemisphere \
    --samples 1
  streamed_run "1500x1000_in_memory" "$small" 20G "$csv"
  field="$out/synth_6000x4000_60"
  [ -d "$field" ] || "$relume" -q synth -o "$field" --size 6000x4000 --lights 60 --hemisphere \
    --samples 1
  streamed_run "24mp" "$field" 4G "$csv"
  rm -rf "$field" "$small"
  cat "$csv"
;;
mpi)
  side="${MPI_FIELD_SIDE:-640}"
  field="$out/synth_${side}_253"
  [ -d "$field" ] || "$relume" -q synth -o "$field" --size "${side}x${side}" --lights 253 \
    --samples 1
  csv="$out/scale_mpi.csv"
  echo "run,ranks,seconds,passes,rank_stored_functions,rank_compute_seconds,rank_bytes_sent,error_masked" >"$csv"
  runs=()
  for run in $(seq "${MPI_RUNS:-1}"); do runs+=("$run 1" "$run 2"); done
  for run_ranks in "${runs[@]}" "1 4" "1 8"; do
    read -r run ranks <<<"$run_ranks"
    report="$out/report_mpi_$ranks.json"
    mpirun --allow-run-as-root --oversubscribe -n "$ranks" "$relume" -q \
      --memory-limit "${MPI_MEMORY_LIMIT:-400M}" \
      compress "$field" -o "$out/mpi_$ranks.relume" -y --clusters 64 --terms 4 --residual 12 \
      --threads 1 --scratch "$out/scratch" --report "$report"
    /usr/bin/python3 - "$report" "$run" "$ranks" >>"$csv" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
s = r["streamed"]
print(",".join([sys.argv[2], sys.argv[3], f"{r['seconds']:.4g}", str(len(s["passes"])),
                ";".join(str(v) for v in s["rank_stored_functions"]),
                ";".join(f"{v:.3g}" for v in s["rank_compute_seconds"]),
                ";".join(str(v) for v in s["rank_bytes_sent"]), f"{r['error_masked']:.6g}"]))
PY
  done
  cat "$csv"
  # The model: per pass, compute divides over the ranks (one rank's measured compute / P) and
  # each pass's exchanges (what a non-root rank sends per pass, measured at 8 ranks) cross a tree
  # of log2(P) steps at an assumed 1.25 GB/s (10 Gb Ethernet) with 50 us per message, 2 messages
  # per F-step round (reduce, broadcast) and 7 rounds per pass.
  /usr/bin/python3 - "$csv" <<'PY'
import csv, math, statistics, sys
table = list(csv.DictReader(open(sys.argv[1])))
rows = {int(r["ranks"]): r for r in table}  # the last run of each rank count
one, eight = rows[1], rows[8]
compute_1 = float(one["rank_compute_seconds"]) / int(one["passes"])
speedups = []
for run in sorted({r["run"] for r in table if r["ranks"] == "2"}, key=int):
    pair = {r["ranks"]: float(r["seconds"]) for r in table if r["run"] == run}
    speedups.append(pair["1"] / pair["2"])
    print(f"strong scaling on this machine, run {run}: 1 rank {pair['1']:.1f} s, 2 ranks "
          f"{pair['2']:.1f} s: {speedups[-1]:.2f}x")
print(f"median over {len(speedups)} runs: {statistics.median(speedups):.2f}x")
sent_8 = max(int(v) for v in eight["rank_bytes_sent"].split(";")[1:]) / int(eight["passes"])
for p in (8, 64):
    messages = 7 * 2 * math.log2(p)
    comm = messages * 50e-6 + sent_8 * math.log2(p) / 1.25e9
    compute = compute_1 / p
    print(f"model at {p} ranks: compute {compute:.3f} s per pass, exchanges {comm:.4f} s per pass"
          f" (a rank sends {sent_8 / 1e6:.2f} MB per pass): efficiency {compute / (compute + comm):.0%}")
PY
;;
*) echo "unknown part '$part' (lights, fields, 24mp, mpi)" >&2; exit 2 ;;
esac
done
