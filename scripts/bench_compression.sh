#!/usr/bin/env bash
# Compression benchmarks of docs/compression.md: runs `relume compress` on the shared real data
# (and a synthetic 640x640, 253-light scene) with 2 threads, prints the key figures of each JSON
# report, and checks one reported error independently (scripts/check_error.py). About 20 minutes
# on 2 cores. Usage: scripts/bench_compression.sh [BUILD_DIR] [OUT_DIR]
# RELUME_DATA overrides the data folder (default ../shared/data next to the repository).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
out="${2:-/tmp/relume-bench-compression}"
data="${RELUME_DATA:-$root/../shared/data}"
relume="$build/apps/relume"
mkdir -p "$out"

summary() {
  python3 - "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
phases = {k: round(v, 1) for k, v in r["phases_seconds"].items()}
clustering = {k: round(v, 1) for k, v in r["clustering"]["seconds"].items()}
prefix = {k: round(v, 4) for k, v in r["error_masked_by_residual_entries"].items()}
print(f"  seconds {r['seconds']:.1f}  bytes {r['bytes']}  ratio {r['ratio']:.4f}  "
      f"error_all {r['error_all']:.4f}  error_masked {r['error_masked']:.4f}  "
      f"peak {r['peak_memory_bytes'] / 2**20:.0f} MiB")
print(f"  masked error by residual entries {prefix}")
print(f"  phases {phases}")
print(f"  clustering {clustering}")
if "target_error" in r:
    print(f"  target_error choice {json.dumps(r['target_error'])}")
print(f"  sparseness {[(s['threshold_relative_to_norm'], round(s['fraction_at_or_below'], 3)) for s in r['sparseness']]}")
PY
}

run() {
  local name="$1"; shift
  echo "== $name: relume compress $* (load average $(cut -d' ' -f1 /proc/loadavg))"
  RELUME_QUIET=1 "$relume" -y compress "$@" --threads 2 -o "$out/$name.relume" --report "$out/$name.json"
  summary "$out/$name.json"
}

ball="$data/olat/diligent-ball-16bit"
harvest="$data/olat/diligent-harvest-crop8"
run ball "$ball" --clusters 64 --terms 4 --residual 5%
run ball-multires "$ball" --clusters 64 --terms 4 --residual 5% --multires 1
run harvest "$harvest" --clusters 64 --terms 4 --residual 10
run harvest-8-iterations "$harvest" --clusters 64 --terms 4 --residual 10 --iterations 8 --irls-iterations 10 --candidates 4
run harvest-haar "$harvest" --clusters 64 --terms 4 --residual 10 --transform haar
run harvest-multires "$harvest" --clusters 64 --terms 4 --residual 10 --multires 1
run harvest-cpu-assign "$harvest" --clusters 64 --terms 4 --residual 10 --assign cpu
run ball-lp-dual "$ball" --clusters 64 --terms 4 --residual 5% --solver lp-dual
run ball-target "$ball" --target-error 0.0005

echo "== independent check of the harvest run's error (scripts/check_error.py)"
"$relume" -y decompress "$out/harvest.relume" -o "$out/harvest-decompressed" > /dev/null
/usr/bin/python3 "$root/scripts/check_error.py" "$harvest" "$out/harvest-decompressed"

if [[ "${SKIP_SYNTH:-0}" != 1 ]]; then
  synth="$out/synth-640"
  [[ -f "$synth/filenames.txt" ]] || "$relume" synth -o "$synth" --size 640x640 --lights 253
  run synth-640 "$synth" --clusters 128 --terms 4 --residual 5%
  run synth-640-multires "$synth" --clusters 128 --terms 4 --residual 5% --multires 1
  run synth-640-multires-haar "$synth" --clusters 128 --terms 4 --residual 5% --multires 1 --transform haar
fi
