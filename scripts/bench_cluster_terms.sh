#!/usr/bin/env bash
# What dropping the terms a cluster does not need buys (relume compress --term-budget,
# lib/model/cluster_terms.hpp), against the other way to save the same bytes: one residual entry
# per function fewer. For each scene the same clustering (same seed) is stored with term budgets
# 0, 0.01, 0.03 and 0.1, and once more with one residual entry fewer and every term kept; the
# table gives bytes, the stored error (Eq. 16 over the masked functions), the terms the clusters
# kept, and the error added per byte saved by each way (smaller is the better trade).
#   scripts/bench_cluster_terms.sh [BUILD_DIR] [OUT_DIR]
# Scenes: DiLiGenT's ball normalised to 8 bit, whole frame (as issue 11 measures it), the bear
# crop, and the demo's synthetic scene (320x320, 253 lights, scripts/demo.sh's settings).
# About 15 minutes on 2 cores. Writes OUT_DIR/cluster_terms.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-/tmp/relume-cluster-terms}"
data="${RELUME_DATA:-../shared/data}"
relume="$build/apps/relume"
ball="$data/olat/diligent-ball-16bit"
mkdir -p "$out"
[ -d "$out/ball8_nomask" ] ||
  /usr/bin/python3 scripts/normalize_to_8bit.py "$ball" "$out/ball8_nomask" --no-mask
[ -f "$out/synth/filenames.txt" ] ||
  "$relume" -q synth -o "$out/synth" --size 320x320 --lights 253

# scene|input|options|residual entries (the run with one fewer drops to residual - 1)
scenes=(
  "ball8 whole frame|$out/ball8_nomask|--linear --clusters 64 --terms 4|3"
  "bear crop|$data/olat/diligent-bear-crop8|--clusters 16 --terms 4|6"
  "synthetic 320x320|$out/synth|--clusters 64 --terms 8|7"
)
csv="$out/cluster_terms.csv"
echo "scene,term_budget,residual,bytes,error_masked,terms_kept,mean_terms" >"$csv"
point() {  # scene name, input, options, term budget, residual
  local report="$out/point.json"
  # shellcheck disable=SC2086  # the options are words
  "$relume" compress -q -y "$2" -o "$out/point.relume" $3 --residual "$5" \
    --term-budget "$4" --threads 2 --report "$report"
  /usr/bin/python3 - "$report" "$1" "$4" "$5" >>"$csv" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
kept = r.get("precision_cost", {}).get("terms_per_cluster", {}).get("terms")
histogram = "" if kept is None else " ".join(
    f"{t}:{kept.count(t)}" for t in sorted(set(kept), reverse=True))
mean = "" if kept is None else f"{sum(kept) / len(kept):.2f}"
print(f'{sys.argv[2]},{sys.argv[3]},{sys.argv[4]},{r["bytes"]},{r["error_masked"]:.6f},'
      f'{histogram},{mean}')
EOF
}
for scene in "${scenes[@]}"; do
  IFS='|' read -r name input options residual <<<"$scene"
  echo "bench_cluster_terms: $name" >&2
  for budget in 0 0.01 0.03 0.1; do point "$name" "$input" "$options" "$budget" "$residual"; done
  point "$name" "$input" "$options" 0 "$((residual - 1))"
done
rm -f "$out/point.relume" "$out/point.json"

/usr/bin/python3 - "$csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("| scene | stored as | bytes | Eq. 16 (masked) | terms kept (terms:clusters) | error added per kB saved |")
print("|---|---|---|---|---|---|")
for scene in dict.fromkeys(r["scene"] for r in rows):
    points = [r for r in rows if r["scene"] == scene]
    base = next(r for r in points if float(r["term_budget"]) == 0 and r is points[0])
    for r in points:
        saved = int(base["bytes"]) - int(r["bytes"])
        added = float(r["error_masked"]) - float(base["error_masked"])
        slope = f"{added / saved * 1000:.3g}" if saved > 0 else ""
        how = (f"term budget {r['term_budget']}, {r['residual']} entries"
               if r is not points[-1] else f"all terms, {r['residual']} entries")
        print(f"| {scene} | {how} | {int(r['bytes']):,} | {float(r['error_masked']):.5f} | "
              f"{r['terms_kept']} | {slope} |")
EOF
