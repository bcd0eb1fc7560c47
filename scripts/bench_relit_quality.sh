#!/usr/bin/env bash
# Relit quality: how a compressed field relights against the uncompressed one. Two parts:
#
# weighting (issue 17): under concentrated light, with and without light weighting (relume
# compress --light-weighting):
#  1. the demo's scene (320x320, 253 lights; scripts/demo.sh) under the built-in sky, seeds 1 to
#     3 (one seed's relit error is not a measurement): bytes, Eq. 16 (masked), 8-bit PSNR of the
#     stored field, and the sky relight's relative squared error against the uncompressed field
#     relit, with the negative values of the raw reconstruction (--allow-negative) beside it;
#  2. DiLiGenT's ball (16 bit), pot1 and harvest at the default 64 clusters x 4 terms x 5% under
#     Grace Cathedral, St. Peter's and a sunny sky (Poly Haven), each map turned onto the lights
#     (--rotate auto): relit error, and negative values inside the mask raw and as relit.
#  Writes OUT_DIR/demo.csv, OUT_DIR/diligent.csv and the demo's images of seed 1 (reference,
#  relit, and the difference x 8). About 30 minutes on 2 cores.
#
# seams (issue 33): what a person sees. The demo's scene, the ball (16 bit) and pot1 at three
# rates each under the built-in sky, Grace Cathedral and St. Peter's (the maps turned onto the
# lights), and the lion (rti-loewenkopf) at three rates under raking lights from the left at 15
# and 30 degrees elevation. Per relight, from `relume compare --model --json` inside the stored
# area: relative L2, luminance SSIM (mean and worst 1% of windows), seam contrast, the pixels
# whose channels lie in different clusters, black pixels, chroma outliers and the channel sums.
# Writes OUT_DIR/seams.csv and OUT_DIR/seams/SUBJECT-RATE-LIGHTING.png: relit, reference and
# |relit - reference| x 8 side by side, all three exposed to the reference's white (its lit 99th
# percentile / 0.9, as --exposure auto). About 30 minutes on 2 cores.
#
# channels (issue 33): one cluster per pixel (`--channel-clusters shared`, the default) against
# each colour channel clustered on its own (`separate`), on the seams part's subjects and
# lightings at the demo's settings (scene), the README's lion settings and the defaults (ball,
# pot1): the same measures and bytes per pixel in OUT_DIR/channels.csv, images in
# OUT_DIR/channels/. About 15 minutes on 2 cores.
#
#   scripts/bench_relit_quality.sh [BUILD_DIR] [OUT_DIR] [weighting|seams|channels|all]
# RELUME_DATA: the shared data folder (default ../shared/data). Needs python3 with numpy and
# OpenImageIO's bindings at /usr/bin/python3 (scripts/install_deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-/tmp/relume-relit-quality}"
part="${3:-all}"
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

# The demo's scene (kept between runs) and the built-in sky.
scene="$out/scene"
make_demo_scene() {
  [ -f "$scene/filenames.txt" ] || "$relume" -q synth -o "$scene" --size 320x320 --lights 253
  "$relume" -q -y sky -o "$out/sky.exr"
}

light_weighting_bench() {
  echo "== demo scene" >&2
  make_demo_scene
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
}

# One CSV row of figures from `relume compare --model --json` on stdin.
quality_row() {
  /usr/bin/python3 -c '
import json, sys
r = json.load(sys.stdin)
s, lit, seams = r["luminance_ssim"], r["lit_pixels"], r["seam_contrast"]
contrast = seams["contrast"]
split = seams["pixels_with_split_channels"] / max(1, seams["pixels_with_every_channel_stored"])
print("%.4f,%.4f,%.4f,%s,%.1f,%d,%d,%.2f,%s" % (
    r["relative_l2_error"], s["mean"], s["worst_1_percent"],
    "n/a" if contrast is None else "%.2f" % contrast, 100 * split, lit["black_pixels"],
    lit["lit_pixels"], 100 * lit["chroma_outlier_share"],
    "/".join("%.4f" % x for x in lit["channel_sum_ratio"])))'
}

# RELIT, REFERENCE (linear images of one size) -> PNG: relit | reference | |difference| x 8, each
# exposed to the reference's white (its lit 99th percentile / 0.9, as --exposure auto), sRGB,
# cropped to the reference's lit pixels (and 8 around) and enlarged to at least 256 pixels high.
side_by_side() {
  /usr/bin/python3 - "$@" <<'EOF'
import sys, numpy as np, OpenImageIO as oiio
relit = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT)[:, :, :3]
reference = oiio.ImageBuf(sys.argv[2]).get_pixels(oiio.FLOAT)[:, :, :3]
luminance = reference @ np.array([0.2126, 0.7152, 0.0722])
lit = np.sort(luminance[luminance > 0])
white = lit[int(0.99 * (len(lit) - 1))] / 0.9 if len(lit) else 1.0
rows, columns = np.nonzero(luminance > 0)
if len(rows):
    top, left = max(0, rows.min() - 8), max(0, columns.min() - 8)
    relit, reference = (image[top:rows.max() + 9, left:columns.max() + 9]
                        for image in (relit, reference))
def shown(image):
    v = np.clip(image / white, 0, 1)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)
gap = np.ones((relit.shape[0], 4, 3))
panels = np.concatenate([shown(relit), gap, shown(reference), gap,
                         shown(np.abs(relit - reference) * 8)], axis=1)
scale = max(1, -(-256 // relit.shape[0]))
panels = np.repeat(np.repeat(panels, scale, axis=0), scale, axis=1)
out = oiio.ImageOutput.create(sys.argv[3])
out.open(sys.argv[3], oiio.ImageSpec(panels.shape[1], panels.shape[0], 3, oiio.UINT8))
out.write_image((panels * 255 + 0.5).astype(np.uint8))
out.close()
EOF
}

# SUBJECT INPUT "SETTING1|SETTING2|SETTING3" LIGHTING...: a light file and the uncompressed
# relight per lighting (sky: the built-in sky; raking15, raking30: a light from the left at that
# elevation; otherwise a map of the shared envmaps/ turned onto the lights), then per setting a
# compression and, per lighting, its relight measured and shown side by side.
# The part whose table and images measure_subject writes: OUT_DIR/TABLE.csv and OUT_DIR/TABLE/.
table=seams
measure_subject() {
  local subject=$1 input=$2 lighting lights rate=0 setting model name bytes_per_pixel row
  local -a settings
  IFS='|' read -r -a settings <<<"$3"
  shift 3
  for lighting in "$@"; do
    lights="$out/$table/$subject-$lighting.txt"
    case $lighting in
      sky) "$relume" -q -y lights --dirs "$input" --env "$out/sky.exr" -o "$lights" ;;
      raking15) "$relume" -q -y lights --dirs "$input" --light-dir -0.966,0,0.259 -o "$lights" ;;
      raking30) "$relume" -q -y lights --dirs "$input" --light-dir -0.866,0,0.5 -o "$lights" ;;
      *) "$relume" -q -y lights --dirs "$input" --env "$data/envmaps/$lighting.hdr" --rotate auto \
        -o "$lights" ;;
    esac
    "$relume" -q -y relight "$input" --lights "$lights" \
      -o "$out/$table/$subject-$lighting-reference.exr"
  done
  for setting in "${settings[@]}"; do
    rate=$((rate + 1))
    echo "$table: $subject, $setting" >&2
    model="$out/$table/$subject-r$rate.relume"
    # shellcheck disable=SC2086  # the options are words
    "$relume" compress -q -y "$input" -o "$model" $setting --report "$out/$table/report.json"
    bytes_per_pixel=$(/usr/bin/python3 -c 'import json, sys
print("%.2f" % json.load(open(sys.argv[1]))["bytes_per_pixel"])' "$out/$table/report.json")
    for lighting in "$@"; do
      name="$subject-r$rate-$lighting"
      "$relume" -q -y relight "$model" --lights "$out/$table/$subject-$lighting.txt" \
        -o "$out/$table/$name.exr"
      row=$("$relume" compare "$out/$table/$name.exr" \
        "$out/$table/$subject-$lighting-reference.exr" --model "$model" --json - 2>/dev/null |
        quality_row)
      echo "$subject,$setting,$bytes_per_pixel,$lighting,$row" >>"$out/$table.csv"
      side_by_side "$out/$table/$name.exr" "$out/$table/$subject-$lighting-reference.exr" \
        "$out/$table/$name.png"
    done
  done
}

# Starts the part TABLE: its folder and the header of its table.
start_table() {
  table=$1
  echo "== $table" >&2
  make_demo_scene
  mkdir -p "$out/$table"
  echo "subject,setting,bytes_per_pixel,lighting,relative_l2,ssim_mean,ssim_worst_1_percent,\
seam_contrast,split_channels_percent,black_pixels,lit_pixels,chroma_outliers_percent,\
channel_sums_rgb" >"$out/$table.csv"
}

seams_bench() {
  start_table seams
  local maps=(sky grace_cross stpeters_cross)
  # The demo's scene: a low rate, the demo's settings (scripts/demo.sh) and a high rate.
  measure_subject scene "$scene" "--clusters 16 --terms 4 --residual 2|\
--clusters 64 --terms 8 --residual 7 --light-weighting 0.5|--clusters 64 --terms 8 --residual 20" \
    "${maps[@]}"
  # Captures: the README's lion settings, the defaults, and the issue's 300 B/px setting.
  local captured="--clusters 16 --terms 4|--clusters 64 --terms 4|\
--clusters 64 --terms 8 --residual 20%"
  measure_subject lion "$data/olat/rti-loewenkopf/dirs.lp" "$captured" raking15 raking30
  measure_subject ball "$data/olat/diligent-ball-16bit" "$captured" "${maps[@]}"
  measure_subject pot1 "$data/olat/diligent-pot1-crop8" "$captured" "${maps[@]}"
  column -s, -t <"$out/$table.csv"
}

channels_bench() {
  start_table channels
  local maps=(sky grace_cross stpeters_cross) defaults="--clusters 64 --terms 4"
  measure_subject scene "$scene" "\
--clusters 64 --terms 8 --residual 7 --light-weighting 0.5 --channel-clusters separate|\
--clusters 64 --terms 8 --residual 7 --light-weighting 0.5 --channel-clusters shared" "${maps[@]}"
  local lion="--clusters 16 --terms 4"
  measure_subject lion "$data/olat/rti-loewenkopf/dirs.lp" "\
$lion --channel-clusters separate|$lion --channel-clusters shared" raking15 raking30
  measure_subject ball "$data/olat/diligent-ball-16bit" "\
$defaults --channel-clusters separate|$defaults --channel-clusters shared" "${maps[@]}"
  measure_subject pot1 "$data/olat/diligent-pot1-crop8" "\
$defaults --channel-clusters separate|$defaults --channel-clusters shared" "${maps[@]}"
  column -s, -t <"$out/$table.csv"
}

case $part in
  weighting) light_weighting_bench ;;
  seams) seams_bench ;;
  channels) channels_bench ;;
  all)
    light_weighting_bench
    seams_bench
    channels_bench
    ;;
  *)
    echo "bench_relit_quality.sh: part '$part' is not weighting, seams, channels or all" >&2
    exit 2
    ;;
esac
