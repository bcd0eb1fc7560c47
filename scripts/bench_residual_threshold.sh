#!/usr/bin/env bash
# The residual threshold against the camera's noise (issue 32: the default must not store sensor
# noise). Each shared DiLiGenT capture (the 16-bit ball, and the 8-bit bear and pot1 crops) is
# compressed at the defaults with `--threshold` set to k noise deviations (the mean of the
# channels' estimates that the default run reports), k = 1, 2, 3, 4, 6, and once with 1
# deviation and 3 entries per function instead of 5: a rate cut by the entry count for
# comparison. Per point: bytes per pixel, the 8-bit PSNR inside the mask and over the frame, and
# the relit error under Grace Cathedral (turned onto the lights) against the captured images
# relit the same way (relative squared error, `relume compare`); and the default run itself: 3
# deviations, at least the input's quantization step (lib/compress/noise_model.hpp).
#   scripts/bench_residual_threshold.sh [BUILD_DIR] [OUT_DIR]
# RELUME_DATA: the shared data folder (default ../shared/data). Writes OUT_DIR/thresholds.csv and
# prints it as a table. About 10 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-/tmp/relume-thresholds}"
data="${RELUME_DATA:-../shared/data}"
relume="$build/apps/relume"
mkdir -p "$out"

# FIELD in REPORT: the report's value at a path of keys, e.g. psnr_8bit.mask.
report_value() {
  /usr/bin/python3 -c 'import json, sys
value = json.load(open(sys.argv[1]))
for key in sys.argv[2].split("."):
    value = value[key]
print(sum(value) / len(value) if isinstance(value, list) else value)' "$1" "$2"
}

# REPORT -> bytes per pixel, PSNR in the mask and over the frame, comma-separated.
point() {
  echo "$(report_value "$1" bytes_per_pixel),$(report_value "$1" psnr_8bit.mask),\
$(report_value "$1" psnr_8bit.whole_frame)"
}

# IMAGE -> its relative squared error against the capture's reference relight.
relit_error() {
  "$relume" compare "$1" "$out/$capture-reference.exr" --json - 2>/dev/null |
    /usr/bin/python3 -c 'import json, sys; print(json.load(sys.stdin)["relative_squared_error"])'
}

echo "capture,setting,threshold,bytes_per_pixel,psnr_mask,psnr_frame,relit_error_grace" \
  >"$out/thresholds.csv"
for capture in diligent-ball-16bit diligent-bear-crop8 diligent-pot1-crop8; do
  input="$data/olat/$capture"
  echo "== $capture" >&2
  "$relume" -q -y lights --dirs "$input" --env "$data/envmaps/grace_cross.hdr" --rotate auto \
    -o "$out/$capture-grace.txt"
  "$relume" -q -y relight "$input" --lights "$out/$capture-grace.txt" \
    -o "$out/$capture-reference.exr"
  "$relume" compress -q -y "$input" -o "$out/$capture-default.relume" \
    --report "$out/$capture-default.json"
  sigma=$(report_value "$out/$capture-default.json" parameters.noise.sigma)
  settings=("1" "2" "3" "4" "6" "1 --residual 3")
  for setting in "${settings[@]}"; do
    k=${setting%% *}
    threshold=$(/usr/bin/python3 -c "print($k * $sigma)")
    name="$out/$capture-${setting// /_}"
    # shellcheck disable=SC2046  # the setting's extra options are words
    "$relume" compress -q -y "$input" -o "$name.relume" --report "$name.json" \
      --threshold "$threshold" $(echo "$setting" | cut -s -d' ' -f2-)
    "$relume" -q -y relight "$name.relume" --lights "$out/$capture-grace.txt" -o "$name.exr"
    relit=$(relit_error "$name.exr")
    echo "$capture,${k} deviations$([ "$k" = "$setting" ] || echo " and 3 entries"),$threshold,\
$(point "$name.json"),$relit" >>"$out/thresholds.csv"
  done
  "$relume" -q -y relight "$out/$capture-default.relume" --lights "$out/$capture-grace.txt" \
    -o "$out/$capture-default.exr"
  echo "$capture,default,$(report_value "$out/$capture-default.json" parameters.residual_threshold),\
$(point "$out/$capture-default.json"),$(relit_error "$out/$capture-default.exr")" \
    >>"$out/thresholds.csv"
done
column -s, -t <"$out/thresholds.csv"
