#!/usr/bin/env bash
# Relit quality under concentrated light (issue 17, docs/relit_quality.md), with and without
# light weighting (relume compress --light-weighting):
#  1. the demo's scene (320x320, 253 lights; scripts/demo.sh) under the built-in sky, seeds 1 to
#     3 (one seed's relit error is not a measurement): bytes, Eq. 16 (masked), 8-bit PSNR of the
#     stored field, and the sky relight's relative squared error against the uncompressed field
#     relit, with the negative values of the raw reconstruction (--allow-negative) beside it;
#  2. DiLiGenT's ball (16 bit), pot1 and harvest at the default 64 clusters x 4 terms x 5% under
#     Grace Cathedral, St. Peter's and a sunny sky (Poly Haven), each map turned onto the lights
#     (--rotate auto): relit error, and negative values inside the mask raw and as relit.
# Writes OUT_DIR/demo.csv, OUT_DIR/diligent.csv and the demo's images of seed 1 (reference,
# relit, and the difference x 8) for docs/relit_quality.md. About 30 minutes on 2 cores.
#   scripts/bench_relit_quality.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-/tmp/relume-relit-quality}"
data="${RELUME_DATA:-../shared/data}"
relume="$build/apps/relume"
mkdir -p "$out"

# The relative squared error and negative values of IMAGE against REFERENCE.
compare() {
  "$relume" compare "$1" "$2" --json - 2>/dev/null | /usr/bin/python3 -c '
import json, sys
r = json.load(sys.stdin)
print("%.6f,%d" % (r["relative_squared_error"], r["negative_values"]))'
}

echo "== demo scene" >&2
scene="$out/scene"
[ -f "$scene/filenames.txt" ] || "$relume" -q synth -o "$scene" --size 320x320 --lights 253
"$relume" -q -y sky -o "$out/sky.exr"
"$relume" -q -y relight "$scene" --env "$out/sky.exr" -o "$out/reference.exr" --cpu
settings=(
  "--terms 8 --residual 7"
  "--terms 8 --residual 7 --light-weighting 0.5"
  "--terms 8 --residual 6 --light-weighting 0.5"
  "--terms 8 --residual 6 --light-weighting 1"
)
echo "setting,seed,bytes,error_masked,psnr_whole_frame,sky_relit_error,sky_negative,sky_negative_raw" \
  >"$out/demo.csv"
for setting in "${settings[@]}"; do
  for seed in 1 2 3; do
    echo "demo: $setting, seed $seed" >&2
    # shellcheck disable=SC2086  # the options are words
    "$relume" compress -q -y "$scene" -o "$out/demo.relume" --clusters 64 $setting --seed "$seed" \
      --report "$out/demo.json"
    "$relume" -q -y relight "$out/demo.relume" --env "$out/sky.exr" -o "$out/relit.exr"
    "$relume" -q -y relight "$out/demo.relume" --env "$out/sky.exr" -o "$out/raw.exr" \
      --allow-negative
    relit=$(compare "$out/relit.exr" "$out/reference.exr")
    raw=$(compare "$out/raw.exr" "$out/reference.exr")
    /usr/bin/python3 - "$out/demo.json" "$setting" "$seed" "$relit" "${raw#*,}" \
      >>"$out/demo.csv" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
print(f'{sys.argv[2]},{sys.argv[3]},{r["bytes"]},{r["error_masked"]:.6f},'
      f'{r["psnr_8bit"]["whole_frame"]:.2f},{sys.argv[4]},{sys.argv[5]}')
EOF
    if [ "$seed" = 1 ]; then
      tag=$(echo "$setting" | tr -d ' -' | tr '.' 'p')
      "$relume" -q -y relight "$out/demo.relume" --env "$out/sky.exr" -o "$out/relit_$tag.png" \
        --exposure -1
      /usr/bin/python3 - "$out/relit.exr" "$out/reference.exr" "$out/difference_$tag.png" <<'EOF'
import sys, numpy as np, OpenImageIO as oiio
a = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT)
b = oiio.ImageBuf(sys.argv[2]).get_pixels(oiio.FLOAT)
d = np.clip(np.abs(a - b) * 8 * 0.5, 0, 1)  # exposure -1 as the images, times 8
out = oiio.ImageOutput.create(sys.argv[3])
out.open(sys.argv[3], oiio.ImageSpec(d.shape[1], d.shape[0], d.shape[2], oiio.UINT8))
out.write_image((np.power(d, 1 / 2.2) * 255 + 0.5).astype(np.uint8))
out.close()
EOF
    fi
  done
done
"$relume" -q -y relight "$scene" --env "$out/sky.exr" -o "$out/reference.png" --exposure -1

echo "== DiLiGenT" >&2
echo "object,light_weighting,bytes,error_masked,map,relit_error,negative,negative_raw" \
  >"$out/diligent.csv"
maps=("$data/envmaps/grace_cross.hdr" "$data/envmaps/stpeters_cross.hdr"
  "$data/envmaps/polyhaven_sky_512x256.exr")
for object in diligent-ball-16bit diligent-pot1-crop8 diligent-harvest-crop8; do
  input="$data/olat/$object"
  for map in "${maps[@]}"; do
    name="$object-$(basename "${map%.*}")"
    "$relume" -q -y lights --dirs "$input" --env "$map" --rotate auto -o "$out/$name.txt"
    "$relume" -q -y relight "$input" --lights "$out/$name.txt" -o "$out/$name-reference.exr"
  done
  for weighting in 0 0.5; do
    echo "DiLiGenT: $object, light weighting $weighting" >&2
    "$relume" compress -q -y "$input" -o "$out/object.relume" --clusters 64 --terms 4 \
      --residual 5% --light-weighting "$weighting" --report "$out/object.json"
    summary=$(/usr/bin/python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))
print("%d,%.6f" % (r["bytes"], r["error_masked"]))' "$out/object.json")
    for map in "${maps[@]}"; do
      name="$object-$(basename "${map%.*}")"
      "$relume" -q -y relight "$out/object.relume" --lights "$out/$name.txt" -o "$out/relit.exr"
      "$relume" -q -y relight "$out/object.relume" --lights "$out/$name.txt" -o "$out/raw.exr" \
        --allow-negative
      relit=$(compare "$out/relit.exr" "$out/$name-reference.exr")
      raw=$(compare "$out/raw.exr" "$out/$name-reference.exr")
      echo "$object,$weighting,$summary,$(basename "${map%.*}"),$relit,${raw#*,}" \
        >>"$out/diligent.csv"
    done
  done
done
column -s, -t <"$out/demo.csv"
column -s, -t <"$out/diligent.csv"
