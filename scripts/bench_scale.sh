#!/usr/bin/env bash
# Scale benchmark (issue 12), the lights-growing part: a 320x320 synthetic field with 64, 253 and
# 1024 lights compressed with 64 clusters, 4 terms and 12 residual entries on 2 threads; seconds
# per phase (and of clustering's parts) from each report, the time ratio against the data ratio,
# and seeding's share of the run.
#   scripts/bench_scale.sh [BUILD_DIR] [OUT_DIR]
# Writes OUT_DIR/scale_lights.csv; the synthetic fields are kept in OUT_DIR for reruns.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-/tmp/relume-scale}"
relume="$build/apps/relume"
mkdir -p "$out"

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
