#!/usr/bin/env bash
# The heavy runs behind docs/results.md: `relume eval` on the shared DiLiGenT data (ball 16-bit,
# bear, pot1, harvest) and on a full-sphere synthetic scene, each into OUT/<name>/, relit under
# Grace Cathedral. Then prints the headline tables of docs/results.md from the CSVs.
#
# Usage: scripts/eval_all.sh [BUILD_DIR] [OUT_DIR] [NAMES...]
#   BUILD_DIR defaults to build, OUT_DIR to out/eval, NAMES to all of ball bear pot1 harvest synth.
#   RELUME_DATA overrides ../shared/data; EVAL_THREADS (default 2) the worker threads.
# Then, per field, `relume compress` at 64 clusters x 4 terms without residual for the L1 method,
# clustered PCA and the L1 method refitted (alone, and choosing per cluster between both
# clusterings): the "beat the baseline at 0 entries" measurement, as the containers store it.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
out="${2:-$root/out/eval}"
shift $(( $# > 2 ? 2 : $# ))
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(ball bear pot1 harvest synth)
data="${RELUME_DATA:-$root/../shared/data}"
threads="${EVAL_THREADS:-2}"
relume="$build/apps/relume"
grace="$data/envmaps/grace_cross.hdr"
mkdir -p "$out"

run_eval() {  # name input extra-options...
  local name="$1" input="$2"
  shift 2
  echo "== $name: relume eval $input -o $out/$name $*" >&2
  "$relume" eval "$input" -o "$out/$name" --threads "$threads" --env "$grace" "$@"
}

for name in "${names[@]}"; do
  case "$name" in
    # The largest field (612x512 at 16 bits): the issue's configuration alone, so that it takes
    # about as long as the others.
    ball) run_eval ball "$data/olat/diligent-ball-16bit" --rotate 180 --exposure 1 \
      --clusters 64 --terms 4 --refit-entries 0,1,3 ;;
    bear) run_eval bear "$data/olat/diligent-bear-crop8" --rotate 180 --exposure 3 ;;
    pot1) run_eval pot1 "$data/olat/diligent-pot1-crop8" --rotate 180 --exposure 3 ;;
    harvest) run_eval harvest "$data/olat/diligent-harvest-crop8" --rotate 180 --exposure 3 ;;
    synth)
      [ -f "$out/synth-scene/light_directions.txt" ] ||
        "$relume" synth -o "$out/synth-scene" --size 128x128 --lights 253 --threads "$threads"
      run_eval synth "$out/synth-scene" --entries 0,1,2,3,5,10,20,40 --exposure -1 ;;
    *) echo "eval_all.sh: unknown name '$name' (ball bear pot1 harvest synth)" >&2; exit 2 ;;
  esac
done

refit_table() {  # name input
  local name="$1" input="$2" dir="$out/$1/refit" variant
  mkdir -p "$dir"
  for variant in "l1:" "cpca:--method cpca" "l1-refit:--trimmed-refit 2" \
    "l1-refit-choose:--trimmed-refit 2 --refit-chooses-clusters"; do
    local label="${variant%%:*}" options="${variant#*:}"
    echo "== $name: relume compress $input --clusters 64 --terms 4 --residual 0 $options" >&2
    # shellcheck disable=SC2086
    "$relume" compress -q "$input" -o "$dir/$label.relume" --clusters 64 --terms 4 --residual 0 \
      --threads "$threads" $options --report "$dir/$label.json"
  done
}

for name in "${names[@]}"; do
  case "$name" in
    ball) refit_table ball "$data/olat/diligent-ball-16bit" ;;
    bear) refit_table bear "$data/olat/diligent-bear-crop8" ;;
    pot1) refit_table pot1 "$data/olat/diligent-pot1-crop8" ;;
    harvest) refit_table harvest "$data/olat/diligent-harvest-crop8" ;;
    synth) refit_table synth "$out/synth-scene" ;;
  esac
done

# The headline figures: Eq. 16 at 0 and 5 entries for every configuration, and where CPCA wins.
/usr/bin/python3 - "$out" "${names[@]}" <<'PY'
import csv, json, os, sys
out, names = sys.argv[1], sys.argv[2:]
for name in names:
    path = os.path.join(out, name, "error_vs_entries.csv")
    rows = list(csv.DictReader(open(path)))
    print(f"\n{name}: Eq. 16 (all masked functions) by entries; l1-refit at its own budget")
    configs = sorted({(int(r["clusters"]), int(r["terms"])) for r in rows})
    entries = sorted({int(r["entries"]) for r in rows})
    print("| clusters x terms | method | " + " | ".join(str(e) for e in entries) + " |")
    print("|---|---|" + "---|" * len(entries))
    for clusters, terms in configs:
        for method in ("l1", "l1-refit", "cpca", "cpca-mean"):
            at = {int(r["entries"]): float(r["error_all"]) for r in rows
                  if r["method"] == method and int(r["clusters"]) == clusters
                  and int(r["terms"]) == terms}
            if at:
                cells = [f"{at[e]:.5f}" if e in at else "" for e in entries]
                print(f"| {clusters} x {terms} | {method} | " + " | ".join(cells) + " |")
for name in names:
    folder = os.path.join(out, name, "refit")
    print(f"\n{name}: 64 x 4, no residual, Eq. 16 as stored (compress report error_masked)")
    print("| method | Eq. 16 | seconds |")
    print("|---|---|---|")
    for label in ("l1", "cpca", "l1-refit", "l1-refit-choose"):
        path = os.path.join(folder, label + ".json")
        if os.path.exists(path):
            report = json.load(open(path))
            print(f"| {label} | {report['error_masked']:.6f} | {report['seconds']:.1f} |")
PY
