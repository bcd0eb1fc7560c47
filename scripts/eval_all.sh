#!/usr/bin/env bash
# The heavy runs behind docs/results.md: `relume eval` on the shared DiLiGenT data (ball 16-bit,
# bear, pot1, harvest) and on a full-sphere synthetic scene, each into OUT/<name>/, relit under
# Grace Cathedral. Then prints the headline tables of docs/results.md from the CSVs.
#
# Usage: scripts/eval_all.sh [BUILD_DIR] [OUT_DIR] [NAMES...]
#   BUILD_DIR defaults to build, OUT_DIR to out/eval, NAMES to all of ball bear pot1 harvest synth.
#   RELUME_DATA overrides ../shared/data; EVAL_THREADS (default 2) the worker threads;
#   EVAL_PARTS (default "eval refit") which of the two kinds of runs to make.
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
parts="${EVAL_PARTS:-eval refit}"
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
  [[ " $parts " == *" eval "* ]] || break
  case "$name" in
    ball) run_eval ball "$data/olat/diligent-ball-16bit" --rotate 180 --exposure 1 ;;
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
  [[ " $parts " == *" refit "* ]] || break
  case "$name" in
    ball) refit_table ball "$data/olat/diligent-ball-16bit" ;;
    bear) refit_table bear "$data/olat/diligent-bear-crop8" ;;
    pot1) refit_table pot1 "$data/olat/diligent-pot1-crop8" ;;
    harvest) refit_table harvest "$data/olat/diligent-harvest-crop8" ;;
    synth) refit_table synth "$out/synth-scene" ;;
  esac
done

# The tables of docs/results.md.
/usr/bin/python3 "$root/scripts/results_tables.py" "$out" "${names[@]}"
